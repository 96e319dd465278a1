"""The QGIS plugin object: the ``birdseye`` Processing provider, a BirdsEye menu and toolbar, and docks.

QGIS creates :class:`BirdsEyePlugin` through ``classFactory`` in the plugin's root ``__init__.py``.
The desktop calls :meth:`BirdsEyePlugin.initGui` and :meth:`BirdsEyePlugin.unload`; ``qgis_process``
has no interface (``iface is None``) and calls only :meth:`BirdsEyePlugin.initProcessing`.
"""
from __future__ import annotations

import importlib
from typing import NamedTuple

from qgis.core import Qgis, QgsApplication, QgsMessageLog, QgsProject
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP, QCoreApplication, QLocale, Qt, QTranslator
from qgis.PyQt.QtGui import QIcon
from qgis.PyQt.QtWidgets import QMenu, QPushButton, QToolBar

try:
    from qgis.PyQt.QtGui import QAction  # Qt 6 (QGIS 4)
except ImportError:
    from qgis.PyQt.QtWidgets import QAction  # Qt 5 (QGIS 3)

from ..__about__ import I18N_DIR, ICON_PATH, LOG_TAG, PLUGIN_ROOT, tr
from ..dependencies import activate, package_folder, statuses
from ..qgis_io import layer_kinds

# The name QGIS imported the plugin under ("birdseye" when installed from the zip), so dock modules
# are found whatever the plugin folder is called.
PLUGIN_PACKAGE = __name__.rsplit(".birdseye_qgis.", 1)[0]
MENU_OBJECT_NAME = "mBirdsEyeMenu"
TOOLBAR_OBJECT_NAME = "mBirdsEyeToolBar"
TOOLBOX_FILTER = "birdseye"
ALGORITHMS_ICON = "resources/icons/algorithms.svg"


class DockEntry(NamedTuple):
    """A dock widget the plugin offers; its module is imported only when the user first opens it.

    ``module`` is relative to the plugin package; the class is called as ``cls(iface)`` and must be a
    ``QDockWidget``. ``icon`` is a path relative to the plugin root (the plugin icon when empty);
    ``tooltip`` says what the dock is for (marked with ``QT_TRANSLATE_NOOP("@default", …)`` so it is
    translated).
    """

    module: str
    class_name: str
    title: str
    icon: str = ""
    tooltip: str = ""


# Later features append their dock here; an entry whose module does not exist yet is simply not shown.
DOCKS: list[DockEntry] = [
    DockEntry("birdseye_qgis.gui.review.dock", "ReviewDock", "Review clusters", "resources/icons/review.svg",
              QT_TRANSLATE_NOOP("@default", "Review clusters: walk through the detected clusters beside the "
                                            "survey, judge each, and see recall and GMCF before and after review")),
    DockEntry("birdseye_qgis.gui.sensor_bound_dock", "SensorBoundDock", "Sensor-bound calculator",
              "resources/icons/sensor_bound.svg",
              QT_TRANSLATE_NOOP("@default", "Sensor-bound calculator: which pose-noise budget keeps labels "
                                            "within their pixel tolerance for a camera and flying height")),
]


def log(message: str, level=Qgis.MessageLevel.Info) -> None:
    QgsMessageLog.logMessage(message, LOG_TAG, level)


def load_translator() -> QTranslator | None:
    """Install the translation for the locale QGIS runs in (Settings ▸ Options ▸ General, e.g. ``de_CH``,
    else ``de``) when the plugin ships one; English, the source language, needs none."""
    locale = QgsApplication.locale() or QLocale().name()
    for name in (locale, locale[:2]):
        path = I18N_DIR / f"birdseye_{name}.qm"
        if name and path.is_file():
            translator = QTranslator()
            if translator.load(str(path)):
                QCoreApplication.installTranslator(translator)
                return translator
    return None


class BirdsEyePlugin:
    """Registers the Processing provider and, in the desktop, the BirdsEye menu, toolbar and docks."""

    def __init__(self, iface, provider_class):
        """``provider_class`` builds the Processing provider; ``classFactory`` passes it in, so this
        library never imports ``processing/`` (see docs/design.md, "Architecture")."""
        self.iface = iface
        self.provider_class = provider_class
        self.provider = None
        self.menu: QMenu | None = None
        self.toolbar: QToolBar | None = None
        self.toolbox_action: QAction | None = None
        self.dock_actions: dict[DockEntry, QAction] = {}
        self.docks: dict[DockEntry, object] = {}
        # Before anything builds a user-visible string: the provider's names come from tr() too.
        self.translator = load_translator()
        self.dependencies_action: QAction | None = None
        # Packages installed by BirdsEye › Install dependencies… (at the end of sys.path: QGIS's own win).
        self.package_folder = package_folder(QgsApplication.qgisSettingsDirPath())
        activate(self.package_folder)

    # ------------------------------------------------------------------ Processing
    def initProcessing(self) -> None:
        """Register the ``birdseye`` provider once (desktop and ``qgis_process`` both call this)."""
        if self.provider is not None:
            return
        self.provider = self.provider_class()
        if not QgsApplication.processingRegistry().addProvider(self.provider):
            log(tr("The BirdsEye Processing provider could not be registered."), Qgis.MessageLevel.Critical)
            self.provider = None

    # ------------------------------------------------------------------ desktop
    def initGui(self) -> None:
        self.initProcessing()
        # From QGIS's start on, so "the most recent layer" of every layer choice is the one added last.
        layer_kinds.track(QgsProject.instance())
        main_window = self.iface.mainWindow()
        icon = QIcon(str(PLUGIN_ROOT / ALGORITHMS_ICON))

        self.menu = QMenu(tr("&BirdsEye"), main_window)
        self.menu.setObjectName(MENU_OBJECT_NAME)
        self.toolbar = QToolBar(tr("BirdsEye"), main_window)
        self.toolbar.setObjectName(TOOLBAR_OBJECT_NAME)

        self.toolbox_action = QAction(icon, tr("BirdsEye algorithms…"), main_window)
        self.toolbox_action.setObjectName("mActionBirdsEyeAlgorithms")
        self.toolbox_action.setToolTip(tr("Open the Processing toolbox showing the BirdsEye algorithms"))
        self.toolbox_action.triggered.connect(self.show_algorithms)
        self.menu.addAction(self.toolbox_action)
        self.toolbar.addAction(self.toolbox_action)

        self.menu.addSeparator()
        for entry in DOCKS:
            action = QAction(self._icon_for(entry), tr(entry.title), main_window)
            action.setObjectName(f"mActionBirdsEye{entry.class_name}")
            if entry.tooltip:
                action.setToolTip(tr(entry.tooltip))
            action.setCheckable(True)
            action.toggled.connect(lambda checked, e=entry: self.set_dock_visible(e, checked))
            self.menu.addAction(action)
            self.toolbar.addAction(action)
            self.dock_actions[entry] = action

        self.menu.addSeparator()
        self.dependencies_action = QAction(tr("Install dependencies…"), main_window)
        self.dependencies_action.setObjectName("mActionBirdsEyeDependencies")
        self.dependencies_action.setToolTip(tr("Install the Python packages BirdsEye's algorithms need"))
        self.dependencies_action.triggered.connect(self.show_dependencies)
        self.menu.addAction(self.dependencies_action)

        self._insert_menu(main_window.menuBar())
        self.iface.addToolBar(self.toolbar)
        self._offer_missing_packages()

    def unload(self) -> None:
        """Remove everything :meth:`initGui` and :meth:`initProcessing` added."""
        for action in self.dock_actions.values():
            action.blockSignals(True)  # hiding the docks below must not re-enter set_dock_visible
            action.deleteLater()
        self.dock_actions.clear()
        for dock in self.docks.values():
            if hasattr(dock, "shutdown"):  # stop worker threads and close files before the widget goes
                dock.shutdown()
            self.iface.removeDockWidget(dock)
            dock.deleteLater()
        self.docks.clear()
        if self.menu is not None:
            menu_bar = self.iface.mainWindow().menuBar()
            menu_bar.removeAction(self.menu.menuAction())
            self.menu.deleteLater()
            self.menu = None
        if self.toolbar is not None:
            self.iface.mainWindow().removeToolBar(self.toolbar)
            self.toolbar.deleteLater()
            self.toolbar = None
        if self.toolbox_action is not None:
            self.toolbox_action.deleteLater()
            self.toolbox_action = None
        if self.dependencies_action is not None:
            self.dependencies_action.deleteLater()
            self.dependencies_action = None
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
        if self.translator is not None:
            QCoreApplication.removeTranslator(self.translator)
            self.translator = None

    # ------------------------------------------------------------------ actions
    def show_algorithms(self) -> None:
        """Show the Processing toolbox filtered to the BirdsEye algorithms."""
        from qgis import utils

        toolbox = getattr(utils.plugins.get("processing"), "toolbox", None)
        if toolbox is None:
            self._warn(tr("The Processing plugin is not active: enable it under Plugins ▸ Manage and "
                          "Install Plugins, then try again."))
            return
        toolbox.setUserVisible(True)
        toolbox.raise_()
        toolbox.searchBox.setText(TOOLBOX_FILTER)

    def show_dependencies(self) -> None:
        """BirdsEye › Install dependencies…: the missing packages, installed on consent."""
        from .dependencies import DependenciesDialog

        DependenciesDialog(self.iface.mainWindow(), folder=self.package_folder).exec()

    def _offer_missing_packages(self) -> None:
        """A message-bar notice (never a dialog at start) when algorithms lack packages."""
        missing = [s.package.distribution for s in statuses(folder=self.package_folder)
                   if s.needs_install and (s.package.use.always or s.package.use.sometimes)]
        if not missing:
            return
        bar = self.iface.messageBar()
        item = bar.createMessage(LOG_TAG, tr("Some algorithms need Python packages that are not installed: "
                                             "{names}.").format(names=", ".join(missing)))
        button = QPushButton(tr("Install dependencies…"), item)
        button.setObjectName("mBirdsEyeInstallDependenciesButton")
        button.clicked.connect(self.show_dependencies)
        item.layout().addWidget(button)
        bar.pushWidget(item, Qgis.MessageLevel.Warning)

    def set_dock_visible(self, entry: DockEntry, visible: bool) -> None:
        """Show or hide a dock, creating it (and importing its module) the first time."""
        dock = self.docks.get(entry)
        if dock is None:
            if not visible:
                return
            dock = self._create_dock(entry)
            if dock is None:
                action = self.dock_actions.get(entry)
                if action is not None:
                    action.blockSignals(True)
                    action.setChecked(False)
                    action.blockSignals(False)
                return
        dock.setVisible(visible)
        if visible:
            dock.raise_()

    def _create_dock(self, entry: DockEntry):
        try:
            module = importlib.import_module(f"{PLUGIN_PACKAGE}.{entry.module}")
            dock = getattr(module, entry.class_name)(self.iface)
        except Exception as exc:  # noqa: BLE001 — a broken dock must never take QGIS down
            self._warn(tr("The '{title}' panel could not be opened ({module}.{cls}: {error}).").format(
                title=tr(entry.title), module=entry.module, cls=entry.class_name, error=exc))
            return None
        if not dock.objectName():
            dock.setObjectName(f"BirdsEye{entry.class_name}")
        self.iface.addDockWidget(Qt.DockWidgetArea.RightDockWidgetArea, dock)
        action = self.dock_actions.get(entry)
        if action is not None:
            dock.visibilityChanged.connect(action.setChecked)
        self.docks[entry] = dock
        return dock

    # ------------------------------------------------------------------ helpers
    def _insert_menu(self, menu_bar) -> None:
        """Put the BirdsEye menu just before Help, as QGIS's own plugin menus (Raster, Web…) sit."""
        help_action = next((a for a in menu_bar.actions()
                            if a.menu() is not None and a.menu().objectName() == "mHelpMenu"), None)
        if help_action is None:
            menu_bar.addMenu(self.menu)
        else:
            menu_bar.insertMenu(help_action, self.menu)

    @staticmethod
    def _icon_for(entry: DockEntry) -> QIcon:
        return QIcon(str(PLUGIN_ROOT / entry.icon)) if entry.icon else QIcon(str(ICON_PATH))

    def _warn(self, message: str) -> None:
        log(message, Qgis.MessageLevel.Warning)
        if self.iface is not None:
            self.iface.messageBar().pushMessage(LOG_TAG, message, Qgis.MessageLevel.Warning, 8)
