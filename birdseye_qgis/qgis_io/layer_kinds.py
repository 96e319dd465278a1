"""Which of BirdsEye's inputs a project layer is (frames, geotags, detections, …) and which one is the most recent.

One rule for every layer choice, in the docks and in the Processing dialogs: a choice offers only the layers
of its kind and starts on the most recent one.

Kinds are recognised by the schema their module owns (docs/design.md §1, rule 5): a layer is of a kind when
it has that schema's identifying fields (:data:`SIGNATURES`; names of at most 10 characters, so a Shapefile
copy is still recognised). Geotags and areas are the exceptions, since any point layer may be a survey and any
polygon layer a surveyed area someone drew: a vector layer with point (polygon) geometry that is of no other
kind.

"Most recent" means added last to the project. QGIS records no such order, and a project file lists its
layers by id, so :func:`recency_key` orders them by, in turn:

1. the order they were added in this QGIS session, recorded by :func:`track` (layers a project file brings
   with it do not count as added: they were added when the project was made);
2. the modification time of their data file (a GeoPackage's write-ahead log included): the layer whose data
   was written last, e.g. by the latest Processing run;
3. their place in the Layers panel, lower = more recent (the order a project script adds them in).
"""
from __future__ import annotations

import itertools
import os

from qgis.core import (
    QgsCoordinateTransform,
    QgsCsException,
    QgsProviderRegistry,
    QgsVectorLayer,
    QgsWkbTypes,
)
from qgis.PyQt.QtCore import QObject

from ..core.field.frame_records import FRAME_FIELDS
from ..core.labels.mark_check import MARK_CHECK_FIELDS
from ..core.plan.flight_plan import WAYPOINT_FIELDS
from ..core.scoring.compare import CHANGE_FIELDS
from ..qgis_enums import GEOMETRY_POINT, GEOMETRY_POLYGON
from .detections import CLUSTER_FIELDS, DETECTION_FIELDS, POINT_FIELDS
from .review_store import VERDICT_COLUMNS

FRAMES = "frames"
GEOTAGS = "geotags"
DETECTIONS = "detections"
CLUSTERS = "clusters"
DEDUP_POINTS = "dedup_points"
VERDICTS = "verdicts"
WAYPOINTS = "waypoints"
LABEL_CHECKS = "label_checks"
AREAS = "areas"
OTHER = "other"
KINDS = (FRAMES, GEOTAGS, DETECTIONS, CLUSTERS, DEDUP_POINTS, VERDICTS, WAYPOINTS, LABEL_CHECKS, AREAS, OTHER)


def _identifying(schema, *names: str) -> frozenset:
    """``names``, each checked to be a field of ``schema`` ((name, type, description) list)."""
    known = {field[0] for field in schema}
    unknown = set(names) - known
    if unknown:
        raise ValueError(f"not fields of the schema: {sorted(unknown)}")
    return frozenset(names)


#: (kind, identifying fields), tried in this order; the first whose fields a layer has is its kind. BirdsEye
#: point outputs that are no survey (detectors' changes: OTHER; label checks) are not geotags.
SIGNATURES = (
    (VERDICTS, _identifying(VERDICT_COLUMNS, "unit_key", "verdict", "provenance", "action_id")),
    (DETECTIONS, _identifying(DETECTION_FIELDS, "frame_id", "u", "v", "score")),
    (DEDUP_POINTS, _identifying(POINT_FIELDS, "point_id", "cluster_id", "core")),
    (CLUSTERS, _identifying(CLUSTER_FIELDS, "cluster_id", "centroid_x", "centroid_y")),
    (FRAMES, _identifying(FRAME_FIELDS, "frame_id", "lat", "lon", "height_m", "qw", "qx", "qy", "qz", "camera")),
    (WAYPOINTS, _identifying(WAYPOINT_FIELDS, "mission", "order", "geotag_ids")),
    (OTHER, _identifying(CHANGE_FIELDS, "change", "kind", "geotag_id")),
    (LABEL_CHECKS, _identifying(MARK_CHECK_FIELDS, "u_mark", "v_mark", "error_px")),
)


def layer_kind(layer) -> str:
    """The kind of ``layer`` (one of :data:`KINDS`); anything that is not a vector layer is OTHER."""
    if not isinstance(layer, QgsVectorLayer) or not layer.isValid():
        return OTHER
    names = set(layer.fields().names())
    for kind, fields in SIGNATURES:
        if fields <= names:
            return kind
    geometry = QgsWkbTypes.geometryType(layer.wkbType())
    if geometry == GEOMETRY_POINT:
        return GEOTAGS
    if geometry == GEOMETRY_POLYGON:
        return AREAS
    return OTHER


# ---------------------------------------------------------------------------------------------- recency
ORDER_OBJECT_NAME = "birdseyeLayerAddOrder"


class _AddOrder(QObject):
    """The order layers are added to one project in this session (child of the project, lives as long)."""

    def __init__(self, project):
        super().__init__(project)
        self.setObjectName(ORDER_OBJECT_NAME)
        self.sequence: dict[str, int] = {}
        self._counter = itertools.count(1)
        project.layersAdded.connect(self._added)
        # A project being read adds its layers between cleared and readProject: they were not added now.
        project.cleared.connect(self._forget)
        project.readProject.connect(self._forget)

    def _added(self, layers) -> None:
        for layer in layers:
            self.sequence[layer.id()] = next(self._counter)

    def _forget(self, *_) -> None:
        self.sequence.clear()


def track(project) -> None:
    """Record from now on the order layers are added to ``project`` (once per project; idempotent).

    The plugin calls this when QGIS starts; a call from :func:`most_recent` covers a project it never saw.
    """
    if project.findChild(_AddOrder, ORDER_OBJECT_NAME) is None:
        _AddOrder(project)


def _data_mtime_ns(layer) -> int:
    """Modification time of the layer's data file (and of a GeoPackage's write-ahead log); 0 for none."""
    parts = QgsProviderRegistry.instance().decodeUri(layer.providerType(), layer.source())
    path = parts.get("path") or ""
    times = []
    for candidate in (path, path + "-wal") if path else ():
        try:
            times.append(os.stat(candidate).st_mtime_ns)
        except OSError:
            pass
    return max(times, default=0)


def recency_key(project):
    """A sort key for ``project``'s layers, from the oldest to the most recent (see the module docstring)."""
    order = project.findChild(_AddOrder, ORDER_OBJECT_NAME)
    added = order.sequence if order is not None else {}
    tree = {layer_id: position for position, layer_id in enumerate(project.layerTreeRoot().findLayerIds())}
    return lambda layer: (added.get(layer.id(), 0), _data_mtime_ns(layer), tree.get(layer.id(), -1))


def layers_of_kind(project, kind: str) -> list:
    """The layers of ``project`` of ``kind``, the most recent first."""
    track(project)
    layers = [layer for layer in project.mapLayers().values() if layer_kind(layer) == kind]
    return sorted(layers, key=recency_key(project), reverse=True)


def overlaps(layer, other, project) -> bool:
    """True when the extents of the two layers meet (compared in ``layer``'s CRS; a one-point extent counts)."""
    if layer is None or other is None or layer.extent().isNull() or other.extent().isNull():
        return False
    try:
        theirs = QgsCoordinateTransform(other.crs(), layer.crs(), project).transformBoundingBox(other.extent())
    except QgsCsException:
        return False
    mine = layer.extent()
    # By coordinates: QgsRectangle.intersects calls a zero-width extent (a single point) empty.
    return (mine.xMinimum() <= theirs.xMaximum() and theirs.xMinimum() <= mine.xMaximum()
            and mine.yMinimum() <= theirs.yMaximum() and theirs.yMinimum() <= mine.yMaximum())


def most_recent(project, kind: str, overlapping=None):
    """The most recent layer of ``kind`` in ``project`` (None when it has none).

    ``overlapping`` (a layer) narrows the choice to the layers that overlap it, e.g. the frames of the flight
    a detection layer was made from, when any does; otherwise every layer of the kind is a candidate.
    """
    candidates = layers_of_kind(project, kind)
    near = [layer for layer in candidates if overlaps(layer, overlapping, project)]
    return (near or candidates or [None])[0]


def other_layers(project, kind: str) -> list:
    """Every layer of ``project`` not of ``kind``: the exceptions of a layer combo box that offers only ``kind``."""
    return [layer for layer in project.mapLayers().values() if layer_kind(layer) != kind]
