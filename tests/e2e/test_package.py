"""`make package`: the zip a user installs with "Install from ZIP", checked as plugins.qgis.org would,
then installed into a fresh QGIS profile — by QGIS's own Install-from-ZIP code in the real desktop, and
by unzipping for ``qgis_process`` — and loaded from there; and the plugin repository file beside it
(plugins.xml), checked against the zip and then added, read and installed from by QGIS's own plugin
installer in the real desktop, as a user does in the Plugin Manager.

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
from test_desktop import OFFLINE_SETTINGS, PROBE_DIR, QGIS_BIN, grab_screen, xvfb_display  # noqa: E402  (the desktop test's X helpers)

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
    archive = REPO_ROOT / "build" / f"birdseye.{metadata['general']['version']}.zip"
    assert archive.is_file(), f"make package did not write {archive}"
    return archive


@pytest.fixture(scope="module")
def repository_file(package) -> Path:
    """build/plugins.xml, written by the same `make package` beside the zip."""
    path = package.parent / "plugins.xml"
    assert path.is_file(), f"make package did not write {path}"
    return path


@pytest.fixture(scope="module")
def names(package) -> list[str]:
    with zipfile.ZipFile(package) as zf:
        assert zf.testzip() is None, "corrupt member"
        return zf.namelist()


def test_one_top_folder_named_birdseye(names):
    assert {name.split("/")[0] for name in names} == {"birdseye"}
    for required in ("__init__.py", "metadata.txt", "LICENSE", "README.md", "requirements.txt",
                     "birdseye_qgis/gui/plugin.py",
                     "processing/provider.py", "resources/icons/birdseye.svg"):
        assert f"birdseye/{required}" in names


def test_no_tests_dev_files_or_caches(names, package):
    offending = [n for n in names
                 if DEV_ONLY & set(n.split("/")[1:-1]) or n.endswith((".pyc", ".pyo"))
                 or any(part.startswith(".") for part in n.split("/"))
                 or n.count("/") == 1 and n.split("/")[1] not in
                 {"__init__.py", "metadata.txt", "LICENSE", "README.md", "requirements.txt"}]
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


# ------------------------------------------------------------------------------ the plugin repository file
def _metadata() -> configparser.SectionProxy:
    parser = configparser.ConfigParser(interpolation=None)
    parser.optionxform = str
    parser.read(REPO_ROOT / "metadata.txt", encoding="utf-8")
    return parser["general"]


def test_repository_file_describes_the_zip(package, repository_file):
    """plugins.xml in the format QGIS's installer reads: one <pyqgis_plugin> whose name, version, QGIS range,
    file name and download URL are metadata.txt's and the zip's; the plugin id QGIS derives from the file
    name (up to the first dot) is the zip's folder."""
    general = _metadata()
    root = ET.parse(repository_file).getroot()
    assert root.tag == "plugins"
    (plugin,) = root.findall("pyqgis_plugin")
    text = {child.tag: (child.text or "").strip() for child in plugin}
    assert plugin.get("name") == general["name"] == "BirdsEye"
    assert plugin.get("version") == text["version"] == general["version"]
    assert text["qgis_minimum_version"] == general["qgisMinimumVersion"]
    assert text["qgis_maximum_version"] == general["qgisMaximumVersion"]
    assert text["file_name"] == package.name
    assert text["file_name"].partition(".")[0] == "birdseye"  # QGIS's plugin id: the zip's one top folder
    assert text["download_url"] == package.resolve().as_uri()  # no base URL given: the zip where it lies
    assert text["experimental"] == ("True" if general["experimental"].lower() == "true" else "False")
    assert text["deprecated"] == "False"
    for tag, key in (("description", "description"), ("about", "about"), ("author_name", "author"),
                     ("homepage", "homepage"), ("tracker", "tracker"), ("repository", "repository"),
                     ("tags", "tags"), ("category", "category")):
        assert text[tag] == general[key].strip(), tag
    assert package_script.repository_file_problems(repository_file, package) == []


def test_repository_file_for_a_web_folder(package, tmp_path):
    """--base-url (make package PLUGIN_BASE_URL=…): the download URL is that folder + the zip's name."""
    result = subprocess.run(["/usr/bin/python3", str(REPO_ROOT / "scripts" / "package.py"), "--out", str(tmp_path),
                             "--base-url", "https://example.org/lab/qgis"], capture_output=True, text=True,
                            timeout=120, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    xml = tmp_path / "plugins.xml"
    assert ET.parse(xml).getroot().findtext("pyqgis_plugin/download_url") == \
        f"https://example.org/lab/qgis/{package.name}"
    assert package_script.repository_file_problems(xml, tmp_path / package.name) == []


REPOSITORY_EDITS = {
    "wrong_version": (lambda t: t.replace('version="', 'version="9', 1), "version"),
    "id_from_a_dashed_name": (lambda t: re.sub(r"<file_name>birdseye\.", "<file_name>birdseye-", t),
                              "plugin 'birdseye-"),
    "relative_download_url": (lambda t: re.sub(r"<download_url>[^<]*/", "<download_url>", t), "download_url"),
    "wrong_maximum": (lambda t: re.sub(r"<qgis_maximum_version>[^<]*<", "<qgis_maximum_version>3.99<", t),
                      "qgis_maximum_version"),
    "not_xml": (lambda t: t.replace("</plugins>", ""), "not well-formed"),
}


@pytest.mark.parametrize("case", sorted(REPOSITORY_EDITS))
def test_repository_check_finds_a_mismatch(package, repository_file, tmp_path, case):
    edit, expected = REPOSITORY_EDITS[case]
    broken = tmp_path / "plugins.xml"
    broken.write_text(edit(repository_file.read_text(encoding="utf-8")), encoding="utf-8")
    problems = package_script.repository_file_problems(broken, package)
    assert problems and any(expected in p for p in problems), problems


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
#: What both install probes record once QGIS's installer is done: where BirdsEye went, whether it loaded and is
#: active and enabled in the profile, which module runs, its algorithms and menu.
INSTALLED_PLUGIN_FACTS = r"""
import json, os, sys, traceback
from qgis.core import QgsApplication, QgsSettings
from qgis.PyQt.QtCore import QTimer
import qgis.utils
from qgis.utils import active_plugins, iface, plugins

result = {"errors": []}


def record_installed():
    # QGIS 3.22 sets qgis.utils.home_plugin_path; later releases renamed it HOME_PLUGIN_PATH.
    home_plugin_path = getattr(qgis.utils, "HOME_PLUGIN_PATH", None) or qgis.utils.home_plugin_path
    result["installed_to"] = os.path.join(home_plugin_path, "birdseye")
    result["metadata_installed"] = os.path.isfile(os.path.join(home_plugin_path, "birdseye", "metadata.txt"))
    result["loaded"] = "birdseye" in plugins
    result["active"] = "birdseye" in active_plugins
    result["enabled_in_profile"] = QgsSettings().value("PythonPlugins/birdseye", False, bool)
    result["module_file"] = sys.modules["birdseye"].__file__
    provider = QgsApplication.processingRegistry().providerById("birdseye")
    result["algorithms"] = sorted(a.id() for a in provider.algorithms()) if provider else None
    result["menu"] = [a.menu().objectName() for a in iface.mainWindow().menuBar().actions() if a.menu()]
"""

INSTALL_PROBE = INSTALLED_PLUGIN_FACTS + r"""
sys.path.insert(0, os.environ["BIRDSEYE_PROBE_DIR"])
from probe_session import message_log  # noqa: E402


def install():
    try:
        import pyplugin_installer
        result["loaded_before"] = "birdseye" in plugins
        # What Plugins > Manage and Install Plugins > Install from ZIP runs on "Install Plugin".
        pyplugin_installer.instance().installFromZipFile(os.environ["BIRDSEYE_ZIP"])
        record_installed()
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
    profiles, probe, env = fresh_profile(tmp_path, "install_probe.py", INSTALL_PROBE)
    report, output = run_desktop_probe(profiles, probe, {**env, "BIRDSEYE_ZIP": str(package)}, tmp_path, 120,
                               "install-from-zip-timeout.png")
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


# ------------------------------------------------------------------------------ from the plugin repository, for real
REPOSITORY_NAME = "BirdsEye"
REPOSITORY_SCREENSHOT = REPO_ROOT / "build" / "screenshots" / "plugin-repository-details.png"

REPOSITORY_PROBE = INSTALLED_PLUGIN_FACTS + r"""
from qgis.PyQt.QtWidgets import QApplication
NAME = os.environ["BIRDSEYE_REPOSITORY_NAME"]
URL = os.environ["BIRDSEYE_REPOSITORY_URL"]


def add_repository():
    # Plugins > Manage and Install Plugins > Settings > Add…: the button runs the installer's addRepository(),
    # which asks for a name and URL, saves them and reloads every enabled repository.
    try:
        import pyplugin_installer
        from pyplugin_installer import installer_data
        official_name, official_url = installer_data.officialRepo
        settings = QgsSettings()  # offline: the official repository is left disabled, so only ours is read
        settings.setValue(f"{installer_data.reposGroup}/{official_name}/url", official_url)
        settings.setValue(f"{installer_data.reposGroup}/{official_name}/enabled", False)
        installer_data.repositories.load()
        result["loaded_before"] = "birdseye" in plugins
        QTimer.singleShot(300, fill_in)
        pyplugin_installer.instance().addRepository()
        repository = installer_data.repositories.all().get(NAME)
        result["repository"] = None if repository is None else {
            "url": repository["url"], "state": repository["state"], "error": repository["error"]}
        result["listed"] = [{k: p[k] for k in ("id", "name", "version_available", "experimental", "filename",
                                               "download_url")}
                            for p in installer_data.plugins.repoCache.get(NAME, [])]
        # "Show also experimental plugins" (Settings page): metadata.txt says experimental=True.
        allow_experimental(settings, installer_data)
        installer_data.plugins.rebuild()
        entry = installer_data.plugins.all().get("birdseye", {})
        result["entry"] = {k: entry.get(k) for k in ("status_exp", "version_available_experimental",
                                                    "download_url_experimental", "zip_repository")}
        # "Install Experimental Plugin" on the plugin's page runs installPlugin(key, stable=False).
        pyplugin_installer.instance().installPlugin("birdseye", stable=False)
        record_installed()
    except Exception:
        result["errors"].append(traceback.format_exc())
    with open(os.environ["BIRDSEYE_PROBE_RESULT"], "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1)
    QgsApplication.instance().quit()


def allow_experimental(settings, installer_data):
    # Where the installer reads the setting: QgsSettings under its settings group (QGIS 3.22), or the
    # settings tree's plugin-manager/allow-experimental (later releases); both are set.
    settings.setValue(getattr(installer_data, "settingsGroup", "app/plugin_installer") + "/allowExperimental", True)
    try:
        from qgis.core import QgsSettingsTree
    except ImportError:
        return
    find = getattr(QgsSettingsTree, "nodeCopy", None) or getattr(QgsSettingsTree, "node", None)
    node = find("plugin-manager") if find is not None else None
    setting = node.childSetting("allow-experimental") if node is not None else None
    if setting is not None:
        setting.setValue(True)


def fill_in():
    try:
        dialog = QApplication.activeModalWidget()
        result["dialog_title"] = dialog.windowTitle()
        dialog.editName.setText(NAME)
        dialog.editURL.setText(URL)
        dialog.grab().save(os.environ["BIRDSEYE_SCREENSHOT"])
        dialog.accept()
    except Exception:
        result["errors"].append(traceback.format_exc())
        QApplication.activeModalWidget().reject()


QTimer.singleShot(500, add_repository)
"""


@pytest.mark.skipif(not QGIS_BIN.exists() or shutil.which("Xvfb") is None,
                    reason="needs Debian's qgis and xvfb (make setup installs them)")
def test_install_from_the_plugin_repository_in_the_desktop(package, repository_file, tmp_path):
    """The real desktop, a fresh profile without BirdsEye, QGIS's own plugin installer: the repository file is
    added by its file:// URL in the Add-repository dialog, read (one plugin, BirdsEye, at the zip's version),
    and the plugin installed from it — downloaded from its download_url — starts, registers every algorithm
    and adds its menu."""
    profiles, probe, env = fresh_profile(tmp_path, "repository_probe.py", REPOSITORY_PROBE)
    REPOSITORY_SCREENSHOT.parent.mkdir(parents=True, exist_ok=True)
    report, output = run_desktop_probe(profiles, probe, {**env, "BIRDSEYE_REPOSITORY_NAME": REPOSITORY_NAME,
                                                         "BIRDSEYE_REPOSITORY_URL": repository_file.resolve().as_uri(),
                                                         "BIRDSEYE_SCREENSHOT": str(REPOSITORY_SCREENSHOT)},
                                       tmp_path, 120, "plugin-repository-timeout.png")
    assert report["errors"] == []
    assert report["loaded_before"] is False
    assert report["dialog_title"] == "Repository details"
    repository = report["repository"]
    assert repository is not None and repository["url"] == repository_file.resolve().as_uri()
    assert (repository["state"], repository["error"]) == (2, ""), repository  # 2: Repositories.STATE_LOADED
    version = _metadata()["version"]
    assert report["listed"] == [{"id": "birdseye", "name": "BirdsEye", "version_available": version,
                                 "experimental": True, "filename": package.name,
                                 "download_url": package.resolve().as_uri()}]
    assert report["entry"] == {"status_exp": "not installed", "version_available_experimental": version,
                               "download_url_experimental": package.resolve().as_uri(),
                               "zip_repository": REPOSITORY_NAME}
    installed = Path(report["installed_to"])
    assert installed.parent.parent.parent == profiles / "profiles" / "default"
    assert (installed / "metadata.txt").is_file()
    assert Path(report["module_file"]).resolve() == (installed / "__init__.py").resolve()
    assert report["loaded"] and report["active"] and report["enabled_in_profile"]
    assert report["algorithms"] == ALGORITHM_IDS
    assert "mBirdsEyeMenu" in report["menu"]
    assert "Traceback" not in output, output


# ------------------------------------------------------------------------------ dependencies from the plugin
DETECT_PACKAGES = ("onnxruntime", "opencv-python-headless")  # what birdseye:detect needs on every run
BARE_PYTHON = "/usr/bin/python3"  # the Python Debian's QGIS embeds, here without .venv's packages
WHEELHOUSE = REPO_ROOT / "build" / "wheelhouse" / f"cp{sys.version_info[0]}{sys.version_info[1]}"
DEPENDENCIES_SCREENSHOT = REPO_ROOT / "build" / "screenshots" / "install-dependencies.png"

DEPENDENCIES_PROBE = r"""
import json, os, traceback
from qgis.core import QgsApplication
from qgis.PyQt.QtCore import Qt, QTimer
from qgis.PyQt.QtWidgets import QApplication
from qgis.utils import iface

result = {"errors": []}
wanted = set(os.environ["BIRDSEYE_WANTED"].split(","))


def rows(dialog):
    table = dialog.table
    return [[table.topLevelItem(r).text(c) for c in range(4)] for r in range(table.topLevelItemCount())]


def open_dialog():
    # What the user does: BirdsEye > Install dependencies... (the dialog is modal; drive() runs inside it).
    try:
        menu = next(a.menu() for a in iface.mainWindow().menuBar().actions()
                    if a.menu() is not None and a.menu().objectName() == "mBirdsEyeMenu")
        action = next(a for a in menu.actions() if a.objectName() == "mActionBirdsEyeDependencies")
        result["menu_text"] = action.text()
        QTimer.singleShot(300, drive)
        action.trigger()
    except Exception:
        result["errors"].append(traceback.format_exc())
    with open(os.environ["BIRDSEYE_PROBE_RESULT"], "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1)
    QgsApplication.instance().quit()


def drive():
    try:
        dialog = QApplication.activeModalWidget()
        result["dialog"] = dialog.objectName()
        result["rows_before"] = rows(dialog)
        for r in range(dialog.table.topLevelItemCount()):  # keep the download small: only detect's packages
            item = dialog.table.topLevelItem(r)
            if item.flags() & Qt.ItemFlag.ItemIsUserCheckable:
                item.setCheckState(0, Qt.CheckState.Checked if item.text(0) in wanted else Qt.CheckState.Unchecked)
        result["ticked"] = [p.distribution for p in dialog.checked_packages()]
        dialog.install_button.click()
        QTimer.singleShot(500, lambda: wait(dialog))
    except Exception:
        result["errors"].append(traceback.format_exc())
        QApplication.activeModalWidget().reject()


def wait(dialog):
    if dialog.is_running():
        QTimer.singleShot(500, lambda: wait(dialog))
        return
    result.update(status=dialog.status.text(), progress=dialog.progress.value(), log=dialog.log.toPlainText(),
                  rows_after=rows(dialog), folder=str(dialog.folder))
    dialog.log_button.setChecked(True)
    dialog.grab().save(os.environ["BIRDSEYE_SCREENSHOT"])
    dialog.reject()


QTimer.singleShot(500, open_dialog)
"""


def bare_qgis_env(config: Path, tmp_path: Path, **extra: str) -> dict[str, str]:
    """qgis_process.sh with the profile in ``config``, QGIS's own Python and nothing of .venv, and pip
    pointed at the local wheel folder only (no index, no pip.conf)."""
    nowhere = tmp_path / "no-extra-plugins"
    nowhere.mkdir(exist_ok=True)
    env = {k: v for k, v in os.environ.items()
           if k not in {"QGIS_CUSTOM_CONFIG_PATH", "QGIS_PLUGINPATH", "PYTHONPATH"} and not k.startswith("PIP_")}
    env.update(BIRDSEYE_QGIS_CONFIG=str(config), BIRDSEYE_PLUGIN_PATH=str(nowhere), BIRDSEYE_VENV="",
               PIP_CONFIG_FILE=os.devnull, PIP_NO_INDEX="1", PIP_FIND_LINKS=str(WHEELHOUSE), **extra)
    return env


def run_bare(env: dict[str, str], *args: str, timeout: float = 300) -> subprocess.CompletedProcess:
    return subprocess.run([str(REPO_ROOT / "scripts" / "qgis_process.sh"), "--json", "run", *args], env=env,
                          capture_output=True, text=True, timeout=timeout, check=False)


@pytest.fixture(scope="module")
def wheelhouse() -> Path:
    """detect's packages and what they need beyond QGIS's Python, as wheels in build/wheelhouse.

    The list comes from pip's own resolution in the bare Python, with its numpy held as the installer
    holds QGIS's (the newest OpenCV wants numpy 2); the wheels are downloaded once from the package index
    and kept for later runs."""
    from birdseye.birdseye_qgis.dependencies import read_requirements

    pins = [p.requirement for p in read_requirements() if p.distribution in DETECT_PACKAGES]
    WHEELHOUSE.mkdir(parents=True, exist_ok=True)
    report = WHEELHOUSE / "plan.json"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    numpy = subprocess.run([BARE_PYTHON, "-c", "import numpy; print(numpy.__version__)"], env=env,
                           capture_output=True, text=True, check=True).stdout.strip()
    held = WHEELHOUSE / "qgis-numpy.txt"
    held.write_text(f"numpy=={numpy}\n", encoding="utf-8")
    resolved = subprocess.run([BARE_PYTHON, "-m", "pip", "install", "--dry-run", "--quiet", "--only-binary=:all:",
                               "--report", str(report), "-c", str(held), *pins], env=env, capture_output=True,
                              text=True, timeout=600, check=False)
    assert resolved.returncode == 0, f"pip could not resolve {pins} for {BARE_PYTHON}:\n{resolved.stderr}"
    plan = [f"{i['metadata']['name']}=={i['metadata']['version']}"
            for i in json.loads(report.read_text(encoding="utf-8"))["install"]]
    fetched = subprocess.run([BARE_PYTHON, "-m", "pip", "download", "--quiet", "--no-deps", "--only-binary=:all:",
                              "--dest", str(WHEELHOUSE), *plan], env=env, capture_output=True, text=True,
                             timeout=1200, check=False)
    assert fetched.returncode == 0, f"pip could not download {plan}:\n{fetched.stderr}"
    return WHEELHOUSE


@pytest.mark.skipif(not QGIS_BIN.exists() or shutil.which("Xvfb") is None,
                    reason="needs Debian's qgis and xvfb (make setup installs them)")
def test_installer_brings_a_bare_profile_to_a_working_detect(package, wheelhouse, tmp_path):
    """A fresh profile whose Python lacks the packages: the algorithms say what to install; BirdsEye ›
    Install dependencies… in the real desktop installs detect's packages from the local wheel folder
    (QGIS's own Python and pip, numpy left to QGIS); then a simulated flight goes through
    simulatecampaign, importflightlog and detect in that profile, with no other Python packages."""
    missing = subprocess.run([BARE_PYTHON, "-c", "import importlib.util as u, sys; "
                              "print([m for m in sys.argv[1:] if u.find_spec(m)])", "onnxruntime", "cv2"],
                             env={k: v for k, v in os.environ.items() if k != "PYTHONPATH"},
                             capture_output=True, text=True, check=True)
    if missing.stdout.strip() != "[]":
        pytest.skip(f"{BARE_PYTHON} itself has {missing.stdout.strip()}: no bare Python to start from")
    profiles = tmp_path / "profiles"
    profile = profiles / "profiles" / "default"
    (profile / "python" / "plugins").mkdir(parents=True)
    with zipfile.ZipFile(package) as zf:
        zf.extractall(profile / "python" / "plugins")
    ini = profile / "QGIS" / "QGIS3.ini"
    ini.parent.mkdir(parents=True)
    ini.write_text("[PythonPlugins]\nbirdseye=true\nprocessing=true\n\n" + OFFLINE_SETTINGS)
    env = bare_qgis_env(profiles, tmp_path)
    campaign = tmp_path / "campaign"
    simulate = ["birdseye:simulatecampaign", "--", "SEED=7", f"OUTPUT_FOLDER={campaign}", "N_TARGETS=3",
                "IMAGE_WIDTH=320", "IMAGE_HEIGHT=200", "FIELD_WIDTH_M=6", "FIELD_LENGTH_M=4"]

    refused = run_bare(env, *simulate)
    assert refused.returncode != 0
    assert ("This algorithm needs the Python package(s) opencv-python-headless, which the Python QGIS runs "
            "does not have. In QGIS, choose BirdsEye › Install dependencies…") in refused.stdout + refused.stderr

    DEPENDENCIES_SCREENSHOT.parent.mkdir(parents=True, exist_ok=True)
    DEPENDENCIES_SCREENSHOT.unlink(missing_ok=True)
    probe = tmp_path / "dependencies_probe.py"
    probe.write_text(DEPENDENCIES_PROBE, encoding="utf-8")
    report, _ = run_desktop_probe(profiles, probe, {**env, "BIRDSEYE_WANTED": ",".join(DETECT_PACKAGES),
                                                 "BIRDSEYE_SCREENSHOT": str(DEPENDENCIES_SCREENSHOT)},
                               tmp_path, 600, "install-dependencies-timeout.png")
    assert report["errors"] == [], report["errors"]
    assert report["menu_text"] == "Install dependencies…" and report["dialog"] == "BirdsEyeDependenciesDialog"
    states = {row[0]: row[2] for row in report["rows_before"]}
    assert states["onnxruntime"] == states["opencv-python-headless"] == "missing"
    assert report["ticked"] == list(DETECT_PACKAGES)
    assert report["status"].startswith("Installed: "), report["log"]
    assert report["progress"] == 100 and DEPENDENCIES_SCREENSHOT.is_file()
    after = {row[0]: row[2] for row in report["rows_after"]}
    assert after["onnxruntime"].startswith("installed by BirdsEye (") and \
        after["opencv-python-headless"].startswith("installed by BirdsEye (")
    folder = Path(report["folder"])
    assert folder == profile / "python" / "birdseye-dependencies" / f"python{sys.version_info[0]}.{sys.version_info[1]}"
    assert (folder / "onnxruntime").is_dir() and (folder / "cv2").is_dir()
    assert not (folder / "numpy").exists(), "QGIS's numpy is used, never a second copy"
    assert f"Looking in links: {WHEELHOUSE}" in report["log"] and "Successfully installed" in report["log"]

    simulated = run_bare(env, *simulate)
    assert simulated.returncode == 0, simulated.stderr
    results = json.loads(simulated.stdout)["results"]
    imported = run_bare(env, "birdseye:importflightlog", "--", f"POSE_LOG={results['POSES']}",
                        f"IMAGES={campaign}", f"CALIBRATION={results['CALIBRATION']}",
                        f"OUTPUT={tmp_path / 'frames.gpkg'}")
    assert imported.returncode == 0, imported.stderr
    detected = run_bare(env, "birdseye:detect", "--", f"FRAMES={tmp_path / 'frames.gpkg'}",
                        f"OUTPUT={tmp_path / 'detections.gpkg'}")
    assert detected.returncode == 0, detected.stderr
    detections = json.loads(detected.stdout)["results"]
    assert detections["FRAMES_PROCESSED"] == results["FRAME_COUNT"] > 0
    assert detections["DETECTION_COUNT"] > 0 and (tmp_path / "detections.gpkg").is_file()


def fresh_profile(tmp_path, probe_name: str, probe_text: str):
    """(a profiles folder whose default profile has only Processing enabled and QGIS kept offline, the probe
    script written beside it, the environment without this checkout's plugin path): QGIS as a user without
    BirdsEye starts it."""
    profiles = tmp_path / "profiles"
    ini = profiles / "profiles" / "default" / "QGIS" / "QGIS3.ini"
    ini.parent.mkdir(parents=True)
    ini.write_text("[PythonPlugins]\nprocessing=true\n\n" + OFFLINE_SETTINGS)
    probe = tmp_path / probe_name
    probe.write_text(probe_text, encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if k not in {"QGIS_CUSTOM_CONFIG_PATH", "QGIS_PLUGINPATH",
                                                            "PYTHONPATH"}}
    return profiles, probe, env


def run_desktop_probe(profiles, probe, env, tmp_path, timeout_s, stuck_png):
    """Run the real desktop under Xvfb with ``probe`` (``--code``) in the given profiles folder and return
    the JSON report the probe writes and the desktop's console output; a desktop that does not quit leaves a
    screenshot named ``stuck_png``."""
    report_path = tmp_path / "report.json"
    runtime_dir = tmp_path / "runtime"
    runtime_dir.mkdir(mode=0o700)
    with xvfb_display() as display:
        desktop_env = {**env, "DISPLAY": display, "QT_QPA_PLATFORM": "xcb", "XDG_RUNTIME_DIR": str(runtime_dir),
                       "BIRDSEYE_PROBE_RESULT": str(report_path), "BIRDSEYE_PROBE_DIR": str(PROBE_DIR)}
        qgis = subprocess.Popen([str(QGIS_BIN), "--nologo", "--noversioncheck", "--profiles-path", str(profiles),
                                 "--code", str(probe)], env=desktop_env, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True)
        try:
            output, _ = qgis.communicate(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            stuck = REPO_ROOT / "build" / "screenshots" / stuck_png
            stuck.parent.mkdir(parents=True, exist_ok=True)
            grab_screen(display, stuck)
            qgis.kill()
            output, _ = qgis.communicate()
            pytest.fail(f"QGIS did not quit — a modal dialog? screen saved to {stuck}\n{output}")
    assert report_path.is_file(), f"the probe wrote no report (QGIS exit {qgis.returncode}):\n{output}"
    return json.loads(report_path.read_text(encoding="utf-8")), output
