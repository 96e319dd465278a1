"""Detection, cluster and verdict layers ↔ core inputs: the schema of the layers Detect and Cluster
detections write, and the readers every scoring algorithm and the review dock share."""
from __future__ import annotations

import numpy as np
from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsFeatureRequest,
    QgsProject,
    QgsWkbTypes,
)

from ..core.errors import InputError
from ..core.field.frame_records import poses_from_records
from ..core.geometry.geodesy import LocalFrame, ProjectedCRS
from ..core.geometry.ground_record import DEM, LEVEL_PLANE, RASTER, GroundRecord
from ..core.scoring.evaluation import Detections
from ..core.scoring.verdicts import VerdictLog
from ..qgis_enums import GEOMETRY_POINT, REQUEST_NO_GEOMETRY
from . import layers

#: (name, type, description) of the detection layer.
DETECTION_FIELDS = [
    ("frame_id", "int", "frame the detection was made in"),
    ("u", "double", "column of the peak in the original (distorted) image, px, pixel-centre convention"),
    ("v", "double", "row of the peak, px"),
    ("score", "double", "peak value of the smoothed probability heatmap (0..1)"),
    ("model", "string", "model file name"),
    ("model_digest", "string", "SHA-256 of the model file"),
    ("threshold", "double", "probability threshold of the run"),
    # The ground model Detect placed the detection on, on every feature so it survives any format and any
    # copy of the features (names of at most 10 characters, so a Shapefile keeps them whole).
    ("ground", "string", "ground model the detection was placed on: level, method_plane, dem, or raster "
                         "(found on a raster, no frame between)"),
    ("dem_source", "string", "the DEM's file (ground = dem; empty otherwise)"),
    ("dem_datum", "string", "what the DEM's heights are measured from: ellipsoidal, msl or unknown"),
    ("dem_n_m", "double", "geoid undulation N given with the DEM (m; ellipsoidal = MSL + N), empty when none"),
    ("height_ref", "string", "what Z, the ground point's height, is measured from: the frames' height_ref "
                             "(ellipsoidal, EGM96, msl, unknown)"),
]
GROUND_FIELDS = ("ground", "dem_source", "dem_datum", "dem_n_m")
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
DETECTION_FIELDS_OPTIONAL = ("model", "model_digest", "threshold") + GROUND_FIELDS



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
    thresholds = sorted({float(v) for v in values.get("threshold", []) if v is not None})
    if len(thresholds) > 1 and thresholds[-1] - thresholds[0] > 1e-9:
        listed = ", ".join(f"{t:g}" for t in thresholds)
        raise InputError(f"mixes detections of {len(thresholds)} thresholds ({listed}); a threshold is a Detect "
                         "run, not a score filter: score one run per layer", source=name, field="threshold")
    ground = _ground_record(values, name)
    # Detections found on a raster have no height (Z 0, height_ref unknown): NaN, which core code reads as
    # the local ground's height.
    height = np.full(int(ok.sum()), np.nan) if ground.model == RASTER else cols["z"][ok]
    det = Detections(cols["lat"][ok], cols["lon"][ok], height, frame_id[ok], score[ok], name=name,
                     model=", ".join(models), model_digest=digests[0] if digests else "",
                     threshold=max(thresholds) if thresholds else None, ground=ground)
    return det, int((~ok).sum())


def found_on_raster(layer) -> bool:
    """Whether a detection layer's detections were found on a raster (Detect targets on a raster), from its first
    feature's ``ground``: the review dock needs no frame layer for those (it cuts their chips from the raster)."""
    if "ground" not in layer.fields().names():
        return False
    request = QgsFeatureRequest().setLimit(1).setSubsetOfAttributes(["ground"], layer.fields())
    request.setFlags(REQUEST_NO_GEOMETRY)
    return any(feature["ground"] == RASTER for feature in layer.getFeatures(request))


def ground_attributes(record: GroundRecord) -> dict:
    """The ground fields (:data:`GROUND_FIELDS`) Detect writes on every detection of a run placed on
    ``record``'s ground."""
    return {"ground": record.model, "dem_source": record.dem_source or None, "dem_datum": record.dem_datum or None,
            "dem_n_m": record.geoid_undulation_m}


def _ground_record(values: dict, name: str) -> GroundRecord:
    """The one ground a detection layer's features were placed on; a layer without the field (made before
    Detect recorded it) was placed on the level plane, as were features where it is empty."""
    if "ground" not in values:
        return GroundRecord()
    n = len(values["ground"])
    columns = [values.get(f, [None] * n) for f in GROUND_FIELDS]
    found = set()
    for model, source, datum, undulation in zip(*columns):
        if not model or model == LEVEL_PLANE:
            found.add(GroundRecord())
            continue
        try:
            found.add(GroundRecord(str(model), str(source or ""), str(datum or ""),
                                   None if undulation is None else float(undulation))
                      if model == DEM else GroundRecord(str(model), str(source or "")) if model == RASTER
                      else GroundRecord(str(model)))
        except (InputError, TypeError, ValueError) as exc:
            raise InputError(str(exc), source=name, field="ground") from exc
    if len(found) > 1:
        listed = "; ".join(sorted(record.describe() for record in found))
        raise InputError(f"mixes detections placed on {len(found)} grounds ({listed}): a Detect run places all its "
                         "detections on one ground; score each run's layer on its own", source=name, field="ground")
    return found.pop() if found else GroundRecord()


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


def read_verdicts(layer, context) -> VerdictLog:
    """The review dock's verdict table (append order = feature id order) as a :class:`VerdictLog`.

    Positions come from ``lat``/``lon`` fields, else from a point geometry (transformed to WGS84).
    """
    names = layer.fields().names()
    use_geometry = ("lat" not in names or "lon" not in names) and layer.isSpatial() and \
        QgsWkbTypes.geometryType(layer.wkbType()) == GEOMETRY_POINT
    transform = wgs84_of(layer, context) if use_geometry else None
    records = []
    for feature in sorted(layer.getFeatures(), key=lambda f: f.id()):
        rec = {n: (None if v is None or (hasattr(v, "isNull") and v.isNull()) else v)
               for n, v in zip(names, feature.attributes())}
        rec["sequence"] = feature.id()
        if transform is not None and feature.hasGeometry():
            p = transform.transform(feature.geometry().asPoint())
            rec["lat"], rec["lon"] = p.y(), p.x()
        records.append(rec)
    return VerdictLog.from_records(records, source=layer.name())
