"""`make package`: the zip a user installs with "Install from ZIP", checked as plugins.qgis.org would,
then installed into a fresh QGIS profile — by QGIS's own Install-from-ZIP code in the real desktop, and
by unzipping for ``qgis_process`` — and loaded from there.

The installed copy is loaded with Debian's Python only (no .venv on PYTHONPATH), as on a user's
machine: every algorithm must still register, which holds the plugin to lazy heavy imports.
"""
from __future__ import annotations

import configparser
import importlib.util
import json
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path
from urllib.parse import urlparse

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO_ROOT / "tests" / "gui"))
from test_desktop import QGIS_BIN, grab_screen, xvfb_display  # noqa: E402  (the desktop test's X helpers)

_spec = importlib.util.spec_from_file_location("birdseye_package_script", REPO_ROOT / "scripts" / "package.py")
package_script = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(package_script)
BUNDLED_MODEL = "birdseye/models/birdseye_demo_heatmap.onnx"
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
    """Nothing the plugin imports or reads at run time is left behind — the bundled model included."""
    assert BUNDLED_MODEL in names, "the bundled detector model is not in the zip"
    for folder in ("birdseye_qgis", "processing", "resources", "models"):
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


# ------------------------------------------------------------------------------ plugins.qgis.org validator
def test_zip_passes_the_repository_validator(package):
    assert package_script.repository_problems(package) == []
    assert package.stat().st_size <= package_script.MAX_UPLOAD_BYTES == MAX_UPLOAD_BYTES


def _copy_zip(source: Path, target: Path, rename=None, drop=(), add=()) -> Path:
    """A copy of the plugin zip with members renamed (name -> name), dropped or added (name, bytes)."""
    with zipfile.ZipFile(source) as zin, zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as zout:
        for info in zin.infolist():
            if info.filename in drop:
                continue
            data = zin.read(info.filename)
            name = rename(info.filename) if rename else info.filename
            if info.filename == "birdseye/metadata.txt" and any(n == "metadata-edit" for n, _ in add):
                data = dict(add)["metadata-edit"](data.decode("utf-8")).encode("utf-8")
            zout.writestr(name, data)
        for name, data in add:
            if name != "metadata-edit":
                zout.writestr(name, data)
    return target


BAD_ZIPS = {
    "bytecode": (dict(add=[("birdseye/processing/__pycache__/provider.cpython-311.pyc", b"x")]), "__pycache__"),
    "no_licence": (dict(drop={"birdseye/LICENSE"}), "LICENSE is missing"),
    "two_top_folders": (dict(add=[("extra/readme.txt", b"x")]), "several top folders"),
    "folder_with_space": (dict(rename=lambda n: n.replace("birdseye/", "Birds Eye/", 1)), "top folder"),
    "no_tracker": (dict(add=[("metadata-edit", lambda t: re.sub(r"(?m)^tracker=.*$", "tracker=", t))]), "tracker"),
    "icon_missing": (dict(drop={"birdseye/resources/icons/birdseye.svg"}), "icon"),
    "author_with_slash": (dict(add=[("metadata-edit", lambda t: re.sub(r"(?m)^author=.*$", "author=A/B", t))]),
                          "author"),
    "empty_dependencies": (dict(add=[("metadata-edit", lambda t: t + "plugin_dependencies=\n")]),
                           "plugin_dependencies"),
    "bad_url": (dict(add=[("metadata-edit", lambda t: re.sub(r"(?m)^repository=.*$", "repository=github", t))]),
                "repository"),
}


@pytest.mark.parametrize("case", sorted(BAD_ZIPS))
def test_validator_refuses_what_the_repository_refuses(package, tmp_path, case):
    """Each fixture breaks one rule of plugins.qgis.org's validator; exactly that is reported."""
    edits, expected = BAD_ZIPS[case]
    broken = _copy_zip(package, tmp_path / f"{case}.zip", **edits)
    problems = package_script.repository_problems(broken)
    assert problems and all(expected in p for p in problems), problems


def test_validator_enforces_the_size_limit(package, monkeypatch):
    monkeypatch.setattr(package_script, "MAX_UPLOAD_BYTES", package.stat().st_size - 1)
    assert ["accepts at most" in p for p in package_script.repository_problems(package)] == [True]


# ------------------------------------------------------------------------------ translations
def test_translation_for_the_qgis_locale_is_loaded(package, tmp_path):
    """A string from i18n/birdseye_en.ts, translated and compiled as `make translations` does, shows in
    qgis_process for a profile whose QGIS locale is that language: the .ts contexts match tr() at run
    time and the plugin installs the translator for the locale."""
    lrelease = shutil.which("lrelease")
    if lrelease is None:
        pytest.skip("needs lrelease (Debian qttools5-dev-tools; make setup installs it)")
    source = "Pose noise Σ0: x, y, z (m), roll, pitch, yaw (deg)"
    translated = "Bruit de pose Σ0 : x, y, z (m), roulis, tangage, lacet (°)"
    tree = ET.parse(REPO_ROOT / "i18n" / "birdseye_en.ts")
    message = next((m for c in tree.getroot() if c.findtext("name") == "SimulateCampaign"
                    for m in c.findall("message") if m.findtext("source") == source), None)
    assert message is not None, f"'{source}' is not in i18n/birdseye_en.ts: run make translations"
    message.find("translation").text = translated
    message.find("translation").attrib.pop("type", None)
    french_ts = tmp_path / "birdseye_fr.ts"
    tree.write(french_ts, encoding="utf-8", xml_declaration=True)

    config = tmp_path / "config"
    plugins_dir = config / "profiles" / "default" / "python" / "plugins"
    plugins_dir.mkdir(parents=True)
    with zipfile.ZipFile(package) as zf:
        zf.extractall(plugins_dir)
    (plugins_dir / "birdseye" / "i18n").mkdir(exist_ok=True)  # English-only zips have no .qm yet
    subprocess.run([lrelease, "-silent", str(french_ts), "-qm", str(plugins_dir / "birdseye" / "i18n" /
                                                                    "birdseye_fr.qm")], check=True, timeout=60)
    ini = config / "profiles" / "default" / "QGIS" / "QGIS3.ini"
    ini.parent.mkdir(parents=True)
    ini.write_text("[locale]\nuserLocale=fr_FR\noverrideFlag=true\n\n[PythonPlugins]\nbirdseye=true\n")
    nowhere = tmp_path / "no-extra-plugins"
    nowhere.mkdir()
    env = {k: v for k, v in os.environ.items()
           if k not in {"QGIS_CUSTOM_CONFIG_PATH", "QGIS_PLUGINPATH", "PYTHONPATH"}}
    env.update(BIRDSEYE_QGIS_CONFIG=str(config), BIRDSEYE_PLUGIN_PATH=str(nowhere), BIRDSEYE_VENV="")
    result = subprocess.run([str(REPO_ROOT / "scripts" / "qgis_process.sh"), "help", "birdseye:simulatecampaign"],
                            env=env, capture_output=True, text=True, timeout=120, check=False)
    assert result.returncode == 0, result.stderr
    assert translated in result.stdout and source not in result.stdout


def ts_messages(path: Path) -> set[tuple[str, str]]:
    return {(c.findtext("name"), m.findtext("source")) for c in ET.parse(path).getroot() for m in c.findall("message")}


def test_english_ts_lists_every_tr_string(tmp_path):
    """i18n/birdseye_en.ts is what `make translations` makes from today's sources (no string missing or stale)."""
    if shutil.which("pylupdate5") is None:
        pytest.skip("needs pylupdate5 (Debian pyqt5-dev-tools; make setup installs it)")
    result = subprocess.run(["make", "--no-print-directory", "-s", "-n", "translations"], cwd=REPO_ROOT,
                            capture_output=True, text=True, check=True)
    command = next(line for line in result.stdout.splitlines() if "pylupdate5" in line)
    fresh = tmp_path / "birdseye_en.ts"
    subprocess.run(command.replace("i18n/birdseye_en.ts", str(fresh)), shell=True, cwd=REPO_ROOT, check=True,
                   capture_output=True, timeout=120)
    committed = ts_messages(REPO_ROOT / "i18n" / "birdseye_en.ts")
    current = ts_messages(fresh)
    assert current - committed == set(), "strings missing from i18n/birdseye_en.ts: run make translations"
    assert committed - current == set(), \
        "i18n/birdseye_en.ts lists strings no longer in the code: run make translations"
    assert len(current) > 200


# ------------------------------------------------------------------------------ Install from ZIP, for real
INSTALL_PROBE = r"""
import json, os, sys, traceback
from qgis.core import QgsApplication, QgsSettings
from qgis.PyQt.QtCore import QTimer
from qgis.PyQt.QtWidgets import QTabWidget, QWidget
from qgis.utils import active_plugins, home_plugin_path, iface, plugins

result = {"errors": []}


def message_log():
    tabs = {}
    for viewer in [w for w in iface.mainWindow().findChildren(QWidget)
                   if w.metaObject().className() == "QgsMessageLogViewer"]:
        for tab_widget in viewer.findChildren(QTabWidget):
            for i in range(tab_widget.count()):
                page = tab_widget.widget(i)
                tabs[tab_widget.tabText(i)] = page.toPlainText() if hasattr(page, "toPlainText") else ""
    return tabs


def install():
    try:
        import pyplugin_installer
        result["loaded_before"] = "birdseye" in plugins
        # What Plugins > Manage and Install Plugins > Install from ZIP runs on "Install Plugin".
        pyplugin_installer.instance().installFromZipFile(os.environ["BIRDSEYE_ZIP"])
        result["installed_to"] = os.path.join(home_plugin_path, "birdseye")
        result["metadata_installed"] = os.path.isfile(os.path.join(home_plugin_path, "birdseye", "metadata.txt"))
        result["loaded"] = "birdseye" in plugins
        result["active"] = "birdseye" in active_plugins
        result["enabled_in_profile"] = QgsSettings().value("PythonPlugins/birdseye", False, bool)
        result["module_file"] = sys.modules["birdseye"].__file__
        provider = QgsApplication.processingRegistry().providerById("birdseye")
        result["algorithms"] = sorted(a.id() for a in provider.algorithms()) if provider else None
        result["menu"] = [a.menu().objectName() for a in iface.mainWindow().menuBar().actions() if a.menu()]
    except Exception:
        result["errors"].append(traceback.format_exc())
    QTimer.singleShot(300, finish)


def finish():
    try:
        result["message_log"] = message_log()
    except Exception:
        result["errors"].append(traceback.format_exc())
    with open(os.environ["BIRDSEYE_PROBE_RESULT"], "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1)
    QgsApplication.instance().quit()


QTimer.singleShot(500, install)
"""


@pytest.mark.skipif(not QGIS_BIN.exists() or shutil.which("Xvfb") is None,
                    reason="needs Debian's qgis and xvfb (make setup installs them)")
def test_install_from_zip_in_the_desktop(package, tmp_path):
    """The real desktop, a fresh profile without BirdsEye, QGIS's own Install-from-ZIP code: the plugin
    lands in the profile's python/plugins, starts, registers every algorithm and adds its menu."""
    profiles = tmp_path / "profiles"
    ini = profiles / "profiles" / "default" / "QGIS" / "QGIS3.ini"
    ini.parent.mkdir(parents=True)
    ini.write_text("[PythonPlugins]\nprocessing=true\n\n[core]\nNewsFeed\\httpsfeedqgisorg\\disabled=true\n")
    probe = tmp_path / "install_probe.py"
    probe.write_text(INSTALL_PROBE, encoding="utf-8")
    report_path = tmp_path / "report.json"
    runtime_dir = tmp_path / "runtime"
    runtime_dir.mkdir(mode=0o700)
    env = {k: v for k, v in os.environ.items() if k not in {"QGIS_CUSTOM_CONFIG_PATH", "QGIS_PLUGINPATH",
                                                            "PYTHONPATH"}}
    with xvfb_display() as display:
        env.update(DISPLAY=display, QT_QPA_PLATFORM="xcb", XDG_RUNTIME_DIR=str(runtime_dir),
                   BIRDSEYE_ZIP=str(package), BIRDSEYE_PROBE_RESULT=str(report_path))
        qgis = subprocess.Popen([str(QGIS_BIN), "--nologo", "--noversioncheck", "--profiles-path", str(profiles),
                                 "--code", str(probe)], env=env, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)
        try:
            output, _ = qgis.communicate(timeout=120)
        except subprocess.TimeoutExpired:
            stuck = REPO_ROOT / "build" / "screenshots" / "install-from-zip-timeout.png"
            stuck.parent.mkdir(parents=True, exist_ok=True)
            grab_screen(display, stuck)
            qgis.kill()
            output, _ = qgis.communicate()
            pytest.fail(f"QGIS did not quit — a modal dialog of the installer? screen saved to {stuck}\n{output}")
    assert report_path.is_file(), f"the probe wrote no report (QGIS exit {qgis.returncode}):\n{output}"
    report = json.loads(report_path.read_text(encoding="utf-8"))
    assert report["errors"] == []
    assert report["loaded_before"] is False
    installed = Path(report["installed_to"])
    assert report["metadata_installed"] and installed.parent.parent.parent == profiles / "profiles" / "default"
    assert Path(report["module_file"]).resolve() == (installed / "__init__.py").resolve()
    assert report["loaded"] and report["active"] and report["enabled_in_profile"]
    assert report["algorithms"] == ALGORITHM_IDS
    assert "mBirdsEyeMenu" in report["menu"]
    log = report["message_log"]
    assert "Python error" not in log, log.get("Python error")
    assert "Traceback" not in output, output
