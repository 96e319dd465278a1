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
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFile,
    QgsProcessingParameterFolderDestination,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.__about__ import tr
from ...birdseye_qgis.core.field.frame_records import local_frame_around, poses_from_records, uses_geotag_heights
from ...birdseye_qgis.core.labels.training_set import (
    LabelRequest,
    LabelWriter,
    frames_without_ground,
    label_sigma_px,
    project_labels,
    review_label_inputs,
)
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, NUMBER_INTEGER, SOURCE_VECTOR_POINT, SOURCE_VECTOR_POLYGON
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from ..parameters.dem import DemParametersMixin
from ..parameters.layer_parameters import source_parameter
from ..parameters.review import ReviewParametersMixin
from .base import BirdsEyeAlgorithm

#: SIGMA_PX's default: the label σ of core's LabelRequest.
DEFAULT_SIGMA_PX = LabelRequest.sigma_px


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


class WriteLabels(ReviewParametersMixin, DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "writelabels"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("WriteLabels", "Write training labels")
    GROUP = "labels"
    GEOTAGS = "GEOTAGS"
    FRAMES = "FRAMES"
    SIGMA_PX = "SIGMA_PX"
    SENSOR_BOUND_JSON = "SENSOR_BOUND_JSON"
    EDGE_BUFFER_PX = "EDGE_BUFFER_PX"
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
        self.addParameter(QgsProcessingParameterNumber(
            self.EDGE_BUFFER_PX, self.tr("Edge buffer at the image border (px)"),
            NUMBER_DOUBLE, 0.0, minValue=0.0, maxValue=1000.0))
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
                           ("HARD_NEGATIVES", "Hard-negative clusters")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    def sigma(self, parameters, context, feedback) -> float:
        """σ_label (px) from the parameters alone: r / 3 of SENSOR_BOUND_JSON when one is given, else SIGMA_PX."""
        bound = self.parameterAsFile(parameters, self.SENSOR_BOUND_JSON, context)
        if bound:
            value = sigma_from_bound_json(bound)
            feedback.pushInfo(self.tr("σ = r / 3 = {value:g} px from {path} (SENSOR_BOUND_JSON; SIGMA_PX is not "
                                      "used)").format(value=value, path=bound))
            return value
        return self.parameterAsDouble(parameters, self.SIGMA_PX, context)

    def processAlgorithm(self, parameters, context, feedback):
        steps = QgsProcessingMultiStepFeedback(4, feedback)
        geotag_source = self.parameterAsSource(parameters, self.GEOTAGS, context)
        frame_source = self.parameterAsSource(parameters, self.FRAMES, context)
        if geotag_source is None or frame_source is None:
            raise QgsProcessingException(self.tr("GEOTAGS and FRAMES are both required."))
        sigma = self.sigma(parameters, context, feedback)
        dem = self.read_dem(parameters, context, frame_source, feedback)
        self.report_dem(feedback, dem)
        geotags = self.run_core(layers.read_geotag_layer, geotag_source, context.transformContext())
        records = self.run_core(layers.read_frame_layer, frame_source)
        groups = self.run_core(poses_from_records, records, frame_source.sourceName())
        survey = geotags
        reviewed = self.read_reviewed_clusters(parameters, context, steps, geotag_source,
                                               [poses for poses, _ in groups], dem=dem)
        review_targets, hard = review_label_inputs(reviewed or [], survey)
        geotags = survey + review_targets
        if reviewed is not None:
            feedback.pushInfo(self.tr("From the review: {targets} target(s) nobody surveyed are labelled "
                                      "(provenance review); {hard} hard negative(s) put their tiles first "
                                      "in the negative sample.").format(targets=len(review_targets), hard=len(hard)))
        request = LabelRequest(
            sigma_px=sigma, edge_buffer_px=self.parameterAsDouble(parameters, self.EDGE_BUFFER_PX, context),
            write_rasters=self.parameterAsBoolean(parameters, self.WRITE_RASTERS, context),
            tile_size=self.parameterAsInt(parameters, self.TILE_SIZE, context)
            if self.parameterAsBoolean(parameters, self.WRITE_TILES, context) else 0,
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
        projected = [self.run_core(project_labels, poses, geotags, request.edge_buffer_px, local,
                                   ground, own) for (poses, _), own in zip(groups, geotag_heights)]
        hard_projected = [self.run_core(project_labels, poses, hard, request.edge_buffer_px, local,
                                        ground, own) if len(hard) else None
                          for (poses, _), own in zip(groups, geotag_heights)]
        steps.setCurrentStep(2)
        done = 0
        with LabelWriter(out_dir, geotags, request, hard) as writer:
            for (poses, idx), frame_labels, hard_labels in zip(groups, projected, hard_projected):
                images = [records[i].get("image") or "" for i in idx]
                progress, is_canceled = self.progress_callbacks(
                    steps, 100.0 * done / len(records), 100.0 * (done + len(idx)) / len(records))
                label_counts[idx] = self.run_core(writer.add_frames, poses, images, frame_labels, progress,
                                                  is_canceled, hard_labels)
                done += len(idx)
        summary = writer.result.summary
        steps.setCurrentStep(3)
        self._log_summary(feedback, summary)
        results = {"OUTPUT_FOLDER": out_dir, "LABEL_COUNT": summary["n_labels"],
                   "FRAMES_WITH_LABELS": summary["n_frames_with_labels"],
                   "GEOTAGS_NEVER_IN_VIEW": len(summary["geotags_never_in_view"]), "SIGMA_USED_PX": sigma,
                   "REVIEW_TARGETS": len(review_targets), "HARD_NEGATIVES": len(hard)}
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
        never = summary["geotags_never_in_view"]
        if never:
            shown = ", ".join(str(i) for i in never[:10]) + (" …" if len(never) > 10 else "")
            feedback.pushWarning(tr("{n_never} geotag(s) never in view of any frame: {shown}").format(
                                     n_never=len(never), shown=shown))
        tiles = summary.get("tiles")
        if tiles and tiles["missing_images"]:
            feedback.reportError(tr("{value} image(s) could not be read for tiles; first: "
                                    "{value2}").format(
                                     value=len(tiles['missing_images']), value2=tiles['missing_images'][0]), False)

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
