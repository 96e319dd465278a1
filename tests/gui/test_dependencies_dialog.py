"""BirdsEye › Install dependencies…, headless (pytest-qgis iface, qtbot).

What the user sees — the packages, their state, the algorithms that need them, what is ticked — and
what follows a press of Install: pip (this Python's, for real, offline against a folder of tiny wheels)
installs into the package folder, the progress bar fills, the packages import at once; on failure the
log opens with pip's message; Cancel stops pip and installs nothing. The plugin's menu action and its
start-up notice open the dialog, and an algorithm refuses to run while a package it needs is missing.
"""
from __future__ import annotations

import importlib
import re
import sys
from pathlib import Path

import pytest
from qgis.core import QgsProcessingException, QgsVectorLayer
from qgis.PyQt.QtCore import Qt
from qgis.PyQt.QtWidgets import QPushButton

from birdseye.birdseye_qgis import dependencies as deps
from birdseye.birdseye_qgis.gui import dependencies as dialog_module
from birdseye.birdseye_qgis.gui import plugin as plugin_module

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from fake_wheels import make_wheel, offline_pip  # noqa: E402

REPO_ROOT = Path(__file__).resolve().parents[2]
SCREENSHOT = REPO_ROOT / "build" / "screenshots" / "dependencies_dialog.png"


def package(name: str, specifier: str, always=(), sometimes=(), available=True) -> deps.RuntimePackage:
    return deps.RuntimePackage(name, specifier, deps.Use(name, tuple(always), tuple(sometimes)), available)


@pytest.fixture
def clean_path(monkeypatch):
    monkeypatch.setattr(sys, "path", list(sys.path))
    yield
    for name in [n for n in sys.modules if n.startswith("birdseyefake")]:
        del sys.modules[name]
    importlib.invalidate_caches()


@pytest.fixture
def wheelhouse(tmp_path, monkeypatch):
    house = tmp_path / "wheelhouse"
    house.mkdir()
    make_wheel(house, "birdseyefake_app", "1.0", ("birdseyefake_lib>=2",))
    make_wheel(house, "birdseyefake_lib", "2.1")
    make_wheel(house, "birdseyefake_tool", "1.0")
    offline_pip(monkeypatch, house)
    return house


PACKAGES = [package("birdseyefake_app", ">=1.0", always=("detect",), sometimes=("importcameras",)),
            package("birdseyefake_tool", ">=1.0"),
            package("pytest", ">=99", always=("planflight",)),  # installed here, below the range
            package("birdseyefake_sfm", ">=4.2", always=("refineposes",), available=False)]
TITLES = {"detect": "Detect targets", "importcameras": "Import camera solution", "planflight": "Plan flight",
          "refineposes": "Refine frame poses"}


def rows(dialog):
    table = dialog.table
    return [[table.topLevelItem(r).text(c) for c in range(4)] for r in range(table.topLevelItemCount())]


def checks(dialog):
    items = [dialog.table.topLevelItem(r) for r in range(dialog.table.topLevelItemCount())]
    return [(bool(i.flags() & Qt.ItemFlag.ItemIsUserCheckable) and i.checkState(0) == Qt.CheckState.Checked,
             bool(i.flags() & Qt.ItemFlag.ItemIsEnabled)) for i in items]


@pytest.fixture
def dialog(qgis_app, qtbot, tmp_path, clean_path):
    widget = dialog_module.DependenciesDialog(folder=tmp_path / "profile-packages", python=sys.executable,
                                              packages=PACKAGES, title=TITLES.get)
    qtbot.addWidget(widget)
    widget.show()
    qtbot.waitExposed(widget)
    return widget


def test_lists_what_is_missing_and_why(dialog):
    import pytest as installed_pytest

    python = "%d.%d" % sys.version_info[:2]
    assert rows(dialog) == [
        ["birdseyefake_app", ">=1.0", "missing", "Detect targets; for some inputs: Import camera solution"],
        ["birdseyefake_tool", ">=1.0", "missing", "no algorithm (developer tools only)"],
        ["pytest", ">=99", f"installed ({installed_pytest.__version__}; untested outside >=99)", "Plan flight"],
        ["birdseyefake_sfm", ">=4.2", f"no release for Python {python}", "Refine frame poses"],
    ]
    assert checks(dialog) == [(True, True), (False, True), (False, False), (False, False)], \
        "missing and used: ticked; missing, unused: offered unticked; QGIS's own or not for this Python: greyed"
    assert "algorithms need 1 Python package(s)" in dialog.intro.text() and str(dialog.folder) in dialog.intro.text()
    assert dialog.install_button.isEnabled() and not dialog.log.isVisible() and not dialog.progress.isVisible()


def test_a_greyed_out_button_says_why(dialog, qgis_app, qtbot, tmp_path, clean_path):
    # Install follows the ticks: unticked, it is greyed out and says what to do.
    app = dialog.table.topLevelItem(0)
    assert dialog.install_button.isEnabled() and str(dialog.folder) in dialog.install_button.toolTip()
    app.setCheckState(0, Qt.CheckState.Unchecked)
    assert not dialog.install_button.isEnabled()
    assert dialog.install_button.toolTip() == "Tick a package in the list to install it."
    app.setCheckState(0, Qt.CheckState.Checked)
    assert dialog.install_button.isEnabled()
    # Everything there: both buttons greyed out, and the group's says so on its face.
    group = deps.PackageGroup("fake", "Fake tools", "cpu", (package("pytest", ">=1"),))
    widget = dialog_module.DependenciesDialog(folder=tmp_path / "packages", python=sys.executable,
                                              packages=[package("pytest", ">=1", always=("planflight",))],
                                              title=TITLES.get, group=group, group_folder=tmp_path / "group")
    qtbot.addWidget(widget)
    assert not widget.install_button.isEnabled()
    assert widget.install_button.toolTip().startswith("Nothing to install: every package in the list is installed")
    assert not widget.group_button.isEnabled() and widget.group_button.text() == "Fake tools is installed"
    assert "pytest" in widget.group_button.toolTip()
    # A group with something missing offers to install it, saying what and where.
    missing = deps.PackageGroup("fake", "Fake tools", "cpu", (package("birdseyefake_sfm", ">=4.2"),))
    widget = dialog_module.DependenciesDialog(folder=tmp_path / "packages", python=sys.executable, packages=[],
                                              title=TITLES.get, group=missing, group_folder=tmp_path / "group")
    qtbot.addWidget(widget)
    assert widget.group_button.isEnabled() and widget.group_button.text() == "Install Fake tools"
    assert "birdseyefake_sfm>=4.2" in widget.group_button.toolTip() and str(tmp_path / "group") in \
        widget.group_button.toolTip()


def test_a_long_list_of_algorithms_wraps_instead_of_being_cut_off(qgis_app, qtbot, tmp_path, clean_path):
    from docks_layout import layout_problems

    many = tuple(f"alg{k}" for k in range(14))
    widget = dialog_module.DependenciesDialog(
        folder=tmp_path / "packages", python=sys.executable, title=lambda a: f"{a[3:]} · An algorithm with a long name",
        packages=[package("birdseyefake_app", ">=1.0", always=many[:10], sometimes=many[10:]),
                  package("birdseyefake_tool", ">=1.0", always=("detect",))])
    qtbot.addWidget(widget)
    widget.show()
    qtbot.waitExposed(widget)
    qtbot.waitUntil(lambda: widget.table.visualItemRect(widget.table.topLevelItem(0)).height() >
                    2 * widget.table.visualItemRect(widget.table.topLevelItem(1)).height())
    assert layout_problems(widget) == []
    widget.resize(700, 600)   # narrower: more lines
    qtbot.wait(50)
    assert layout_problems(widget) == []


def test_install_on_consent_streams_pip_and_makes_the_package_importable(dialog, qtbot, wheelhouse):
    assert not (dialog.folder / "birdseyefake_app").exists(), "nothing is installed before Install"
    with qtbot.waitSignal(dialog.installed, timeout=120_000):
        qtbot.mouseClick(dialog.install_button, Qt.MouseButton.LeftButton)
        assert dialog.close_button.text() == "Cancel" and not dialog.table.isEnabled()
        assert dialog.progress.isVisible() and dialog.progress.maximum() == 0, "busy while pip resolves"
    qtbot.waitUntil(lambda: not dialog.is_running(), timeout=10_000)
    installed = re.fullmatch(r"Installed: (.*)\. The algorithms can use them now; no restart needed\.",
                             dialog.status.text())
    assert installed and sorted(installed[1].split(", ")) == ["birdseyefake_app==1.0", "birdseyefake_lib==2.1"]
    assert dialog.progress.value() == 100
    assert "Successfully installed" in dialog.log.toPlainText(), "pip's output streamed into the log"
    assert rows(dialog)[0][2] == "installed by BirdsEye (1.0)" and checks(dialog)[0] == (False, False)
    assert not (dialog.folder / "birdseyefake_tool").exists(), "an unticked package is not installed"
    assert importlib.import_module("birdseyefake_app").VERSION == "1.0"
    assert dialog.close_button.text() == "Close" and dialog.table.isEnabled()
    SCREENSHOT.parent.mkdir(parents=True, exist_ok=True)
    dialog.log_button.setChecked(True)
    dialog.grab().save(str(SCREENSHOT))


def test_a_failure_opens_the_log_with_pips_message(qgis_app, qtbot, tmp_path, clean_path, wheelhouse):
    widget = dialog_module.DependenciesDialog(folder=tmp_path / "packages", python=sys.executable,
                                              packages=[package("birdseyefake_app", "==9.9", always=("detect",))],
                                              title=TITLES.get)
    qtbot.addWidget(widget)
    widget.show()
    qtbot.mouseClick(widget.install_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: not widget.is_running(), timeout=120_000)
    assert widget.status.text().startswith("The installation failed: pip stopped with exit status")
    assert widget.log.isVisible() and widget.log_button.isChecked()
    assert "No matching distribution found for birdseyefake_app==9.9" in widget.log.toPlainText()
    assert rows(widget)[0][2] == "missing" and widget.install_button.isEnabled(), "the user can try again"


def test_cancel_stops_pip_and_installs_nothing(dialog, qtbot, wheelhouse):
    qtbot.mouseClick(dialog.install_button, Qt.MouseButton.LeftButton)
    qtbot.mouseClick(dialog.close_button, Qt.MouseButton.LeftButton)  # "Cancel" while pip runs
    assert dialog.isVisible(), "Cancel stops pip; it does not close the dialog under it"
    qtbot.waitUntil(lambda: not dialog.is_running(), timeout=60_000)
    assert dialog.status.text() == "Cancelled; nothing was installed."
    assert not (dialog.folder / "birdseyefake_app").exists()
    assert rows(dialog)[0][2] == "missing" and dialog.close_button.text() == "Close"
    qtbot.mouseClick(dialog.close_button, Qt.MouseButton.LeftButton)
    assert not dialog.isVisible()


def test_needed_by_names_algorithms_as_the_toolbox_does(birdseye_provider):
    detect = birdseye_provider.algorithm("detect")
    text = dialog_module.needed_by(package("x", ">=1", always=("detect",)))
    assert text == detect.displayName()


# ------------------------------------------------------------------------------ the plugin and the algorithms
@pytest.fixture
def plugin(qgis_iface, monkeypatch):
    opened = []
    monkeypatch.setattr(dialog_module.DependenciesDialog, "exec", lambda self: opened.append(self) or 0)
    instance = plugin_module.BirdsEyePlugin(qgis_iface, ProviderUnderTest)
    instance.opened = opened
    yield instance
    instance.unload()


class ProviderUnderTest:
    """Stands in for the provider (the session's registry already holds ``birdseye``)."""

    def __new__(cls):
        from birdseye.processing.provider import BirdsEyeProvider

        class Provider(BirdsEyeProvider):
            def id(self):
                return "birdseye_dependencies_test"

        return Provider()


def test_menu_action_opens_the_dialog(plugin):
    plugin.initGui()
    action = next(a for a in plugin.menu.actions() if a.objectName() == "mActionBirdsEyeDependencies")
    assert action.text() == "Install dependencies…"
    action.trigger()
    assert len(plugin.opened) == 1 and plugin.opened[0].folder == plugin.package_folder
    assert plugin.package_folder == deps.package_folder(plugin_module.QgsApplication.qgisSettingsDirPath())
    assert str(plugin.package_folder) in sys.path, "the plugin adds its package folder at start"


def test_start_offers_the_dialog_when_a_package_is_missing(plugin, qgis_iface, monkeypatch):
    monkeypatch.setitem(sys.modules, "onnxruntime", None)
    before = qgis_iface.messageBar().findChildren(QPushButton, "mBirdsEyeInstallDependenciesButton")
    plugin.initGui()
    buttons = qgis_iface.messageBar().findChildren(QPushButton, "mBirdsEyeInstallDependenciesButton")
    [new] = [b for b in buttons if b not in before]
    new.click()
    assert len(plugin.opened) == 1


def test_no_notice_when_nothing_is_missing(plugin, qgis_iface):
    """This test environment has every package of requirements.txt, as `make setup` installs them."""
    before = len(qgis_iface.messageBar().findChildren(QPushButton, "mBirdsEyeInstallDependenciesButton"))
    plugin.initGui()
    assert len(qgis_iface.messageBar().findChildren(QPushButton, "mBirdsEyeInstallDependenciesButton")) == before


def test_an_algorithm_that_needs_a_missing_package_says_so(birdseye_provider, monkeypatch):
    import processing

    monkeypatch.setitem(sys.modules, "onnxruntime", None)
    detect = birdseye_provider.algorithm("detect")
    ok, message = detect.canExecute()
    assert not ok
    assert message.startswith("This algorithm needs the Python package(s) onnxruntime, which the Python QGIS")
    assert "BirdsEye › Install dependencies…" in message and 'python -m pip install "onnxruntime>=' in message
    assert birdseye_provider.algorithm("selectarms").canExecute() == (True, "")
    frames = QgsVectorLayer("Polygon?crs=EPSG:32756", "frames", "memory")
    with pytest.raises(QgsProcessingException) as info:  # processing.run does not ask canExecute itself
        processing.run("birdseye:detect", {"FRAMES": frames, "OUTPUT": "memory:"})
    assert str(info.value) == message


def test_a_package_needed_for_some_inputs_is_named_when_reached(birdseye_provider, monkeypatch, tmp_path):
    """importcameras needs pycolmap only for COLMAP models: it starts, and says so when it gets there."""
    import processing

    monkeypatch.setitem(sys.modules, "pycolmap", None)
    assert birdseye_provider.algorithm("importcameras").canExecute() == (True, "")
    model = tmp_path / "sparse" / "cameras.txt"
    model.parent.mkdir()
    model.write_text("# COLMAP cameras\n")
    with pytest.raises(QgsProcessingException) as info:
        processing.run("birdseye:importcameras", {"CAMERAS": str(model), "GROUND_HEIGHT_M": 0.0,
                                                  "OUTPUT": "memory:"})
    assert str(info.value).startswith("This algorithm needs the Python package(s) pycolmap, which")


def test_an_algorithm_whose_package_has_no_release_for_this_python_says_so(birdseye_provider, monkeypatch):
    """pycolmap has no wheels for Python 3.9: there refineposes is refused with that reason, not sent to
    the installer."""
    real = deps.read_requirements(python=(3, 9))
    assert not next(p for p in real if p.distribution == "pycolmap").available
    monkeypatch.setattr(deps, "read_requirements", lambda *args, **kwargs: real)
    monkeypatch.setitem(sys.modules, "pycolmap", None)
    ok, message = birdseye_provider.algorithm("refineposes").canExecute()
    python = "%d.%d" % sys.version_info[:2]
    assert not ok and message == ("This algorithm needs the Python package(s) pycolmap, which have no release for "
                                  f"the Python QGIS runs (Python {python}); it runs in a QGIS with a newer Python.")
