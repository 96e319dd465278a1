"""birdseye:writelabels — every geotag in every frame that sees it, written as a training set."""
from __future__ import annotations

import itertools
import json

import numpy as np
from qgis.core import (
    QgsFeature,
    QgsFeatureSink,
    QgsField,
    QgsFields,
    QgsProcessingException,
    QgsProcessingMultiStepFeedback,
    QgsProcessingOutputNumber,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFile,
    QgsProcessingParameterFolderDestination,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.__about__ import tr
from ...birdseye_qgis.core.field.frame_records import local_frame_around, poses_from_records, uses_geotag_heights
from ...birdseye_qgis.core.labels.mark_check import CONTROL_POINT, FEW_MARKS, measured_sigma
from ...birdseye_qgis.core.labels.relief import LOGGED_FRAMES, RELIEF_WINDOW_M, TargetRelief, dem_relief_m
from ...birdseye_qgis.core.labels.training_set import (
    LabelRequest,
    LabelWriter,
    frames_without_ground,
    label_sigma_px,
    project_labels,
)
from ...birdseye_qgis.qgis_enums import (
    NUMBER_DOUBLE,
    NUMBER_INTEGER,
    SOURCE_VECTOR,
    SOURCE_VECTOR_POINT,
    SOURCE_VECTOR_POLYGON,
)
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from ..parameters.dem import DemParametersMixin
from ..parameters.layer_parameters import source_parameter, vector_parameter
from ..parameters.review import ReviewParametersMixin
from ..parameters.surveyed_area import SurveyedAreaParametersMixin
from .base import BirdsEyeAlgorithm

#: SIGMA_PX's default: the label σ of core's LabelRequest.
DEFAULT_SIGMA_PX = LabelRequest.sigma_px
#: SIGMA_SOURCE's options: σ given (SIGMA_PX, or r/3 of SENSOR_BOUND_JSON), or measured on a label check.
SIGMA_SOURCES = ("Given (σ, or r/3 of the sensor bound)",
                 "Measured (RMS error of a label check)")
SIGMA_MEASURED = 1


def sigma_from_bound_json(path: str) -> float:
    """σ_label (px) from a ``sensorbound`` JSON: the label radius r at 3σ divided by 3."""
    try:
        doc = json.loads(open(path, encoding="utf-8").read())
        tolerance = float(doc["inputs"]["tolerance_px"])
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise QgsProcessingException(
            tr("{path}: not a sensorbound result (expected inputs.tolerance_px): {exc}").format(
                path=path, exc=exc)) from exc
    rejected = [a["altitude_m"] for a in doc.get("altitudes", []) if a.get("verdict_exact") == "reject"]
    if rejected:
        raise QgsProcessingException(
            tr("{path}: the pose-noise budget is rejected at {items}; labels of σ = {value:g} px "
               "would not contain the projection error there").format(
                path=path, items=', '.join(f'{a:g} m' for a in rejected), value=label_sigma_px(tolerance)))
    return label_sigma_px(tolerance)


class WriteLabels(ReviewParametersMixin, DemParametersMixin, SurveyedAreaParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "writelabels"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("WriteLabels", "Write training labels")
    GROUP = "labels"
    GEOTAGS = "GEOTAGS"
    FRAMES = "FRAMES"
    SIGMA_PX = "SIGMA_PX"
    SENSOR_BOUND_JSON = "SENSOR_BOUND_JSON"
    SIGMA_SOURCE = "SIGMA_SOURCE"
    MARK_CHECK = "MARK_CHECK"
    EDGE_BUFFER_PX = "EDGE_BUFFER_PX"
    RELIEF_M = "RELIEF_M"
    WRITE_RASTERS = "WRITE_RASTERS"
    WRITE_TILES = "WRITE_TILES"
    TILE_SIZE = "TILE_SIZE"
    NEGATIVE_RATIO = "NEGATIVE_RATIO"
    SEED = "SEED"
    WRITE_COCO = "WRITE_COCO"
    OUTPUT_FOLDER = "OUTPUT_FOLDER"
    OUTPUT_FRAMES = "OUTPUT_FRAMES"
    OUTPUT_GEOTAGS = "OUTPUT_GEOTAGS"

    def initAlgorithm(self, config=None):
        self.addParameter(source_parameter(  # the survey of the frames' field
            self.GEOTAGS, self.tr("Geotags (surveyed targets)"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT],
            near=self.FRAMES))
        self.addParameter(source_parameter(self.FRAMES, self.tr("Frames"), layer_kinds.FRAMES, [SOURCE_VECTOR_POLYGON]))
        self.addParameter(QgsProcessingParameterNumber(
            self.SIGMA_PX, self.tr("Soft-label σ (px)"), NUMBER_DOUBLE, DEFAULT_SIGMA_PX, minValue=0.5,
            maxValue=500.0))
        self.addParameter(QgsProcessingParameterFile(
            self.SENSOR_BOUND_JSON, self.tr("…or σ = r/3 from a sensorbound JSON"), optional=True,
            fileFilter="JSON (*.json)"))
        self.addParameter(QgsProcessingParameterEnum(
            self.SIGMA_SOURCE, self.tr("Where σ comes from"), options=[self.tr(o) for o in SIGMA_SOURCES],
            defaultValue=0))
        self.addParameter(vector_parameter(
            self.MARK_CHECK, self.tr("Label check (pinned marks) for a measured σ"), layer_kinds.LABEL_CHECKS,
            [SOURCE_VECTOR], optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.EDGE_BUFFER_PX, self.tr("Edge buffer at the image border (px)"),
            NUMBER_DOUBLE, 0.0, minValue=0.0, maxValue=1000.0))
        self.add_surveyed_area_parameters()
        self.addParameter(QgsProcessingParameterNumber(
            self.RELIEF_M, self.tr("Target relief h (m; empty: from the DEM)"),
            NUMBER_DOUBLE, None, optional=True, minValue=0.0, maxValue=100.0))
        self.add_dem_parameters(ground_model=True)
        self.addParameter(QgsProcessingParameterBoolean(
            self.WRITE_RASTERS, self.tr("Write one soft-label raster per frame"), defaultValue=True))
        self.addParameter(QgsProcessingParameterBoolean(
            self.WRITE_TILES, self.tr("Write a tiled training set (image and label tiles)"), defaultValue=False))
        self.addParameter(QgsProcessingParameterNumber(
            self.TILE_SIZE, self.tr("Tile size (px)"), NUMBER_INTEGER, 224,
            minValue=16, maxValue=4096))
        self.addParameter(QgsProcessingParameterNumber(
            self.NEGATIVE_RATIO, self.tr("Negative tiles kept per positive tile"),
            NUMBER_DOUBLE, 1.0, minValue=0.0, maxValue=100.0))
        self.addParameter(QgsProcessingParameterNumber(
            self.SEED, self.tr("Random seed for the negative-tile sample"), NUMBER_INTEGER,
            0, minValue=0))
        self.addParameter(QgsProcessingParameterBoolean(
            self.WRITE_COCO, self.tr("Write COCO-keypoints JSON"), defaultValue=False))
        self.add_review_parameters(with_frames=False, edge_buffer=False)
        self.addParameter(QgsProcessingParameterFolderDestination(self.OUTPUT_FOLDER, self.tr("Label folder")))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT_FRAMES, self.tr("Frames with label counts"), SOURCE_VECTOR_POLYGON,
            optional=True, createByDefault=True))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT_GEOTAGS, self.tr("Geotags with frames seen"), SOURCE_VECTOR_POINT,
            optional=True, createByDefault=True))
        for name, text in (("LABEL_COUNT", "Labels written"), ("FRAMES_WITH_LABELS", "Frames with labels"),
                           ("GEOTAGS_NEVER_IN_VIEW", "Geotags never in view"), ("SIGMA_USED_PX", "σ used (px)"),
                           ("REVIEW_TARGETS", "Review targets (confirmed clusters no geotag matches)"),
                           ("HARD_NEGATIVES", "Hard-negative clusters"),
                           ("RELIEF_FRAMES_OVER", "Frames whose relief displacement exceeds the label radius")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    def sigma(self, parameters, context, feedback) -> tuple[float, dict]:
        """σ_label (px) and where it came from, from the parameters alone: with SIGMA_SOURCE measured, the per-axis
        RMS error of MARK_CHECK (``mark_check.measured_sigma``); else r / 3 of SENSOR_BOUND_JSON when one is
        given, else SIGMA_PX."""
        check = self.parameterAsVectorLayer(parameters, self.MARK_CHECK, context)
        if self.parameterAsEnum(parameters, self.SIGMA_SOURCE, context) == SIGMA_MEASURED:
            if check is None:
                raise QgsProcessingException(self.tr(
                    "SIGMA_SOURCE asks for σ measured on a label check: give MARK_CHECK (the label check Import "
                    "camera solution writes from the pinned image marks)."))
            measured = self.run_core(measured_sigma, self.run_core(layers.read_mark_check_layer, check, check.name()),
                                     check.source())
            feedback.pushInfo(self.tr(
                "σ = {value:.2f} px measured on {path}: the per-axis RMS of label − mark over {n} {kind} mark(s) "
                "(RMS u {u:.2f} px, v {v:.2f} px, largest error {max:.1f} px); SIGMA_PX and SENSOR_BOUND_JSON are "
                "not used").format(value=measured.sigma_px, path=check.source(), n=measured.n_marks,
                                    kind=measured.kind, u=measured.rms_u_px, v=measured.rms_v_px, max=measured.max_px))
            if measured.n_without_label:
                feedback.pushWarning(self.tr("{n} {kind} mark(s) have no label (the point falls outside its image) "
                                             "and are left out of σ: check them in the label check.").format(
                                         n=measured.n_without_label, kind=measured.kind))
            if measured.kind == CONTROL_POINT:
                feedback.pushWarning(self.tr("The label check has no check point with a label: σ comes from control "
                                             "points, which took part in the adjustment and flatter the labels."))
            if measured.few:
                feedback.pushWarning(self.tr("σ from {n} mark(s) (fewer than {few}) is uncertain by about ±{pct:.0f} "
                                             "%.").format(n=measured.n_marks, few=FEW_MARKS,
                                                          pct=100.0 * measured.relative_uncertainty))
            return measured.sigma_px, measured.to_dict()
        if check is not None:
            feedback.pushInfo(self.tr("MARK_CHECK is not used: SIGMA_SOURCE is the given σ."))
        bound = self.parameterAsFile(parameters, self.SENSOR_BOUND_JSON, context)
        if bound:
            value = sigma_from_bound_json(bound)
            feedback.pushInfo(self.tr("σ = r / 3 = {value:g} px from {path} (SENSOR_BOUND_JSON; SIGMA_PX is not "
                                      "used)").format(value=value, path=bound))
            return value, {"source": "sensor_bound", "file": bound, "rule": "r / 3"}
        value = self.parameterAsDouble(parameters, self.SIGMA_PX, context)
        feedback.pushInfo(self.tr("σ = {value:g} px as given (SIGMA_PX)").format(value=value))
        return value, {"source": "given", "parameter": "SIGMA_PX"}

    def relief(self, parameters, context, feedback, geotags, dem):
        """Each target's relief for the relief check: RELIEF_M, else the DEM's range around it, else None."""
        if parameters.get(self.RELIEF_M) not in (None, ""):
            h = self.parameterAsDouble(parameters, self.RELIEF_M, context)
            return TargetRelief(np.full(len(geotags), h), f"RELIEF_M = {h:g} m")
        if dem is not None:
            return TargetRelief(self.run_core(dem_relief_m, dem, geotags.lat, geotags.lon),
                                f"DEM height range within {RELIEF_WINDOW_M:g} m of each target")
        feedback.pushInfo(self.tr("Relief check skipped: give the targets' relief (RELIEF_M) or a DEM."))
        return None

    def processAlgorithm(self, parameters, context, feedback):
        steps = QgsProcessingMultiStepFeedback(4, feedback)
        geotag_source = self.parameterAsSource(parameters, self.GEOTAGS, context)
        frame_source = self.parameterAsSource(parameters, self.FRAMES, context)
        if geotag_source is None or frame_source is None:
            raise QgsProcessingException(self.tr("GEOTAGS and FRAMES are both required."))
        sigma, sigma_source = self.sigma(parameters, context, feedback)
        dem = self.read_dem(parameters, context, frame_source, feedback)
        self.report_dem(feedback, dem)
        geotags = self.run_core(layers.read_geotag_layer, geotag_source, context.transformContext())
        write_tiles = self.parameterAsBoolean(parameters, self.WRITE_TILES, context)
        if geotags.problems:
            # A target without a position may lie in any tile: no tile could be called background.
            if write_tiles:
                raise QgsProcessingException(self.tr(
                    "{problem}: a target without a position may lie in any negative tile. Give it its position or "
                    "remove it, then write the tiles.").format(problem=geotags.problems[0]))
            feedback.pushWarning(self.tr("{n} geotag(s) without a position are left out; first: {problem}").format(
                n=len(geotags.problems), problem=geotags.problems[0]))
        records = self.run_core(layers.read_frame_layer, frame_source)
        groups = self.run_core(poses_from_records, records, frame_source.sourceName())
        survey = geotags
        area = self.surveyed(parameters, context, feedback, survey)
        reviewed = self.read_reviewed_clusters(parameters, context, steps, geotag_source,
                                               [poses for poses, _ in groups], dem=dem)
        review_targets, hard, unresolved = self.review_label_inputs(feedback, reviewed, survey)
        geotags = survey + review_targets
        relief = self.relief(parameters, context, feedback, geotags, dem)
        request = LabelRequest(
            sigma_px=sigma, sigma_source=sigma_source,
            edge_buffer_px=self.parameterAsDouble(parameters, self.EDGE_BUFFER_PX, context),
            write_rasters=self.parameterAsBoolean(parameters, self.WRITE_RASTERS, context),
            tile_size=self.parameterAsInt(parameters, self.TILE_SIZE, context) if write_tiles else 0,
            negative_ratio=self.parameterAsDouble(parameters, self.NEGATIVE_RATIO, context),
            seed=self.parameterAsInt(parameters, self.SEED, context),
            coco=self.parameterAsBoolean(parameters, self.WRITE_COCO, context))
        out_dir = self.parameterAsString(parameters, self.OUTPUT_FOLDER, context)
        local = local_frame_around(groups, geotags.lat, geotags.lon)
        feedback.pushInfo(self.tr("{n_records} frames ({n_groups} camera(s)), {n_geotags} "
                                  "geotags, σ = {sigma:g} px, edge buffer {edge_buffer_px:g} px").format(
                              n_records=len(records), n_groups=len(groups), n_geotags=len(geotags), sigma=sigma,
                              edge_buffer_px=request.edge_buffer_px))

        geotag_heights = [uses_geotag_heights(records, idx) for _, idx in groups]
        no_ground = [poses.frame_id[i] for (poses, _), own in zip(groups, geotag_heights) if not own
                     for i in np.flatnonzero(frames_without_ground(poses))]
        steep = [r["frame_id"] for r in records if "steep_terrain" in (r.get("flags") or "")]
        unrefined = [r["frame_id"] for r in records if "not_refined" in (r.get("flags") or "").split(",")]
        if unrefined:
            feedback.pushWarning(self.tr("{n} frame(s) could not be refined and keep their metadata pose (flag "
                                         "not_refined; first: {items}): their labels are only as good as the drone's "
                                         "metadata. Leave them out with a filter such as \"flags\" NOT LIKE "
                                         "'%not_refined%'").format(
                                     n=len(unrefined), items=', '.join(str(i) for i in unrefined[:5])))
        if steep and dem is None:
            feedback.pushWarning(self.tr("{n_steep} frame(s) lie on terrain steeper than the "
                                         "level plane's 10° envelope (flag steep_terrain; first: "
                                         "{items}): their labels drift off target — give the DEM "
                                         "(parameter DEM)").format(
                                     n_steep=len(steep), items=', '.join(str(i) for i in steep[:5])))
        if no_ground and dem is None:
            feedback.pushWarning(self.tr("{n_no_ground} frame(s) have no ground height (no "
                                         "usable altimeter reading, flag no_ground_height) and "
                                         "get no labels; first: {items}").format(
                                     n_no_ground=len(no_ground), items=', '.join(str(i) for i in no_ground[:5])))
        label_counts = np.zeros(len(records), dtype=np.int64)
        steps.setCurrentStep(1)
        ground = self.dem_ground(dem, [poses for poses, _ in groups], feedback)
        # A target whose label disc reaches into the image is in view: its tile is no negative.
        reach = request.label_radius_px
        projected = [self.run_core(project_labels, poses, geotags, request.edge_buffer_px, local,
                                   ground, own, reach) for (poses, _), own in zip(groups, geotag_heights)]
        hard_projected = [self.run_core(project_labels, poses, hard, request.edge_buffer_px, local,
                                        ground, own) if len(hard) else None
                          for (poses, _), own in zip(groups, geotag_heights)]
        unresolved_projected = [self.run_core(project_labels, poses, unresolved, request.edge_buffer_px, local,
                                              ground, own, reach) if len(unresolved) else None
                                for (poses, _), own in zip(groups, geotag_heights)]
        steps.setCurrentStep(2)
        done = 0
        with LabelWriter(out_dir, geotags, request, hard, area, relief) as writer:
            for (poses, idx), frame_labels, hard_labels, unresolved_labels in zip(groups, projected, hard_projected,
                                                                                   unresolved_projected):
                images = [records[i].get("image") or "" for i in idx]
                progress, is_canceled = self.progress_callbacks(
                    steps, 100.0 * done / len(records), 100.0 * (done + len(idx)) / len(records))
                label_counts[idx] = self.run_core(writer.add_frames, poses, images, frame_labels, progress,
                                                  is_canceled, hard_labels, unresolved_labels)
                done += len(idx)
        summary = writer.result.summary
        steps.setCurrentStep(3)
        self._log_summary(feedback, summary)
        results = {"OUTPUT_FOLDER": out_dir, "LABEL_COUNT": summary["n_labels"],
                   "FRAMES_WITH_LABELS": summary["n_frames_with_labels"],
                   "GEOTAGS_NEVER_IN_VIEW": len(summary["geotags_never_in_view"]), "SIGMA_USED_PX": sigma,
                   "REVIEW_TARGETS": len(review_targets), "HARD_NEGATIVES": len(hard),
                   "RELIEF_FRAMES_OVER": summary["relief"]["n_frames_over"] if summary["relief"] else 0}
        results.update(self._write_frames(parameters, context, frame_source, label_counts))
        results.update(self._write_geotags(parameters, context, geotag_source, survey.source_row,
                                           writer.result.frames_per_geotag[:len(survey)]))
        return results

    @staticmethod
    def _log_summary(feedback, summary) -> None:
        lpf, fpg = summary["labels_per_frame"], summary["frames_per_geotag"]
        feedback.pushInfo(
            tr("{n_labels} labels in {n_frames_with_labels} of {n_frames} frames (labels per "
               "labelled frame: mean {mean:g}, max {max}); {n_geotags_in_view} of {n_geotags} "
               "geotags in view (frames per geotag: mean {mean2:g}, max {max2})").format(
                n_labels=summary['n_labels'], n_frames_with_labels=summary['n_frames_with_labels'],
                n_frames=summary['n_frames'], mean=lpf['mean'], max=lpf['max'],
                n_geotags_in_view=summary['n_geotags_in_view'], n_geotags=summary['n_geotags'], mean2=fpg['mean'],
                max2=fpg['max']))
        review = summary["provenance"]["review"]
        if review["n_targets"]:
            feedback.pushInfo(tr("Of these, review targets: {n_in_view} of {n_targets} in view, {n_labels} "
                                 "labels.").format(**review))
        hard = summary["hard_negatives"]
        if hard["n_clusters"]:
            tiles = summary.get("tiles")
            feedback.pushInfo(tr("Hard negatives: {n_in_view} of {n_clusters} in view, in {n_frames} frame(s); "
                                 "{n_tiles} hard-negative tile(s) written.").format(
                                     n_tiles=tiles["hard_negative"] if tiles else 0, **hard))
        if summary["n_occluded"]:
            feedback.pushInfo(tr("{n_occluded} projections were hidden behind terrain (not "
                                 "written)").format(n_occluded=summary['n_occluded']))
        if summary["n_edge"]:
            feedback.pushInfo(tr("{n_edge} projections fell within the edge buffer (not written)").format(
                                  n_edge=summary['n_edge']))
        if summary["n_beyond_border"]:
            feedback.pushInfo(tr("{n} projections lay just beyond the image border, their label disc reaching in "
                                 "(not written)").format(n=summary["n_beyond_border"]))
        never = summary["geotags_never_in_view"]
        if never:
            shown = ", ".join(str(i) for i in never[:10]) + (" …" if len(never) > 10 else "")
            feedback.pushWarning(tr("{n_never} geotag(s) never in view of any frame: {shown}").format(
                                     n_never=len(never), shown=shown))
        tiles = summary.get("tiles")
        if tiles:
            skipped = tiles["skipped"]
            reasons = [text.format(n=skipped[key]) for key, text in (
                ("unlabelled_target", tr("{n} near a target in view but not labelled (edge buffer, beyond the border, "
                                         "an unresolved cluster)")),
                ("outside_surveyed_area", tr("{n} without a positive not wholly inside the surveyed area")),
                ("frames_without_ground", tr("every tile of {n} frame(s) without a ground height"))) if skipped[key]]
            feedback.pushInfo(tr("Tiles: {positive} positive, {negative} negative written; skipped: {reasons}.").format(
                positive=tiles["positive"], negative=tiles["negative"],
                reasons="; ".join(reasons) if reasons else tr("none")))
        WriteLabels._log_relief(feedback, summary["relief"])
        if tiles and tiles["missing_images"]:
            feedback.reportError(tr("{value} image(s) could not be read for tiles; first: "
                                    "{value2}").format(
                                     value=len(tiles['missing_images']), value2=tiles['missing_images'][0]), False)

    @staticmethod
    def _log_relief(feedback, relief) -> None:
        if relief is None:
            return
        over = relief["frames_over"]
        line = tr("Relief check ({source}): {n} label(s), largest displacement h·r/d {cm:.1f} cm = {px:.1f} px against "
                  "the label radius {radius:.1f} px; {over} frame(s) exceed it").format(
            source=relief["source"], n=relief["n_labels_checked"], cm=relief["max_displacement_cm"],
            px=relief["max_displacement_px"], radius=relief["label_radius_px"], over=len(over))
        if not over:
            feedback.pushInfo(line + ".")
            return
        shown = "; ".join(tr("frame {frame_id}: geotag {geotag_id}, {displacement_cm:g} cm = {displacement_px:g} px "
                             "> {label_radius_cm:g} cm = {label_radius_px:g} px").format(**f)
                          for f in over[:LOGGED_FRAMES])
        feedback.pushWarning(line + tr(" (summary.json lists them all): {shown}").format(shown=shown))

    def _write_copy(self, parameters, context, name, source, extra: QgsField, values, style):
        """A copy of ``source`` with one more field; the user's input layer is never modified. A JSON field (a
        GeoJSON layer hands a frame's camera back as one) is copied as text, which every format can store."""
        fields = QgsFields()
        for field in source.fields():
            if field.name() != extra.name():
                fields.append(layers.qgs_field(field.name(), "string") if field.typeName().upper() == "JSON"
                              else field)
        fields.append(extra)
        sink, dest_id = self.parameterAsSink(parameters, name, context, fields, source.wkbType(),
                                             source.sourceCrs())
        if sink is None:
            return {}
        for feature, value in zip(source.getFeatures(), values):
            out = QgsFeature(fields)
            out.setGeometry(feature.geometry())
            for field in source.fields():
                if field.name() != extra.name():
                    kept = feature[field.name()]
                    out[field.name()] = json.dumps(kept, separators=(",", ":")) if isinstance(kept, (dict, list)) \
                        else kept
            out[extra.name()] = int(value)
            sink.addFeature(out, QgsFeatureSink.Flag.FastInsert)
        layers.style_on_load(context, dest_id, style)
        return {name: dest_id}

    def _write_frames(self, parameters, context, source, counts):
        return self._write_copy(parameters, context, self.OUTPUT_FRAMES, source,
                                layers.qgs_field("n_labels", "int", "labels written in this frame"),
                                counts.tolist(), "frames.qml")

    def _write_geotags(self, parameters, context, source, rows, frames_per_geotag):
        # Geotags without a usable position were left out when reading: each count goes to its row.
        per_row = dict(zip(rows.tolist(), frames_per_geotag.tolist()))
        counts = (per_row.get(row, 0) for row in itertools.count(1))
        return self._write_copy(parameters, context, self.OUTPUT_GEOTAGS, source,
                                layers.qgs_field("frames_seen", "int", "frames whose labels include this geotag"),
                                counts, "geotags.qml")
