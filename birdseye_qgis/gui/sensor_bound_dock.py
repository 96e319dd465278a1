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

import html
from pathlib import Path

from qgis.gui import QgsDockWidget, QgsDoubleSpinBox, QgsFileWidget, QgsSpinBox
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP, Qt, QTimer
from qgis.PyQt.QtGui import QBrush, QColor, QFont, QGuiApplication
from qgis.PyQt.QtWidgets import (
    QAbstractItemView,
    QAbstractSpinBox,
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

from ..__about__ import tr
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

SENSOR_BOUND_ALG = "birdseye:sensorbound"
WRITE_LABELS_ALG = "birdseye:writelabels"
PRESET_DEPLOYED = DEPLOYED.name
PRESET_CUSTOM = "Custom"
PRESETS = tuple(p.name for p in PLATFORMS) + (PRESET_CUSTOM,)
#: Names shorter than the platform's, where its own would not fit a dock (the item's tooltip gives it whole).
PRESET_LABELS = {"dji_metadata": QT_TRANSLATE_NOOP("@default", "DJI RTK drone, poses from photos")}
LIVE_DELAY_MS = 250
#: The narrowest the dock gets (QGIS's usual dock width): every field, header and cell fits it
#: (tests/gui/test_docks_desktop.py looks).
MINIMUM_WIDTH = 360
PREVIEW_MAX_POINTS = 150_000
AXIS_TIPS = {
    "x": QT_TRANSLATE_NOOP("@default", "Horizontal position error across the flight direction (image right), metres."),
    "y": QT_TRANSLATE_NOOP("@default", "Horizontal position error along the flight direction (image down), metres."),
    "z": QT_TRANSLATE_NOOP("@default", "Vertical position / altimeter error (along the optical axis), metres."),
    "roll": QT_TRANSLATE_NOOP("@default", "Roll attitude error, degrees; the camera mount says which way it turns "
                                          "the camera."),
    "pitch": QT_TRANSLATE_NOOP("@default", "Pitch attitude error, degrees; the camera mount says which way it turns "
                                           "the camera."),
    "yaw": QT_TRANSLATE_NOOP("@default", "Heading error (about the vertical / optical axis), degrees."),
}
#: The axes in words, their symbol after (the pose-noise labels) and alone (the budget table's rows, whose
#: tooltips give the symbol).
AXIS_NAMES = {"x": QT_TRANSLATE_NOOP("@default", "Across (x)"), "y": QT_TRANSLATE_NOOP("@default", "Along (y)"),
              "z": QT_TRANSLATE_NOOP("@default", "Height (z)"), "roll": QT_TRANSLATE_NOOP("@default", "Roll"),
              "pitch": QT_TRANSLATE_NOOP("@default", "Pitch"), "yaw": QT_TRANSLATE_NOOP("@default", "Yaw")}
AXIS_WORDS = {"x": QT_TRANSLATE_NOOP("@default", "Across"), "y": QT_TRANSLATE_NOOP("@default", "Along"),
              "z": QT_TRANSLATE_NOOP("@default", "Height"), "roll": QT_TRANSLATE_NOOP("@default", "Roll"),
              "pitch": QT_TRANSLATE_NOOP("@default", "Pitch"), "yaw": QT_TRANSLATE_NOOP("@default", "Yaw")}
#: Short names of the camera mounts for the dock's narrow combo box; each item's tooltip spells the mount out.
MOUNT_NAMES = {"method": QT_TRANSLATE_NOOP("@default", "As the method"),
               "nadir_top_forward": QT_TRANSLATE_NOOP("@default", "Nadir, image top forward")}
#: What the numbers mean, for the tooltips of the results table and the note under it.
SPREAD_TIP = QT_TRANSLATE_NOOP("@default", "The spread of a label is the variance of where pose noise moves it, in "
                                           "square pixels (px²): its standard deviation squared.")
TOTAL_TIP = QT_TRANSLATE_NOOP("@default", "Total spread, sup tr Σ: the largest sum of the spreads along u and v over "
                                          "the image (px²), the trace of the label covariance Σ. Quick to check and "
                                          "pessimistic: it is never smaller than the largest spread.")
LARGEST_TIP = QT_TRANSLATE_NOOP("@default", "Largest spread, sup λmax: the largest spread in the worst direction over "
                                            "the image (px²), the largest eigenvalue λmax of the label covariance Σ. "
                                            "This is what the tolerance limits.")
TRACE_BOUND_TIP = QT_TRANSLATE_NOOP("@default", "Trace bound: safety factor κ* = λ_target / total spread. Sufficient "
                                                "but pessimistic: when it accepts, the exact bound accepts too.")
EXACT_BOUND_TIP = QT_TRANSLATE_NOOP("@default", "Exact bound: safety factor κ* = λ_target / largest spread, the exact "
                                                "eigenvalue bound. Accept (✓) when κ* ≥ 1: every variance of the pose "
                                                "noise may grow by κ* (every σ by √κ*) and labels still stay within "
                                                "their tolerance.")


def _spin(decimals: int, minimum: float, maximum: float, step: float, suffix: str,
          arrows: bool = True) -> QgsDoubleSpinBox:
    spin = QgsDoubleSpinBox()
    spin.setDecimals(decimals)
    spin.setRange(minimum, maximum)
    spin.setSingleStep(step)
    spin.setSuffix(suffix)
    spin.setShowClearButton(False)
    spin.setKeyboardTracking(True)  # every keystroke restarts the live-update timer
    _shrinkable(spin, arrows)
    return spin


def _shrinkable(widget, arrows: bool = True) -> None:
    """Let a spin box shrink below the width of its widest possible value, so the dock stays narrow.

    Without ``arrows`` (values one types, such as a focal length to 0.0001 px) the arrows' room goes to the text.
    """
    widget.setAlignment(Qt.AlignmentFlag.AlignRight)
    widget.setMinimumWidth(64)
    widget.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Fixed)
    if not arrows:
        widget.setButtonSymbols(QAbstractSpinBox.ButtonSymbols.NoButtons)


def _form(group: QGroupBox) -> QFormLayout:
    """A form whose fields go under their label when the dock is too narrow for both on one line."""
    form = QFormLayout(group)
    form.setFieldGrowthPolicy(QFormLayout.FieldGrowthPolicy.AllNonFixedFieldsGrow)
    form.setRowWrapPolicy(QFormLayout.RowWrapPolicy.WrapLongRows)
    return form


def _pair(first, second, between: str = "") -> QWidget:
    """Two fields side by side in one form row (``between``: a word or sign set between them)."""
    row = QWidget()
    box = QHBoxLayout(row)
    box.setContentsMargins(0, 0, 0, 0)
    box.addWidget(first, 1)
    if between:
        box.addWidget(QLabel(between))
    box.addWidget(second, 1)
    return row


def sigma_text(value: float, unit: str) -> str:
    """A sigma for the narrow budget table, to about three significant digits: metres in millimetres below 1 m
    (0.1 mm below 10 cm; a thin space before the unit), degrees to 0.001°."""
    if unit != "m":
        return f"{value:.3f}°"
    if value >= 1.0:
        return f"{value:.2f}\u2009m"
    return f"{1000.0 * value:.{1 if value < 0.1 else 0}f}\u2009mm"


def spread_text(px2: float) -> str:
    """A spread (px²) to three significant digits, without an exponent below 10⁶ px²."""
    return f"{px2:.3g}" if px2 < 1000 else f"{px2:,.0f}".replace(",", "\u2009")


def summary_line(entry: dict) -> str:
    """The exact bound's verdict at one altitude, in words (rich text)."""
    accepted = entry["verdict_exact"] == "accept"
    verdict = (tr("✓ labels stay within their tolerance") if accepted
               else tr("✗ labels leave their tolerance"))
    return tr("<b>{altitude} m</b>: <span style='color:{colour}'><b>{verdict}</b></span> (safety factor κ* {kappa})"
              ).format(altitude=f"{entry['altitude_m']:g}", colour=ACCEPT_COLOUR if accepted else REJECT_COLOUR,
                       verdict=verdict, kappa=format_kappa(entry["kappa_exact"]))


def where_in_frame(u: float, v: float, width: int, height: int) -> str:
    """Where a pixel lies, in words: a corner, an edge or inside the frame."""
    side_u = tr("left") if u <= 0 else tr("right") if u >= width - 1 else ""
    side_v = tr("top") if v <= 0 else tr("bottom") if v >= height - 1 else ""
    if side_u and side_v:
        return tr("the {v}-{u} corner").format(v=side_v, u=side_u)
    if side_u or side_v:
        return tr("the {side} edge").format(side=side_u or side_v)
    return tr("inside the frame")


def _cell(text: str, tip: str = "",
          align=Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter) -> QTableWidgetItem:
    item = QTableWidgetItem(text)
    item.setTextAlignment(int(align))
    item.setFlags(Qt.ItemFlag.ItemIsEnabled | Qt.ItemFlag.ItemIsSelectable)
    if tip:
        item.setToolTip(tip)
    return item


def kappa_text(kappa) -> str:
    """κ* for a narrow cell: three significant digits from 0.01 to 999, beyond that only which side it is."""
    if kappa is None:
        return "∞"   # a zero budget
    if kappa < 0.01:
        return "< 0.01"
    return "> 999" if kappa >= 999.5 else format_kappa(kappa)


def _verdict_cell(kappa, verdict: str, bound_tip: str) -> QTableWidgetItem:
    accepted = verdict == "accept"
    item = _cell(f"{kappa_text(kappa)} {'✓' if accepted else '✗'}",
                 (tr("Accepted: κ* = {k}") if accepted else tr("Rejected: κ* = {k}")).format(k=format_kappa(kappa))
                 + ". " + bound_tip, Qt.AlignmentFlag.AlignCenter)
    item.setBackground(QBrush(QColor(ACCEPT_COLOUR if accepted else REJECT_COLOUR)))
    item.setForeground(QBrush(QColor("white")))
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
        self.setMinimumWidth(MINIMUM_WIDTH)
        self.apply_preset(PRESET_DEPLOYED)
        self.recompute()

    # ================================================================== layout
    def _build(self) -> None:
        body = QWidget()
        layout = QVBoxLayout(body)
        layout.setContentsMargins(6, 6, 6, 6)
        layout.setSpacing(8)
        # The answer first, above the inputs: on a laptop screen the tables are a scroll away.
        self.summary_label = QLabel()
        self.summary_label.setObjectName("boundSummary")
        self.summary_label.setWordWrap(True)
        self.summary_label.setTextFormat(Qt.TextFormat.RichText)
        self.summary_label.setToolTip(tr(EXACT_BOUND_TIP))
        layout.addWidget(self.summary_label)
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
        form = _form(group)
        self.preset_combo = QComboBox()
        for index, preset in enumerate(PLATFORMS):
            self.preset_combo.addItem(tr(PRESET_LABELS.get(preset.key, preset.name)))
            self.preset_combo.setItemData(index, tr(preset.name), Qt.ItemDataRole.ToolTipRole)
        self.preset_combo.addItem(tr(PRESET_CUSTOM))
        # As wide as the longest name: where the dock is narrower, the form puts it under its label.
        self.preset_combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToContents)
        self.preset_combo.setToolTip(tr("A platform sets the camera and the pose-noise budget together."))
        self.preset_combo.activated.connect(lambda index: self.apply_preset(PRESETS[index]))
        form.addRow(tr("Platform"), self.preset_combo)
        self.calibration_widget = QgsFileWidget()
        self.calibration_widget.setFilter(CALIBRATION_FILE_FILTER)
        self.calibration_widget.setDialogTitle(tr("Camera calibration (Kalibr or OpenCV YAML)"))
        self.calibration_widget.setToolTip(tr("Load fx, fy, cx, cy and the image size from a Kalibr camchain "
                                              "or OpenCV YAML file."))
        self.calibration_widget.lineEdit().setPlaceholderText(tr("a Kalibr or OpenCV YAML file"))
        self.calibration_widget.fileChanged.connect(self.load_calibration)
        form.addRow(tr("Calibration"), self.calibration_widget)

        self.fx_spin, self.fy_spin = (_spin(4, 1.0, 1e6, 1.0, " px", arrows=False) for _ in range(2))
        self.cx_spin, self.cy_spin = (_spin(4, -1e6, 1e6, 1.0, " px", arrows=False) for _ in range(2))
        self.width_spin, self.height_spin = QgsSpinBox(), QgsSpinBox()
        for spin in (self.width_spin, self.height_spin):
            spin.setRange(1, 100_000)
            spin.setSuffix(" px")
            spin.setShowClearButton(False)
            _shrinkable(spin, arrows=False)
        for widget, tip in ((self.fx_spin, tr("Focal length fx: along u (image right), in pixels")),
                            (self.fy_spin, tr("Focal length fy: along v (image down), in pixels")),
                            (self.cx_spin, tr("Principal point cx: where the optical axis meets the image, u (px)")),
                            (self.cy_spin, tr("Principal point cy: where the optical axis meets the image, v (px)")),
                            (self.width_spin, tr("Image width W (px)")), (self.height_spin, tr("Image height H (px)"))):
            widget.setToolTip(tip)
            widget.valueChanged.connect(self._platform_edited)
        for label, first, second, between, tip in (
                (tr("Focal length"), self.fx_spin, self.fy_spin, "", tr("fx, fy (px)")),
                (tr("Principal point"), self.cx_spin, self.cy_spin, "", tr("cx, cy (px)")),
                (tr("Image size"), self.width_spin, self.height_spin, "×", tr("width × height (px)"))):
            name = QLabel(label)
            name.setToolTip(tip)
            form.addRow(name, _pair(first, second, between))
        return group

    def _noise_group(self) -> QGroupBox:
        group = QGroupBox(tr("Pose noise, one standard deviation (1σ)"))
        group.setToolTip(TRANSLATION_CONVENTION)
        grid = QGridLayout(group)
        grid.setHorizontalSpacing(6)
        self.sigma_spins = []
        for i, (axis, unit) in enumerate(zip(AXES, SIGMA_UNITS)):
            spin = _spin(4, 0.0, 10.0, 0.001, " m") if unit == "m" else _spin(3, 0.0, 45.0, 0.01, " °")
            spin.setToolTip(tr(AXIS_TIPS[axis]))
            spin.valueChanged.connect(self._platform_edited)
            label = QLabel(tr(AXIS_NAMES[axis]))
            label.setToolTip(spin.toolTip())
            row, column = i % 3, 2 * (i // 3)
            grid.addWidget(label, row, column)
            grid.addWidget(spin, row, column + 1)
            self.sigma_spins.append(spin)
        self.mount_combo = QComboBox()
        self.mount_combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.mount_combo.setMinimumContentsLength(12)
        for index, mount in enumerate(MOUNTS):
            self.mount_combo.addItem(tr(MOUNT_NAMES[mount.key]))
            self.mount_combo.setItemData(index, f"{tr(mount.name)}. {mount.convention}", Qt.ItemDataRole.ToolTipRole)
        self.mount_combo.setToolTip(tr("How roll, pitch and yaw turn the camera. As the method: about the camera's "
                                       "x, y and optical axes; nadir, image top towards the nose: roll and pitch "
                                       "trade places."))
        self.mount_combo.currentIndexChanged.connect(self._platform_edited)
        mount_label = QLabel(tr("Mount"))
        mount_label.setToolTip(self.mount_combo.toolTip())
        grid.addWidget(mount_label, 3, 0)
        grid.addWidget(self.mount_combo, 3, 1, 1, 3)
        grid.setColumnStretch(1, 1)
        grid.setColumnStretch(3, 1)
        return group

    def _mission_group(self) -> QGroupBox:
        group = QGroupBox(tr("Label tolerance and altitudes"))
        form = _form(group)
        self.tolerance_spin = _spin(1, 0.1, 1000.0, 1.0, " px")
        self.tolerance_spin.setToolTip(tr("Label tolerance: the radius r, in pixels, within which a label must stay "
                                          "around its target, at 3σ (99.7 % of the time)."))
        self.tolerance_spin.valueChanged.connect(self._mission_edited)
        tolerance_label = QLabel(tr("Label radius r (3σ)"))
        tolerance_label.setToolTip(self.tolerance_spin.toolTip())
        form.addRow(tolerance_label, self.tolerance_spin)
        self.sigma_label = QLabel()
        self.sigma_label.setWordWrap(True)
        self.sigma_label.setToolTip(tr("σ_label = r/3: the Gaussian sigma of the soft labels Write labels draws; "
                                       "its square λ_target = σ_label² is the spread a label may have."))
        form.addRow(self.sigma_label)
        self.altitudes_edit = QLineEdit()
        self.altitudes_edit.setPlaceholderText(tr("e.g. 10, 20"))
        self.altitudes_edit.setToolTip(tr("Heights above the ground in metres, separated by commas."))
        self.altitudes_edit.textEdited.connect(self._mission_edited)
        altitudes_label = QLabel(tr("Altitudes (m)"))
        altitudes_label.setToolTip(self.altitudes_edit.toolTip())
        form.addRow(altitudes_label, self.altitudes_edit)
        return group

    def _results_group(self) -> QGroupBox:
        group = QGroupBox(tr("Verdicts"))
        box = QVBoxLayout(group)
        box.setContentsMargins(2, 6, 2, 6)   # the tables need the width
        self.status_label = QLabel()
        self.status_label.setWordWrap(True)
        self.status_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        box.addWidget(self.status_label)

        self.results_table = QTableWidget(0, 5)
        self.results_table.setHorizontalHeaderLabels(
            [tr("Altitude"), tr("Total\nspread"), tr("Largest\nspread"), tr("Trace\nbound"), tr("Exact\nbound")])
        for column, tip in enumerate((tr("Height above the ground."), tr(TOTAL_TIP), tr(LARGEST_TIP),
                                      tr(TRACE_BOUND_TIP), tr(EXACT_BOUND_TIP))):
            self.results_table.horizontalHeaderItem(column).setToolTip(tip)
        self._style_table(self.results_table)
        for column in (0, 1, 2):   # short numbers; the verdicts take the rest
            self.results_table.horizontalHeader().setSectionResizeMode(column, QHeaderView.ResizeMode.ResizeToContents)
        box.addWidget(self.results_table)
        note = QLabel(tr("Spread: how far pose noise scatters a label, in px² (a variance). Bounds: the safety "
                         "factor κ* by which the pose noise may grow, ✓ when κ* ≥ 1; the exact bound decides, the "
                         "trace bound is a quicker, pessimistic check."))
        note.setWordWrap(True)
        note.setStyleSheet("color:#555;")
        note.setToolTip(tr(SPREAD_TIP))
        box.addWidget(note)

        row = QHBoxLayout()
        details = QLabel(tr("Details for"))
        row.addWidget(details)
        self.altitude_combo = QComboBox()
        self.altitude_combo.setToolTip(tr("The altitude whose budget table and spread map are shown."))
        self.altitude_combo.currentIndexChanged.connect(self._show_selected_altitude)
        row.addWidget(self.altitude_combo)
        row.addStretch(1)
        box.addLayout(row)
        self.worst_label = QLabel()
        self.worst_label.setWordWrap(True)
        self.worst_label.setToolTip(tr("The pixel (u, v) where the largest spread occurs; pixel (0, 0) is the "
                                       "centre of the top-left pixel."))
        box.addWidget(self.worst_label)
        self.budget_table = QTableWidget(len(AXES), 4)
        self.budget_table.setHorizontalHeaderLabels(
            [tr("Your σ"), tr("Balanced\ntrace"), tr("Balanced\nexact"), tr("Share of\nerror")])
        for column, tip in enumerate((
                tr("The pose noise you entered (1σ)."),
                tr("The largest budget with no axis starved (maximum Σ log σ²) that meets the trace bound: "
                   "each axis takes a sixth of it."),
                tr("The largest budget with no axis starved (maximum Σ log σ²) that meets the exact bound."),
                tr("Each axis's share of the error of your budget at the worst pixel: improve the largest "
                   "first."))):
            self.budget_table.horizontalHeaderItem(column).setToolTip(tip)
        self._style_table(self.budget_table)
        self.budget_table.horizontalHeader().setSectionResizeMode(3, QHeaderView.ResizeMode.ResizeToContents)
        self.budget_table.setVerticalHeaderLabels([tr(AXIS_WORDS[axis]) for axis in AXES])
        for row_index, axis in enumerate(AXES):
            self.budget_table.verticalHeaderItem(row_index).setToolTip(f"{axis}: {tr(AXIS_TIPS[axis])}")
        self.budget_table.verticalHeader().setVisible(True)
        box.addWidget(self.budget_table)
        return group

    @staticmethod
    def _style_table(table: QTableWidget) -> None:
        table.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        table.setSelectionMode(QAbstractItemView.SelectionMode.NoSelection)
        table.setFocusPolicy(Qt.FocusPolicy.NoFocus)
        table.setAlternatingRowColors(True)
        table.setWordWrap(False)
        table.verticalHeader().setVisible(False)
        table.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Stretch)
        table.horizontalHeader().setDefaultAlignment(Qt.AlignmentFlag.AlignCenter)
        table.horizontalHeader().setMinimumSectionSize(24)
        table.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        table.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        table.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Fixed)

    def _plot_group(self) -> QGroupBox:
        import warnings

        with warnings.catch_warnings():
            # A pip matplotlib beside the system's reports that 3-D plots are unavailable; this one is 2-D.
            warnings.filterwarnings("ignore", message="Unable to import Axes3D")
            from matplotlib.backends.backend_qtagg import FigureCanvasQTAgg
            from matplotlib.figure import Figure

        group = QGroupBox(tr("Spread over the image"))
        box = QVBoxLayout(group)
        box.setContentsMargins(4, 4, 4, 4)
        caption = QLabel(tr("The largest spread λmax (px²) at each pixel; red: the tolerance λ_target, ○ the worst "
                            "pixel, + the principal point."))
        caption.setWordWrap(True)
        caption.setStyleSheet("color:#555;")
        box.addWidget(caption)
        self.figure = Figure(figsize=(4.2, 3.2), dpi=90)
        self.canvas = FigureCanvasQTAgg(self.figure)
        self.field_plot = LmaxFieldPlot(self.figure)
        self.field_plot.legend.set_visible(False)   # the caption names the marks: the legend is wider than a dock
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
        self.sigma_button = QPushButton(tr("Write labels with this σ…"))
        self.sigma_button.setToolTip(tr("Open Write labels with its label sigma (SIGMA_PX) set to σ_label = r/3 px "
                                        "from this tolerance; you see the value before you run it."))
        self.sigma_button.clicked.connect(self.open_write_labels)
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
        """The intrinsics shown; those of the calibration file, to every digit, while they come from one."""
        if self._calibration is not None:
            camera = self._calibration[1]
            return Intrinsics(fx=camera.fx, fy=camera.fy, cx=camera.cx, cy=camera.cy, width=camera.width,
                              height=camera.height)
        return self._shown_camera()

    def _shown_camera(self) -> Intrinsics:
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

    def preset(self) -> str:
        """The name of the platform the inputs are (``PRESET_CUSTOM`` when they are none of them)."""
        return PRESETS[self.preset_combo.currentIndex()]

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
        """True when the spins show ``camera``, to the digits they show (a file may hold more)."""
        spins = {"fx": self.fx_spin, "fy": self.fy_spin, "cx": self.cx_spin, "cy": self.cy_spin,
                 "width": self.width_spin, "height": self.height_spin}
        return all(abs(spin.value() - getattr(camera, key)) <= 0.5 * 10.0 ** -getattr(spin, "decimals", int)()
                   for key, spin in spins.items())

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
        self.sigma_label.setText(tr("Label sigma σ_label = r/3 = {value:.2f} px").format(value=self.sigma_label_px()))

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
                else tr("a preview: every {s} px and the frame edges").format(s=stride))
        self.status_label.setStyleSheet("")
        for widget in self._result_widgets:
            widget.setEnabled(True)
        self.status_label.setText(tr("A label may spread λ_target = (r/3)² = {lam:.4g} px². Evaluated at {grid}.")
                                  .format(lam=result["inputs"]["lambda_target_px2"], grid=grid))
        self._fill_results()
        return True

    def _show_error(self, message: str) -> None:
        self.status_label.setStyleSheet(f"color: {REJECT_COLOUR}; font-weight: bold;")
        self.status_label.setText(message)
        self.summary_label.setText(f"<span style='color:{REJECT_COLOUR}'><b>"
                                   + tr("Cannot evaluate:") + f"</b> {html.escape(message)}</span>")
        for widget in self._result_widgets:
            widget.setEnabled(False)

    def _fill_results(self) -> None:
        entries = self.result["altitudes"]
        self.summary_label.setText("<br>".join(summary_line(e) for e in entries))
        table = self.results_table
        table.setRowCount(len(entries))
        for row, e in enumerate(entries):
            (u, v), (ut, vt) = e["worst_pixel"], e["worst_pixel_trace"]
            table.setItem(row, 0, _cell(f"{e['altitude_m']:g} m", align=Qt.AlignmentFlag.AlignCenter))
            table.setItem(row, 1, _cell(spread_text(e["sup_trace_px2"]), tr(
                "sup tr Σ = {value:.6g} px² at pixel ({u:.0f}, {v:.0f})").format(value=e["sup_trace_px2"], u=ut,
                                                                                 v=vt)))
            table.setItem(row, 2, _cell(spread_text(e["sup_lmax_px2"]), tr(
                "sup λmax = {value:.6g} px² at pixel ({u:.0f}, {v:.0f})").format(value=e["sup_lmax_px2"], u=u, v=v)))
            table.setItem(row, 3, _verdict_cell(e["kappa_trace"], e["verdict_trace"], tr(TRACE_BOUND_TIP)))
            table.setItem(row, 4, _verdict_cell(e["kappa_exact"], e["verdict_exact"], tr(EXACT_BOUND_TIP)))
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
        u, v = entry["worst_pixel"]
        size = inputs["intrinsics"]
        self.worst_label.setText(tr("Worst pixel ({u:.0f}, {v:.0f}): {where}.").format(
            u=u, v=v, where=where_in_frame(u, v, size["width"], size["height"])))
        share_max = max(entry["budget_share"])
        for row, (unit, mine, trace, exact, share) in enumerate(zip(
                SIGMA_UNITS, inputs["sigmas"], entry["balanced_trace_sigma"], entry["balanced_exact_sigma"],
                entry["budget_share"])):
            share_item = _cell(f"{100.0 * share:.1f} %")
            if share_max > 0 and share == share_max:
                font = QFont(share_item.font())
                font.setBold(True)
                share_item.setFont(font)
            for column, item in enumerate((_cell(sigma_text(mine, unit), format_sigma(mine, unit)),
                                           _cell(sigma_text(trace, unit), format_sigma(trace, unit)),
                                           _cell(sigma_text(exact, unit), format_sigma(exact, unit)), share_item)):
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
    def open_write_labels(self) -> None:
        """Open ``birdseye:writelabels`` with SIGMA_PX = σ_label = r/3 px: the hand-over is a parameter value the
        user sees in the dialog, never a value kept out of sight that would change a result."""
        import processing  # QGIS's Processing framework: this plugin's own package is only imported relatively

        processing.execAlgorithmDialog(WRITE_LABELS_ALG, {"SIGMA_PX": round(self.sigma_label_px(), 2)})

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
