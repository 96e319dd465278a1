"""The screenshots of the README and the user guide (docs/images/), taken in the real QGIS desktop.

QGIS starts twice under its own Xvfb, each time with a fresh profile and QGIS's own Python only (none
of .venv's packages): once with the plugin zip (built here, as `make package` builds it) unpacked into
the profile, as Install from ZIP leaves it, and once without it, as before installing — what a new
user sees. A probe (``--code``) plays the steps the README describes and saves each picture:

- ``birdseye-menu.png``: the BirdsEye menu open, with the message bar about missing packages;
- ``install-dependencies.png``: BirdsEye › Install dependencies…, before installing;
- ``processing-toolbox.png``: the Processing Toolbox opened by BirdsEye › BirdsEye algorithms…;
- ``simulate-campaign-dialog.png``: Simulate a campaign, set up as the README's demo sets it;
- ``repository-details.png``: the Plugin Manager's Add… dialog for a plugin repository, filled in;
- ``plugin-manager-install-from-zip.png``, ``plugin-manager-settings.png`` and
  ``plugin-manager-all.png``: the Plugin Manager's *Install from ZIP* page, its *Settings* page with
  the repository added and experimental plugins shown, and BirdsEye found under *All*.

Run on this machine's QGIS, or on QGIS 3.40 LTR in the Debian 13 chroot (what users run)::

    .venv/bin/python scripts/user_guide_screenshots.py [--out docs/images]
    scripts/qgis_chroot.sh trixie /opt/birdseye-venv/bin/python scripts/user_guide_screenshots.py

Needs Debian's qgis and Xvfb (``make setup``). Nothing outside the output folder and a temporary folder
is written; the network is not used.
"""
from __future__ import annotations

import argparse
import importlib.util
import json
import os
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[1]
QGIS_BIN = Path("/usr/bin/qgis.bin")  # Debian's /usr/bin/qgis only adds $QGIS_OPTS from /etc/default
SCREEN = "1280x800x24"
# No news feed, no font downloads: the desktop stays offline (as in tests/gui/test_desktop.py).
OFFLINE_SETTINGS = "[core]\nNewsFeed\\httpsfeedqgisorg\\disabled=true\n\n[fonts]\ndownloadMissingFonts=false\n"

PROBE = r'''
import json, os, traceback
from qgis.core import QgsApplication, QgsSettings
from qgis.PyQt.QtCore import QPoint, QTimer
from qgis.PyQt.QtWidgets import QApplication, QDockWidget, QListWidget, QTreeView
from qgis.utils import iface

OUT = os.environ["BIRDSEYE_SHOTS"]
ZIP = os.environ["BIRDSEYE_ZIP"]
REPOSITORY_URL = os.environ["BIRDSEYE_REPOSITORY_URL"]
DEMO_FOLDER = os.environ["BIRDSEYE_DEMO_FOLDER"]
report = {"saved": [], "errors": []}
steps = []


def step(delay_ms, part):
    """Run ``fn`` ``delay_ms`` after the previous step, in the session ``part`` (BIRDSEYE_SHOTS_PART)."""
    def wrap(fn):
        if part == os.environ["BIRDSEYE_SHOTS_PART"]:
            steps.append((delay_ms, fn))
        return fn
    return wrap


def run_next():
    if not steps:
        finish()
        return
    delay, fn = steps.pop(0)

    def call():
        try:
            fn()
        except Exception:
            report["errors"].append(f"{fn.__name__}: {traceback.format_exc()}")
        run_next()
    QTimer.singleShot(delay, call)


def save(widget_or_pixmap, name):
    pixmap = widget_or_pixmap if hasattr(widget_or_pixmap, "save") else widget_or_pixmap.grab()
    path = os.path.join(OUT, name)
    if pixmap.save(path):
        report["saved"].append(name)
    else:
        report["errors"].append(f"could not save {path}")


def screen(x, y, w, h):
    return QApplication.primaryScreen().grabWindow(0, x, y, w, h)


def birdseye_menu():
    bar = iface.mainWindow().menuBar()
    return next(a for a in bar.actions() if a.menu() is not None and a.menu().objectName() == "mBirdsEyeMenu")


@step(2500, "plugin")
def menu_open():
    window = iface.mainWindow()  # Xvfb has no window manager to maximise it
    window.move(0, 0)
    window.resize(QApplication.primaryScreen().size())
    action = birdseye_menu()
    bar = iface.mainWindow().menuBar()
    rect = bar.actionGeometry(action)
    action.menu().popup(bar.mapToGlobal(QPoint(rect.left(), rect.bottom())))


@step(800, "plugin")
def menu_shot():
    menu = birdseye_menu().menu()
    top_left = iface.mainWindow().mapToGlobal(QPoint(0, 0))
    corner = menu.mapToGlobal(QPoint(menu.width(), menu.height()))
    width = max(corner.x() - top_left.x() + 280, 900)
    save(screen(top_left.x(), top_left.y(), min(width, 1280), max(corner.y() - top_left.y() + 40, 300)),
         "birdseye-menu.png")
    menu.hide()


@step(300, "plugin")
def dependencies():
    from birdseye.birdseye_qgis.gui.dependencies import DependenciesDialog
    dialog = DependenciesDialog(iface.mainWindow())
    dialog.resize(960, 560)
    dialog.show()
    QTimer.singleShot(600, lambda: (save(dialog, "install-dependencies.png"), dialog.close()))


@step(1200, "plugin")
def toolbox():
    menu = birdseye_menu().menu()
    next(a for a in menu.actions() if a.objectName() == "mActionBirdsEyeAlgorithms").trigger()


@step(800, "plugin")
def toolbox_shot():
    dock = next(d for d in iface.mainWindow().findChildren(QDockWidget) if d.objectName() == "ProcessingToolbox")
    for tree in dock.findChildren(QTreeView):
        tree.expandAll()
    dock.setFloating(True)
    dock.resize(440, 720)
    QTimer.singleShot(500, lambda: (save(dock, "processing-toolbox.png"), dock.setFloating(False)))


@step(1200, "plugin")
def simulate_dialog():
    import processing
    dialog = processing.createAlgorithmDialog("birdseye:simulatecampaign", {
        "N_TARGETS": 20, "FIELD_WIDTH_M": 8, "FIELD_LENGTH_M": 6, "OUTPUT_FOLDER": DEMO_FOLDER})
    dialog.resize(1060, 760)
    dialog.show()
    QTimer.singleShot(1000, lambda: (save(dialog, "simulate-campaign-dialog.png"), dialog.close()))


@step(2500, "manager")
def repository():
    # Plugins > Manage and Install Plugins > Settings > Add…: the installer's addRepository() and its dialog.
    import pyplugin_installer
    from pyplugin_installer import installer_data
    name, url = installer_data.officialRepo
    settings = QgsSettings()  # offline: the official repository stays disabled
    settings.setValue(f"{installer_data.reposGroup}/{name}/url", url)
    settings.setValue(f"{installer_data.reposGroup}/{name}/enabled", False)
    installer_data.repositories.load()

    def fill():
        try:
            dialog = QApplication.activeModalWidget()
            dialog.editName.setText("BirdsEye")
            dialog.editURL.setText(REPOSITORY_URL)
            save(dialog, "repository-details.png")
            dialog.accept()
        except Exception:
            report["errors"].append("repository dialog: " + traceback.format_exc())
            QApplication.activeModalWidget().reject()
    QTimer.singleShot(600, fill)
    pyplugin_installer.instance().addRepository()


def on_plugin_manager(what):
    """A step inside the Plugin Manager, run from a timer: an exception is recorded under ``what`` and the modal
    window closed, so the desktop never waits for a click."""
    def wrap(fn):
        def run(*args):
            try:
                fn(*args)
            except Exception:
                report["errors"].append(f"{what}: " + traceback.format_exc())
                close_modal()
        return run
    return wrap


@step(500, "manager")
def plugin_manager():
    @on_plugin_manager("plugin manager")
    def pages():
        manager = next(w for w in QApplication.topLevelWidgets()
                       if w.metaObject().className() == "QgsPluginManager" and w.isVisible())
        manager.resize(1000, 640)
        items = manager.findChild(QListWidget, "mOptionsListWidget")
        by_text = {items.item(i).text(): i for i in range(items.count())}
        report["plugin_manager_pages"] = list(by_text)
        items.setCurrentRow(by_text["Install from ZIP"])
        from qgis.gui import QgsFileWidget
        for widget in manager.findChildren(QgsFileWidget):
            if widget.isVisible():
                widget.setFilePath(ZIP)
        QTimer.singleShot(500, lambda: settings_page(manager, items, by_text))

    @on_plugin_manager("plugin manager settings")
    def settings_page(manager, items, by_text):
        save(manager, "plugin-manager-install-from-zip.png")
        items.setCurrentRow(by_text["Settings"])
        from qgis.PyQt.QtWidgets import QCheckBox, QGroupBox
        for box in manager.findChildren(QCheckBox):  # README step: show experimental plugins (3.22)
            if "experimental" in box.text().lower():
                box.setChecked(True)
        for box in manager.findChildren(QGroupBox):  # a checkable group box in 3.40
            if box.isCheckable() and "experimental" in box.title().lower():
                box.setChecked(True)
        QTimer.singleShot(800, lambda: all_page(manager, items, by_text))

    @on_plugin_manager("plugin manager all")
    def all_page(manager, items, by_text):
        save(manager, "plugin-manager-settings.png")
        items.setCurrentRow(by_text["All"])
        from qgis.PyQt.QtWidgets import QLineEdit, QListView
        manager.findChild(QLineEdit, "leFilter").setText("BirdsEye")
        view = manager.findChild(QListView, "vwPlugins")
        view.setCurrentIndex(view.model().index(0, 0))
        QTimer.singleShot(1500, lambda: (save(manager, "plugin-manager-all.png"), manager.close()))

    QTimer.singleShot(2500, pages)
    iface.actionManagePlugins().trigger()


def close_modal():
    widget = QApplication.activeModalWidget()
    if widget is not None:
        widget.close()


@step(2500, "plugin")
def plugin_done():
    pass


@step(6000, "manager")
def manager_done():
    pass


def finish():
    with open(os.path.join(OUT, f".report-{os.environ['BIRDSEYE_SHOTS_PART']}.json"), "w", encoding="utf-8") as f:
        json.dump(report, f, indent=1)
    QgsApplication.instance().quit()


run_next()
'''


def start_xvfb() -> tuple[subprocess.Popen, str]:
    """A private X server; Xvfb picks a free display number itself and reports it (-displayfd)."""
    read_end, write_end = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write_end), "-screen", "0", SCREEN, "-nolisten", "tcp"],
                              pass_fds=(write_end,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write_end)
    with os.fdopen(read_end) as reader:
        number = reader.readline().strip()
    if not number:
        server.kill()
        sys.exit("user_guide_screenshots: Xvfb did not start")
    return server, f":{number}"


def run_session(part: str, tmp: Path, archive: Path, env: dict[str, str], out: Path) -> list[str]:
    """One QGIS session in its own fresh profile: ``plugin`` with BirdsEye unpacked from the zip, as
    Install from ZIP leaves it; ``manager`` without it, as before installing. Returns the errors."""
    profile = tmp / part / "profiles" / "default"
    (profile / "python" / "plugins").mkdir(parents=True)
    enabled = "processing=true\n"
    if part == "plugin":
        with zipfile.ZipFile(archive) as zf:
            zf.extractall(profile / "python" / "plugins")
        enabled = "birdseye=true\n" + enabled
    (profile / "QGIS").mkdir()
    (profile / "QGIS" / "QGIS3.ini").write_text("[PythonPlugins]\n" + enabled + "\n" + OFFLINE_SETTINGS,
                                                encoding="utf-8")
    server, display = start_xvfb()
    try:
        result = subprocess.run([str(QGIS_BIN), "--nologo", "--noversioncheck", "--profiles-path", str(tmp / part),
                                 "--code", str(tmp / "probe.py")],
                                env={**env, "DISPLAY": display, "BIRDSEYE_SHOTS_PART": part},
                                capture_output=True, text=True, timeout=240, check=False)
    finally:
        server.terminate()
        server.wait(timeout=10)
    report_path = out / f".report-{part}.json"
    if not report_path.is_file():
        return [f"{part}: QGIS wrote no report (exit {result.returncode}):\n{result.stdout}"]
    report = json.loads(report_path.read_text(encoding="utf-8"))
    report_path.unlink()
    for name in report["saved"]:
        print(out / name)
    return report["errors"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=REPO_ROOT / "docs" / "images", help="output folder")
    args = parser.parse_args()
    if not QGIS_BIN.exists():
        sys.exit(f"user_guide_screenshots: {QGIS_BIN} not found (make setup installs Debian's qgis)")
    spec = importlib.util.spec_from_file_location("birdseye_package_script", REPO_ROOT / "scripts" / "package.py")
    package = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(package)
    out = args.out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="birdseye-shots-") as tmp_name:
        tmp = Path(tmp_name)
        archive = package.build(tmp / "dist")
        repository = package.write_repository_file(archive)
        (tmp / "probe.py").write_text(PROBE, encoding="utf-8")
        runtime = tmp / "runtime"
        runtime.mkdir(mode=0o700)
        downloads = tmp / "Downloads"  # where the README's user keeps the zip: shown in Install from ZIP
        downloads.mkdir()
        (downloads / archive.name).write_bytes(archive.read_bytes())
        # QGIS's own Python only, as on a user's machine: none of .venv's packages.
        env = {k: v for k, v in os.environ.items() if k not in {"QGIS_CUSTOM_CONFIG_PATH", "QGIS_PLUGINPATH",
                                                                "PYTHONPATH"}}
        env.update(QT_QPA_PLATFORM="xcb", XDG_RUNTIME_DIR=str(runtime), BIRDSEYE_SHOTS=str(out),
                   BIRDSEYE_ZIP=str(downloads / archive.name),
                   BIRDSEYE_REPOSITORY_URL=repository.resolve().as_uri(),
                   BIRDSEYE_DEMO_FOLDER=str(Path.home() / "Documents" / "birdseye-demo"))
        errors = run_session("plugin", tmp, archive, env, out) + run_session("manager", tmp, archive, env, out)
    if errors:
        sys.exit("user_guide_screenshots: some pictures failed:\n" + "\n".join(errors))


if __name__ == "__main__":
    main()
