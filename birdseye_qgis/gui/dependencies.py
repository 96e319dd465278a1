"""BirdsEye › Install dependencies…: which Python packages are missing, why, and installing them on consent.

The dialog lists every package of ``requirements.txt`` with its state in the Python QGIS runs and the
algorithms that need it; the missing ones are ticked. *Install* runs
:class:`~birdseye_qgis.dependencies.Installer` in a worker thread (pip's output streams into the log,
the progress bar follows it, *Cancel* stops pip); when pip fails the log opens by itself. Nothing is
installed until the user presses *Install*. A package no algorithm uses (only developer tools) is
listed but not ticked.
"""
from __future__ import annotations

import sys
import traceback
from pathlib import Path
from typing import Callable, Sequence

from qgis.core import QgsApplication
from qgis.PyQt.QtCore import QEvent, QRect, QSize, Qt, QThread, QTimer, pyqtSignal
from qgis.PyQt.QtGui import QFontDatabase
from qgis.PyQt.QtWidgets import (
    QAbstractItemView,
    QDialog,
    QDialogButtonBox,
    QHeaderView,
    QLabel,
    QPlainTextEdit,
    QProgressBar,
    QPushButton,
    QStyle,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
)

from ..__about__ import tr
from ..core.errors import Cancelled
from ..dependencies import (
    Installer,
    InstallError,
    PackageGroup,
    PackageStatus,
    RuntimePackage,
    group_statuses,
    package_folder,
    read_requirements,
    statuses,
    torch_folder,
    torch_group,
)

PACKAGE_COLUMN, VERSION_COLUMN, STATE_COLUMN, NEEDED_BY_COLUMN = range(4)


def default_folder() -> Path:
    """BirdsEye's package folder in the active QGIS profile."""
    return package_folder(QgsApplication.qgisSettingsDirPath())


def algorithm_title(algorithm_id: str) -> str:
    """The name the Processing toolbox shows for ``birdseye:<algorithm_id>``."""
    algorithm = QgsApplication.processingRegistry().algorithmById(f"birdseye:{algorithm_id}")
    return algorithm.displayName() if algorithm is not None else algorithm_id


def needed_by(package: RuntimePackage, title: Callable[[str], str] = algorithm_title) -> str:
    always = ", ".join(title(a) for a in package.use.always)
    sometimes = ", ".join(title(a) for a in package.use.sometimes)
    if always and sometimes:
        return tr("{always}; for some inputs: {sometimes}").format(always=always, sometimes=sometimes)
    if sometimes:
        return tr("for some inputs: {sometimes}").format(sometimes=sometimes)
    return always or tr("no algorithm (developer tools only)")


def state_text(status: PackageStatus) -> str:
    if not status.package.available and status.installed_version is None:
        return tr("no release for Python {version}").format(version="%d.%d" % sys.version_info[:2])
    if status.installed_version is None:
        return tr("missing")
    if status.needs_install:
        return tr("update from {version}").format(version=status.installed_version)
    if status.in_folder:
        return tr("installed by BirdsEye ({version})").format(version=status.installed_version)
    if not status.in_range:
        return tr("installed ({version}; untested outside {versions})").format(
            version=status.installed_version, versions=status.package.specifier)
    return tr("installed ({version})").format(version=status.installed_version)


class InstallThread(QThread):
    """Runs the installer off the UI thread; every callback reaches the dialog as a signal."""

    line = pyqtSignal(str)
    fraction = pyqtSignal(float)
    succeeded = pyqtSignal(object)  # the list of distributions pip installed
    failed = pyqtSignal(str, str)  # message, pip's log
    stopped = pyqtSignal()

    def __init__(self, folder: Path, packages: Sequence[RuntimePackage], python: str | None, parent=None,
                 pip_options: Sequence[str] = ()):
        super().__init__(parent)
        self.folder, self.packages, self.python = folder, list(packages), python
        self.pip_options = tuple(pip_options)
        self.cancel_requested = False

    def run(self) -> None:
        installer = Installer(self.folder, self.python, log=self.line.emit, progress=self.fraction.emit,
                              is_canceled=lambda: self.cancel_requested, pip_options=self.pip_options)
        try:
            self.succeeded.emit(installer.install(self.packages))
        except Cancelled:
            self.stopped.emit()
        except InstallError as exc:
            self.failed.emit(str(exc), exc.log or "\n".join(installer.output))
        except Exception as exc:  # noqa: BLE001 — shown in the dialog, never a crash of QGIS
            self.failed.emit(str(exc), "\n".join(installer.output + [traceback.format_exc()]))


class DependenciesDialog(QDialog):
    """Lists the runtime packages and installs the ticked ones.

    ``folder`` and ``python`` default to the profile's package folder and the interpreter found next
    to QGIS (:func:`~birdseye_qgis.dependencies.find_python`); tests pass their own.
    """

    installed = pyqtSignal()

    def __init__(self, parent=None, folder: Path | None = None, python: str | None = None,
                 packages: Sequence[RuntimePackage] | None = None,
                 title: Callable[[str], str] = algorithm_title, group: PackageGroup | None = None,
                 group_folder: Path | None = None):
        super().__init__(parent)
        self.setObjectName("BirdsEyeDependenciesDialog")
        self.setWindowTitle(tr("BirdsEye — Python packages"))
        self.folder = default_folder() if folder is None else Path(folder)
        self.python = python
        self.packages = read_requirements() if packages is None else list(packages)
        self.title = title
        # The optional PyTorch group (Train detector), in its own folder; never ticked by default.
        self.group = torch_group() if group is None else group
        self.group_folder = (torch_folder(QgsApplication.qgisSettingsDirPath()) if group_folder is None
                             else Path(group_folder))
        self.thread: InstallThread | None = None
        self._busy = False

        self.intro = QLabel()
        self.intro.setWordWrap(True)
        self.intro.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.table = QTreeWidget()
        self.table.setObjectName("packageTable")
        self.table.setRootIsDecorated(False)
        self.table.setSelectionMode(QAbstractItemView.SelectionMode.NoSelection)
        self.table.setHeaderLabels([tr("Package"), tr("Versions"), tr("State"), tr("Needed by")])
        header = self.table.header()
        for column in (PACKAGE_COLUMN, VERSION_COLUMN, STATE_COLUMN):
            header.setSectionResizeMode(column, QHeaderView.ResizeMode.ResizeToContents)
        header.setStretchLastSection(True)
        # "Needed by" lists many algorithms: wrapped to the column, never cut off (a tree sizes its rows for one
        # line unless told otherwise).
        self.table.setWordWrap(True)
        self.table.viewport().installEventFilter(self)
        self.table.itemChanged.connect(self._explain_install_button)   # a tick or an untick
        self.progress = QProgressBar()
        self.progress.setRange(0, 100)
        self.progress.setVisible(False)
        self.status = QLabel()
        self.status.setWordWrap(True)
        self.status.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.log = QPlainTextEdit()
        self.log.setObjectName("pipLog")
        self.log.setReadOnly(True)
        self.log.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
        self.log.setVisible(False)

        self.buttons = QDialogButtonBox()
        self.install_button = QPushButton(tr("Install"))
        self.install_button.setObjectName("installButton")
        self.install_button.setDefault(True)
        self.install_button.clicked.connect(self.start_install)
        self.log_button = QPushButton(tr("Show pip's log"))
        self.log_button.setCheckable(True)
        self.log_button.toggled.connect(self.log.setVisible)
        self.close_button = QPushButton(tr("Close"))
        self.close_button.clicked.connect(self.reject)
        self.group_label = QLabel()
        self.group_label.setObjectName("groupLabel")
        self.group_label.setWordWrap(True)
        self.group_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.group_button = QPushButton()
        self.group_button.setObjectName("installGroupButton")
        self.group_button.clicked.connect(self.start_group_install)
        self.buttons.addButton(self.install_button, QDialogButtonBox.ButtonRole.AcceptRole)
        self.buttons.addButton(self.log_button, QDialogButtonBox.ButtonRole.HelpRole)
        self.buttons.addButton(self.close_button, QDialogButtonBox.ButtonRole.RejectRole)

        layout = QVBoxLayout(self)
        for widget in (self.intro, self.table, self.group_label, self.group_button, self.progress, self.status,
                       self.log, self.buttons):
            layout.addWidget(widget)
        self.resize(900, 600)
        self.refresh()

    # ------------------------------------------------------------------ state
    def refresh(self) -> None:
        """Read each package's state again and rebuild the list; missing packages come ticked."""
        self.statuses = statuses(self.packages, self.folder)
        self.table.clear()
        for status in self.statuses:
            item = QTreeWidgetItem([status.package.distribution, status.package.specifier, state_text(status),
                                    needed_by(status.package, self.title)])
            item.setData(PACKAGE_COLUMN, Qt.ItemDataRole.UserRole, status.package.distribution)
            if status.needs_install:
                used = status.package.use.always or status.package.use.sometimes
                item.setFlags(item.flags() | Qt.ItemFlag.ItemIsUserCheckable)
                item.setCheckState(PACKAGE_COLUMN, Qt.CheckState.Checked if used else Qt.CheckState.Unchecked)
            else:
                item.setFlags(item.flags() & ~Qt.ItemFlag.ItemIsEnabled)
            item.setToolTip(NEEDED_BY_COLUMN, item.text(NEEDED_BY_COLUMN))
            self.table.addTopLevelItem(item)
        self._wrap_needed_by()
        needed = [s for s in self.statuses if s.needs_install and (s.package.use.always or s.package.use.sometimes)]
        if needed:
            self.intro.setText(tr(
                "BirdsEye's algorithms need {count} Python package(s) that the Python QGIS runs does not have. "
                "Tick the ones to install and press Install: pip installs them, at versions that suit this "
                "Python and the packages QGIS already has, with what they depend on, into a folder of your "
                "QGIS profile:\n{folder}\nQGIS's own packages are not changed. pip downloads them from the "
                "Python Package Index (or the index your pip is set up to use).").format(count=len(needed),
                                                                                      folder=self.folder))
        else:
            self.intro.setText(tr("Every Python package BirdsEye's algorithms need is installed in the Python "
                                  "QGIS runs."))
        self._explain_install_button()
        self.refresh_group()

    def _wrap_needed_by(self, *_) -> None:
        """Each row as tall as its "Needed by" text wrapped to the column's width."""
        margin = self.table.style().pixelMetric(QStyle.PixelMetric.PM_FocusFrameHMargin, None, self.table) + 1
        width = max(1, self.table.header().sectionSize(NEEDED_BY_COLUMN) - 2 * margin)
        metrics = self.table.fontMetrics()
        for i in range(self.table.topLevelItemCount()):
            item = self.table.topLevelItem(i)
            text = metrics.boundingRect(QRect(0, 0, width, 100_000), int(Qt.TextFlag.TextWordWrap),
                                        item.text(NEEDED_BY_COLUMN))
            item.setSizeHint(NEEDED_BY_COLUMN, QSize(width, text.height() + 2 * margin))

    def _explain_install_button(self, *_) -> None:
        """Install is enabled when a package is ticked; greyed out, its tooltip says why."""
        if self.is_running():
            return
        missing = [s for s in self.statuses if s.needs_install]
        ticked = bool(self.checked_packages())
        self.install_button.setEnabled(ticked)
        if ticked:
            self.install_button.setToolTip(tr("Install the ticked packages into {folder}").format(folder=self.folder))
        elif missing:
            self.install_button.setToolTip(tr("Tick a package in the list to install it."))
        else:
            self.install_button.setToolTip(tr("Nothing to install: every package in the list is installed or has "
                                              "no release for this Python."))

    def refresh_group(self) -> None:
        """The optional PyTorch group: its state in its folder and what installing it does."""
        self.group_statuses = group_statuses(self.group, self.group_folder)
        state = ", ".join(f"{s.package.distribution} {s.installed_version or tr('missing')}"
                          for s in self.group_statuses)
        self.group_label.setText(tr(
            "Optional — {title} for Train detector ({build} build{why}): {state}. It is installed into its own "
            "folder, {folder}, and runs in a separate training process: QGIS itself never loads it. Several "
            "hundred MB (the CUDA build: gigabytes).").format(
                title=self.group.title, build=self.group.build.upper(), state=state, folder=self.group_folder,
                why=tr(", an NVIDIA driver is present") if self.group.build == "cuda" else ""))
        missing = [s for s in self.group_statuses if s.needs_install]
        self.group_button.setEnabled(bool(missing))
        if missing:
            self.group_button.setText(tr("Install {title}").format(title=self.group.title))
            self.group_button.setToolTip(tr("Install {names} into {folder}").format(
                names=", ".join(s.package.requirement for s in missing), folder=self.group_folder))
        else:   # greyed out: say so on the button itself, not only in a tooltip
            self.group_button.setText(tr("{title} is installed").format(title=self.group.title))
            self.group_button.setToolTip(tr("Nothing to install: {state}.").format(state=state))

    def checked_packages(self) -> list[RuntimePackage]:
        by_name = {s.package.distribution: s.package for s in self.statuses}
        items = (self.table.topLevelItem(i) for i in range(self.table.topLevelItemCount()))
        return [by_name[item.data(PACKAGE_COLUMN, Qt.ItemDataRole.UserRole)] for item in items
                if item.flags() & Qt.ItemFlag.ItemIsUserCheckable
                and item.checkState(PACKAGE_COLUMN) == Qt.CheckState.Checked]

    def is_running(self) -> bool:
        """True from Install until the outcome is shown: the thread's last signals are queued to this
        thread, so the worker may have stopped a moment before its result reaches the dialog."""
        return self._busy

    # ------------------------------------------------------------------ install
    def start_group_install(self) -> None:
        """Install the PyTorch group's missing packages into its folder, from its index."""
        packages = [s.package for s in self.group_statuses if s.needs_install]
        if packages and not self.is_running():
            self._start(self.group_folder, packages, self.group.pip_options)

    def start_install(self) -> None:
        packages = self.checked_packages()
        if not packages or self.is_running():
            return
        self._start(self.folder, packages, ())

    def _start(self, folder: Path, packages: Sequence[RuntimePackage], pip_options: Sequence[str]) -> None:
        self.log.clear()
        self.progress.setRange(0, 0)  # busy while pip resolves: it cannot say how long that takes
        self.progress.setVisible(True)
        self.status.setText(tr("Installing {names}…").format(names=", ".join(p.requirement for p in packages)))
        self.install_button.setEnabled(False)
        self.group_button.setEnabled(False)
        for button in (self.install_button, self.group_button):
            button.setToolTip(tr("pip is installing; press Cancel to stop it."))
        self.table.setEnabled(False)
        self.close_button.setText(tr("Cancel"))
        self._busy = True
        self.thread = InstallThread(folder, packages, self.python, self, pip_options)
        self.thread.line.connect(self.log.appendPlainText)
        self.thread.fraction.connect(self._show_fraction)
        self.thread.succeeded.connect(self._succeeded)
        self.thread.failed.connect(self._failed)
        self.thread.stopped.connect(self._stopped)
        self.thread.finished.connect(self._finished)
        self.thread.start()

    def _show_fraction(self, fraction: float) -> None:
        if fraction > 0:
            self.progress.setRange(0, 100)
            self.progress.setValue(round(100 * fraction))

    def _succeeded(self, plan) -> None:
        self.status.setText(tr("Installed: {names}. The algorithms can use them now; no restart needed.").format(
            names=", ".join(p.requirement for p in plan) or tr("nothing new")))
        self.installed.emit()

    def _failed(self, message: str, log: str) -> None:
        self.status.setText(tr("The installation failed: {message}\npip's log is below; the packages "
                               "already there are unchanged.").format(message=message))
        self.log.setPlainText(log)
        self.log_button.setChecked(True)

    def _stopped(self) -> None:
        self.status.setText(tr("Cancelled; nothing was installed."))

    def _finished(self) -> None:
        self.table.setEnabled(True)
        self.close_button.setText(tr("Close"))
        self._busy = False
        self.refresh()

    def reject(self) -> None:
        """Close; while pip runs, Cancel (and Esc) stop it first."""
        if self.is_running():
            self.thread.cancel_requested = True
            self.status.setText(tr("Cancelling…"))
            return
        super().reject()

    def eventFilter(self, watched, event) -> bool:  # noqa: N802 — Qt's name
        if watched is self.table.viewport() and event.type() == QEvent.Type.Resize:
            QTimer.singleShot(0, self._wrap_needed_by)   # once the column has its new width
        return super().eventFilter(watched, event)

    def closeEvent(self, event) -> None:  # noqa: N802 — Qt's name
        if self.is_running():
            self.reject()
            event.ignore()
            return
        super().closeEvent(event)
