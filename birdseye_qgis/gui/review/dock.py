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

import time

from qgis.core import (
    Qgis,
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsMessageLog,
    QgsPointXY,
    QgsProject,
    QgsSettings,
)
from qgis.gui import QgsDockWidget
from qgis.PyQt.QtCore import Qt, QThreadPool, QTimer
from qgis.PyQt.QtWidgets import QApplication, QFrame, QLabel, QScrollArea, QVBoxLayout, QWidget

from ...__about__ import LOG_TAG, tr
from ...core.errors import InputError
from ...core.review.actions import REVIEW_VERDICTS, UnitStatus, resume_key, unit_status
from ...core.review.chips import (
    FrameIndex,
    RasterIndex,
    plan_point_chips,
    plan_raster_point_chips,
    plan_raster_unit_chips,
    plan_unit_chips,
)
from ...core.review.digests import InputCheck, check_inputs
from ...core.review.navigation import Entries, display_verdict
from ...core.review.units import ADDED_PREFIX, CONSENSUS_UNITS, ReviewParameters, ReviewUnits, build_units
from ...core.scoring.operating_point import RECORDED_WITHOUT_CORE_COUNT, OperatingPoint
from ...qgis_io.detections import found_on_raster
from ...qgis_io.layer_kinds import DETECTIONS, FRAMES, GEOTAGS, layers_of_kind, most_recent, other_layers
from ...qgis_io.raster_reader import RasterPixels
from ...qgis_io.review_project import save_propagate, save_review, saved_review
from ...qgis_io.review_store import ReviewSession, RowMeta, default_store_path, open_store, read_review_inputs
from ..add_target_tool import AddTargetTool
from .jobs import ChipLoader, JobSignals, ScoreJob
from .map_context import ReviewMap
from .model import VERDICT_COLOURS, fill_scores_table, unit_summary_html
from .widgets import (
    CHIP_DISPLAY_PX,
    SETTINGS_REVIEWER,
    ReviewPanel,
    build_review_area,
    build_setup_box,
    default_reviewer,
    frames_tip,
    show_banner,
    show_chips,
)

SCORE_DELAY_MS = 120


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
        # A review of detections found on a raster: its pixels (chip windows, map → pixel) and the chips' view.
        self.raster_pixels: RasterPixels | None = None
        self.raster: RasterIndex | None = None
        self.geotag_local = None
        self.geotag_labels: list[str] = []
        self.params = ReviewParameters()
        self.entries: Entries | None = None
        self.visible: list[str] = []
        self.current_key: str | None = None
        self.input_check: InputCheck | None = None
        self.scores: dict = {}
        self.scores_error: str | None = None
        self.chip_latencies_ms: list[float] = []
        self._score_generation = 0
        self._shown_score_generation = 0
        self._input_layer_ids: set = set()
        self._status_cache: dict = {}
        self._nav_started: float | None = None
        self._shown_chips_for: str | None = None
        self._flights = []
        self._pool = QThreadPool(self)
        self._pool.setMaxThreadCount(2)
        self.chip_loader = ChipLoader(self._pool, CHIP_DISPLAY_PX)
        self.chip_loader.loaded.connect(self._on_chips)
        self._signals = JobSignals()
        self._signals.scores_ready.connect(self._on_scores)
        self._score_timer = QTimer(self)
        self._score_timer.setSingleShot(True)
        self._score_timer.timeout.connect(self._start_scores)
        self._tool: AddTargetTool | None = None
        # The layer choices the user made; the others follow the project (see _refresh_layer_choices).
        self._chosen: set[str] = set()
        # The verdict log path the dock filled in as the default of the layers then chosen (None: the user's own
        # choice): it follows the layers, so a review of other layers does not write into that layer's file.
        self._default_store_path: str | None = None
        self._filling_choices = False
        self.map = ReviewMap(self.canvas, self)
        self._build_ui()
        project = QgsProject.instance()
        project.layersAdded.connect(self._refresh_layer_choices)
        project.layersRemoved.connect(self._on_layers_removed)
        project.readProject.connect(self._restore_from_project)
        self._refresh_layer_choices()
        QTimer.singleShot(0, self._restore_from_project)

    # ------------------------------------------------------------------ UI
    def _build_ui(self):
        scroll = QScrollArea()
        scroll.setWidgetResizable(True)
        scroll.setFrameShape(QFrame.Shape.NoFrame)
        scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        body = QWidget()
        outer = QVBoxLayout(body)
        outer.setContentsMargins(6, 6, 6, 6)
        outer.setSpacing(6)
        outer.addWidget(build_setup_box(self))
        # A layer the user picks (or a detection layer ticked) stays chosen; the other choices follow it.
        self.detections_combo.checkedItemsChanged.connect(lambda *_: self._on_layer_chosen(DETECTIONS))
        self.frames_combo.activated.connect(lambda *_: self._on_layer_chosen(FRAMES))
        self.geotags_combo.activated.connect(lambda *_: self._on_layer_chosen(GEOTAGS))
        self.banner = QLabel()
        self.banner.setWordWrap(True)
        self.banner.setTextFormat(Qt.TextFormat.RichText)
        self.banner.hide()
        outer.addWidget(self.banner)
        self.panel = ReviewPanel(self)
        self.panel.setEnabled(False)
        outer.addWidget(self.panel)
        build_review_area(self, self.panel)
        scroll.setWidget(body)
        self.setWidget(scroll)
        self.setMinimumWidth(360)

    # ------------------------------------------------------------------ layer choices
    def _refresh_layer_choices(self, *_):
        """Offer only layers of each input's kind; a choice the user has not made follows the project: the
        most recent detection layer, and the most recent frames and geotags over the same ground."""
        project = QgsProject.instance()
        self._filling_choices = True
        try:
            checked = set(self.detections_combo.checkedItemsData())
            detection_layers = layers_of_kind(project, DETECTIONS)
            if DETECTIONS not in self._chosen:
                checked = {detection_layers[0].id()} if detection_layers else set()
            self.detections_combo.clear()
            for layer in sorted(detection_layers, key=lambda layer: layer.name().lower()):   # as the other combos
                self.detections_combo.addItemWithCheckState(
                    layer.name(), Qt.CheckState.Checked if layer.id() in checked else Qt.CheckState.Unchecked,
                    layer.id())
            self.frames_combo.setExceptedLayerList(other_layers(project, FRAMES))
            self.geotags_combo.setExceptedLayerList(other_layers(project, GEOTAGS))
            chosen = self._chosen_detection_layers()
            if FRAMES not in self._chosen:
                self.frames_combo.setLayer(most_recent(project, FRAMES, chosen[0] if chosen else None))
            if GEOTAGS not in self._chosen:
                self.geotags_combo.setLayer(most_recent(project, GEOTAGS, self.frames_combo.currentLayer()
                                                        or (chosen[0] if chosen else None)))
        finally:
            self._filling_choices = False
        self._show_frames_needed()

    def _show_frames_needed(self):
        """Detections found on a raster need no frame layer: the frame choice is disabled then, saying why."""
        on_raster = self._reviews_a_raster()
        self.frames_combo.setEnabled(not on_raster)
        self.frames_combo.setToolTip(frames_tip(on_raster))

    def _reviews_a_raster(self) -> bool:
        """Whether every detection layer chosen was found on a raster (a mix is refused at Start)."""
        chosen = self._chosen_detection_layers()
        return bool(chosen) and all(found_on_raster(layer) for layer in chosen)

    def _on_layer_chosen(self, kind: str):
        """The user picked a layer (or ticked a detection layer): that choice stays; the others follow it."""
        if self._filling_choices:
            return
        self._chosen.add(kind)
        self._refresh_layer_choices()

    def set_inputs(self, detection_layers, frame_layer, geotag_layer, store_path: str | None = None):
        """Choose the review's layers (what the user does in the setup box)."""
        self._chosen |= {DETECTIONS, FRAMES, GEOTAGS}
        self._refresh_layer_choices()
        ids = {layer.id() for layer in detection_layers}
        self._filling_choices = True
        try:
            for i in range(self.detections_combo.count()):
                self.detections_combo.setItemCheckState(
                    i, Qt.CheckState.Checked if self.detections_combo.itemData(i) in ids else Qt.CheckState.Unchecked)
            self.frames_combo.setLayer(frame_layer)
            self.geotags_combo.setLayer(geotag_layer)
        finally:
            self._filling_choices = False
        self._show_frames_needed()
        if store_path is not None:
            self.store_widget.setFilePath(store_path)

    def _chosen_detection_layers(self):
        project = QgsProject.instance()
        return [project.mapLayer(i) for i in self.detections_combo.checkedItemsData() if project.mapLayer(i)]

    def _read_params(self) -> ReviewParameters:
        return ReviewParameters(self.dedup_spin.value(), self.eps_spin.value(), self.min_samples_spin.value(),
                                self.eps_pred_spin.value(), self.edge_spin.value(), self.units_combo.currentData(),
                                core_count=self.core_count_combo.currentData())

    # ------------------------------------------------------------------ start / resume
    def start_review(self) -> bool:
        """Read the inputs, build the units, open the log and go to where the review stopped."""
        detection_layers = self._chosen_detection_layers()
        frame_layer, geotag_layer = self.frames_combo.currentLayer(), self.geotags_combo.currentLayer()
        if self._reviews_a_raster():
            # Not part of the review: not read, not saved with it, and removing it does not stop it.
            frame_layer = None
        if not detection_layers:
            show_banner(self.banner, [tr("Choose at least one detection layer (an output of Detect targets).")],
                        error=True)
            return False
        chosen_path = self.store_widget.filePath().strip()
        if chosen_path and chosen_path == self._default_store_path:
            chosen_path = ""
        store_path = chosen_path or default_store_path(detection_layers, QgsProject.instance().fileName())
        if not store_path:
            show_banner(self.banner, [tr("Choose a GeoPackage for the verdict log (save the project first to get "
                                         "one next to it).")], error=True)
            return False
        if not store_path.lower().endswith(".gpkg"):
            store_path += ".gpkg"
        QApplication.setOverrideCursor(Qt.CursorShape.WaitCursor)
        try:
            params = self._read_params()
            inputs = read_review_inputs(detection_layers, frame_layer, geotag_layer)
            units = build_units(inputs.layers, inputs.local, inputs.geotags, inputs.pose_groups, params, inputs.ground,
                                inputs.view_mask)
            raster_pixels = RasterPixels(inputs.raster, QgsProject.instance().transformContext()) \
                if inputs.raster else None
            store = open_store(store_path, QgsProject.instance())
        except (InputError, OSError, ValueError) as exc:   # a message naming the layer, field or file
            show_banner(self.banner, [str(exc)], error=True)
            return False
        finally:
            QApplication.restoreOverrideCursor()
        self._stop_session()
        self.store_widget.setFilePath(store_path)
        self._default_store_path = None if chosen_path else store_path
        self.params, self.inputs, self.units = params, inputs, units
        reviewer = self.reviewer_edit.text().strip() or default_reviewer()
        QgsSettings().setValue(SETTINGS_REVIEWER, reviewer)
        self.session = ReviewSession(store, units, reviewer, inputs.digests, params)
        self.frames = FrameIndex(inputs.pose_groups, inputs.images, inputs.local, inputs.ground)
        g = inputs.geotags
        self.geotag_local = g.in_local(inputs.local) if len(g) else None
        self.geotag_labels = [str(i) for i in g.ids]
        self.raster_pixels = raster_pixels
        self.raster = raster_pixels.index(g) if raster_pixels is not None else None
        self._flights = inputs.flights()
        self.chip_loader.pixels = raster_pixels or self.chip_loader.frame_images
        self.chip_loader.reset()
        self.input_check = check_inputs(self.session.ledger.rows, inputs.digests,
                                           {**params.postprocessing(), **params.matching()}, units.keys)
        notes = [] if self.input_check.ok else self.input_check.messages()
        if inputs.ground_fallback:
            notes.append(tr("The detections were placed on {ground}, which cannot be used here ({reason}). Chips and "
                            "geotags in view stand on the level plane instead: positions in the chips and the scores "
                            "may differ from those of Evaluate detections given that DEM.").format(
                ground=inputs.layers[0].detections.ground.describe(), reason=inputs.ground_fallback))
        if notes:
            show_banner(self.banner, notes, title=None if not self.input_check.ok
                        else tr("The review stands on the level plane, not on the detections' DEM"))
        else:
            self.banner.hide()
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
        self._input_layer_ids = {layer.id() for layer in detection_layers + [frame_layer, geotag_layer] if layer}
        self._chosen |= {DETECTIONS, FRAMES, GEOTAGS}   # the setup keeps showing the layers under review
        self._save_to_project(detection_layers, frame_layer, geotag_layer, store_path)
        self.map.show_survey(geotag_layer)
        self.map.show_verdicts(self.session.store, tr("Review verdicts"))
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
        self._pool.clear()
        self.chip_loader.reset()
        self._status_cache.clear()
        if self.session is not None:
            self.session.store.close()
        self.session = None
        self.current_key = None
        self.entries, self.visible = None, []
        self.model.set_keys([])

    @staticmethod
    def _set_combo(combo, data):
        i = combo.findData(data)
        combo.blockSignals(True)
        combo.setCurrentIndex(max(i, 0))
        combo.blockSignals(False)

    # ------------------------------------------------------------------ project persistence
    def _save_to_project(self, detection_layers, frame_layer, geotag_layer, store_path):
        parameters = {**self.params.postprocessing(), **self.params.matching(), "window_px": self.window_spin.value(),
                      "scale": self.scale_spin.value()}
        save_review(QgsProject.instance(), detection_layers, frame_layer, geotag_layer, store_path, parameters,
                    self.propagate_check.isChecked())

    def _on_reviewer_changed(self):
        reviewer = self.reviewer_edit.text().strip() or default_reviewer()
        QgsSettings().setValue(SETTINGS_REVIEWER, reviewer)
        if self.session is not None:   # the next verdicts carry the new name
            self.session.meta = RowMeta.of(reviewer, self.session.digests, self.session.params)

    def _on_propagate_toggled(self, checked):
        if self.session is not None:   # part of the review's setup: reopening the project keeps it
            save_propagate(QgsProject.instance(), checked)

    def _restore_from_project(self, *_):
        """Reopen the review a project was saved with (layers, log, parameters) where it stopped."""
        saved = saved_review(QgsProject.instance())
        if saved is None:
            return
        for spin, name in ((self.dedup_spin, "dedup_cm"), (self.eps_spin, "eps_m"),
                           (self.min_samples_spin, "min_samples"), (self.eps_pred_spin, "eps_pred_m"),
                           (self.edge_spin, "edge_buffer_px"), (self.window_spin, "window_px"),
                           (self.scale_spin, "scale")):
            if name in saved.parameters:
                spin.setValue(saved.parameters[name])
        self._set_combo(self.units_combo, saved.parameters.get("units", CONSENSUS_UNITS))
        # A review saved before core_count was recorded built its units counting cells: reopen it as it was.
        self._set_combo(self.core_count_combo, saved.parameters.get("core_count", RECORDED_WITHOUT_CORE_COUNT))
        self.propagate_check.setChecked(saved.propagate)
        self.set_inputs(saved.detection_layers, saved.frame_layer, saved.geotag_layer, saved.store_path)
        self.start_review()

    def _on_layers_removed(self, layer_ids):
        self._refresh_layer_choices()
        if self.inputs is None or self.session is None:
            return
        self.map.forget_layers(layer_ids)
        if self._input_layer_ids & set(layer_ids):
            self._stop_session()
            self.panel.setEnabled(False)
            self.setup_box.setCollapsed(False)
            show_banner(self.banner, [tr("A layer of the review was removed from the project; the review stopped. "
                                         "Every verdict is in the log; choose the layers again to resume.")])

    # ------------------------------------------------------------------ entries, filters, status
    def _rebuild_entries(self):
        self.entries = Entries(self.units, [t.key for t in self.session.ledger.added_targets()])
        self._apply_filter()

    def _apply_filter(self):
        self.visible = self.entries.shown(self.layer_filter.currentData() or "",
                                          self.verdict_filter.currentData() or "all", self.status)
        self.model.set_keys(self.visible)
        self._select_current_row()
        self._update_progress()

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
        return display_verdict(key, self.status(key))

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
        return self.entries.neighbour(self.visible, key, step) if self.entries is not None else None

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
        elif self.current_key in self.entries:
            self._show_current()
        else:  # the undone action added the target on screen, which is gone: show the first unit left
            self.current_key = self.visible[0] if self.visible else None
            if self.current_key is not None:
                self.go_to(self.current_key, save=False)
            else:
                self._show_current()

    def _after_append(self, rows):
        self._status_cache.clear()
        added = [t.key for t in self.session.ledger.added_targets()]
        if self.entries.added_keys() != added:
            self._rebuild_entries()
        else:
            self._apply_filter()
        self._schedule_scores()
        self.map.refresh_verdicts_soon()

    def _report_store_error(self, exc):
        message = tr("The verdict was NOT saved: {error}. Check that {path} is writable and not locked, then try "
                     "again.").format(error=exc, path=self.session.store.path)
        show_banner(self.banner, [message], error=True)
        QgsMessageLog.logMessage(message, LOG_TAG, Qgis.MessageLevel.Critical)

    # ------------------------------------------------------------------ add a missed target
    def start_add_target(self):
        if self.canvas is None:
            return
        if self._tool is None:
            self._tool = AddTargetTool(self.canvas)
            self._tool.target_added.connect(self.add_target_at)
            self._tool.cancelled.connect(self._end_add_target)
        self._tool.take_over()
        self.add_button.setChecked(True)
        self.status_label.setText(tr("Click the map where the missed target is (Esc or right click cancels)."))

    def _end_add_target(self):
        if self._tool is not None:
            self._tool.hand_back()
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
        ref = self.session.ref(key)
        self.map.centre_on(ref.lat, ref.lon, self.scale_spin.value(), VERDICT_COLOURS[self.display_verdict(key)])
        for verdict, button in self.verdict_buttons.items():
            button.setChecked(not key.startswith(ADDED_PREFIX) and self.status(key).direct == verdict
                              and verdict != "unreviewed")
        if key in self.chip_loader.chips:
            self._display_chips(key)
        else:
            if self._shown_chips_for != key:
                self.chips.show_message(tr("Loading the raster…") if self.raster is not None
                                        else tr("Loading frames…"))
            self.chip_loader.request(key, self._planner(key), priority=10)
        self.chip_loader.prefetch(self.visible, key, self._planner)

    def _show_unit_text(self, key):
        if key.startswith(ADDED_PREFIX):
            ref = self.session.ref(key)
            self.unit_label.setText(tr("<b>Added target</b> {key}<br>{lat:.7f}°, {lon:.7f}° · recorded as a target "
                                       "the detector missed (the <i>a</i> term). 0 withdraws it.").format(
                key=key, lat=ref.lat, lon=ref.lon))
            return
        self.unit_label.setText(unit_summary_html(key, self.units, self.entries, self.status(key),
                                                  self.params.eps_pred_m, self.raster is not None))

    # ------------------------------------------------------------------ chips
    def _planner(self, key):
        """A chip-planning call for a worker thread, with everything it reads captured now."""
        units, frames, window = self.units, self.frames, self.window_spin.value()
        geotags, labels = self.geotag_local, self.geotag_labels
        raster = self.raster
        if key.startswith(ADDED_PREFIX):
            ref = self.session.ref(key)
            if raster is not None:   # placed on the raster here: the worker has no coordinate transform
                (col,), (row,) = self.raster_pixels.to_pixel([ref.lat], [ref.lon])
                return lambda k: plan_raster_point_chips(k, float(col), float(row), raster, window)
            return lambda k: plan_point_chips(k, ref.lat, ref.lon, frames, geotags, labels, window)
        if raster is not None:
            return lambda k: plan_raster_unit_chips(units, units.index[k], raster, window)
        return lambda k: plan_unit_chips(units, units.index[k], frames, geotags, labels, window)

    def _on_chips(self, key):
        if key == self.current_key:
            self._display_chips(key)

    def _display_chips(self, key):
        plans, images, n_frames, error = self.chip_loader.get(key)
        show_chips(self.chips, self.chip_legend, plans, images, n_frames, error, self.units.layer_names,
                   self.raster is not None)
        self._shown_chips_for = key
        if self._nav_started is not None:
            self.chip_latencies_ms.append((time.perf_counter() - self._nav_started) * 1000.0)
            self._nav_started = None

    def _on_window_changed(self, *_):
        self.chip_loader.reset()          # chips in flight were cut with the old window
        self._shown_chips_for = None
        if self.session is not None and self.current_key is not None:
            self._show_current()

    @property
    def verdict_layer(self):
        return self.map.verdict_layer

    @property
    def chips_shown_for(self) -> str | None:
        return self._shown_chips_for

    # ------------------------------------------------------------------ scores
    def _schedule_scores(self):
        self._score_timer.start(SCORE_DELAY_MS)

    def operating_point(self) -> OperatingPoint:
        return self.params.operating_point()

    def _start_scores(self):
        if self.session is None:
            return
        self._score_generation += 1
        self._pool.start(ScoreJob(self._signals, self._score_generation, self._flights, self.inputs.geotags,
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
        fill_scores_table(self.scores_table, result)

    # ------------------------------------------------------------------ map context
    # ------------------------------------------------------------------ lifetime
    def closeEvent(self, event):
        self._end_add_target()
        super().closeEvent(event)

    def shutdown(self):
        """Stop workers and close the log (the plugin's unload and the tests call this)."""
        self._score_timer.stop()
        self._pool.clear()
        self._pool.waitForDone(5000)
        self._end_add_target()
        self.map.remove_marker()
        self._stop_session()
        project = QgsProject.instance()
        for signal, slot in ((project.layersAdded, self._refresh_layer_choices),
                             (project.layersRemoved, self._on_layers_removed),
                             (project.readProject, self._restore_from_project)):
            try:
                signal.disconnect(slot)
            except (TypeError, RuntimeError):
                pass
