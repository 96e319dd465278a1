"""The review dock: walk through detection clusters beside the survey and record verdicts.

What it shows comes from the core: review units, ordering, propagation, chips and digests from
``core.review``; PRE and POST scores from ``core.scoring.evaluate_flights`` — the function behind
``birdseye:evaluatedetections``, fed with the same layers and the same verdict table, so the dock and
the algorithm agree to the last digit. Storage is ``review_store``: every verdict is committed in its own
transaction before the dock moves on, and reopening the project resumes where the reviewer stopped.

Keyboard (when the review area has the focus): 1 / C confirmed real, 2 / H hard negative,
3 / U uncertain, 0 / Backspace unreviewed, N / → next, P / ← previous, Home / End first / last,
Ctrl+Z undo, A add a missed target on the map (Esc cancels).
"""
from __future__ import annotations

import getpass
import json
import time
from collections import OrderedDict

import numpy as np

from qgis.core import (Qgis, QgsCoordinateReferenceSystem, QgsCoordinateTransform, QgsMapLayerProxyModel,
                       QgsMessageLog, QgsPointXY, QgsProject, QgsRectangle, QgsSettings, QgsVectorLayer, QgsWkbTypes)
from qgis.gui import (QgsCheckableComboBox, QgsCollapsibleGroupBox, QgsDockWidget, QgsDoubleSpinBox, QgsFileWidget,
                      QgsMapLayerComboBox, QgsSpinBox, QgsVertexMarker)
from qgis.PyQt.QtCore import (QAbstractTableModel, QCoreApplication, QEvent, QModelIndex, QObject, QRunnable, Qt,
                              QThreadPool, QTimer, pyqtSignal)
from qgis.PyQt.QtGui import QColor, QFont, QImage, QPixmap
from qgis.PyQt.QtWidgets import (QAbstractItemView, QApplication, QCheckBox, QComboBox, QFormLayout, QFrame,
                                 QGridLayout, QHBoxLayout, QHeaderView, QLabel, QLineEdit, QProgressBar, QPushButton,
                                 QScrollArea, QSizePolicy, QTableView, QTableWidget, QTableWidgetItem, QToolButton,
                                 QVBoxLayout, QWidget)

from qgis.PyQt import sip

from ..core.detect.clustering import DEFAULT_DEDUP_CM
from ..core.review.actions import REVIEW_VERDICTS, UnitStatus, resume_key, unit_status
from ..core.review.chips import DEFAULT_WINDOW_PX, FrameIndex, GEOTAG_COLOUR, ImageCache, LAYER_COLOURS, load_chips, plan_point_chips, plan_unit_chips
from ..core.review.digests import InputCheck, check_inputs
from ..core.review.units import ADDED_PREFIX, PROPAGATION_EPS_M, PROPAGATION_RULE, ReviewParameters, ReviewUnits, build_units
from ..core.errors import InputError
from ..core.scoring.evaluation import Flight, evaluate_flights
from ..core.scoring.operating_point import OperatingPoint
from ..core.scoring.verdicts import CONVENTIONS
from ..qgis_io.review_store import ReviewSession, RowMeta, VerdictStore, default_store_path, read_review_inputs
from .add_target_tool import AddTargetTool

LOG_TAG = "BirdsEye"
PROJECT_SCOPE = "BirdsEye"
SETTINGS_REVIEWER = "birdseye/review/reviewer"
PREFETCH_AHEAD = 3
CHIP_CACHE_UNITS = 64
CHIP_DISPLAY_PX = 150
SCORE_DELAY_MS = 120
DEFAULT_SCALE = 100

VERDICT_COLOURS = {"confirmed_real": "#2e7d32", "hard_negative": "#c62828", "uncertain": "#ef8f00",
                   "unreviewed": "#757575", "added": "#00897b"}
VERDICT_TEXT = {"confirmed_real": "Confirmed real", "hard_negative": "Hard negative", "uncertain": "Uncertain",
                "unreviewed": "Unreviewed", "added": "Added target"}
CONVENTION_TEXT = {"positive_wins": "positive-wins", "majority_wins": "majority-wins",
                   "hard_negative_wins": "hard-negative-wins"}
FILTERS = [("all", "All units"), ("todo", "To review (no vote yet)"), ("confirmed_real", "Confirmed real"),
           ("hard_negative", "Hard negative"), ("uncertain", "Uncertain"),
           ("propagated", "Propagated votes only"), ("conflict", "Conventions disagree"),
           ("unmatched", "No geotag nearby"), ("added", "Added targets")]

# Keys → command; digits also arrive with the keypad modifier.
KEYMAP = {Qt.Key_1: "confirmed_real", Qt.Key_C: "confirmed_real", Qt.Key_2: "hard_negative",
          Qt.Key_H: "hard_negative", Qt.Key_3: "uncertain", Qt.Key_U: "uncertain", Qt.Key_0: "unreviewed",
          Qt.Key_Backspace: "unreviewed", Qt.Key_N: "next", Qt.Key_Right: "next", Qt.Key_P: "previous",
          Qt.Key_Left: "previous", Qt.Key_Home: "first", Qt.Key_End: "last", Qt.Key_A: "add",
          Qt.Key_Escape: "cancel_add"}


def tr(text: str) -> str:
    return QCoreApplication.translate("ReviewDock", text)


def _fmt(value, digits=3) -> str:
    return "–" if value is None else f"{value:.{digits}f}"


# ====================================================================================== workers
class _Signals(QObject):
    """Carries worker results to the UI thread (parentless: workers keep it alive)."""

    chips_ready = pyqtSignal(int, str, object)
    scores_ready = pyqtSignal(int, object)


class _ChipJob(QRunnable):
    def __init__(self, signals, generation, key, plan_fn, out_px, cache):
        super().__init__()
        self.signals, self.generation, self.key = signals, generation, key
        self.plan_fn, self.out_px, self.cache = plan_fn, out_px, cache

    def run(self):
        try:
            plans, n_frames = self.plan_fn(self.key)
            images = load_chips(plans, self.out_px, self.cache)
            payload = (plans, images, n_frames, None)
        except Exception as exc:  # noqa: BLE001 — report in the dock, never kill the worker thread
            payload = ([], [], 0, str(exc))
        self.signals.chips_ready.emit(self.generation, self.key, payload)


class _ScoreJob(QRunnable):
    def __init__(self, signals, generation, flights, geotags, op, log):
        super().__init__()
        self.signals, self.generation = signals, generation
        self.flights, self.geotags, self.op, self.log = flights, geotags, op, log

    def run(self):
        try:
            result = {f.name: evaluate_flights([f], self.geotags, self.op, self.log).to_dict() for f in self.flights}
        except Exception as exc:  # noqa: BLE001
            result = exc
        self.signals.scores_ready.emit(self.generation, result)


# ====================================================================================== unit table
class UnitTableModel(QAbstractTableModel):
    HEADERS = ["#", "Verdict", "Geotag", "Frames", "Score"]

    def __init__(self, dock):
        super().__init__()
        self.dock = dock
        self.keys: list[str] = []

    def set_keys(self, keys):
        self.beginResetModel()
        self.keys = list(keys)
        self.endResetModel()

    def refresh(self):
        if self.keys:
            self.dataChanged.emit(self.index(0, 0), self.index(len(self.keys) - 1, len(self.HEADERS) - 1))

    def rowCount(self, parent=QModelIndex()):  # noqa: N802
        return 0 if parent.isValid() else len(self.keys)

    def columnCount(self, parent=QModelIndex()):  # noqa: N802
        return 0 if parent.isValid() else len(self.HEADERS)

    def headerData(self, section, orientation, role=Qt.DisplayRole):  # noqa: N802
        if orientation == Qt.Horizontal and role == Qt.DisplayRole:
            return self.HEADERS[section]
        return None

    def data(self, index, role=Qt.DisplayRole):
        if not index.isValid() or self.dock.session is None or index.row() >= len(self.keys):
            return None
        key, col = self.keys[index.row()], index.column()
        d = self.dock
        if role == Qt.DisplayRole:
            return d.cell_text(key, col)
        if role == Qt.DecorationRole and col == 1:
            return QColor(VERDICT_COLOURS[d.display_verdict(key)])
        if role == Qt.ToolTipRole:
            return d.row_tooltip(key)
        if role == Qt.TextAlignmentRole and col in (0, 3, 4):
            return int(Qt.AlignRight | Qt.AlignVCenter)
        if role == Qt.FontRole and key == d.current_key:
            font = QFont()
            font.setBold(True)
            return font
        return None


# ====================================================================================== chips
class ChipStrip(QWidget):
    """Chips side by side, reflowed to the dock's width."""

    def __init__(self, parent=None):
        super().__init__(parent)
        self.grid = QGridLayout(self)
        self.grid.setContentsMargins(0, 0, 0, 0)
        self.grid.setSpacing(6)
        self.tiles: list[QWidget] = []
        self.message = QLabel()
        self.message.setAlignment(Qt.AlignCenter)
        self.message.setMinimumHeight(CHIP_DISPLAY_PX // 2)
        self.message.setStyleSheet("color:#666; border:1px dashed #bbb; border-radius:4px; padding:12px;")
        self.grid.addWidget(self.message, 0, 0, 1, 3)
        self.pixmaps: list[QPixmap] = []

    def show_message(self, text: str):
        self._clear()
        self.message.setText(text)
        self.message.show()
        self.grid.addWidget(self.message, 0, 0, 1, max(3, self.grid.columnCount()))

    def set_chips(self, items):
        """``items``: (QPixmap, caption, tooltip)."""
        self._clear()
        self.message.hide()
        self.pixmaps = [p for p, _, _ in items]
        for pixmap, caption, tip in items:
            tile = QFrame()
            tile.setObjectName("chipTile")
            tile.setStyleSheet("#chipTile{background:#262626;border-radius:4px;}")
            v = QVBoxLayout(tile)
            v.setContentsMargins(3, 3, 3, 3)
            v.setSpacing(2)
            image = QLabel()
            image.setPixmap(pixmap)
            image.setFixedSize(pixmap.size())
            image.setToolTip(tip)
            text = QLabel(caption)
            text.setStyleSheet("color:#eee; font-size:11px;")
            text.setAlignment(Qt.AlignCenter)
            v.addWidget(image)
            v.addWidget(text)
            self.tiles.append(tile)
        self._reflow()

    def _clear(self):
        for tile in self.tiles:
            self.grid.removeWidget(tile)
            tile.deleteLater()
        self.tiles = []
        self.pixmaps = []
        self.grid.removeWidget(self.message)

    def _reflow(self):
        fit = max(1, (self.width() + 6) // (CHIP_DISPLAY_PX + 12))
        rows = -(-len(self.tiles) // fit)
        columns = -(-len(self.tiles) // max(rows, 1))   # balanced: 4 chips in 2 × 2, not 3 + 1
        for c in range(self.grid.columnCount()):
            self.grid.setColumnStretch(c, 0)
        self.grid.setColumnStretch(0, 1)                # empty side columns centre the chips
        self.grid.setColumnStretch(columns + 1, 1)
        for i, tile in enumerate(self.tiles):
            self.grid.addWidget(tile, i // columns, 1 + i % columns, Qt.AlignCenter)

    def resizeEvent(self, event):  # noqa: N802
        super().resizeEvent(event)
        if self.tiles:
            self._reflow()


class ReviewPanel(QWidget):
    """The review area: owns the keyboard (see the module docstring) while it has the focus."""

    def __init__(self, dock):
        super().__init__()
        self.dock = dock
        self.setFocusPolicy(Qt.StrongFocus)

    @staticmethod
    def command(event) -> str | None:
        modifiers = event.modifiers() & ~Qt.KeypadModifier
        if event.key() == Qt.Key_Z and modifiers == Qt.ControlModifier:
            return "undo"
        if modifiers not in (Qt.NoModifier, Qt.ShiftModifier) and event.key() not in (Qt.Key_Left, Qt.Key_Right):
            return None
        return KEYMAP.get(event.key())

    def event(self, event):
        # Our keys win over QGIS's window-wide shortcuts while the review area has the focus.
        if event.type() == QEvent.ShortcutOverride and self.command(event) is not None:
            event.accept()
            return True
        return super().event(event)

    def keyPressEvent(self, event):  # noqa: N802
        command = self.command(event)
        if command is None:
            super().keyPressEvent(event)
            return
        event.accept()
        self.dock.run_command(command)


# ====================================================================================== the dock
class ReviewDock(QgsDockWidget):
    """Review detection clusters beside the survey (see the module docstring)."""

    def __init__(self, iface, parent=None):
        super().__init__(tr("Review clusters"), parent)
        self.setObjectName("BirdsEyeReviewDock")
        self.iface = iface
        self.canvas = iface.mapCanvas() if iface is not None else None
        self.session: ReviewSession | None = None
        self.inputs = None
        self.units: ReviewUnits | None = None
        self.frames: FrameIndex | None = None
        self.geotag_local = None
        self.geotag_labels: list[str] = []
        self.params = ReviewParameters()
        self.entries: list[str] = []
        self._entry_pos: dict = {}
        self.visible: list[str] = []
        self.current_key: str | None = None
        self.input_check: InputCheck | None = None
        self.scores: dict = {}
        self.scores_error: str | None = None
        self.chip_latencies_ms: list[float] = []
        self._generation = 0
        self._score_generation = 0
        self._shown_score_generation = 0
        self._input_layer_ids: set = set()
        self._status_cache: dict = {}
        self._chips: OrderedDict = OrderedDict()
        self._pending: set = set()
        self._nav_started: float | None = None
        self._shown_chips_for: str | None = None
        self._flights = []
        self._image_cache = ImageCache(24)
        self._pool = QThreadPool(self)
        self._pool.setMaxThreadCount(2)
        self._signals = _Signals()
        self._signals.chips_ready.connect(self._on_chips)
        self._signals.scores_ready.connect(self._on_scores)
        self._score_timer = QTimer(self)
        self._score_timer.setSingleShot(True)
        self._score_timer.timeout.connect(self._start_scores)
        self._marker: QgsVertexMarker | None = None
        self._tool: AddTargetTool | None = None
        self._previous_tool = None
        self.verdict_layer: QgsVectorLayer | None = None
        self._verdict_layer_id = ""
        self._layer_refresh = QTimer(self)
        self._layer_refresh.setSingleShot(True)
        self._layer_refresh.timeout.connect(self._refresh_verdict_layer)
        self._build_ui()
        project = QgsProject.instance()
        project.layersAdded.connect(self._refill_detection_layers)
        project.layersRemoved.connect(self._on_layers_removed)
        project.readProject.connect(self._restore_from_project)
        self._refill_detection_layers()
        QTimer.singleShot(0, self._restore_from_project)

    # ------------------------------------------------------------------ UI
    def _build_ui(self):
        scroll = QScrollArea()
        scroll.setWidgetResizable(True)
        scroll.setFrameShape(QFrame.NoFrame)
        scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarAlwaysOff)
        body = QWidget()
        outer = QVBoxLayout(body)
        outer.setContentsMargins(6, 6, 6, 6)
        outer.setSpacing(6)
        outer.addWidget(self._build_setup())
        self.banner = QLabel()
        self.banner.setWordWrap(True)
        self.banner.setTextFormat(Qt.RichText)
        self.banner.hide()
        outer.addWidget(self.banner)
        self.panel = ReviewPanel(self)
        self.panel.setEnabled(False)
        outer.addWidget(self.panel)
        self._build_review(self.panel)
        scroll.setWidget(body)
        self.setWidget(scroll)
        self.setMinimumWidth(360)

    def _build_setup(self):
        box = QgsCollapsibleGroupBox(tr("Review setup"))
        form = QFormLayout(box)
        form.setFieldGrowthPolicy(QFormLayout.AllNonFixedFieldsGrow)
        self.detections_combo = QgsCheckableComboBox()
        self.detections_combo.setDefaultText(tr("choose one or more detection layers"))
        self.detections_combo.setToolTip(tr("Outputs of Detect targets over one flight (several checkpoints or "
                                            "thresholds are reviewed together: one verdict per spot)."))
        form.addRow(tr("Detections"), self.detections_combo)
        self.frames_combo = QgsMapLayerComboBox()
        self.frames_combo.setFilters(QgsMapLayerProxyModel.VectorLayer)
        self.frames_combo.setAllowEmptyLayer(True)
        self.frames_combo.setToolTip(tr("The flight's frame layer (Import flight log or Import DJI images): "
                                        "poses, camera and image of every frame."))
        form.addRow(tr("Frames"), self.frames_combo)
        self.geotags_combo = QgsMapLayerComboBox()
        self.geotags_combo.setFilters(QgsMapLayerProxyModel.PointLayer)
        self.geotags_combo.setAllowEmptyLayer(True)
        self.geotags_combo.setToolTip(tr("The survey points (Import geotags)."))
        form.addRow(tr("Geotags"), self.geotags_combo)
        self.store_widget = QgsFileWidget()
        self.store_widget.setStorageMode(QgsFileWidget.SaveFile)
        self.store_widget.setConfirmOverwrite(False)
        self.store_widget.setFilter("GeoPackage (*.gpkg)")
        self.store_widget.setToolTip(tr("GeoPackage holding the append-only verdict log (table birdseye_verdicts). "
                                        "Default: the first detection layer's GeoPackage, else one next to the "
                                        "project."))
        form.addRow(tr("Verdict log"), self.store_widget)
        self.reviewer_edit = QLineEdit(QgsSettings().value(SETTINGS_REVIEWER, "") or _os_user())
        self.reviewer_edit.setToolTip(tr("Recorded with every verdict."))
        self.reviewer_edit.editingFinished.connect(self._on_reviewer_changed)
        form.addRow(tr("Reviewer"), self.reviewer_edit)

        params = QgsCollapsibleGroupBox(tr("Clustering and matching"))
        params.setCollapsed(True)
        pform = QFormLayout(params)
        self.dedup_spin = self._double(0.1, 100.0, DEFAULT_DEDUP_CM, 1, " cm",
                                       "De-duplication grid cell, as in Cluster detections.")
        self.eps_spin = self._double(0.001, 50.0, self.params.eps_m, 3, " m", "DBSCAN radius EPS of the units.")
        self.min_samples_spin = QgsSpinBox()
        self.min_samples_spin.setRange(1, 1000)
        self.min_samples_spin.setValue(self.params.min_samples)
        self.min_samples_spin.setClearValue(self.params.min_samples)
        self.min_samples_spin.setToolTip(tr("DBSCAN minimum points per neighbourhood (itself included)."))
        self.eps_pred_spin = self._double(0.001, 50.0, self.params.eps_pred_m, 3, " m",
                                          "Match radius geotag ↔ cluster core points (EPS_PRED).")
        self.edge_spin = self._double(0.0, 1000.0, self.params.edge_buffer_px, 1, " px",
                                      "Edge buffer of the in-view test.")
        self.window_spin = QgsSpinBox()
        self.window_spin.setRange(32, 1024)
        self.window_spin.setSingleStep(16)
        self.window_spin.setValue(DEFAULT_WINDOW_PX)
        self.window_spin.setClearValue(DEFAULT_WINDOW_PX)
        self.window_spin.setSuffix(" px")
        self.window_spin.setToolTip(tr("Size of the image window cut around a detection."))
        self.window_spin.valueChanged.connect(self._on_window_changed)
        self.scale_spin = QgsSpinBox()
        self.scale_spin.setRange(10, 100000)
        self.scale_spin.setValue(DEFAULT_SCALE)
        self.scale_spin.setClearValue(DEFAULT_SCALE)
        self.scale_spin.setPrefix("1:")
        self.scale_spin.setToolTip(tr("Map scale the canvas zooms to around each unit."))
        for label, widget in ((tr("Grid cell"), self.dedup_spin), (tr("EPS"), self.eps_spin),
                              (tr("Min. points"), self.min_samples_spin), (tr("EPS_PRED"), self.eps_pred_spin),
                              (tr("Edge buffer"), self.edge_spin), (tr("Chip window"), self.window_spin),
                              (tr("Map scale"), self.scale_spin)):
            pform.addRow(label, widget)
        form.addRow(params)
        self.start_button = QPushButton(tr("Start / resume review"))
        self.start_button.setDefault(True)
        self.start_button.clicked.connect(self.start_review)
        form.addRow(self.start_button)
        self.setup_box = box
        return box

    def _double(self, lo, hi, value, decimals, suffix, tip):
        spin = QgsDoubleSpinBox()
        spin.setRange(lo, hi)
        spin.setDecimals(decimals)
        spin.setValue(value)
        spin.setClearValue(value)
        spin.setSuffix(suffix)
        spin.setToolTip(tr(tip))
        return spin

    def _build_review(self, panel):
        v = QVBoxLayout(panel)
        v.setContentsMargins(0, 0, 0, 0)
        v.setSpacing(6)
        # progress
        row = QHBoxLayout()
        self.progress_label = QLabel(tr("No review started"))
        self.progress_bar = QProgressBar()
        self.progress_bar.setTextVisible(False)
        self.progress_bar.setMaximumHeight(8)
        row.addWidget(self.progress_label, 1)
        v.addLayout(row)
        v.addWidget(self.progress_bar)
        # filters
        row = QHBoxLayout()
        self.layer_filter = QComboBox()
        self.layer_filter.addItem(tr("All layers"), "")
        self.verdict_filter = QComboBox()
        for key, text in FILTERS:
            self.verdict_filter.addItem(tr(text), key)
        for combo in (self.layer_filter, self.verdict_filter):
            combo.setSizeAdjustPolicy(QComboBox.AdjustToMinimumContentsLengthWithIcon)
            combo.setMinimumContentsLength(6)
            combo.setFocusPolicy(Qt.ClickFocus)
            combo.currentIndexChanged.connect(self._on_filter)
            combo.activated.connect(lambda *_: self.panel.setFocus())
        row.addWidget(QLabel(tr("Fired by")))
        row.addWidget(self.layer_filter, 1)
        row.addWidget(QLabel(tr("Show")))
        row.addWidget(self.verdict_filter, 1)
        v.addLayout(row)
        # units
        self.model = UnitTableModel(self)
        self.table = QTableView()
        self.table.setModel(self.model)
        self.table.setFocusPolicy(Qt.NoFocus)
        self.table.setSelectionBehavior(QAbstractItemView.SelectRows)
        self.table.setSelectionMode(QAbstractItemView.SingleSelection)
        self.table.setAlternatingRowColors(True)
        self.table.verticalHeader().hide()
        self.table.verticalHeader().setDefaultSectionSize(20)
        header = self.table.horizontalHeader()
        header.setMinimumSectionSize(24)
        header.setSectionResizeMode(QHeaderView.ResizeToContents)
        header.setSectionResizeMode(1, QHeaderView.Stretch)
        self.table.setMinimumHeight(120)
        self.table.setMaximumHeight(150)
        self.table.clicked.connect(lambda index: self.go_to(self.model.keys[index.row()]))
        v.addWidget(self.table)
        # the current unit
        self.unit_label = QLabel()
        self.unit_label.setWordWrap(True)
        self.unit_label.setTextFormat(Qt.RichText)
        self.unit_label.setStyleSheet("QLabel{background:#f5f7fa;border:1px solid #d8dde6;border-radius:4px;"
                                      "padding:6px;}")
        v.addWidget(self.unit_label)
        self.chips = ChipStrip()
        self.chips.setSizePolicy(QSizePolicy.Expanding, QSizePolicy.Minimum)
        v.addWidget(self.chips)
        self.chip_legend = QLabel()
        self.chip_legend.setTextFormat(Qt.RichText)
        self.chip_legend.setStyleSheet("color:#555; font-size:11px;")
        v.addWidget(self.chip_legend)
        # verdicts and moves
        grid = QGridLayout()
        grid.setSpacing(4)
        self.prev_button = self._button("◀  " + tr("Previous (P)"), lambda: self.run_command("previous"),
                                        "Previous unit of the list (P or ←)")
        self.next_button = self._button(tr("Next (N)") + "  ▶", lambda: self.run_command("next"),
                                        "Next unit of the list (N or →)")
        grid.addWidget(self.prev_button, 0, 0)
        grid.addWidget(self.next_button, 0, 1)
        self.verdict_buttons = {}
        for i, (verdict, key, other) in enumerate((("confirmed_real", "1", "C"), ("hard_negative", "2", "H"),
                                                   ("uncertain", "3", "U"), ("unreviewed", "0", "Backspace"))):
            b = self._button(f"{VERDICT_TEXT[verdict]}  ({key})", lambda _, x=verdict: self.run_command(x),
                             f"Record '{verdict}' for this unit (key {key} or {other})")
            colour = VERDICT_COLOURS[verdict]
            b.setStyleSheet(f"QToolButton{{border:1px solid {colour};border-left:6px solid {colour};border-radius:3px;"
                            f"padding:6px 8px;background:white;}}"
                            f"QToolButton:hover{{background:{colour}22;}}"
                            f"QToolButton:checked{{background:{colour};color:white;font-weight:bold;}}")
            b.setCheckable(True)
            grid.addWidget(b, 1 + i // 2, i % 2)
            self.verdict_buttons[verdict] = b
        self.undo_button = self._button("↶  " + tr("Undo (Ctrl+Z)"), lambda: self.run_command("undo"),
                                        "Undo the last action (appends rows restoring the previous verdicts)")
        self.add_button = self._button("+  " + tr("Add missed target (A)"), lambda: self.run_command("add"),
                                       "Click the map where a target was missed (A; Esc cancels)")
        self.add_button.setCheckable(True)
        grid.addWidget(self.undo_button, 3, 0)
        grid.addWidget(self.add_button, 3, 1)
        v.addLayout(grid)
        self.propagate_check = QCheckBox(tr("Propagate to units within {:.2f} m").format(PROPAGATION_EPS_M))
        self.propagate_check.setToolTip(tr("Off by default. When on, a verdict also votes (provenance "
                                           "propagated:{rule}) on the units chained to this one by gaps of at "
                                           "most {eps:.2f} m; conflicting votes are resolved under the three "
                                           "conventions, all shown.").format(rule=PROPAGATION_RULE,
                                                                             eps=PROPAGATION_EPS_M))
        self.advance_check = QCheckBox(tr("Next unit after a verdict"))
        self.advance_check.setChecked(True)
        for c in (self.propagate_check, self.advance_check):
            c.setFocusPolicy(Qt.NoFocus)
            v.addWidget(c)
        self.propagate_check.toggled.connect(self._on_propagate_toggled)
        # scores
        title = QLabel(tr("<b>Scores per detection layer</b> — after review under each tie-break convention"))
        title.setWordWrap(True)
        title.setToolTip(tr("Recall and the geotag-matched cluster fraction (GMCF), computed as Evaluate "
                            "detections computes them from this verdict log."))
        v.addWidget(title)
        self.scores_table = QTableWidget(0, 5)
        self.scores_table.setHorizontalHeaderLabels(["", tr("before\nreview")] +
                                                    [CONVENTION_TEXT[c].replace("-wins", "\nwins").replace(
                                                        "hard-negative", "hard-neg.") for c in CONVENTIONS])
        for c, convention in enumerate(CONVENTIONS):
            self.scores_table.horizontalHeaderItem(c + 2).setToolTip(tr("After review, {}").format(
                CONVENTION_TEXT[convention]))
        self.scores_table.verticalHeader().hide()
        self.scores_table.setFocusPolicy(Qt.NoFocus)
        self.scores_table.setEditTriggers(QAbstractItemView.NoEditTriggers)
        self.scores_table.setSelectionMode(QAbstractItemView.NoSelection)
        self.scores_table.horizontalHeader().setSectionResizeMode(QHeaderView.Stretch)
        self.scores_table.horizontalHeader().setSectionResizeMode(0, QHeaderView.ResizeToContents)
        self.scores_table.horizontalHeader().setSectionResizeMode(1, QHeaderView.ResizeToContents)
        self.scores_table.setWordWrap(False)
        self.scores_table.horizontalHeader().setStyleSheet("QHeaderView::section{padding:1px 2px;font-size:11px;}")
        self.scores_table.verticalHeader().setDefaultSectionSize(20)
        self.scores_table.setVerticalScrollBarPolicy(Qt.ScrollBarAlwaysOff)
        v.addWidget(self.scores_table)
        self.scores_note = QLabel(tr("GMCF is a lower bound on precision, not precision; recall after review is an "
                                     "upper bound (≥). The spread between the conventions is part of the result."))
        self.scores_note.setWordWrap(True)
        self.scores_note.setStyleSheet("color:#555; font-size:11px;")
        v.addWidget(self.scores_note)
        self.status_label = QLabel()
        self.status_label.setWordWrap(True)
        self.status_label.setStyleSheet("color:#555;")
        v.addWidget(self.status_label)
        v.addStretch(1)

    def _button(self, text, slot, tip):
        b = QToolButton()
        b.setText(tr(text))
        b.setToolTip(tr(tip))
        b.setFocusPolicy(Qt.NoFocus)
        b.setToolButtonStyle(Qt.ToolButtonTextOnly)
        b.setSizePolicy(QSizePolicy.Expanding, QSizePolicy.Fixed)
        b.clicked.connect(slot)
        return b

    # ------------------------------------------------------------------ layer choices
    def _refill_detection_layers(self, *_):
        checked = set(self.detections_combo.checkedItemsData())
        self.detections_combo.clear()
        for layer in QgsProject.instance().mapLayers().values():
            if isinstance(layer, QgsVectorLayer) and layer.isValid() and \
                    QgsWkbTypes.geometryType(layer.wkbType()) == QgsWkbTypes.PointGeometry and \
                    {"frame_id", "score", "u", "v"} <= set(layer.fields().names()):
                self.detections_combo.addItemWithCheckState(layer.name(), Qt.Checked if layer.id() in checked
                                                            else Qt.Unchecked, layer.id())

    def set_inputs(self, detection_layers, frame_layer, geotag_layer, store_path: str | None = None):
        """Choose the review's layers (what the user does in the setup box)."""
        self._refill_detection_layers()
        ids = {layer.id() for layer in detection_layers}
        for i in range(self.detections_combo.count()):
            self.detections_combo.setItemCheckState(i, Qt.Checked if self.detections_combo.itemData(i) in ids
                                                    else Qt.Unchecked)
        self.frames_combo.setLayer(frame_layer)
        self.geotags_combo.setLayer(geotag_layer)
        if store_path is not None:
            self.store_widget.setFilePath(store_path)

    def _chosen_detection_layers(self):
        project = QgsProject.instance()
        return [project.mapLayer(i) for i in self.detections_combo.checkedItemsData() if project.mapLayer(i)]

    def _read_params(self) -> ReviewParameters:
        return ReviewParameters(self.dedup_spin.value(), self.eps_spin.value(), self.min_samples_spin.value(),
                                   self.eps_pred_spin.value(), self.edge_spin.value())

    # ------------------------------------------------------------------ start / resume
    def start_review(self) -> bool:
        """Read the inputs, build the units, open the log and go to where the review stopped."""
        detection_layers = self._chosen_detection_layers()
        frame_layer, geotag_layer = self.frames_combo.currentLayer(), self.geotags_combo.currentLayer()
        if not detection_layers:
            self._show_banner([tr("Choose at least one detection layer (an output of Detect targets).")], error=True)
            return False
        store_path = self.store_widget.filePath().strip() or default_store_path(
            detection_layers, QgsProject.instance().fileName())
        if not store_path:
            self._show_banner([tr("Choose a GeoPackage for the verdict log (save the project first to get one next "
                                  "to it).")], error=True)
            return False
        if not store_path.lower().endswith(".gpkg"):
            store_path += ".gpkg"
        QApplication.setOverrideCursor(Qt.WaitCursor)
        try:
            params = self._read_params()
            inputs = read_review_inputs(detection_layers, frame_layer, geotag_layer)
            units = build_units(inputs.layers, inputs.local, inputs.geotags, inputs.pose_groups, params)
            store = VerdictStore(store_path)
        except (InputError, OSError, ValueError) as exc:   # a message naming the layer, field or file
            self._show_banner([str(exc)], error=True)
            return False
        finally:
            QApplication.restoreOverrideCursor()
        self._stop_session()
        self.store_widget.setFilePath(store_path)
        self.params, self.inputs, self.units = params, inputs, units
        reviewer = self.reviewer_edit.text().strip() or _os_user()
        QgsSettings().setValue(SETTINGS_REVIEWER, reviewer)
        self.session = ReviewSession(store, units, reviewer, inputs.digests, params)
        self.frames = FrameIndex(inputs.pose_groups, inputs.images, inputs.local)
        g = inputs.geotags
        self.geotag_local = inputs.local.from_geodetic(g.lat, g.lon, np.where(np.isfinite(g.height), g.height,
                                                                             inputs.local.h0)) if len(g) else None
        self.geotag_labels = [str(i) for i in g.ids]
        self._flights = [Flight(layer.detections, inputs.pose_groups, layer.name) for layer in inputs.layers]
        self._generation += 1
        self.input_check = check_inputs(self.session.ledger.rows, inputs.digests,
                                           {**params.postprocessing(), **params.matching()}, units.keys)
        if self.input_check.ok:
            self.banner.hide()
        else:
            self._show_banner(self.input_check.messages())
        self.layer_filter.blockSignals(True)
        while self.layer_filter.count() > 1:
            self.layer_filter.removeItem(1)
        for name in units.layer_names:
            self.layer_filter.addItem(name, name)
        self.layer_filter.blockSignals(False)
        cursor = self.session.load_cursor() or {}
        self._set_combo(self.layer_filter, cursor.get("layer_filter", ""))
        self._set_combo(self.verdict_filter, cursor.get("verdict_filter", "all"))
        self._rebuild_entries()
        self.panel.setEnabled(True)
        self.setup_box.setCollapsed(True)
        self._input_layer_ids = {layer.id() for layer in detection_layers + [frame_layer, geotag_layer]}
        self._save_to_project(detection_layers, frame_layer, geotag_layer, store_path)
        self._show_survey(geotag_layer)
        self._add_verdict_layer()
        key = resume_key(self.visible or self.entries, self.session.ledger, cursor.get("unit_key"))
        self.status_label.setText(tr("{n} units from {k} layer(s); verdict log {path}").format(
            n=len(units), k=len(inputs.layers), path=store_path))
        if key is not None:
            self.go_to(key, save=False)
        else:
            self._show_current()
        self._schedule_scores()
        self.panel.setFocus()
        return True

    def _stop_session(self):
        self._generation += 1
        self._pool.clear()
        self._chips.clear()
        self._pending.clear()
        self._status_cache.clear()
        if self.session is not None:
            self.session.store.close()
        self.session = None
        self.current_key = None
        self.entries, self.visible, self._entry_pos = [], [], {}
        self.model.set_keys([])

    @staticmethod
    def _set_combo(combo, data):
        i = combo.findData(data)
        combo.blockSignals(True)
        combo.setCurrentIndex(max(i, 0))
        combo.blockSignals(False)

    # ------------------------------------------------------------------ project persistence
    def _save_to_project(self, detection_layers, frame_layer, geotag_layer, store_path):
        p = QgsProject.instance()
        p.writeEntry(PROJECT_SCOPE, "review/detections", [layer.id() for layer in detection_layers])
        p.writeEntry(PROJECT_SCOPE, "review/frames", frame_layer.id())
        p.writeEntry(PROJECT_SCOPE, "review/geotags", geotag_layer.id())
        p.writeEntry(PROJECT_SCOPE, "review/store", store_path)
        p.writeEntry(PROJECT_SCOPE, "review/parameters", json.dumps(
            {**self.params.postprocessing(), **self.params.matching(), "window_px": self.window_spin.value(),
             "scale": self.scale_spin.value()}))
        p.writeEntry(PROJECT_SCOPE, "review/propagate", bool(self.propagate_check.isChecked()))

    def _on_reviewer_changed(self):
        reviewer = self.reviewer_edit.text().strip() or _os_user()
        QgsSettings().setValue(SETTINGS_REVIEWER, reviewer)
        if self.session is not None:   # the next verdicts carry the new name
            self.session.meta = RowMeta.of(reviewer, self.session.digests, self.session.params)

    def _on_propagate_toggled(self, checked):
        if self.session is not None:   # part of the review's setup: reopening the project keeps it
            QgsProject.instance().writeEntry(PROJECT_SCOPE, "review/propagate", bool(checked))

    def _restore_from_project(self, *_):
        """Reopen the review a project was saved with (layers, log, parameters) where it stopped."""
        p = QgsProject.instance()
        ids, ok = p.readListEntry(PROJECT_SCOPE, "review/detections")
        if not ok or not ids:
            return
        layers = [p.mapLayer(i) for i in ids]
        frame_layer = p.mapLayer(p.readEntry(PROJECT_SCOPE, "review/frames")[0])
        geotag_layer = p.mapLayer(p.readEntry(PROJECT_SCOPE, "review/geotags")[0])
        store = p.readEntry(PROJECT_SCOPE, "review/store")[0]
        if None in layers or frame_layer is None or geotag_layer is None or not store:
            return
        params = json.loads(p.readEntry(PROJECT_SCOPE, "review/parameters", "{}")[0] or "{}")
        for spin, name in ((self.dedup_spin, "dedup_cm"), (self.eps_spin, "eps_m"),
                           (self.min_samples_spin, "min_samples"), (self.eps_pred_spin, "eps_pred_m"),
                           (self.edge_spin, "edge_buffer_px"), (self.window_spin, "window_px"),
                           (self.scale_spin, "scale")):
            if name in params:
                spin.setValue(params[name])
        self.propagate_check.setChecked(p.readBoolEntry(PROJECT_SCOPE, "review/propagate", False)[0])
        self.set_inputs(layers, frame_layer, geotag_layer, store)
        self.start_review()

    def _on_layers_removed(self, layer_ids):
        self._refill_detection_layers()
        if self.inputs is None or self.session is None:
            return
        if self._verdict_layer_id in layer_ids:   # (the layer object is already deleted here)
            self.verdict_layer, self._verdict_layer_id = None, ""
        if self._input_layer_ids & set(layer_ids):
            self._stop_session()
            self.panel.setEnabled(False)
            self.setup_box.setCollapsed(False)
            self._show_banner([tr("A layer of the review was removed from the project; the review stopped. Every "
                                  "verdict is in the log; choose the layers again to resume.")])

    # ------------------------------------------------------------------ entries, filters, status
    def _rebuild_entries(self):
        self.entries = [self.units.keys[i] for i in self.units.order] + \
            [t.key for t in self.session.ledger.added_targets()]
        self._entry_pos = {k: i for i, k in enumerate(self.entries)}
        self._apply_filter()

    def _apply_filter(self):
        layer = self.layer_filter.currentData() or ""
        mode = self.verdict_filter.currentData() or "all"
        self.visible = [k for k in self.entries if self._passes(k, layer, mode)]
        self.model.set_keys(self.visible)
        self._select_current_row()
        self._update_progress()

    def _passes(self, key, layer, mode) -> bool:
        added = key.startswith(ADDED_PREFIX)
        if layer and (added or layer not in self.units.layers_fired[self.units.index[key]]):
            return False
        if mode == "all":
            return True
        if mode == "added":
            return added
        if added:
            return False
        status = self.status(key)
        return {"todo": not status.reviewed, "propagated": status.propagated_only, "conflict": status.conflict,
                "unmatched": not self.units.matched[self.units.index[key]]}.get(mode, status.direct == mode)

    def _on_filter(self, *_):
        if self.session is None:
            return
        self._apply_filter()
        if self.current_key not in self.visible and self.visible:
            self.go_to(self._neighbour(self.current_key, +1) or self.visible[0])
        else:
            self._save_cursor()

    def status(self, key) -> UnitStatus:
        if key not in self._status_cache:
            self._status_cache[key] = unit_status(self.session.log(), self.session.ledger, key)
        return self._status_cache[key]

    def display_verdict(self, key) -> str:
        if key.startswith(ADDED_PREFIX):
            return "added"
        s = self.status(key)
        if s.direct != "unreviewed":
            return s.direct
        return s.resolved["majority_wins"] if s.reviewed else "unreviewed"

    def cell_text(self, key, col) -> str:
        if col == 0:
            return str(self._entry_pos[key] + 1)
        if key.startswith(ADDED_PREFIX):
            return ["", tr("Added target"), "", "", ""][col]
        i = self.units.index[key]
        s = self.status(key)
        if col == 1:
            if s.direct != "unreviewed":
                text = VERDICT_TEXT[s.direct]
            elif s.reviewed:
                text = "↳ " + VERDICT_TEXT[s.resolved["majority_wins"]]
            else:
                text = "—"
            return text + ("  ⚠" if s.conflict else "")
        if col == 2:
            ids = self.units.matched_geotags[i]
            return ", ".join(map(str, ids)) if ids else "–"
        if col == 3:
            return str(int(self.units.n_frames[i]))
        return _fmt(float(self.units.max_score[i]), 2)

    def row_tooltip(self, key) -> str:
        if key.startswith(ADDED_PREFIX):
            return key
        return f"{key}\n{tr('fired by')}: {', '.join(self.units.layers_fired[self.units.index[key]])}"

    def _update_progress(self):
        n = len(self.units)
        done = sum(1 for k in self.units.keys if self.status(k).reviewed)
        added = len(self.entries) - n
        pos = self.visible.index(self.current_key) + 1 if self.current_key in self.visible else 0
        self.progress_label.setText(tr("<b>{pos}</b> of {vis} shown · {done} of {n} units reviewed · {added} added")
                                    .format(pos=pos, vis=len(self.visible), done=done, n=n, added=added))
        self.progress_bar.setRange(0, max(n, 1))
        self.progress_bar.setValue(done)

    def _select_current_row(self):
        if self.current_key in self.visible:
            row = self.visible.index(self.current_key)
            self.table.selectRow(row)
            self.table.scrollTo(self.model.index(row, 0))
        else:
            self.table.clearSelection()

    # ------------------------------------------------------------------ commands
    def run_command(self, command: str) -> None:
        """What a key or button does (see the module docstring)."""
        if self.session is None:
            return
        if command not in ("add", "cancel_add"):   # chip latency counts from the key, commit included
            self._nav_started = time.perf_counter()
        if command in REVIEW_VERDICTS:
            self.set_verdict(command)
        elif command == "next":
            self.go_to(self._neighbour(self.current_key, +1))
        elif command == "previous":
            self.go_to(self._neighbour(self.current_key, -1))
        elif command == "first" and self.visible:
            self.go_to(self.visible[0])
        elif command == "last" and self.visible:
            self.go_to(self.visible[-1])
        elif command == "undo":
            self.undo()
        elif command == "add":
            self.start_add_target()
        elif command == "cancel_add":
            self._end_add_target()

    def _neighbour(self, key, step) -> str | None:
        """The next (step +1) or previous (−1) shown entry from ``key``'s place in the full order."""
        if not self.visible:
            return None
        if key not in self.entries:
            return self.visible[0]
        shown = set(self.visible)
        p = self._entry_pos[key]
        seq = self.entries[p + 1:] if step > 0 else reversed(self.entries[:p])
        return next((k for k in seq if k in shown), None)

    def _cursor(self, key) -> dict:
        return {"unit_key": key, "layer_filter": self.layer_filter.currentData() or "",
                "verdict_filter": self.verdict_filter.currentData() or "all"}

    def _save_cursor(self):
        if self.session is not None and self.current_key is not None:
            self.session.save_cursor(self._cursor(self.current_key))

    def set_verdict(self, verdict: str) -> None:
        key = self.current_key
        if key is None:
            return
        if key.startswith(ADDED_PREFIX) and verdict != "unreviewed":
            self.status_label.setText(tr("An added target can only be withdrawn (0 or Backspace) or undone."))
            return
        target = self._neighbour(key, +1) if self.advance_check.isChecked() else None
        try:
            rows = self.session.set_verdict(key, verdict, self.propagate_check.isChecked(),
                                            cursor=self._cursor(target or key))
        except Exception as exc:  # noqa: BLE001 — the verdict is not recorded: say so, stay on the unit
            self._report_store_error(exc)
            return
        self._after_append(rows)
        if rows:
            self.status_label.setText(tr("Saved: {key} → {verdict}{more} ({time} UTC)").format(
                key=key, verdict=verdict, time=rows[0]["time"][11:19],
                more=tr(", {} propagated vote(s)").format(len(rows) - 1) if len(rows) > 1 else ""))
        if target is not None:
            self.go_to(target, save=False)
        else:
            self._show_current()

    def undo(self) -> None:
        try:
            done = self.session.undo(cursor_for=self._cursor)
        except Exception as exc:  # noqa: BLE001
            self._report_store_error(exc)
            return
        if done is None:
            self.status_label.setText(tr("Nothing to undo."))
            return
        action, about = done
        self._after_append(None)
        self.status_label.setText(tr("Undone: action {action} on {key} (rows appended; nothing deleted).").format(
            action=action, key=about))
        if about in self.entries:
            self.go_to(about, save=False)
        else:
            self._show_current()

    def _after_append(self, rows):
        self._status_cache.clear()
        added = [t.key for t in self.session.ledger.added_targets()]
        if [k for k in self.entries if k.startswith(ADDED_PREFIX)] != added:
            self._rebuild_entries()
        else:
            self._apply_filter()
        self._schedule_scores()
        self._layer_refresh.start(300)

    def _report_store_error(self, exc):
        message = tr("The verdict was NOT saved: {error}. Check that {path} is writable and not locked, then try "
                     "again.").format(error=exc, path=self.session.store.path)
        self._show_banner([message], error=True)
        QgsMessageLog.logMessage(message, LOG_TAG, Qgis.Critical)

    # ------------------------------------------------------------------ add a missed target
    def start_add_target(self):
        if self.canvas is None:
            return
        if self._tool is None:
            self._tool = AddTargetTool(self.canvas)
            self._tool.target_added.connect(self.add_target_at)
            self._tool.cancelled.connect(self._end_add_target)
        if self.canvas.mapTool() is not self._tool:
            self._previous_tool = self.canvas.mapTool()
            self.canvas.setMapTool(self._tool)
        self.add_button.setChecked(True)
        self.status_label.setText(tr("Click the map where the missed target is (Esc or right click cancels)."))

    def _end_add_target(self):
        if self._tool is not None and self.canvas is not None and self.canvas.mapTool() is self._tool:
            if self._previous_tool is not None:
                self.canvas.setMapTool(self._previous_tool)
            else:
                self.canvas.unsetMapTool(self._tool)
        self._previous_tool = None
        self.add_button.setChecked(False)
        self.panel.setFocus()

    def add_target_at(self, point: QgsPointXY, crs: QgsCoordinateReferenceSystem):
        """Record an added target at ``point`` (in ``crs``)."""
        if self.session is None:
            return
        wgs84 = QgsCoordinateTransform(crs, QgsCoordinateReferenceSystem("EPSG:4326"), QgsProject.instance())
        p = wgs84.transform(point)
        try:
            key = self.session.add_target(p.y(), p.x(), cursor=self._cursor(self.current_key))
        except Exception as exc:  # noqa: BLE001
            self._report_store_error(exc)
            return
        self._end_add_target()
        self._after_append(None)
        self.status_label.setText(tr("Added target {key} (Ctrl+Z undoes it).").format(key=key) if key
                                  else tr("A target is already recorded there."))
        self._show_current()

    # ------------------------------------------------------------------ showing a unit
    def go_to(self, key, save: bool = True):
        if key is None or self.session is None:
            return
        if self._nav_started is None:
            self._nav_started = time.perf_counter()
        self.current_key = key
        if save:
            self._save_cursor()
        self.model.refresh()
        self._select_current_row()
        self._update_progress()
        self._show_current()

    def _show_current(self):
        key = self.current_key
        if key is None:
            self.unit_label.setText(tr("No units: the detection layers have no clusters at these settings."))
            self.chips.show_message(tr("Nothing to show"))
            return
        self._show_unit_text(key)
        self._centre_map(key)
        for verdict, button in self.verdict_buttons.items():
            button.setChecked(not key.startswith(ADDED_PREFIX) and self.status(key).direct == verdict
                              and verdict != "unreviewed")
        if key in self._chips:
            self._display_chips(key)
        else:
            if self._shown_chips_for != key:
                self.chips.show_message(tr("Loading frames…"))
            self._request_chips(key, priority=10)
        self._prefetch(key)

    def _show_unit_text(self, key):
        if key.startswith(ADDED_PREFIX):
            ref = self.session.ref(key)
            self.unit_label.setText(tr("<b>Added target</b> {key}<br>{lat:.7f}°, {lon:.7f}° · recorded as a target "
                                       "the detector missed (the <i>a</i> term). 0 withdraws it.").format(
                key=key, lat=ref.lat, lon=ref.lon))
            return
        i = self.units.index[key]
        s = self.status(key)
        ids = self.units.matched_geotags[i]
        match = (tr("geotag {ids} within {eps:.2f} m").format(ids=", ".join(map(str, ids)), eps=self.params.eps_pred_m)
                 if ids else "<span style='color:#c62828'>" + tr("no geotag within {eps:.2f} m").format(
                     eps=self.params.eps_pred_m) + "</span>")
        fired = ", ".join(self.units.layers_fired[i])
        resolved = " · ".join(f"{CONVENTION_TEXT[c]} <span style='color:{VERDICT_COLOURS[v]}'>{v}</span>"
                              for c, v in s.resolved.items())
        votes = ", ".join(f"{v} ({'direct' if p == 'direct' else 'from ' + p.rsplit('/', 1)[-1]})"
                          for p, v in sorted(s.votes.items())) or tr("none yet")
        warn = " <b style='color:#ef8f00'>⚠ " + tr("the conventions disagree") + "</b>" if s.conflict else ""
        self.unit_label.setText(
            f"<b>{tr('Unit')} {self._entry_pos[key] + 1}</b> · {match}<br>"
            f"{tr('fired by')} <b>{fired}</b> · {int(self.units.n_detections[i])} {tr('detections in')} "
            f"{int(self.units.n_frames[i])} {tr('frames')} · {tr('best score')} "
            f"{_fmt(float(self.units.max_score[i]), 2)}"
            f"<br>{tr('Votes')}: {votes}{warn}<br><span style='font-size:11px;color:#555'>{resolved}</span>"
            f"<br><span style='font-size:10px;color:#888'>{key}</span>")

    def _centre_map(self, key):
        if self.canvas is None:
            return
        ref = self.session.ref(key)
        to_canvas = QgsCoordinateTransform(QgsCoordinateReferenceSystem("EPSG:4326"),
                                           self.canvas.mapSettings().destinationCrs(), QgsProject.instance())
        try:
            point = to_canvas.transform(QgsPointXY(ref.lon, ref.lat))
        except Exception:  # noqa: BLE001 — a canvas CRS that cannot hold the site: leave the map alone
            return
        if self.canvas.extent().isEmpty():   # a canvas that never showed a layer: give it the site
            self.canvas.setExtent(QgsRectangle(point.x() - 10, point.y() - 10, point.x() + 10, point.y() + 10))
        self.canvas.setCenter(point)
        if abs(self.canvas.scale() - self.scale_spin.value()) > 0.5:
            self.canvas.zoomScale(self.scale_spin.value())
        if self._marker is None:
            self._marker = QgsVertexMarker(self.canvas)
            self._marker.setIconType(QgsVertexMarker.ICON_CIRCLE)
            self._marker.setIconSize(22)
            self._marker.setPenWidth(3)
        self._marker.setColor(QColor(VERDICT_COLOURS[self.display_verdict(key)]))
        self._marker.setCenter(point)
        self.canvas.refresh()

    # ------------------------------------------------------------------ chips
    def _planner(self, key):
        """A chip-planning call for a worker thread, with everything it reads captured now."""
        units, frames, window = self.units, self.frames, self.window_spin.value()
        geotags, labels = self.geotag_local, self.geotag_labels
        if key.startswith(ADDED_PREFIX):
            ref = self.session.ref(key)
            return lambda k: plan_point_chips(k, ref.lat, ref.lon, frames, geotags, labels, window)
        return lambda k: plan_unit_chips(units, units.index[k], frames, geotags, labels, window)

    def _request_chips(self, key, priority=0):
        if key in self._chips or key in self._pending:
            return
        self._pending.add(key)
        self._pool.start(_ChipJob(self._signals, self._generation, key, self._planner(key), CHIP_DISPLAY_PX,
                                  self._image_cache), priority)

    def _prefetch(self, key):
        if key not in self.visible:
            return
        p = self.visible.index(key)
        for k in self.visible[p + 1:p + 1 + PREFETCH_AHEAD] + self.visible[max(0, p - 1):p]:
            self._request_chips(k)

    def _on_chips(self, generation, key, payload):
        if generation != self._generation:
            return
        self._pending.discard(key)
        plans, images, n_frames, error = payload
        self._chips[key] = (plans, images, n_frames, error)
        while len(self._chips) > CHIP_CACHE_UNITS:
            self._chips.popitem(last=False)
        if key == self.current_key:
            self._display_chips(key)

    def _display_chips(self, key):
        plans, images, n_frames, error = self._chips[key]
        self._chips.move_to_end(key)
        if error:
            self.chips.show_message(tr("The frames could not be read: {}").format(error))
        elif not plans:
            self.chips.show_message(tr("No frame of the frame layer shows this spot."))
        else:
            items = []
            for plan, rgb in zip(plans, images):
                h, w = rgb.shape[:2]
                pixmap = QPixmap.fromImage(QImage(rgb.tobytes(), w, h, 3 * w, QImage.Format_RGB888).copy())
                caption = tr("frame {f}").format(f=plan.frame_id) + (
                    f" · {plan.score:.2f}" if plan.score is not None else "")
                items.append((pixmap, caption, plan.image))
            self.chips.set_chips(items)
        names = self.units.layer_names
        legend = " ".join(f"<span style='color:rgb{LAYER_COLOURS[k % len(LAYER_COLOURS)]}'>◯</span> {n}"
                          for k, n in enumerate(names))
        self.chip_legend.setText(f"{legend} &nbsp; <span style='color:rgb{GEOTAG_COLOUR}'>✕</span> "
                                 f"{tr('geotag')} &nbsp; " + tr("{shown} of {n} frames").format(
                                     shown=len(plans), n=n_frames))
        self._shown_chips_for = key
        if self._nav_started is not None:
            self.chip_latencies_ms.append((time.perf_counter() - self._nav_started) * 1000.0)
            self._nav_started = None

    def _on_window_changed(self, *_):
        self._generation += 1          # chips in flight were cut with the old window
        self._chips.clear()
        self._pending.clear()
        self._shown_chips_for = None
        if self.session is not None and self.current_key is not None:
            self._show_current()

    @property
    def chips_shown_for(self) -> str | None:
        return self._shown_chips_for

    # ------------------------------------------------------------------ scores
    def _schedule_scores(self):
        self._score_timer.start(SCORE_DELAY_MS)

    def operating_point(self) -> OperatingPoint:
        p = self.params
        return OperatingPoint(None, p.dedup_cm, p.eps_m, p.min_samples, p.eps_pred_m, p.edge_buffer_px)

    def _start_scores(self):
        if self.session is None:
            return
        self._score_generation += 1
        self._pool.start(_ScoreJob(self._signals, self._score_generation, self._flights, self.inputs.geotags,
                                   self.operating_point(), self.session.log()), 5)
        self.scores_table.setToolTip(tr("updating…"))

    def _on_scores(self, generation, result):
        if generation != self._score_generation:
            return
        self._shown_score_generation = generation
        self.scores_table.setToolTip("")
        if isinstance(result, Exception):
            self.scores, self.scores_error = {}, str(result)
            self.scores_note.setText(tr("Scores could not be computed: {}").format(result))
            return
        self.scores, self.scores_error = result, None
        t = self.scores_table
        t.clearSpans()
        t.setRowCount(3 * len(result))
        bold = QFont()
        bold.setBold(True)
        for k, (name, d) in enumerate(result.items()):
            post = d.get("post", {})
            title = QTableWidgetItem(name)
            title.setFont(bold)
            title.setBackground(QColor("#eef1f5"))
            t.setItem(3 * k, 0, title)
            t.setSpan(3 * k, 0, 1, 5)
            recall = [tr("recall"), f"{_fmt(d['recall_pre'])}  ({d['n_recovered']}/{d['n_in_view']})"] + \
                [post.get(c, {}).get("recall_post") or "–" for c in CONVENTIONS]
            gmcf = [tr("GMCF"), f"{_fmt(d['gmcf_pre'])}  ({d['n_hit_clusters']}/{d['n_clusters']})"] + \
                [_fmt(post.get(c, {}).get("gmcf_post")) for c in CONVENTIONS]
            tips = [f"c = {post[c]['c']} (confirmed, not hit), a = {post[c]['a']} (added)" if c in post else ""
                    for c in CONVENTIONS]
            for r, cells in ((3 * k + 1, recall), (3 * k + 2, gmcf)):
                for c, text in enumerate(cells):
                    item = QTableWidgetItem(text)
                    item.setTextAlignment(Qt.AlignCenter if c else Qt.AlignLeft | Qt.AlignVCenter)
                    if c >= 2:
                        item.setToolTip(tips[c - 2])
                    t.setItem(r, c, item)
        t.resizeRowsToContents()
        t.setFixedHeight(t.horizontalHeader().sizeHint().height() +
                         sum(t.rowHeight(i) for i in range(t.rowCount())) + 2 * t.frameWidth())

    # ------------------------------------------------------------------ map context
    def _show_survey(self, geotag_layer):
        node = QgsProject.instance().layerTreeRoot().findLayer(geotag_layer.id())
        if node is not None:
            node.setItemVisibilityChecked(True)

    def _add_verdict_layer(self):
        """Show the current direct verdicts (and added targets) on the map, from the log itself."""
        uri = self.session.store.layer_uri
        project = QgsProject.instance()
        for layer in project.mapLayers().values():
            if isinstance(layer, QgsVectorLayer) and layer.source().split("|")[0] == str(self.session.store.path) \
                    and "birdseye_verdicts" in layer.source():
                self.verdict_layer, self._verdict_layer_id = layer, layer.id()
                return
        layer = QgsVectorLayer(uri, tr("Review verdicts"), "ogr")
        if not layer.isValid():
            QgsMessageLog.logMessage(f"Verdict layer {uri} could not be loaded", LOG_TAG, Qgis.Warning)
            return
        layer.setSubsetString("fid IN (SELECT MAX(fid) FROM birdseye_verdicts WHERE provenance = 'direct' "
                              "GROUP BY unit_key) AND verdict <> 'unreviewed'")
        _style_verdicts(layer)
        project.addMapLayer(layer)
        self.verdict_layer, self._verdict_layer_id = layer, layer.id()

    def _refresh_verdict_layer(self):
        if self.verdict_layer is not None and not sip.isdeleted(self.verdict_layer):
            self.verdict_layer.dataProvider().reloadData()
            self.verdict_layer.triggerRepaint()

    def _show_banner(self, messages, error=False):
        colour, background = ("#c62828", "#fdecea") if error else ("#ef8f00", "#fff4e5")
        self.banner.setStyleSheet(f"QLabel{{background:{background};border-left:5px solid {colour};"
                                  "border-radius:3px;padding:6px;}")
        title = tr("Cannot start the review") if error else tr("Inputs changed since verdicts were recorded")
        self.banner.setText(f"<b>{title}</b><ul style='margin:2px 0 0 -20px'>" +
                            "".join(f"<li>{m}</li>" for m in messages) + "</ul>")
        self.banner.show()

    # ------------------------------------------------------------------ lifetime
    def closeEvent(self, event):  # noqa: N802
        self._end_add_target()
        super().closeEvent(event)

    def shutdown(self):
        """Stop workers and close the log (the plugin's unload and the tests call this)."""
        self._score_timer.stop()
        self._pool.clear()
        self._pool.waitForDone(5000)
        self._end_add_target()
        if self._marker is not None and self.canvas is not None:
            self.canvas.scene().removeItem(self._marker)
            self._marker = None
        self._stop_session()
        project = QgsProject.instance()
        for signal, slot in ((project.layersAdded, self._refill_detection_layers),
                             (project.layersRemoved, self._on_layers_removed),
                             (project.readProject, self._restore_from_project)):
            try:
                signal.disconnect(slot)
            except (TypeError, RuntimeError):
                pass


def _os_user() -> str:
    try:
        return getpass.getuser()
    except Exception:  # noqa: BLE001 — no login name (some containers): still a valid review
        return "reviewer"


def _style_verdicts(layer):
    from qgis.core import QgsCategorizedSymbolRenderer, QgsMarkerSymbol, QgsRendererCategory

    categories = []
    for verdict in ("confirmed_real", "hard_negative", "uncertain", "added"):
        colour = VERDICT_COLOURS[verdict]
        symbol = QgsMarkerSymbol.createSimple(
            {"name": "cross2", "color": colour, "size": "4", "outline_color": colour, "outline_width": "0.8"}
            if verdict == "added" else
            {"name": "circle", "color": colour, "size": "3.2", "outline_color": "white", "outline_width": "0.4"})
        categories.append(QgsRendererCategory(verdict, symbol, VERDICT_TEXT[verdict]))
    layer.setRenderer(QgsCategorizedSymbolRenderer("verdict", categories))
