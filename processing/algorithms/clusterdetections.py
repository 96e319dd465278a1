"""birdseye:clusterdetections — detections → de-duplicated points and DBSCAN cluster polygons."""
from __future__ import annotations

import numpy as np
from qgis.core import (
    QgsGeometry,
    QgsPointXY,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterFeatureSink,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.detect.clustering import HULL_BUFFER_M, cluster_detections, cluster_hulls
from ...birdseye_qgis.core.geometry.geodesy import LocalFrame
from ...birdseye_qgis.core.geometry.ground_record import RASTER
from ...birdseye_qgis.core.scoring.evaluation import Detections, local_frame_for, min_samples_for
from ...birdseye_qgis.core.scoring.matching import in_view
from ...birdseye_qgis.core.scoring.pre_review import score_flight
from ...birdseye_qgis.qgis_enums import (
    SOURCE_VECTOR,
    SOURCE_VECTOR_POINT,
    SOURCE_VECTOR_POLYGON,
    WKB_POINT,
    WKB_POLYGON,
)
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from ...birdseye_qgis.qgis_io.detections import (
    CLUSTER_FIELDS,
    POINT_FIELDS,
    read_detections,
    read_pose_groups,
    to_layer_xy,
)
from ...birdseye_qgis.qgis_io.raster_reader import covered_geotags
from ..parameters.clustering import ClusteringParametersMixin
from ..parameters.dem import DemParametersMixin
from ..parameters.layer_parameters import source_parameter
from .base import BirdsEyeAlgorithm


class ClusterDetections(ClusteringParametersMixin, DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "clusterdetections"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("ClusterDetections", "Cluster detections")
    GROUP = "detect"
    DETECTIONS = "DETECTIONS"
    GEOTAGS = "GEOTAGS"
    FRAMES = "FRAMES"
    OUTPUT = "OUTPUT"
    OUTPUT_POINTS = "OUTPUT_POINTS"

    def initAlgorithm(self, config=None):
        self.addParameter(source_parameter(
            self.DETECTIONS, self.tr("Detections (from Detect targets)"), layer_kinds.DETECTIONS,
            [SOURCE_VECTOR_POINT]))
        self.add_clustering_parameters(with_prediction=False)
        self.addParameter(source_parameter(
            self.GEOTAGS, self.tr("Geotags (to mark the clusters hitting one)"), layer_kinds.GEOTAGS,
            [SOURCE_VECTOR_POINT], optional=True))
        self.addParameter(source_parameter(
            self.FRAMES, self.tr("Frames (only geotags in view match)"), layer_kinds.FRAMES,
            [SOURCE_VECTOR], optional=True))
        self.add_matching_parameters()
        self.add_dem_parameters()
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("Clusters"), SOURCE_VECTOR_POLYGON))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT_POINTS, self.tr("De-duplicated points"), SOURCE_VECTOR_POINT, optional=True,
            createByDefault=False))
        for name, text in (("CLUSTER_COUNT", "Clusters"), ("HIT_COUNT", "Hit clusters"),
                           ("NOISE_POINTS", "De-duplicated points left as noise")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    def processAlgorithm(self, parameters, context, feedback):
        source = self.parameterAsSource(parameters, self.DETECTIONS, context)
        if source is None:
            raise QgsProcessingException(self.tr("DETECTIONS: the detection layer cannot be read."))
        det, dropped = self.run_core(read_detections, source, context)
        if dropped:
            feedback.pushWarning(self.tr("{dropped} detection(s) without a position or score "
                                         "were left out").format(dropped=dropped))
        geotag_source = self.parameterAsSource(parameters, self.GEOTAGS, context)
        frame_source = self.parameterAsSource(parameters, self.FRAMES, context)
        geotags = (self.run_core(layers.read_geotag_layer, geotag_source, context.transformContext())
                   if geotag_source is not None else None)
        groups = self.run_core(read_pose_groups, frame_source)[0] if frame_source is not None else []
        feedback.setProgress(30)
        if len(det) == 0:
            raise QgsProcessingException(self.tr("The detection layer holds no detection with a position."))
        local = self._local_frame(det, groups, geotags)
        positions = det.ground_positions(local)
        on_raster = det.ground.model == RASTER
        asked = self.parameterAsInt(parameters, self.MIN_SAMPLES, context)
        min_samples = min_samples_for(det, asked)
        if on_raster:
            feedback.pushInfo(self.tr("The detections were found on a raster, which shows each target once: each "
                                      "detection can be a cluster by itself (MIN_SAMPLES {used}, not {asked}), and "
                                      "the geotags in view are those on the raster's valid pixels.").format(
                                  used=min_samples, asked=asked))
        clustering = self.run_core(cluster_detections, positions, det.frame_id, det.score,
                                   self.parameterAsDouble(parameters, self.DEDUP_CM, context),
                                   self.parameterAsDouble(parameters, self.EPS_M, context), min_samples,
                                   core_count=self.read_core_count(parameters, context))
        feedback.setProgress(55)
        n = clustering.n_clusters
        matched = [""] * n
        hit = np.zeros(n, dtype=bool)
        if geotags is not None and len(geotags):
            g_local = geotags.in_local(local)
            if on_raster:
                visible = self.run_core(covered_geotags, det.ground.dem_source, geotags.lat, geotags.lon,
                                        context.transformContext())
            elif groups:
                dem = self.read_dem(parameters, context, frame_source, feedback)
                self.report_dem(feedback, dem)
                view = self.run_core(in_view, groups, local, g_local,
                                     self.parameterAsDouble(parameters, self.EDGE_BUFFER_PX, context),
                                     self.recorded_ground(det, dem, feedback))
                visible = view.mask
                if view.n_frames_without_ground:
                    # Their geotags leave the recall denominator: say so rather than score them silently.
                    ids = [fid for poses in groups for fid in poses.frame_id[~np.isfinite(poses.ground_height)]]
                    feedback.pushWarning(self.tr("{n} frame(s) without a ground height (flag no_ground_height; "
                                                 "first: {items}) were not counted as processed: the geotags "
                                                 "only they see are not in view.").format(
                                             n=view.n_frames_without_ground, items=", ".join(map(str, ids[:5]))))
            else:
                feedback.pushWarning(self.tr("No FRAMES given: every geotag is treated as in "
                                             "view."))
                visible = np.ones(len(geotags), dtype=bool)
            score = score_flight(clustering, g_local[:, :2], visible,
                                 self.parameterAsDouble(parameters, self.EPS_PRED_M, context))
            hit = score.cluster_hit
            matched = [",".join(str(geotags.ids[i]) for i in g) for g in score.cluster_geotags]
            feedback.pushInfo(self.tr("{n_hit_clusters} of {n} clusters match an in-view geotag; "
                                      "{n_recovered} of {n_in_view} in-view geotags recovered.").format(
                                  n_hit_clusters=score.counts.n_hit_clusters, n=n,
                                  n_recovered=score.counts.n_recovered, n_in_view=score.counts.n_in_view))
        feedback.setProgress(65)
        crs = source.sourceCrs()
        outputs = {"CLUSTER_COUNT": n, "HIT_COUNT": int(hit.sum()),
                   "NOISE_POINTS": int((clustering.dbscan.labels < 0).sum())}
        outputs[self.OUTPUT] = self._write_clusters(parameters, context, feedback, clustering, positions.xy, matched,
                                                    hit, local, crs)
        if parameters.get(self.OUTPUT_POINTS):
            outputs[self.OUTPUT_POINTS] = self._write_points(parameters, context, feedback, clustering, det, local, crs)
        feedback.pushInfo(self.tr("{n_det} detections → {n_points} de-duplicated points → {n} clusters "
                                  "({NOISE_POINTS} points are noise; minimum points counted {counted}).").format(
                              n_det=len(det), n_points=len(clustering.points), n=n,
                              NOISE_POINTS=outputs['NOISE_POINTS'], counted=clustering.core_count))
        return outputs

    @staticmethod
    def _local_frame(det: Detections, groups, geotags) -> LocalFrame:
        if groups:
            return local_frame_for(groups, geotags)
        return LocalFrame.around(det.lat, det.lon, det.height[np.isfinite(det.height)]
                                 if np.isfinite(det.height).any() else None)

    def _write_clusters(self, parameters, context, feedback, clustering, xy, matched, hit, local, crs):
        fields = layers.qgs_fields(CLUSTER_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, self.OUTPUT, context, fields, WKB_POLYGON, crs)
        if sink is None:
            raise QgsProcessingException(self.tr("OUTPUT: the cluster layer cannot be created."))
        n = clustering.n_clusters
        s = clustering.summary
        rings = cluster_hulls(xy, clustering.detection_cluster, n, HULL_BUFFER_M)
        rx, ry = to_layer_xy(local, rings.reshape(-1, 2), crs)
        # Every hull has the same number of vertices (reshape(0, -1) cannot infer them when no cluster formed).
        rx, ry = np.reshape(rx, rings.shape[:2]), np.reshape(ry, rings.shape[:2])
        cx, cy = to_layer_xy(local, s.centroid, crs)
        records = ({"cluster_id": k, "centroid_x": float(cx[k]), "centroid_y": float(cy[k]),
                    "n_detections": int(s.n_detections[k]), "n_frames": int(s.n_frames[k]),
                    "median_extent_m": float(s.median_extent_m[k]),
                    "max_score": None if not np.isfinite(s.max_score[k]) else float(s.max_score[k]),
                    "matched_geotag_ids": matched[k], "hit": int(hit[k])} for k in range(n))
        geometries = (QgsGeometry.fromPolygonXY([[QgsPointXY(x, y) for x, y in zip(rx[k], ry[k])]
                                                 + [QgsPointXY(rx[k][0], ry[k][0])]]) for k in range(n))
        self.run_core(layers.write_records, sink, fields, records, geometries, feedback, 65.0, 90.0, n)
        layers.style_on_load(context, dest_id, "clusters.qml")
        return dest_id

    def _write_points(self, parameters, context, feedback, clustering, det, local, crs):
        fields = layers.qgs_fields(POINT_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, self.OUTPUT_POINTS, context, fields, WKB_POINT, crs)
        if sink is None:
            raise QgsProcessingException(self.tr("OUTPUT_POINTS: the point layer cannot be created."))
        pts = clustering.points
        max_score = np.full(len(pts), -np.inf)
        np.maximum.at(max_score, pts.inverse, det.score)
        px, py = to_layer_xy(local, pts.xy, crs)
        labels, core = clustering.dbscan.labels, clustering.dbscan.core
        records = ({"point_id": k, "cluster_id": int(labels[k]), "core": int(core[k]),
                    "n_detections": int(pts.count[k]), "score": float(max_score[k])} for k in range(len(pts)))
        geometries = (QgsGeometry.fromPointXY(QgsPointXY(x, y)) for x, y in zip(px.tolist(), py.tolist()))
        self.run_core(layers.write_records, sink, fields, records, geometries, feedback, 90.0, 100.0, len(pts))
        layers.style_on_load(context, dest_id, "cluster_points.qml")
        return dest_id
