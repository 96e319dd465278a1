"""Layer choices offer only layers of their kind and start on the most recent one (qgis_io/layer_kinds.py and
the review dock's setup box), headless with pytest-qgis.

Kinds are told by the schemas of the modules that own them; geotags are every other point layer. "Most recent"
is the layer added last in this session, else the one whose data was written last, else the lowest in the
Layers panel.
"""
from __future__ import annotations

import os

import pytest
from qgis.core import QgsFeature, QgsGeometry, QgsPointXY, QgsProject, QgsRasterLayer, QgsVectorLayer

from birdseye.birdseye_qgis.core.field.frame_records import FRAME_FIELD_NAMES
from birdseye.birdseye_qgis.core.labels.mark_check import MARK_CHECK_FIELDS
from birdseye.birdseye_qgis.core.plan.flight_plan import WAYPOINT_FIELDS
from birdseye.birdseye_qgis.core.scoring.compare import CHANGE_FIELDS
from birdseye.birdseye_qgis.gui.review import dock as dock_module
from birdseye.birdseye_qgis.qgis_io import layer_kinds as lk
from birdseye.birdseye_qgis.qgis_io.detections import CLUSTER_FIELDS, DETECTION_FIELDS, POINT_FIELDS
from birdseye.birdseye_qgis.qgis_io.review_store import VERDICT_FIELD_NAMES

SITE_A = (151.95, -27.55)
SITE_B = (151.96, -27.55)   # about 1 km east: another paddock


def names(schema) -> list:
    return [f[0] if isinstance(f, tuple) else f for f in schema]


def memory_layer(geometry: str, fields, name: str, at=SITE_A) -> QgsVectorLayer:
    """A memory layer with ``fields`` (all text) and one feature at ``at`` (lon, lat)."""
    uri = f"{geometry}?crs=EPSG:4326" + "".join(f"&field={n}:string" for n in fields)
    layer = QgsVectorLayer(uri, name, "memory")
    assert layer.isValid(), name
    feature = QgsFeature(layer.fields())
    point = QgsGeometry.fromPointXY(QgsPointXY(*at))
    feature.setGeometry(point if geometry == "Point" else point.buffer(0.0005, 4) if geometry == "Polygon"
                        else QgsGeometry.fromPolylineXY([QgsPointXY(*at), QgsPointXY(at[0] + 0.0001, at[1])]))
    layer.dataProvider().addFeatures([feature])
    layer.updateExtents()
    return layer


def frames(name, at=SITE_A):
    return memory_layer("Polygon", FRAME_FIELD_NAMES, name, at)


def detections(name, at=SITE_A):
    return memory_layer("Point", names(DETECTION_FIELDS), name, at)


def geotags(name, at=SITE_A):
    return memory_layer("Point", ["id", "label"], name, at)


def write_gpkg(layer, path) -> str:
    """``layer`` saved as a GeoPackage; the error message, empty when it was written."""
    from qgis.core import QgsCoordinateTransformContext, QgsVectorFileWriter

    options = QgsVectorFileWriter.SaveVectorOptions()
    options.driverName = "GPKG"
    result = QgsVectorFileWriter.writeAsVectorFormatV3(layer, str(path), QgsCoordinateTransformContext(), options)
    return "" if result[0] == QgsVectorFileWriter.WriterError.NoError else result[1]


@pytest.fixture
def project(qgis_iface):
    project = QgsProject.instance()
    project.clear()
    lk.track(project)
    yield project
    project.clear()


def test_each_schema_is_its_kind_and_other_points_are_geotags(project, tmp_path):
    layers = {
        lk.FRAMES: frames("frames"),
        lk.DETECTIONS: detections("detections"),
        lk.CLUSTERS: memory_layer("Polygon", names(CLUSTER_FIELDS), "clusters"),
        lk.DEDUP_POINTS: memory_layer("Point", names(POINT_FIELDS), "de-duplicated points"),
        lk.VERDICTS: memory_layer("Point", VERDICT_FIELD_NAMES[1:], "verdicts"),
        lk.WAYPOINTS: memory_layer("Point", names(WAYPOINT_FIELDS), "waypoints"),
        lk.GEOTAGS: geotags("survey"),
    }
    for kind, layer in layers.items():
        assert lk.layer_kind(layer) == kind, layer.name()
    # A point layer of any other fields is a survey; BirdsEye's other point outputs and non-point layers are not.
    assert lk.layer_kind(memory_layer("Point", ["name"], "rover points")) == lk.GEOTAGS
    # A label check is its own kind (Write labels' MARK_CHECK); a polygon layer of no other kind is an area.
    assert lk.layer_kind(memory_layer("Point", names(MARK_CHECK_FIELDS), "label check")) == lk.LABEL_CHECKS
    assert lk.layer_kind(memory_layer("Polygon", ["id"], "fields")) == lk.AREAS
    for other in (memory_layer("Point", names(CHANGE_FIELDS), "what changed"),
                  memory_layer("LineString", ["segment"], "flight line")):
        assert lk.layer_kind(other) == lk.OTHER, other.name()
    assert lk.layer_kind(QgsRasterLayer(str(tmp_path / "missing.tif"), "no raster")) == lk.OTHER
    # A frame layer copied to a Shapefile keeps its kind: every identifying name fits in 10 characters.
    assert all(len(name) <= 10 for _, fields in lk.SIGNATURES for name in fields)


def test_most_recent_is_the_layer_added_last(project):
    first, second = frames("first flight"), frames("second flight")
    project.addMapLayers([first, second])
    assert lk.most_recent(project, lk.FRAMES) is second
    third = frames("third flight")
    project.addMapLayer(third)
    assert lk.layers_of_kind(project, lk.FRAMES) == [third, second, first]
    assert lk.most_recent(project, lk.GEOTAGS) is None


def test_in_a_project_read_from_file_the_data_written_last_is_the_most_recent(project, tmp_path):
    paths = []
    for name, written_s in (("older", 1_700_000_100), ("newer", 1_700_000_200), ("oldest", 1_700_000_000)):
        path = tmp_path / f"{name}.gpkg"
        assert write_gpkg(frames(name), path) == ""
        os.utime(path, (written_s, written_s))
        paths.append(path)
    for path in paths:
        project.addMapLayer(QgsVectorLayer(str(path), path.stem, "ogr"))
    project_file = tmp_path / "p.qgz"
    assert project.write(str(project_file))
    project.clear()
    assert project.read(str(project_file))
    # Read from the file, no layer counts as added now: the newest data wins, whatever the order in the file.
    assert [layer.name() for layer in lk.layers_of_kind(project, lk.FRAMES)] == ["newer", "older", "oldest"]
    added = frames("added after opening")
    project.addMapLayer(added)
    assert lk.most_recent(project, lk.FRAMES) is added


def test_overlapping_prefers_the_layers_over_the_same_ground(project):
    here, elsewhere = frames("frames here", SITE_A), frames("frames elsewhere", SITE_B)
    det = detections("detections here", SITE_A)
    project.addMapLayers([here, elsewhere, det])
    assert lk.most_recent(project, lk.FRAMES) is elsewhere
    assert lk.most_recent(project, lk.FRAMES, overlapping=det) is here
    far = detections("detections far away", (150.0, -30.0))
    assert lk.most_recent(project, lk.FRAMES, overlapping=far) is elsewhere   # none overlaps: the most recent


# ---------------------------------------------------------------------------------------------- the review dock
@pytest.fixture
def review_dock(qgis_iface, qtbot):
    docks = []

    def make():
        dock = dock_module.ReviewDock(qgis_iface)
        qtbot.addWidget(dock)
        docks.append(dock)
        return dock

    yield make
    for dock in docks:
        dock.shutdown()


def offered(combo) -> list:
    return [combo.layer(i).name() for i in range(combo.count()) if combo.layer(i) is not None]


def checked(dock) -> list:
    project = QgsProject.instance()
    return [project.mapLayer(i).name() for i in dock.detections_combo.checkedItemsData()]


def test_the_review_offers_only_layers_of_each_kind_and_starts_on_the_flight_of_the_newest_detections(
        project, review_dock):
    project.addMapLayers([geotags("survey here", SITE_A), frames("frames here", SITE_A),
                          detections("detections here", SITE_A),
                          memory_layer("Polygon", names(CLUSTER_FIELDS), "clusters here"),
                          memory_layer("Point", names(POINT_FIELDS), "de-duplicated points here"),
                          memory_layer("Point", names(WAYPOINT_FIELDS), "waypoints here"),
                          frames("frames elsewhere", SITE_B), geotags("survey elsewhere", SITE_B)])
    dock = review_dock()
    assert offered(dock.frames_combo) == ["frames elsewhere", "frames here"]
    assert offered(dock.geotags_combo) == ["survey elsewhere", "survey here"]
    assert [dock.detections_combo.itemText(i) for i in range(dock.detections_combo.count())] == ["detections here"]
    # Newer frames and geotags exist elsewhere; the ones under the detections are chosen.
    assert checked(dock) == ["detections here"]
    assert dock.frames_combo.currentLayer().name() == "frames here"
    assert dock.geotags_combo.currentLayer().name() == "survey here"

    # New detections of the other flight: the choices follow them while the user has chosen nothing.
    project.addMapLayer(detections("detections elsewhere", SITE_B))
    assert checked(dock) == ["detections elsewhere"]
    assert dock.frames_combo.currentLayer().name() == "frames elsewhere"
    assert dock.geotags_combo.currentLayer().name() == "survey elsewhere"
    # A layer of another kind never appears, even when added later.
    project.addMapLayer(memory_layer("Point", names(POINT_FIELDS), "more de-duplicated points"))
    assert "more de-duplicated points" not in offered(dock.geotags_combo)


def test_a_layer_the_user_chose_stays_chosen(project, review_dock):
    here = frames("frames here", SITE_A)
    project.addMapLayers([here, detections("detections here", SITE_A), geotags("survey here", SITE_A)])
    dock = review_dock()
    assert dock.frames_combo.currentLayer() is here
    other = frames("other frames", SITE_A)
    project.addMapLayer(other)
    assert dock.frames_combo.currentLayer() is other       # the most recent, as long as the user has not chosen
    dock.frames_combo.setLayer(here)
    dock.frames_combo.activated.emit(dock.frames_combo.currentIndex())   # what a click on an item emits
    project.addMapLayer(frames("yet more frames", SITE_A))
    assert dock.frames_combo.currentLayer() is here
    project.removeMapLayer(other.id())
    assert dock.frames_combo.currentLayer() is here and offered(dock.frames_combo) == ["frames here",
                                                                                       "yet more frames"]


def test_the_plugin_records_the_order_layers_are_added_from_the_start(qgis_iface):
    from birdseye.birdseye_qgis.gui.plugin import BirdsEyePlugin
    from birdseye.processing.provider import BirdsEyeProvider

    project = QgsProject.instance()
    for order in project.findChildren(lk._AddOrder, lk.ORDER_OBJECT_NAME):
        order.setParent(None)          # as in a QGIS that has just started
        order.deleteLater()
    class Provider(BirdsEyeProvider):   # the session's registry already holds "birdseye"
        def id(self):
            return "birdseye_layer_kinds_test"

    plugin = BirdsEyePlugin(qgis_iface, Provider)
    plugin.initGui()
    try:
        assert project.findChild(lk._AddOrder, lk.ORDER_OBJECT_NAME) is not None
    finally:
        plugin.unload()
