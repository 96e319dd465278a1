"""`make package`: the zip a user installs with "Install from ZIP", checked as plugins.qgis.org would,
then installed into a fresh QGIS profile and loaded by ``qgis_process`` from there.

The installed copy is loaded with Debian's Python only (no .venv on PYTHONPATH), as on a user's
machine: every algorithm must still register, which holds the plugin to lazy heavy imports.
"""
from __future__ import annotations

import configparser
import json
import os
import re
import subprocess
import zipfile
from pathlib import Path
from urllib.parse import urlparse

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
ALGORITHM_IDS = sorted(f"birdseye:{p.stem}" for p in (REPO_ROOT / "processing" / "algorithms").glob("*.py")
                       if p.stem not in {"__init__", "base"})
# plugins.qgis.org's validator: size limit, metadata it requires, a LICENSE at the top level
MAX_UPLOAD_BYTES = 25_000_000
REQUIRED_METADATA = ["name", "description", "version", "qgisMinimumVersion", "author", "email", "about",
                     "tracker", "repository"]
ALSO_EXPECTED = ["homepage", "tags", "category", "icon", "experimental", "hasProcessingProvider",
                 "changelog"]
DEV_ONLY = {"tests", "benchmarks", "scripts", ".venv", "build", ".ci", ".git", "birdseye-demo",
            "__pycache__", ".pytest_cache", ".hypothesis", ".qgis-settings", "__MACOSX"}

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def package() -> Path:
    result = subprocess.run(["make", "--no-print-directory", "-s", "package"], cwd=REPO_ROOT,
                            capture_output=True, text=True, timeout=120, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    metadata = configparser.ConfigParser(interpolation=None)
    metadata.read(REPO_ROOT / "metadata.txt", encoding="utf-8")
    archive = REPO_ROOT / "build" / f"birdseye-{metadata['general']['version']}.zip"
    assert archive.is_file(), f"make package did not write {archive}"
    return archive


@pytest.fixture(scope="module")
def names(package) -> list[str]:
    with zipfile.ZipFile(package) as zf:
        assert zf.testzip() is None, "corrupt member"
        return zf.namelist()


def test_one_top_folder_named_birdseye(names):
    assert {name.split("/")[0] for name in names} == {"birdseye"}
    for required in ("__init__.py", "metadata.txt", "LICENSE", "README.md", "birdseye_qgis/gui/plugin.py",
                     "processing/provider.py", "resources/icons/birdseye.svg"):
        assert f"birdseye/{required}" in names


def test_no_tests_dev_files_or_caches(names, package):
    offending = [n for n in names
                 if DEV_ONLY & set(n.split("/")[1:-1]) or n.endswith((".pyc", ".pyo"))
                 or any(part.startswith(".") for part in n.split("/"))
                 or n.count("/") == 1 and n.split("/")[1] not in
                 {"__init__.py", "metadata.txt", "LICENSE", "README.md"}]
    assert offending == []
    assert package.stat().st_size < MAX_UPLOAD_BYTES


def test_every_plugin_source_file_is_packaged(names):
    """Nothing the plugin imports or reads at run time is left behind."""
    for folder in ("birdseye_qgis", "processing", "resources"):
        for path in (REPO_ROOT / folder).rglob("*"):
            if path.is_file() and "__pycache__" not in path.parts and path.suffix != ".pyc":
                assert f"birdseye/{path.relative_to(REPO_ROOT).as_posix()}" in names


def test_metadata_passes_the_repository_checks(package, names):
    with zipfile.ZipFile(package) as zf:
        text = zf.read("birdseye/metadata.txt").decode("utf-8")
    parser = configparser.ConfigParser(interpolation=None)
    parser.optionxform = str  # keys are case-sensitive (qgisMinimumVersion)
    parser.read_string(text)
    general = parser["general"]
    missing = [k for k in REQUIRED_METADATA + ALSO_EXPECTED if not general.get(k, "").strip()]
    assert missing == []
    assert general["name"] == "BirdsEye"
    assert general["qgisMinimumVersion"] == "3.22"
    assert re.fullmatch(r"\d+\.\d+\.\d+", general["version"])
    assert general["hasProcessingProvider"] == "yes"
    assert general["category"] == "Analysis"
    assert "/" not in general["author"]
    assert f"birdseye/{general['icon']}" in names
    for key in ("tracker", "repository", "homepage"):
        url = urlparse(general[key])
        assert url.scheme == "https" and url.netloc, f"{key} is not a URL"


def test_installed_zip_loads_in_qgis_process(package, tmp_path):
    """Unzip into a fresh profile's python/plugins, as Install from ZIP does, and list the provider."""
    config = tmp_path / "config"
    plugins_dir = config / "profiles" / "default" / "python" / "plugins"
    plugins_dir.mkdir(parents=True)
    with zipfile.ZipFile(package) as zf:
        zf.extractall(plugins_dir)
    nowhere = tmp_path / "no-extra-plugins"
    nowhere.mkdir()
    env = {k: v for k, v in os.environ.items()
           if k not in {"QGIS_CUSTOM_CONFIG_PATH", "QGIS_PLUGINPATH", "PYTHONPATH"}}
    env.update(BIRDSEYE_QGIS_CONFIG=str(config), BIRDSEYE_PLUGIN_PATH=str(nowhere), BIRDSEYE_VENV="")
    result = subprocess.run([str(REPO_ROOT / "scripts" / "qgis_process.sh"), "--json", "list"], env=env,
                            capture_output=True, text=True, timeout=120, check=False)
    assert result.returncode == 0, result.stderr
    provider = json.loads(result.stdout)["providers"].get("birdseye")
    assert provider is not None, "the installed plugin did not register its provider"
    assert sorted(provider["algorithms"]) == ALGORITHM_IDS, (
        "an algorithm module failed to import without the venv's packages — heavy imports must be lazy")
