"""birdseye:comparedetectors — two detectors on one flight: figures side by side and what changed."""
from __future__ import annotations

import json
from pathlib import Path

from qgis.core import (
    QgsGeometry,
    QgsPointXY,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFileDestination,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.geometry.ground_record import RASTER, common_ground
from ...birdseye_qgis.core.scoring.compare import CHANGE_FIELDS, compare_detectors
from ...birdseye_qgis.core.scoring.reports import comparison_report_html
from ...birdseye_qgis.qgis_enums import SOURCE_VECTOR, SOURCE_VECTOR_POINT, WKB_POINT
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from ...birdseye_qgis.qgis_io.detections import (
    read_detections,
    read_pose_groups,
    read_verdicts,
    to_layer_xy,
)
from ...birdseye_qgis.qgis_io.raster_reader import covered_geotags
from ..parameters.clustering import ClusteringParametersMixin
from ..parameters.dem import DemParametersMixin
from ..parameters.layer_parameters import source_parameter, vector_parameter
from .base import BirdsEyeAlgorithm


class CompareDetectors(ClusteringParametersMixin, DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "comparedetectors"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("CompareDetectors", "Compare detectors")
    GROUP = "detect"
    DETECTIONS_OLD = "DETECTIONS_OLD"
    DETECTIONS_NEW = "DETECTIONS_NEW"
    FRAMES = "FRAMES"
    GEOTAGS = "GEOTAGS"
    REVIEW = "REVIEW"
    OUTPUT = "OUTPUT"
    OUTPUT_JSON = "OUTPUT_JSON"
    OUTPUT_REPORT = "OUTPUT_REPORT"

    def initAlgorithm(self, config=None):
        # The new detector's layer starts on the latest detection layer; the old one, the frames and the geotags on
        # the latest over the same ground (the old detector's: the one before).
        self.addParameter(source_parameter(
            self.DETECTIONS_OLD, self.tr("Detections of the old detector (before)"), layer_kinds.DETECTIONS,
            [SOURCE_VECTOR_POINT], start=1, near=self.DETECTIONS_NEW))
        self.addParameter(source_parameter(
            self.DETECTIONS_NEW, self.tr("Detections of the new detector (same flight)"), layer_kinds.DETECTIONS,
            [SOURCE_VECTOR_POINT]))
        self.addParameter(source_parameter(
            self.FRAMES, self.tr("Frames of the flight"), layer_kinds.FRAMES, [SOURCE_VECTOR],
            near=self.DETECTIONS_NEW))
        self.addParameter(source_parameter(
            self.GEOTAGS, self.tr("Geotags"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT], near=self.DETECTIONS_NEW))
        self.add_clustering_parameters()
        self.add_dem_parameters()
        self.addParameter(vector_parameter(
            self.REVIEW, self.tr("Review verdicts (for scores after review)"), layer_kinds.VERDICTS,
            [SOURCE_VECTOR], optional=True))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("What changed"), SOURCE_VECTOR_POINT))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_JSON, self.tr("Comparison (JSON)"), "JSON (*.json)"))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_REPORT, self.tr("Report (HTML)"), "HTML (*.html)", optional=True, createByDefault=True))
        for name, text in (("RECALL_PRE_OLD", "recall_pre before"), ("RECALL_PRE_NEW", "recall_pre after"),
                           ("GMCF_PRE_OLD", "gmcf_pre before"), ("GMCF_PRE_NEW", "gmcf_pre after"),
                           ("FOUND_ONLY_BY_NEW", "Targets found only by the new detector"),
                           ("LOST_BY_NEW", "Targets lost by the new detector"),
                           ("FALSE_REMOVED", "False clusters removed"), ("FALSE_ADDED", "False clusters added")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    def processAlgorithm(self, parameters, context, feedback):
        sources = {}
        for name in (self.DETECTIONS_OLD, self.DETECTIONS_NEW, self.FRAMES, self.GEOTAGS):
            sources[name] = self.parameterAsSource(parameters, name, context)
            if sources[name] is None:
                raise QgsProcessingException(self.tr("{name}: the layer cannot be read.").format(name=name))
        detections = []
        for name in (self.DETECTIONS_OLD, self.DETECTIONS_NEW):
            det, dropped = self.run_core(read_detections, sources[name], context, sources[name].sourceName())
            if dropped:
                feedback.pushWarning(self.tr("{name}: {n} detection(s) without a position or score left out").format(
                    name=name, n=dropped))
            detections.append(det)
        old, new = detections
        if old.model_digest and old.model_digest == new.model_digest and old.threshold == new.threshold \
                and old.ground.model == new.ground.model:  # frames against mosaic compares images, not detectors
            feedback.pushWarning(self.tr("Both layers come from the same model file (model_digest) at the same "
                                         "threshold: the comparison shows no change of detector."))
        # A change of ground is not a change of detector: both layers must stand on one, which the
        # in-view test of both then uses — or one was found on the flight's orthomosaic (frames or mosaic).
        on_raster = [d for d in (old, new) if d.ground.model == RASTER]
        on_frames = [d for d in (old, new) if d.ground.model != RASTER]
        one_ground = on_frames or on_raster  # two raster layers must come from one raster
        self.run_core(common_ground, [d.ground for d in one_ground], [d.name for d in one_ground])
        dem = self.read_dem(parameters, context, sources[self.FRAMES], feedback)
        self.report_dem(feedback, dem)
        ground = self.recorded_ground(on_frames[0], dem, feedback) if on_frames else None
        groups = self.run_core(read_pose_groups, sources[self.FRAMES])[0]
        geotags = self.run_core(layers.read_geotag_layer, sources[self.GEOTAGS], context.transformContext())
        if len(geotags) == 0:
            raise QgsProcessingException(self.tr("GEOTAGS: the layer holds no point with a position."))
        inside_raster = None
        if on_raster:
            inside_raster = self.run_core(covered_geotags, on_raster[0].ground.dem_source, geotags.lat, geotags.lon,
                                          context.transformContext())
            feedback.pushInfo(self.tr("{name} was found on the raster {raster}: both layers are scored over the "
                                      "geotags in view of the frames and on the raster's pixels ({n} of {total} "
                                      "lie on the raster); its detections beyond the frames' view are left out, "
                                      "and each of its detections can be a cluster by itself (one image shows a "
                                      "target once).").format(name=on_raster[0].name,
                                                              raster=on_raster[0].ground.dem_source,
                                                              n=int(inside_raster.sum()), total=len(geotags)))
        review = self.parameterAsVectorLayer(parameters, self.REVIEW, context)
        log = self.run_core(read_verdicts, review, context) if review is not None else None
        op = self.read_operating_point(parameters, context)
        feedback.setProgress(10)
        progress, is_canceled = self.progress_callbacks(feedback, 10.0, 85.0)
        comparison = self.run_core(compare_detectors, old, new, groups, geotags, op, log, ground, progress,
                                   is_canceled, inside_raster)
        for note in comparison.before.review_notes:
            feedback.pushWarning(note)
        result = comparison.to_dict()
        outputs = {self.OUTPUT: self._write_changes(parameters, context, feedback, comparison, geotags,
                                                    sources[self.DETECTIONS_NEW].sourceCrs())}
        outputs.update(self._write_files(parameters, context, comparison, result))
        counts = result["changes"]
        before, after = comparison.before.pooled, comparison.after.pooled
        outputs.update({"RECALL_PRE_OLD": before.recall_pre, "RECALL_PRE_NEW": after.recall_pre,
                        "GMCF_PRE_OLD": before.gmcf_pre, "GMCF_PRE_NEW": after.gmcf_pre,
                        "FOUND_ONLY_BY_NEW": counts["found_only_by_new"], "LOST_BY_NEW": counts["lost_by_new"],
                        "FALSE_REMOVED": counts["false_removed"], "FALSE_ADDED": counts["false_added"]})
        feedback.pushInfo(self._summary(result))
        feedback.setProgress(100)
        return outputs

    def _write_changes(self, parameters, context, feedback, comparison, geotags, crs):
        fields = layers.qgs_fields(CHANGE_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, self.OUTPUT, context, fields, WKB_POINT, crs)
        if sink is None:
            raise QgsProcessingException(self.tr("OUTPUT: the change layer cannot be created."))
        changes = comparison.changes
        x, y = to_layer_xy(comparison.before.local, [(c.x, c.y) for c in changes], crs)
        size_old = comparison.before.flights[0].clustering.summary.n_detections
        size_new = comparison.after.flights[0].clustering.summary.n_detections
        records = ({"change": c.change, "kind": c.kind,
                    "geotag_id": None if c.geotag is None else str(geotags.ids[c.geotag]),
                    "cluster_old": c.cluster_old, "cluster_new": c.cluster_new,
                    "n_detections_old": None if c.cluster_old is None else int(size_old[c.cluster_old]),
                    "n_detections_new": None if c.cluster_new is None else int(size_new[c.cluster_new])}
                   for c in changes)
        geometries = (QgsGeometry.fromPointXY(QgsPointXY(px, py)) for px, py in zip(x.tolist(), y.tolist()))
        self.run_core(layers.write_records, sink, fields, records, geometries, feedback, 85.0, 95.0, len(changes))
        layers.style_on_load(context, dest_id, "changes.qml")
        return dest_id

    def _write_files(self, parameters, context, comparison, result) -> dict:
        outputs = {}
        out_json = self.parameterAsFileOutput(parameters, self.OUTPUT_JSON, context)
        out_report = self.parameterAsFileOutput(parameters, self.OUTPUT_REPORT, context)
        for name, path, text in ((self.OUTPUT_JSON, out_json,
                                  lambda: json.dumps(result, indent=2, ensure_ascii=False) + "\n"),
                                 (self.OUTPUT_REPORT, out_report, lambda: comparison_report_html(comparison))):
            if not path:
                continue
            try:
                Path(path).write_text(text(), encoding="utf-8")
            except OSError as exc:
                raise QgsProcessingException(self.tr("{name}: cannot write {path} ({exc})").format(
                    name=name, path=path, exc=exc)) from exc
            outputs[name] = path
        return outputs

    @staticmethod
    def _summary(result: dict) -> str:
        def fmt(v):
            if v is None:
                return "undefined"
            return f"{v:.3f}" if isinstance(v, float) else str(v)

        lines = [f"{'figure':<24}{'before':>12}{'after':>12}"]
        lines += [f"{r['figure']:<24}{fmt(r['before']):>12}{fmt(r['after']):>12}" for r in result["side_by_side"]]
        lines.append(", ".join(f"{k}: {v}" for k, v in result["changes"].items()))
        return "\n".join(lines)
