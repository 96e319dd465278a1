"""The sensor-bound calculator dock: a pose-noise budget against a label tolerance, live.

Every number comes from ``core.design.sensor_bound.evaluate_bounds``, the function behind
``birdseye:sensorbound``; the λ_max plot is ``core.design.bound_report.LmaxFieldPlot``, the one in the
algorithm's HTML report. While the user types, the bound is re-evaluated (debounced) on a coarse grid
(``PREVIEW_MAX_POINTS``; the frame edges, where the worst pixel lies, are always on it); "Evaluate every
pixel" runs the full-resolution grid, as the algorithm does by default.

Units: intrinsics in px; sigmas x, y, z in metres and roll, pitch, yaw in degrees, turned into camera
rotations by the chosen mount (``sensor_bound.CameraMount``); tolerance r in px at 3σ; altitudes in
metres above the ground.
"""
from __future__ import annotations

from pathlib import Path

from qgis.core import Qgis, QgsProject
from qgis.gui import QgsDockWidget, QgsDoubleSpinBox, QgsFileWidget, QgsSpinBox
from qgis.PyQt.QtCore import Qt, QTimer
from qgis.PyQt.QtGui import QBrush, QColor, QFont, QGuiApplication
from qgis.PyQt.QtWidgets import (
    QAbstractItemView,
    QComboBox,
    QFormLayout,
    QFrame,
    QGridLayout,
    QGroupBox,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QLineEdit,
    QPushButton,
    QScrollArea,
    QSizePolicy,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from ..__about__ import LOG_TAG, tr
from ..core.design.bound_report import (
    ACCEPT_COLOUR,
    REJECT_COLOUR,
    LmaxFieldPlot,
    format_kappa,
    format_sigma,
    stride_for,
)
from ..core.design.number_lists import format_number_list, parse_altitudes
from ..core.design.platforms import DEPLOYED, PLATFORMS
from ..core.design.sensor_bound import (
    AXES,
    MOUNTS,
    SIGMA_UNITS,
    TRANSLATION_CONVENTION,
    Intrinsics,
    camera_mount,
    evaluate_bounds,
)
from ..core.errors import InputError
from ..core.geometry.camera import CALIBRATION_FILE_FILTER, load_calibration
from ..core.labels.training_set import label_sigma_px
from ..qgis_io.project_settings import store_sigma_label_px

SENSOR_BOUND_ALG = "birdseye:sensorbound"
PRESET_DEPLOYED = DEPLOYED.name
PRESET_CUSTOM = "Custom"
PRESETS = tuple(p.name for p in PLATFORMS) + (PRESET_CUSTOM,)
LIVE_DELAY_MS = 250
PREVIEW_MAX_POINTS = 150_000
AXIS_TIPS = {
    "x": "Horizontal position error across the flight direction (image right), metres.",
    "y": "Horizontal position error along the flight direction (image down), metres.",
    "z": "Vertical position / altimeter error (along the optical axis), metres.",
    "roll": "Roll attitude error, degrees; the camera mount says which way it turns the camera.",
    "pitch": "Pitch attitude error, degrees; the camera mount says which way it turns the camera.",
    "yaw": "Heading error (about the vertical / optical axis), degrees.",
}


def _spin(decimals: int, minimum: float, maximum: float, step: float, suffix: str) -> QgsDoubleSpinBox:
    spin = QgsDoubleSpinBox()
    spin.setDecimals(decimals)
    spin.setRange(minimum, maximum)
    spin.setSingleStep(step)
    spin.setSuffix(suffix)
    spin.setShowClearButton(False)
    spin.setKeyboardTracking(True)  # every keystroke restarts the live-update timer
    _shrinkable(spin)
    return spin


def _shrinkable(widget) -> None:
    """Let a spin box shrink below the width of its widest possible value, so the dock stays narrow."""
    widget.setAlignment(Qt.AlignmentFlag.AlignRight)
    widget.setMinimumWidth(64)
    widget.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Fixed)


def _cell(text: str, tip: str = "",
          align=Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter) -> QTableWidgetItem:
    item = QTableWidgetItem(text)
    item.setTextAlignment(int(align))
    item.setFlags(Qt.ItemFlag.ItemIsEnabled | Qt.ItemFlag.ItemIsSelectable)
    if tip:
        item.setToolTip(tip)
    return item


def _verdict_cell(kappa, verdict: str) -> QTableWidgetItem:
    accepted = verdict == "accept"
    item = _cell(f"{format_kappa(kappa)}  {'✓' if accepted else '✗'}",
                 (tr("Accept") if accepted else tr("Reject")) + tr(
                     ": κ* = λ_target / sup; every variance of the budget may grow by this factor. "
                     "Accept when κ* ≥ 1."), Qt.AlignmentFlag.AlignCenter)
    item.setBackground(QBrush(QColor(ACCEPT_COLOUR if accepted else REJECT_COLOUR)))
    item.setForeground(QBrush(QColor("white")))
    font = item.font()
    font.setBold(True)
    item.setFont(font)
    return item


def _fit_height(table: QTableWidget) -> None:
    """Fix a table's height to its rows, so the dock scrolls as a whole and no row hides."""
    table.resizeRowsToContents()
    rows = sum(table.rowHeight(r) for r in range(table.rowCount()))
    table.setFixedHeight(rows + table.horizontalHeader().sizeHint().height() + 2 * table.frameWidth())


class SensorBoundDock(QgsDockWidget):
    """The calculator; constructed by the plugin as ``SensorBoundDock(iface)``."""

    def __init__(self, iface, parent=None):
        super().__init__(tr("Sensor-bound calculator"), parent or (iface.mainWindow() if iface else None))
        self.iface = iface
        self.setObjectName("BirdsEyeSensorBoundDock")
        self.result = None
        self.full_resolution = False
        self._calibration = None  # (path, CameraModel) while the intrinsics still come from that file
        self._updating = False
        self._timer = QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(LIVE_DELAY_MS)
        self._timer.timeout.connect(self.recompute)
        self._build()
        self.apply_preset(PRESET_DEPLOYED)
        self.recompute()

    # ================================================================== layout
    def _build(self) -> None:
        body = QWidget()
        layout = QVBoxLayout(body)
        layout.setContentsMargins(6, 6, 6, 6)
        layout.setSpacing(8)
        layout.addWidget(self._camera_group())
        layout.addWidget(self._noise_group())
        layout.addWidget(self._mission_group())
        layout.addWidget(self._results_group())
        layout.addWidget(self._plot_group(), 1)
        layout.addLayout(self._buttons())
        # Shown greyed out while an input is invalid, so stale numbers are never read as current.
        self._result_widgets = (self.results_table, self.altitude_combo, self.budget_table, self.canvas,
                                self.full_button, self.processing_button)
        scroll = QScrollArea()
        scroll.setWidgetResizable(True)
        scroll.setFrameShape(QFrame.Shape.NoFrame)
        scroll.setWidget(body)
        self.setWidget(scroll)

    def _camera_group(self) -> QGroupBox:
        group = QGroupBox(tr("Camera"))
        form = QFormLayout(group)
        form.setFieldGrowthPolicy(QFormLayout.FieldGrowthPolicy.AllNonFixedFieldsGrow)
        self.preset_combo = QComboBox()
        self.preset_combo.addItems([tr(name) for name in PRESETS])
        self.preset_combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.preset_combo.setMinimumContentsLength(12)
        self.preset_combo.setToolTip(tr("A platform sets the camera and the pose-noise budget together."))
        self.preset_combo.activated.connect(lambda index: self.apply_preset(PRESETS[index]))
        form.addRow(tr("Platform"), self.preset_combo)
        self.calibration_widget = QgsFileWidget()
        self.calibration_widget.setFilter(CALIBRATION_FILE_FILTER)
        self.calibration_widget.setDialogTitle(tr("Camera calibration (Kalibr or OpenCV YAML)"))
        self.calibration_widget.setToolTip(tr("Load fx, fy, cx, cy and the image size from a Kalibr camchain "
                                              "or OpenCV YAML file."))
        self.calibration_widget.fileChanged.connect(self.load_calibration)
        form.addRow(tr("Calibration"), self.calibration_widget)

        grid = QGridLayout()
        grid.setHorizontalSpacing(6)
        self.fx_spin, self.fy_spin = (_spin(4, 1.0, 1e6, 1.0, " px") for _ in range(2))
        self.cx_spin, self.cy_spin = (_spin(4, -1e6, 1e6, 1.0, " px") for _ in range(2))
        self.width_spin, self.height_spin = QgsSpinBox(), QgsSpinBox()
        for spin in (self.width_spin, self.height_spin):
            spin.setRange(1, 100_000)
            spin.setSuffix(" px")
            spin.setShowClearButton(False)
            _shrinkable(spin)
        cells = [("f<sub>x</sub>", self.fx_spin, "Focal length along u"), ("f<sub>y</sub>", self.fy_spin,
                 "Focal length along v"), ("c<sub>x</sub>", self.cx_spin, "Principal point, u"),
                 ("c<sub>y</sub>", self.cy_spin, "Principal point, v"), (tr("Width"), self.width_spin,
                 "Image width"), (tr("Height"), self.height_spin, "Image height")]
        for k, (label, widget, tip) in enumerate(cells):
            widget.setToolTip(tr(tip) + " [px]")
            grid.addWidget(QLabel(label), k // 2, 2 * (k % 2))
            grid.addWidget(widget, k // 2, 2 * (k % 2) + 1)
            widget.valueChanged.connect(self._platform_edited)
        grid.setColumnStretch(1, 1)
        grid.setColumnStretch(3, 1)
        form.addRow(grid)
        return group

    def _noise_group(self) -> QGroupBox:
        group = QGroupBox(tr("Pose noise (1σ)"))
        group.setToolTip(TRANSLATION_CONVENTION)
        grid = QGridLayout(group)
        grid.setHorizontalSpacing(6)
        self.sigma_spins = []
        for i, (axis, unit) in enumerate(zip(AXES, SIGMA_UNITS)):
            spin = _spin(4, 0.0, 10.0, 0.001, " m") if unit == "m" else _spin(3, 0.0, 45.0, 0.01, " °")
            spin.setToolTip(tr(AXIS_TIPS[axis]))
            spin.valueChanged.connect(self._platform_edited)
            label = QLabel(f"σ {axis}")
            label.setToolTip(spin.toolTip())
            row, column = i % 3, 2 * (i // 3)
            grid.addWidget(label, row, column)
            grid.addWidget(spin, row, column + 1)
            self.sigma_spins.append(spin)
        self.mount_combo = QComboBox()
        self.mount_combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.mount_combo.setMinimumContentsLength(12)
        for index, mount in enumerate(MOUNTS):
            self.mount_combo.addItem(tr(mount.name))
            self.mount_combo.setItemData(index, mount.convention, Qt.ItemDataRole.ToolTipRole)
        self.mount_combo.setToolTip(tr("How roll, pitch and yaw turn the camera. As the method: about the camera's "
                                       "x, y and optical axes; nadir, image top towards the nose: roll and pitch "
                                       "trade places."))
        self.mount_combo.currentIndexChanged.connect(self._platform_edited)
        grid.addWidget(QLabel(tr("Mount")), 3, 0)
        grid.addWidget(self.mount_combo, 3, 1, 1, 3)
        grid.setColumnStretch(1, 1)
        grid.setColumnStretch(3, 1)
        return group

    def _mission_group(self) -> QGroupBox:
        group = QGroupBox(tr("Label tolerance and altitudes"))
        form = QFormLayout(group)
        form.setFieldGrowthPolicy(QFormLayout.FieldGrowthPolicy.AllNonFixedFieldsGrow)
        row = QHBoxLayout()
        self.tolerance_spin = _spin(1, 0.1, 1000.0, 1.0, " px")
        self.tolerance_spin.setToolTip(tr("Label radius r at 3σ: the label must stay within r px of the target."))
        self.tolerance_spin.valueChanged.connect(self._mission_edited)
        self.sigma_label = QLabel()
        self.sigma_label.setWordWrap(True)
        self.sigma_label.setToolTip(tr("σ_label = r/3: the Gaussian sigma of the soft labels "
                                       "(λ_target = σ_label²)."))
        row.addWidget(self.tolerance_spin, 1)
        row.addWidget(self.sigma_label)
        form.addRow(tr("Tolerance r (3σ)"), row)
        self.altitudes_edit = QLineEdit()
        self.altitudes_edit.setPlaceholderText(tr("e.g. 10, 20"))
        self.altitudes_edit.setToolTip(tr("Heights above the ground in metres, separated by commas."))
        self.altitudes_edit.textEdited.connect(self._mission_edited)
        form.addRow(tr("Altitudes [m]"), self.altitudes_edit)
        return group

    def _results_group(self) -> QGroupBox:
        group = QGroupBox(tr("Verdicts"))
        box = QVBoxLayout(group)
        self.status_label = QLabel()
        self.status_label.setWordWrap(True)
        self.status_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        box.addWidget(self.status_label)

        self.results_table = QTableWidget(0, 5)
        self.results_table.setHorizontalHeaderLabels(
            [tr("Altitude"), tr("sup tr Σ\n[px²]"), tr("sup λmax\n[px²]"), tr("κ* trace"), tr("κ* exact")])
        self.results_table.horizontalHeaderItem(1).setToolTip(tr("Largest trace of the label covariance over the "
                                                                 "frame (the linear, pessimistic criterion)."))
        self.results_table.horizontalHeaderItem(2).setToolTip(tr("Largest eigenvalue of the label covariance over "
                                                                 "the frame (the exact criterion)."))
        self._style_table(self.results_table)
        box.addWidget(self.results_table)

        row = QHBoxLayout()
        row.addWidget(QLabel(tr("Details for")))
        self.altitude_combo = QComboBox()
        self.altitude_combo.setToolTip(tr("The altitude whose budget table and λ_max field are shown."))
        self.altitude_combo.currentIndexChanged.connect(self._show_selected_altitude)
        row.addWidget(self.altitude_combo)
        self.worst_label = QLabel()
        self.worst_label.setWordWrap(True)
        row.addWidget(self.worst_label, 1)
        box.addLayout(row)
        self.budget_table = QTableWidget(len(AXES), 4)
        self.budget_table.setHorizontalHeaderLabels(
            [tr("Your σ"), tr("Balanced σ\n(trace)"), tr("Balanced σ\n(exact)"), tr("Share of\nerror")])
        self.budget_table.horizontalHeaderItem(2).setToolTip(tr(
            "The largest budget with no axis starved (maximum Σ log σ²) that meets the exact bound."))
        self.budget_table.horizontalHeaderItem(3).setToolTip(tr(
            "Each axis's share of the error of your budget at the worst pixel: improve the largest first."))
        self._style_table(self.budget_table)
        self.budget_table.setVerticalHeaderLabels(list(AXES))
        self.budget_table.verticalHeader().setVisible(True)
        box.addWidget(self.budget_table)
        return group

    @staticmethod
    def _style_table(table: QTableWidget) -> None:
        table.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        table.setSelectionMode(QAbstractItemView.SelectionMode.NoSelection)
        table.setFocusPolicy(Qt.FocusPolicy.NoFocus)
        table.setAlternatingRowColors(True)
        table.verticalHeader().setVisible(False)
        table.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Stretch)
        table.horizontalHeader().setDefaultAlignment(Qt.AlignmentFlag.AlignCenter)
        table.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        table.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        table.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Fixed)

    def _plot_group(self) -> QGroupBox:
        from matplotlib.backends.backend_qtagg import FigureCanvasQTAgg
        from matplotlib.figure import Figure

        group = QGroupBox(tr("λ_max field — red: the tolerance λ_target"))
        box = QVBoxLayout(group)
        box.setContentsMargins(4, 4, 4, 4)
        self.figure = Figure(figsize=(4.2, 3.2), dpi=90)
        self.canvas = FigureCanvasQTAgg(self.figure)
        self.field_plot = LmaxFieldPlot(self.figure)
        self.canvas.setMinimumHeight(270)
        self.canvas.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Expanding)
        box.addWidget(self.canvas)
        return group

    def _buttons(self) -> QGridLayout:
        grid = QGridLayout()
        self.full_button = QPushButton(tr("Evaluate every pixel"))
        self.full_button.setToolTip(tr("Re-evaluate on the full-resolution grid (stride 1 px), as the "
                                       "Processing algorithm does by default."))
        self.full_button.clicked.connect(lambda: self.recompute(full_resolution=True))
        self.sigma_button = QPushButton(tr("Use σ_label in Write labels"))
        self.sigma_button.setToolTip(tr("Store σ_label = r/3 px in the project; Write labels uses it as its "
                                        "default label sigma (SIGMA_PX)."))
        self.sigma_button.clicked.connect(self.store_sigma_label)
        self.processing_button = QPushButton(tr("Run in Processing…"))
        self.processing_button.setToolTip(tr("Open the Sensor bound algorithm with these values, to write the "
                                             "JSON results, the HTML report and the λ_max raster."))
        self.processing_button.clicked.connect(self.open_processing_dialog)
        grid.addWidget(self.full_button, 0, 0)
        grid.addWidget(self.processing_button, 0, 1)
        grid.addWidget(self.sigma_button, 1, 0, 1, 2)
        return grid

    # ================================================================== inputs
    def camera(self) -> Intrinsics:
        return Intrinsics(fx=self.fx_spin.value(), fy=self.fy_spin.value(), cx=self.cx_spin.value(),
                          cy=self.cy_spin.value(), width=self.width_spin.value(), height=self.height_spin.value())

    def sigmas(self) -> list[float]:
        return [spin.value() for spin in self.sigma_spins]

    def mount(self):
        """The chosen ``CameraMount``."""
        return MOUNTS[self.mount_combo.currentIndex()]

    def tolerance_px(self) -> float:
        return self.tolerance_spin.value()

    def altitudes(self) -> list[float]:
        """Parsed altitudes (m); raises ``InputError`` naming the field."""
        return parse_altitudes(self.altitudes_edit.text(), tr("Altitudes"))

    def sigma_label_px(self) -> float:
        """σ_label = r/3 px."""
        return label_sigma_px(self.tolerance_px())

    def apply_preset(self, name: str) -> None:
        """Set the inputs to a platform preset: camera, pose sigmas, mount, tolerance r and altitudes."""
        for preset in PLATFORMS:
            if preset.name == name:
                self._set_values(preset.camera, preset.sigmas, preset.tolerance_px, preset.altitudes_m, preset.mount)
                self._calibration = None
        self._sync_preset()
        self.schedule()

    def load_calibration(self, path: str) -> bool:
        """Take the intrinsics from a calibration file; a bad file is reported in the status line."""
        if not path:
            self._calibration = None
            return False
        try:
            camera = load_calibration(path)
        except InputError as exc:
            self._show_error(str(exc))
            return False
        self._set_values(camera)
        self._calibration = (path, camera)
        self._sync_preset()
        self.schedule()
        return True

    def _set_values(self, camera, sigmas=None, tolerance=None, altitudes=None, mount=None) -> None:
        self._updating = True
        try:
            for spin, value in ((self.fx_spin, camera.fx), (self.fy_spin, camera.fy), (self.cx_spin, camera.cx),
                                (self.cy_spin, camera.cy), (self.width_spin, camera.width),
                                (self.height_spin, camera.height)):
                spin.setValue(value)
            if sigmas is not None:
                for spin, value in zip(self.sigma_spins, sigmas):
                    spin.setValue(value)
            if tolerance is not None:
                self.tolerance_spin.setValue(tolerance)
            if altitudes is not None:
                self.altitudes_edit.setText(", ".join(f"{a:g}" for a in altitudes))
            if mount is not None:
                self.mount_combo.setCurrentIndex(MOUNTS.index(mount))
        finally:
            self._updating = False
        self._update_sigma_label()

    def _matches(self, camera) -> bool:
        mine = self.camera()
        return all(abs(getattr(mine, k) - getattr(camera, k)) <= 1e-9 * max(1.0, abs(getattr(camera, k)))
                   for k in ("fx", "fy", "cx", "cy", "width", "height"))

    def _sync_preset(self) -> None:
        """Show the platform the inputs match (camera, sigmas and mount), else Custom."""
        matching = [k for k, preset in enumerate(PLATFORMS) if self._matches(preset.camera) and all(
            abs(a - b) < 1e-9 for a, b in zip(self.sigmas(), preset.sigmas)) and self.mount() is preset.mount]
        self.preset_combo.setCurrentIndex(matching[0] if matching else PRESETS.index(PRESET_CUSTOM))
        if self._calibration is not None and not self._matches(self._calibration[1]):
            self._calibration = None
        if self._calibration is None and self.calibration_widget.filePath():
            self.calibration_widget.blockSignals(True)
            self.calibration_widget.setFilePath("")
            self.calibration_widget.blockSignals(False)

    def _platform_edited(self, *_):
        """A camera, sigma or mount value set by the user (not by a preset or a calibration file)."""
        if not self._updating:
            self._sync_preset()
            self.schedule()

    def _mission_edited(self, *_):
        if not self._updating:
            self._update_sigma_label()
            self.schedule()

    def _update_sigma_label(self) -> None:
        self.sigma_label.setText(tr("σ_label = {value:.2f} px").format(value=self.sigma_label_px()))

    # ================================================================== evaluation
    def schedule(self) -> None:
        """Re-evaluate (preview grid) once the user pauses typing."""
        self._timer.start()

    def recompute(self, full_resolution: bool = False) -> bool:
        """Evaluate the bound for the current inputs and refresh the tables and the plot.

        ``full_resolution`` uses every pixel (stride 1), otherwise the preview stride. Returns False
        (and says why in the status line) when an input is invalid.
        """
        self._timer.stop()
        try:
            camera, altitudes = self.camera(), self.altitudes()
            stride = 1 if full_resolution else stride_for(camera, PREVIEW_MAX_POINTS)
            QGuiApplication.setOverrideCursor(Qt.CursorShape.WaitCursor)
            try:
                result = evaluate_bounds(camera, altitudes, self.sigmas(), self.tolerance_px(), stride,
                                         mount=self.mount())
            finally:
                QGuiApplication.restoreOverrideCursor()
        except InputError as exc:
            self._show_error(str(exc))
            return False
        self.result, self.full_resolution = result, full_resolution
        grid = (tr("every pixel") if stride == 1
                else tr("preview grid: every {s} px and the frame edges").format(s=stride))
        self.status_label.setStyleSheet("")
        for widget in self._result_widgets:
            widget.setEnabled(True)
        self.status_label.setText(tr("λ_target = (r/3)² = {lam:.4g} px² · {grid}").format(
            lam=result["inputs"]["lambda_target_px2"], grid=grid))
        self._fill_results()
        return True

    def _show_error(self, message: str) -> None:
        self.status_label.setStyleSheet(f"color: {REJECT_COLOUR}; font-weight: bold;")
        self.status_label.setText(message)
        for widget in self._result_widgets:
            widget.setEnabled(False)

    def _fill_results(self) -> None:
        entries = self.result["altitudes"]
        table = self.results_table
        table.setRowCount(len(entries))
        for row, e in enumerate(entries):
            u, v = e["worst_pixel"]
            table.setItem(row, 0, _cell(f"{e['altitude_m']:g} m", align=Qt.AlignmentFlag.AlignCenter))
            table.setItem(row, 1, _cell(f"{e['sup_trace_px2']:.4g}"))
            table.setItem(row, 2, _cell(f"{e['sup_lmax_px2']:.4g}", tr("worst pixel ({u:.0f}, {v:.0f})").format(
                u=u, v=v)))
            table.setItem(row, 3, _verdict_cell(e["kappa_trace"], e["verdict_trace"]))
            table.setItem(row, 4, _verdict_cell(e["kappa_exact"], e["verdict_exact"]))
        _fit_height(table)
        shown = max(0, self.altitude_combo.currentIndex())
        self.altitude_combo.blockSignals(True)
        self.altitude_combo.clear()
        self.altitude_combo.addItems([f"{e['altitude_m']:g} m" for e in entries])
        self.altitude_combo.setCurrentIndex(min(shown, len(entries) - 1))
        self.altitude_combo.blockSignals(False)
        self._show_selected_altitude()

    def _show_selected_altitude(self, *_) -> None:
        if self.result is None:
            return
        entry = self.result["altitudes"][max(0, self.altitude_combo.currentIndex())]
        inputs = self.result["inputs"]
        self.worst_label.setText(tr("worst at ({u:.0f}, {v:.0f})").format(
            u=entry["worst_pixel"][0], v=entry["worst_pixel"][1]))
        share_max = max(entry["budget_share"])
        for row, (unit, mine, trace, exact, share) in enumerate(zip(
                SIGMA_UNITS, inputs["sigmas"], entry["balanced_trace_sigma"], entry["balanced_exact_sigma"],
                entry["budget_share"])):
            share_item = _cell(f"{100.0 * share:.1f} %")
            if share_max > 0 and share == share_max:
                font = QFont(share_item.font())
                font.setBold(True)
                share_item.setFont(font)
            for column, item in enumerate((_cell(format_sigma(mine, unit)), _cell(format_sigma(trace, unit)),
                                           _cell(format_sigma(exact, unit)), share_item)):
                self.budget_table.setItem(row, column, item)
        _fit_height(self.budget_table)
        self._draw_plot(entry)

    def _draw_plot(self, entry: dict) -> None:
        inputs = self.result["inputs"]
        self.field_plot.update(Intrinsics(**inputs["intrinsics"]), entry["altitude_m"], inputs["sigmas"],
                               inputs["tolerance_px"], worst_pixel=entry["worst_pixel"],
                               mount=camera_mount(inputs["mount"]))
        self.canvas.draw_idle()

    # ================================================================== hand-over
    def store_sigma_label(self) -> float:
        """Store σ_label = r/3 px in the current project for ``writelabels`` (see qgis_io.project_settings)."""
        sigma = self.sigma_label_px()
        store_sigma_label_px(QgsProject.instance(), sigma)
        if self.iface is not None:
            self.iface.messageBar().pushMessage(
                LOG_TAG, tr("σ_label = {s:.2f} px stored in the project: Write labels will use it as its label "
                               "sigma (project variable @birdseye_sigma_label_px).").format(s=sigma),
                Qgis.MessageLevel.Success, 6)
        return sigma

    def processing_parameters(self) -> dict:
        """The dock's inputs as ``birdseye:sensorbound`` parameters."""
        camera = self.camera()
        parameters = {
            "FX": camera.fx, "FY": camera.fy, "CX": camera.cx, "CY": camera.cy,
            "WIDTH": camera.width, "HEIGHT": camera.height,
            "ALTITUDES": self.altitudes_edit.text().strip(), "SIGMAS": format_number_list(self.sigmas()),
            "MOUNT": MOUNTS.index(self.mount()),
            "TOLERANCE_PX": self.tolerance_px(), "STRIDE_PX": 1,
        }
        if self._calibration is not None:
            parameters["CALIBRATION"] = str(Path(self._calibration[0]))
        return parameters

    def open_processing_dialog(self) -> None:
        import processing  # QGIS's Processing framework: this plugin's own package is only imported relatively

        processing.execAlgorithmDialog(SENSOR_BOUND_ALG, self.processing_parameters())
