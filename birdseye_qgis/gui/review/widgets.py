"""The review dock's widgets: the chip strip, the keyboard-driven review panel, and the setup and review
areas, whose widgets become attributes of the dock so its slots (and tests) reach them by name."""
from __future__ import annotations

from qgis.core import QgsSettings
from qgis.gui import (
    QgsCheckableComboBox,
    QgsCollapsibleGroupBox,
    QgsDoubleSpinBox,
    QgsFileWidget,
    QgsMapLayerComboBox,
    QgsSpinBox,
)
from qgis.PyQt.QtCore import QEvent, Qt
from qgis.PyQt.QtGui import QImage, QPixmap
from qgis.PyQt.QtWidgets import (
    QAbstractItemView,
    QCheckBox,
    QComboBox,
    QFormLayout,
    QFrame,
    QGridLayout,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QLineEdit,
    QProgressBar,
    QPushButton,
    QSizePolicy,
    QTableView,
    QTableWidget,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from ...__about__ import tr
from ...core.detect.clustering import CORE_COUNT_CELLS, CORE_COUNT_DETECTIONS, DEFAULT_DEDUP_CM
from ...core.review.chips import DEFAULT_WINDOW_PX, GEOTAG_COLOUR, LAYER_COLOURS
from ...core.review.units import CONSENSUS_UNITS, METHOD_UNITS, PROPAGATION_EPS_M, PROPAGATION_RULE
from ...core.scoring.verdicts import CONVENTIONS
from ...qgis_enums import FILTER_POINT_LAYER, FILTER_VECTOR_LAYER
from .model import CONVENTION_TEXT, VERDICT_COLOURS, VERDICT_TEXT, UnitTableModel, fit_scores_height, size_score_names

SETTINGS_REVIEWER = "birdseye/review/reviewer"
CHIP_DISPLAY_PX = 150
DEFAULT_SCALE = 100
#: The unit filters: (mode of core.review.navigation.passes_filter, label).
FILTERS = [("all", "All units"), ("todo", "To review (no vote yet)"), ("confirmed_real", "Confirmed real"),
           ("hard_negative", "Hard negative"), ("uncertain", "Uncertain"),
           ("propagated", "Propagated votes only"), ("conflict", "Conventions disagree"),
           ("unmatched", "No geotag nearby"), ("added", "Added targets")]
# Keys → command; digits also arrive with the keypad modifier.
KEYMAP = {Qt.Key.Key_1: "confirmed_real", Qt.Key.Key_C: "confirmed_real",
          Qt.Key.Key_2: "hard_negative", Qt.Key.Key_H: "hard_negative",
          Qt.Key.Key_3: "uncertain", Qt.Key.Key_U: "uncertain",
          Qt.Key.Key_0: "unreviewed", Qt.Key.Key_Backspace: "unreviewed",
          Qt.Key.Key_N: "next", Qt.Key.Key_Right: "next", Qt.Key.Key_P: "previous", Qt.Key.Key_Left: "previous",
          Qt.Key.Key_Home: "first", Qt.Key.Key_End: "last", Qt.Key.Key_A: "add", Qt.Key.Key_Escape: "cancel_add"}


def default_reviewer() -> str:
    """The login name, the reviewer a verdict is recorded under unless the user types another."""
    import getpass

    try:
        return getpass.getuser()
    except Exception:  # noqa: BLE001 — no login name (some containers): still a valid review
        return "reviewer"

class ChipStrip(QWidget):
    """Chips side by side, reflowed to the dock's width."""

    def __init__(self, parent=None):
        super().__init__(parent)
        self.grid = QGridLayout(self)
        self.grid.setContentsMargins(0, 0, 0, 0)
        self.grid.setSpacing(6)
        self.tiles: list[QWidget] = []
        self.message = QLabel()
        self.message.setAlignment(Qt.AlignmentFlag.AlignCenter)
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
            text.setAlignment(Qt.AlignmentFlag.AlignCenter)
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
            self.grid.addWidget(tile, i // columns, 1 + i % columns, Qt.AlignmentFlag.AlignCenter)

    def resizeEvent(self, event):
        super().resizeEvent(event)
        if self.tiles:
            self._reflow()


class ReviewPanel(QWidget):
    """The review area: owns the keyboard (see the module docstring) while it has the focus."""

    def __init__(self, dock):
        super().__init__()
        self.dock = dock
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)

    @staticmethod
    def command(event) -> str | None:
        modifiers = event.modifiers() & ~Qt.KeyboardModifier.KeypadModifier
        if event.key() == Qt.Key.Key_Z and modifiers == Qt.KeyboardModifier.ControlModifier:
            return "undo"
        if modifiers not in (Qt.KeyboardModifier.NoModifier, Qt.KeyboardModifier.ShiftModifier) \
                and event.key() not in (Qt.Key.Key_Left, Qt.Key.Key_Right):
            return None
        return KEYMAP.get(event.key())

    def event(self, event):
        # Our keys win over QGIS's window-wide shortcuts while the review area has the focus.
        if event.type() == QEvent.Type.ShortcutOverride and self.command(event) is not None:
            event.accept()
            return True
        return super().event(event)

    def keyPressEvent(self, event):
        command = self.command(event)
        if command is None:
            super().keyPressEvent(event)
            return
        event.accept()
        self.dock.run_command(command)


def spin_box(lo, hi, value, decimals, suffix, tip):
    spin = QgsDoubleSpinBox()
    spin.setRange(lo, hi)
    spin.setDecimals(decimals)
    spin.setValue(value)
    spin.setClearValue(value)
    spin.setSuffix(suffix)
    spin.setToolTip(tr(tip))
    return spin


def tool_button(text, slot, tip):
    b = QToolButton()
    b.setText(tr(text))
    b.setToolTip(tr(tip))
    b.setFocusPolicy(Qt.FocusPolicy.NoFocus)
    b.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextOnly)
    b.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Fixed)
    b.clicked.connect(slot)
    return b


def frames_tip(on_raster: bool) -> str:
    """The frame choice's tooltip: what it is for, or (detections found on a raster) why it is not needed."""
    if on_raster:
        return tr("Not needed: the detections chosen were found on a raster (Detect targets on a raster). Their "
                  "chips are cut from that raster, and the geotags in view are those it covers.")
    return tr("The flight's frame layer (Import flight log, Import drone images or Import camera solution): poses, "
              "camera and image of every frame. Only frame layers are listed. Detections found on a raster need "
              "none.")


def build_setup_box(dock):
    box = QgsCollapsibleGroupBox(tr("Review setup"))
    form = QFormLayout(box)
    form.setFieldGrowthPolicy(QFormLayout.FieldGrowthPolicy.AllNonFixedFieldsGrow)
    dock.detections_combo = QgsCheckableComboBox()
    dock.detections_combo.setDefaultText(tr("choose one or more detection layers"))
    dock.detections_combo.setToolTip(tr("Outputs of Detect targets over one flight (several checkpoints or "
                                        "thresholds are reviewed together: one verdict per spot)."))
    form.addRow(tr("Detections"), dock.detections_combo)
    dock.frames_combo = QgsMapLayerComboBox()
    dock.frames_combo.setFilters(FILTER_VECTOR_LAYER)
    dock.frames_combo.setAllowEmptyLayer(True)
    dock.frames_combo.setToolTip(frames_tip(False))
    form.addRow(tr("Frames"), dock.frames_combo)
    dock.geotags_combo = QgsMapLayerComboBox()
    dock.geotags_combo.setFilters(FILTER_POINT_LAYER)
    dock.geotags_combo.setAllowEmptyLayer(True)
    dock.geotags_combo.setToolTip(tr("The survey points (Import geotags). Point layers that BirdsEye made for "
                                     "something else (detections, clusters, waypoints, verdicts) are not "
                                     "listed."))
    form.addRow(tr("Geotags"), dock.geotags_combo)
    dock.store_widget = QgsFileWidget()
    dock.store_widget.setStorageMode(QgsFileWidget.StorageMode.SaveFile)
    dock.store_widget.setConfirmOverwrite(False)
    dock.store_widget.setFilter("GeoPackage (*.gpkg)")
    dock.store_widget.setToolTip(tr("GeoPackage holding the append-only verdict log (table birdseye_verdicts). "
                                    "Default: the first detection layer's GeoPackage, else one next to the "
                                    "project."))
    dock.store_widget.lineEdit().setPlaceholderText(tr("the detections' GeoPackage"))
    form.addRow(tr("Verdict log"), dock.store_widget)
    dock.reviewer_edit = QLineEdit(QgsSettings().value(SETTINGS_REVIEWER, "") or default_reviewer())
    dock.reviewer_edit.setToolTip(tr("Recorded with every verdict."))
    dock.reviewer_edit.editingFinished.connect(dock._on_reviewer_changed)
    form.addRow(tr("Reviewer"), dock.reviewer_edit)

    params = QgsCollapsibleGroupBox(tr("Clustering and matching"))
    params.setCollapsed(True)
    pform = QFormLayout(params)
    dock.units_combo = QComboBox()
    dock.units_combo.addItem(tr("One per spot"), CONSENSUS_UNITS)
    dock.units_combo.addItem(tr("One per spot and frame (the method's)"), METHOD_UNITS)
    dock.units_combo.setItemData(0, tr("Consensus clusters: one unit per spot, pooling all layers"),
                                 Qt.ItemDataRole.ToolTipRole)
    dock.units_combo.setItemData(1, tr("The method's units: per frame, complete linkage at {px:.0f} px").format(
        px=dock.params.group_px), Qt.ItemDataRole.ToolTipRole)
    dock.units_combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
    dock.units_combo.setMinimumContentsLength(12)
    dock.units_combo.setToolTip(tr("How detections become review units. Consensus clusters (the default) pool "
                                   "the layers and judge each spot once. The method's: detections within "
                                   "EPS_PRED of an in-view geotag are set aside one by one; per frame, the rest "
                                   "are grouped so that every two detections of a group are at most {px:.0f} px "
                                   "apart; each group is a unit, so a spot is judged once per frame.").format(
                                       px=dock.params.group_px))
    dock.dedup_spin = spin_box(0.1, 100.0, DEFAULT_DEDUP_CM, 1, " cm",
                                   "De-duplication grid cell, as in Cluster detections.")
    dock.eps_spin = spin_box(0.001, 50.0, dock.params.eps_m, 3, " m", "DBSCAN radius EPS of the units.")
    dock.min_samples_spin = QgsSpinBox()
    dock.min_samples_spin.setRange(1, 1000)
    dock.min_samples_spin.setValue(dock.params.min_samples)
    dock.min_samples_spin.setClearValue(dock.params.min_samples)
    dock.min_samples_spin.setToolTip(tr("DBSCAN minimum points per neighbourhood (itself included)."))
    dock.core_count_combo = QComboBox()
    dock.core_count_combo.addItem(tr("Detections"), CORE_COUNT_DETECTIONS)
    dock.core_count_combo.addItem(tr("Cells (the method's)"), CORE_COUNT_CELLS)
    dock.core_count_combo.setCurrentIndex(dock.core_count_combo.findData(dock.params.core_count))
    dock.core_count_combo.setToolTip(tr("What the minimum points count, as in Cluster detections: the detections "
                                        "in the grid cells within EPS (the default), or the occupied cells, one "
                                        "point each (the method's: a spot whose detections all fall in one cell "
                                        "never forms a unit)."))
    dock.eps_pred_spin = spin_box(0.001, 50.0, dock.params.eps_pred_m, 3, " m",
                                      "Match radius geotag ↔ cluster core points (EPS_PRED).")
    dock.edge_spin = spin_box(0.0, 1000.0, dock.params.edge_buffer_px, 1, " px",
                                  "Edge buffer of the in-view test.")
    dock.window_spin = QgsSpinBox()
    dock.window_spin.setRange(32, 1024)
    dock.window_spin.setSingleStep(16)
    dock.window_spin.setValue(DEFAULT_WINDOW_PX)
    dock.window_spin.setClearValue(DEFAULT_WINDOW_PX)
    dock.window_spin.setSuffix(" px")
    dock.window_spin.setToolTip(tr("Size of the image window cut around a detection."))
    dock.window_spin.valueChanged.connect(dock._on_window_changed)
    dock.scale_spin = QgsSpinBox()
    dock.scale_spin.setRange(10, 100000)
    dock.scale_spin.setValue(DEFAULT_SCALE)
    dock.scale_spin.setClearValue(DEFAULT_SCALE)
    dock.scale_spin.setPrefix("1:")
    dock.scale_spin.setToolTip(tr("Map scale the canvas zooms to around each unit."))
    for label, widget in ((tr("Review units"), dock.units_combo), (tr("Grid cell"), dock.dedup_spin),
                          (tr("EPS"), dock.eps_spin),
                          (tr("Min. points"), dock.min_samples_spin), (tr("Points count"), dock.core_count_combo),
                          (tr("EPS_PRED"), dock.eps_pred_spin),
                          (tr("Edge buffer"), dock.edge_spin), (tr("Chip window"), dock.window_spin),
                          (tr("Map scale"), dock.scale_spin)):
        pform.addRow(label, widget)
    form.addRow(params)
    dock.start_button = QPushButton(tr("Start / resume review"))
    dock.start_button.setDefault(True)
    dock.start_button.clicked.connect(dock.start_review)
    form.addRow(dock.start_button)
    dock.setup_box = box
    return box


def build_review_area(dock, panel):
    v = QVBoxLayout(panel)
    v.setContentsMargins(0, 0, 0, 0)
    v.setSpacing(6)
    # progress
    row = QHBoxLayout()
    dock.progress_label = QLabel(tr("No review started"))
    dock.progress_label.setWordWrap(True)
    dock.progress_bar = QProgressBar()
    dock.progress_bar.setTextVisible(False)
    dock.progress_bar.setMaximumHeight(8)
    row.addWidget(dock.progress_label, 1)
    v.addLayout(row)
    v.addWidget(dock.progress_bar)
    # filters
    row = QHBoxLayout()
    dock.layer_filter = QComboBox()
    dock.layer_filter.addItem(tr("All layers"), "")
    dock.verdict_filter = QComboBox()
    for key, text in FILTERS:
        dock.verdict_filter.addItem(tr(text), key)
    for combo in (dock.layer_filter, dock.verdict_filter):
        combo.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        combo.setMinimumContentsLength(6)
        combo.setFocusPolicy(Qt.FocusPolicy.ClickFocus)
        combo.currentIndexChanged.connect(dock._on_filter)
        combo.activated.connect(lambda *_: dock.panel.setFocus())
    row.addWidget(QLabel(tr("Fired by")))
    row.addWidget(dock.layer_filter, 1)
    row.addWidget(QLabel(tr("Show")))
    row.addWidget(dock.verdict_filter, 1)
    v.addLayout(row)
    # units
    dock.model = UnitTableModel(dock)
    dock.table = QTableView()
    dock.table.setModel(dock.model)
    dock.table.setFocusPolicy(Qt.FocusPolicy.NoFocus)
    dock.table.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
    dock.table.setSelectionMode(QAbstractItemView.SelectionMode.SingleSelection)
    dock.table.setAlternatingRowColors(True)
    dock.table.verticalHeader().hide()
    dock.table.verticalHeader().setDefaultSectionSize(20)
    header = dock.table.horizontalHeader()
    header.setMinimumSectionSize(24)
    header.setSectionResizeMode(QHeaderView.ResizeMode.ResizeToContents)
    header.setSectionResizeMode(1, QHeaderView.ResizeMode.Stretch)
    dock.table.setMinimumHeight(120)
    dock.table.setMaximumHeight(150)
    dock.table.clicked.connect(lambda index: dock.go_to(dock.model.keys[index.row()]))
    v.addWidget(dock.table)
    # the current unit
    dock.unit_label = QLabel(tr("Choose the layers above and press Start: each unit to judge shows here."))
    dock.unit_label.setWordWrap(True)
    dock.unit_label.setTextFormat(Qt.TextFormat.RichText)
    dock.unit_label.setStyleSheet("QLabel{background:#f5f7fa;border:1px solid #d8dde6;border-radius:4px;"
                                  "padding:6px;}")
    v.addWidget(dock.unit_label)
    # verdicts and moves
    grid = QGridLayout()
    grid.setSpacing(4)
    dock.prev_button = tool_button("◀  " + tr("Previous (P)"), lambda: dock.run_command("previous"),
                                    "Previous unit of the list (P or ←)")
    dock.next_button = tool_button(tr("Next (N)") + "  ▶", lambda: dock.run_command("next"),
                                    "Next unit of the list (N or →)")
    grid.addWidget(dock.prev_button, 0, 0)
    grid.addWidget(dock.next_button, 0, 1)
    dock.verdict_buttons = {}
    for i, (verdict, key, other) in enumerate((("confirmed_real", "1", "C"), ("hard_negative", "2", "H"),
                                               ("uncertain", "3", "U"), ("unreviewed", "0", "Backspace"))):
        b = tool_button(f"{VERDICT_TEXT[verdict]}  ({key})", lambda _, x=verdict: dock.run_command(x),
                         f"Record '{verdict}' for this unit (key {key} or {other})")
        colour = VERDICT_COLOURS[verdict]
        b.setStyleSheet(f"QToolButton{{border:1px solid {colour};border-left:6px solid {colour};border-radius:3px;"
                        f"padding:6px 8px;background:white;}}"
                        f"QToolButton:hover{{background:{colour}22;}}"
                        f"QToolButton:checked{{background:{colour};color:white;font-weight:bold;}}")
        b.setCheckable(True)
        grid.addWidget(b, 1 + i // 2, i % 2)
        dock.verdict_buttons[verdict] = b
    dock.undo_button = tool_button("↶  " + tr("Undo (Ctrl+Z)"), lambda: dock.run_command("undo"),
                                    "Undo the last action (appends rows restoring the previous verdicts)")
    dock.add_button = tool_button("+  " + tr("Missed target (A)"), lambda: dock.run_command("add"),
                                   "Click the map where a target was missed (A; Esc cancels)")
    dock.add_button.setCheckable(True)
    grid.addWidget(dock.undo_button, 3, 0)
    grid.addWidget(dock.add_button, 3, 1)
    v.addLayout(grid)
    # the frames that show the unit, under the buttons: on a laptop screen the buttons stay in view
    dock.chips = ChipStrip()
    dock.chips.show_message(tr("The frames that show the unit"))
    dock.chips.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Minimum)
    v.addWidget(dock.chips)
    dock.chip_legend = QLabel()
    dock.chip_legend.setWordWrap(True)   # one entry per detection layer: as long as their names
    dock.chip_legend.setTextFormat(Qt.TextFormat.RichText)
    dock.chip_legend.setStyleSheet("color:#555; font-size:11px;")
    v.addWidget(dock.chip_legend)
    dock.propagate_check = QCheckBox(tr("Propagate to units within {:.2f} m").format(PROPAGATION_EPS_M))
    dock.propagate_check.setToolTip(tr("Off by default. When on, a verdict also votes (provenance "
                                       "propagated:{rule}) on the units chained to this one by gaps of at "
                                       "most {eps:.2f} m; conflicting votes are resolved under the three "
                                       "conventions, all shown.").format(rule=PROPAGATION_RULE,
                                                                         eps=PROPAGATION_EPS_M))
    dock.advance_check = QCheckBox(tr("Next unit after a verdict"))
    dock.advance_check.setChecked(True)
    for c in (dock.propagate_check, dock.advance_check):
        c.setFocusPolicy(Qt.FocusPolicy.NoFocus)
        v.addWidget(c)
    dock.propagate_check.toggled.connect(dock._on_propagate_toggled)
    # scores
    title = QLabel(tr("<b>Scores per detection layer</b> — after review under each tie-break convention"))
    title.setWordWrap(True)
    title.setToolTip(tr("Recall and the geotag-matched cluster fraction (GMCF), computed as Evaluate "
                        "detections computes them from this verdict log."))
    v.addWidget(title)
    dock.scores_table = QTableWidget(0, 5)
    dock.scores_table.setHorizontalHeaderLabels(["", tr("before\nreview")] +
                                                [CONVENTION_TEXT[c].replace("-wins", "\nwins").replace(
                                                    "hard-negative", "hard-neg.") for c in CONVENTIONS])
    for c, convention in enumerate(CONVENTIONS):
        dock.scores_table.horizontalHeaderItem(c + 2).setToolTip(tr("After review, {}").format(
            CONVENTION_TEXT[convention]))
    dock.scores_table.verticalHeader().hide()
    dock.scores_table.setFocusPolicy(Qt.FocusPolicy.NoFocus)
    dock.scores_table.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
    dock.scores_table.setSelectionMode(QAbstractItemView.SelectionMode.NoSelection)
    dock.scores_table.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Stretch)
    # Column 0 is as wide as its row names, not as the layer titles spanning the table.
    dock.scores_table.horizontalHeader().setSectionResizeMode(0, QHeaderView.ResizeMode.Fixed)
    size_score_names(dock.scores_table)
    dock.scores_table.horizontalHeader().setSectionResizeMode(1, QHeaderView.ResizeMode.ResizeToContents)
    dock.scores_table.setWordWrap(False)
    dock.scores_table.horizontalHeader().setStyleSheet("QHeaderView::section{padding:1px 2px;font-size:11px;}")
    dock.scores_table.verticalHeader().setDefaultSectionSize(20)
    dock.scores_table.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
    fit_scores_height(dock.scores_table)
    v.addWidget(dock.scores_table)
    dock.scores_note = QLabel(tr("GMCF is a lower bound on precision, not precision; recall after review is an "
                                 "upper bound (≥). The spread between the conventions is part of the result."))
    dock.scores_note.setWordWrap(True)
    dock.scores_note.setStyleSheet("color:#555; font-size:11px;")
    v.addWidget(dock.scores_note)
    dock.status_label = QLabel()
    dock.status_label.setWordWrap(True)
    dock.status_label.setStyleSheet("color:#555;")
    v.addWidget(dock.status_label)
    v.addStretch(1)


def show_chips(strip: ChipStrip, legend_label: QLabel, plans, images, n_frames: int, error, layer_names,
               on_raster: bool = False) -> None:
    """A unit's chips (or why there are none) and the legend: one colour per layer, the geotag cross.
    ``on_raster``: the chips are windows of the raster the detections were found on, not frames."""
    if error:
        strip.show_message((tr("The raster could not be read: {}") if on_raster
                            else tr("The frames could not be read: {}")).format(error))
    elif not plans:
        strip.show_message(tr("This spot is off the raster.") if on_raster
                           else tr("No frame of the frame layer shows this spot."))
    else:
        items = []
        for plan, rgb in zip(plans, images):
            h, w = rgb.shape[:2]
            pixmap = QPixmap.fromImage(QImage(rgb.tobytes(), w, h, 3 * w, QImage.Format.Format_RGB888).copy())
            caption = (tr("raster") if on_raster else tr("frame {f}").format(f=plan.frame_id)) + (
                f" · {plan.score:.2f}" if plan.score is not None else "")
            items.append((pixmap, caption, plan.image))
        strip.set_chips(items)
    legend = " ".join(f"<span style='color:rgb{LAYER_COLOURS[k % len(LAYER_COLOURS)]}'>◯</span> {n}"
                      for k, n in enumerate(layer_names))
    shown = tr("cut from the raster") if on_raster else tr("{shown} of {n} frames").format(shown=len(plans),
                                                                                          n=n_frames)
    legend_label.setText(f"{legend} &nbsp; <span style='color:rgb{GEOTAG_COLOUR}'>✕</span> {tr('geotag')} &nbsp; "
                         + shown)


def show_banner(label: QLabel, messages, error: bool = False, title: str | None = None) -> None:
    """A warning (by default: inputs changed since verdicts were recorded) or an error (cannot start) above
    the review."""
    colour, background = ("#c62828", "#fdecea") if error else ("#ef8f00", "#fff4e5")
    label.setStyleSheet(f"QLabel{{background:{background};border-left:5px solid {colour};"
                        "border-radius:3px;padding:6px;}")
    title = title or (tr("Cannot start the review") if error else tr("Inputs changed since verdicts were recorded"))
    label.setText(f"<b>{title}</b><ul style='margin:2px 0 0 -20px'>" +
                  "".join(f"<li>{m}</li>" for m in messages) + "</ul>")
    label.show()
