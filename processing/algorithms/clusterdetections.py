"""birdseye:clusterdetections — detections → de-duplicated points and DBSCAN cluster polygons.

Also home of the small QGIS glue the detection-scoring algorithms share (reading detection,
geotag, frame and verdict layers into core inputs; writing clusters), kept here because every
module of ``processing/algorithms`` must be exactly one algorithm.
"""
from __future__ import annotations

import numpy as np
from qgis.core import (QgsCoordinateReferenceSystem, QgsCoordinateTransform, QgsFeatureRequest, QgsGeometry,
                       QgsPointXY, QgsProcessing, QgsProcessingException, QgsProcessingOutputNumber,
                       QgsProcessingParameterFeatureSink, QgsProcessingParameterFeatureSource,
                       QgsProcessingParameterNumber, QgsProject, QgsWkbTypes)

from ...birdseye_qgis import layers
from ...birdseye_qgis.core.detect.clustering import (DEFAULT_DEDUP_CM, DEFAULT_EPS_M, DEFAULT_MIN_SAMPLES, HULL_BUFFER_M,
                                              cluster_detections, cluster_hulls)
from ...birdseye_qgis.core.errors import InputError
from ...birdseye_qgis.core.field.frame_records import poses_from_records
from ...birdseye_qgis.core.geometry.geodesy import LocalFrame, ProjectedCRS
from ...birdseye_qgis.core.scoring.scoring import (DEFAULT_EDGE_BUFFER_PX, DEFAULT_EPS_PRED_M, Detections, Geotags,
                                           in_view, local_frame_for, score_flight)
from .base import BirdsEyeAlgorithm

CLUSTER_FIELDS = [
    ("cluster_id", "int", "cluster number, 0.. (DBSCAN order)"),
    ("centroid_x", "double", "mean position of the cluster's detections, x in the layer CRS"),
    ("centroid_y", "double", "mean position of the cluster's detections, y in the layer CRS"),
    ("n_detections", "int", "detections in the cluster"),
    ("n_frames", "int", "distinct frames that detected it"),
    ("median_extent_m", "double", "twice the median distance of its detections from the centroid (m)"),
    ("max_score", "double", "highest detection score"),
    ("matched_geotag_ids", "string", "in-view geotags within EPS_PRED_M of a core point, comma-separated"),
    ("hit", "int", "1 if at least one in-view geotag matches, else 0"),
]
POINT_FIELDS = [
    ("point_id", "int", "de-duplicated point number (3 cm cell)"),
    ("cluster_id", "int", "cluster number, −1 = noise"),
    ("core", "int", "1 for a DBSCAN core point"),
    ("n_detections", "int", "detections merged into this point"),
    ("score", "double", "highest score of those detections"),
]
DETECTION_FIELDS_REQUIRED = ("frame_id", "score")
DETECTION_FIELDS_OPTIONAL = ("model", "model_digest", "threshold")


# ------------------------------------------------------------------------------------ shared parameters
def add_clustering_parameters(alg: BirdsEyeAlgorithm, with_prediction: bool = True) -> None:
    """DEDUP_CM, EPS_M, MIN_SAMPLES (and EPS_PRED_M, EDGE_BUFFER_PX) with the method's defaults."""
    alg.addParameter(QgsProcessingParameterNumber(
        "DEDUP_CM", alg.tr("De-duplication grid cell (cm)"), QgsProcessingParameterNumber.Double,
        DEFAULT_DEDUP_CM, minValue=0.1, maxValue=100.0))
    alg.addParameter(QgsProcessingParameterNumber(
        "EPS_M", alg.tr("DBSCAN radius EPS (m)"), QgsProcessingParameterNumber.Double, DEFAULT_EPS_M,
        minValue=0.001, maxValue=50.0))
    alg.addParameter(QgsProcessingParameterNumber(
        "MIN_SAMPLES", alg.tr("DBSCAN minimum points per neighbourhood (itself included)"),
        QgsProcessingParameterNumber.Integer, DEFAULT_MIN_SAMPLES, minValue=1, maxValue=1000))
    if with_prediction:
        add_matching_parameters(alg)


def add_matching_parameters(alg: BirdsEyeAlgorithm) -> None:
    alg.addParameter(QgsProcessingParameterNumber(
        "EPS_PRED_M", alg.tr("Match radius geotag ↔ cluster core points EPS_PRED (m)"),
        QgsProcessingParameterNumber.Double, DEFAULT_EPS_PRED_M, minValue=0.001, maxValue=50.0))
    alg.addParameter(QgsProcessingParameterNumber(
        "EDGE_BUFFER_PX", alg.tr("Edge buffer of the in-view test (px)"), QgsProcessingParameterNumber.Double,
        DEFAULT_EDGE_BUFFER_PX, minValue=0.0, maxValue=1000.0))


# ------------------------------------------------------------------------------------ readers
def read_detections(source, context, name: str | None = None) -> tuple[Detections, int]:
    """A BirdsEye detection layer (detect's output) as core :class:`Detections`, and the number of
    features left out for want of a position or a score."""
    name = name or source.sourceName()
    names = source.fields().names()
    missing = [f for f in DETECTION_FIELDS_REQUIRED if f not in names]
    if missing:
        raise InputError(f"is not a BirdsEye detection layer: no field(s) {', '.join(missing)} "
                         "(make it with Detect targets)", source=name)
    wanted = list(DETECTION_FIELDS_REQUIRED) + [f for f in DETECTION_FIELDS_OPTIONAL if f in names]
    cols = layers.read_point_layer(source, context.transformContext(), wanted, name)
    values = cols["attributes"]
    try:
        score = np.array([np.nan if v is None else float(v) for v in values["score"]], dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"holds a score that is not a number ({exc})", source=name, field="score") from exc
    frame_id = np.array([-1 if v is None else v for v in values["frame_id"]], dtype=object)
    ok = np.isfinite(cols["lat"]) & np.isfinite(score)
    models = sorted({str(v) for v in values.get("model", []) if v})
    digests = sorted({str(v) for v in values.get("model_digest", []) if v})
    if len(digests) > 1:
        raise InputError(f"mixes detections of {len(digests)} models (model_digest); score one model per "
                         "layer", source=name, field="model_digest")
    thresholds = [float(v) for v in values.get("threshold", []) if v is not None]
    det = Detections(cols["lat"][ok], cols["lon"][ok], cols["z"][ok], frame_id[ok], score[ok], name=name,
                     model=", ".join(models), model_digest=digests[0] if digests else "",
                     threshold=max(thresholds) if thresholds else None)
    return det, int((~ok).sum())


def read_geotags(source, context) -> Geotags:
    """Any point layer as geotags: ids from an ``id`` field when present, else the feature ids."""
    name = source.sourceName()
    has_id = "id" in source.fields().names()
    cols = layers.read_point_layer(source, context.transformContext(), ["id"] if has_id else [], name)
    if has_id:
        ids = [row if v is None else v for v, row in zip(cols["attributes"]["id"], cols["row"].tolist())]
    else:
        request = QgsFeatureRequest().setNoAttributes().setFlags(QgsFeatureRequest.NoGeometry)
        ids = [f.id() for f in source.getFeatures(request)]
    ok = np.isfinite(cols["lat"])
    return Geotags(np.asarray(ids, dtype=object)[ok], cols["lat"][ok], cols["lon"][ok], cols["z"][ok])


def read_pose_groups(source, name: str | None = None):
    """The frames of a frame layer as FramePoses groups (one per camera), and the records."""
    name = name or source.sourceName()
    records = layers.read_frame_layer(source, name)
    groups = poses_from_records(records, name)
    return [poses for poses, _ in groups], records, groups


def to_layer_xy(local: LocalFrame, xy: np.ndarray, crs: QgsCoordinateReferenceSystem):
    """Local ENU (N, 2) metres → x, y in ``crs`` (via WGS84)."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    if len(xy) == 0:
        return np.empty(0), np.empty(0)
    lat, lon, _ = local.to_geodetic(np.column_stack([xy, np.full(len(xy), 0.0)]))
    return ProjectedCRS(layers.pyproj_crs(crs)).from_geodetic(lat, lon)


def wgs84_of(source, context):
    """Transform from a source's CRS to WGS84 (for reading verdict positions from geometry)."""
    return QgsCoordinateTransform(source.sourceCrs(), QgsCoordinateReferenceSystem(layers.WGS84),
                                  context.transformContext() if context else QgsProject.instance().transformContext())


class ClusterDetections(BirdsEyeAlgorithm):
    ALG_ID = "clusterdetections"
    DISPLAY_NAME = "Cluster detections"
    GROUP = "detect"

    def initAlgorithm(self, config=None):  # noqa: N802
        self.addParameter(QgsProcessingParameterFeatureSource(
            "DETECTIONS", self.tr("Detections (from Detect targets)"), [QgsProcessing.TypeVectorPoint]))
        add_clustering_parameters(self, with_prediction=False)
        self.addParameter(QgsProcessingParameterFeatureSource(
            "GEOTAGS", self.tr("Geotags (optional: fills matched_geotag_ids and hit)"),
            [QgsProcessing.TypeVectorPoint], optional=True))
        self.addParameter(QgsProcessingParameterFeatureSource(
            "FRAMES", self.tr("Frames of the flight (optional: only in-view geotags can match)"),
            [QgsProcessing.TypeVector], optional=True))
        add_matching_parameters(self)
        self.addParameter(QgsProcessingParameterFeatureSink(
            "OUTPUT", self.tr("Clusters"), QgsProcessing.TypeVectorPolygon))
        self.addParameter(QgsProcessingParameterFeatureSink(
            "OUTPUT_POINTS", self.tr("De-duplicated points"), QgsProcessing.TypeVectorPoint, optional=True,
            createByDefault=False))
        for name, text in (("CLUSTER_COUNT", "Clusters"), ("HIT_COUNT", "Hit clusters"),
                           ("NOISE_POINTS", "De-duplicated points left as noise")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        source = self.parameterAsSource(parameters, "DETECTIONS", context)
        if source is None:
            raise QgsProcessingException(self.tr("DETECTIONS: the detection layer cannot be read."))
        det, dropped = self.run_core(read_detections, source, context)
        if dropped:
            feedback.pushWarning(f"{dropped} detection(s) without a position or score were left out")
        geotag_source = self.parameterAsSource(parameters, "GEOTAGS", context)
        frame_source = self.parameterAsSource(parameters, "FRAMES", context)
        geotags = self.run_core(read_geotags, geotag_source, context) if geotag_source is not None else None
        groups = self.run_core(read_pose_groups, frame_source)[0] if frame_source is not None else []
        feedback.setProgress(30)
        if len(det) == 0:
            raise QgsProcessingException(self.tr("The detection layer holds no detection with a position."))
        local = self._local_frame(det, groups, geotags)
        xy = det.local_xy(local)
        clustering = self.run_core(cluster_detections, xy, det.frame_id, det.score,
                                   self.parameterAsDouble(parameters, "DEDUP_CM", context),
                                   self.parameterAsDouble(parameters, "EPS_M", context),
                                   self.parameterAsInt(parameters, "MIN_SAMPLES", context))
        feedback.setProgress(55)
        n = clustering.n_clusters
        matched = [""] * n
        hit = np.zeros(n, dtype=bool)
        if geotags is not None and len(geotags):
            h = np.where(np.isfinite(geotags.height), geotags.height, local.h0)
            g_local = local.from_geodetic(geotags.lat, geotags.lon, h)
            if groups:
                visible = self.run_core(in_view, groups, local, g_local,
                                        self.parameterAsDouble(parameters, "EDGE_BUFFER_PX", context)).mask
            else:
                feedback.pushWarning("No FRAMES given: every geotag is treated as in view.")
                visible = np.ones(len(geotags), dtype=bool)
            score = score_flight(clustering, g_local[:, :2], visible,
                                 self.parameterAsDouble(parameters, "EPS_PRED_M", context))
            hit = score.cluster_hit
            matched = [",".join(str(geotags.ids[i]) for i in g) for g in score.cluster_geotags]
            feedback.pushInfo(f"{score.counts.n_hit_clusters} of {n} clusters match an in-view geotag; "
                              f"{score.counts.n_recovered} of {score.counts.n_in_view} in-view geotags recovered.")
        feedback.setProgress(65)
        crs = source.sourceCrs()
        outputs = {"CLUSTER_COUNT": n, "HIT_COUNT": int(hit.sum()),
                   "NOISE_POINTS": int((clustering.dbscan.labels < 0).sum())}
        outputs["OUTPUT"] = self._write_clusters(parameters, context, feedback, clustering, xy, matched, hit, local,
                                                 crs)
        if parameters.get("OUTPUT_POINTS"):
            outputs["OUTPUT_POINTS"] = self._write_points(parameters, context, feedback, clustering, det, local, crs)
        feedback.pushInfo(f"{len(det)} detections → {len(clustering.points)} de-duplicated points → {n} clusters "
                          f"({outputs['NOISE_POINTS']} points are noise).")
        return outputs

    @staticmethod
    def _local_frame(det: Detections, groups, geotags) -> LocalFrame:
        if groups:
            return local_frame_for(groups, geotags)
        return LocalFrame.around(det.lat, det.lon, det.height[np.isfinite(det.height)]
                                 if np.isfinite(det.height).any() else None)

    def _write_clusters(self, parameters, context, feedback, clustering, xy, matched, hit, local, crs):
        fields = layers.qgs_fields(CLUSTER_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, "OUTPUT", context, fields, QgsWkbTypes.Polygon, crs)
        if sink is None:
            raise QgsProcessingException(self.tr("OUTPUT: the cluster layer cannot be created."))
        n = clustering.n_clusters
        s = clustering.summary
        rings = cluster_hulls(xy, clustering.detection_cluster, n, HULL_BUFFER_M)
        rx, ry = to_layer_xy(local, rings.reshape(-1, 2), crs)
        rx, ry = rx.reshape(n, -1), ry.reshape(n, -1)
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
        sink, dest_id = self.parameterAsSink(parameters, "OUTPUT_POINTS", context, fields, QgsWkbTypes.Point, crs)
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
        layers.style_on_load(context, dest_id, "detections.qml")
        return dest_id
