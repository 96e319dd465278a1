"""``birdseye:planflight`` through the Processing registry: layers, mission files, bad input."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from qgis.core import (
    NULL,
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsFeature,
    QgsField,
    QgsGeometry,
    QgsPointXY,
    QgsProcessingContext,
    QgsProcessingException,
    QgsProject,
    QgsVectorLayer,
    QgsWkbTypes,
)
from qgis.PyQt.QtCore import QVariant
from registry import Recorder

from birdseye.birdseye_qgis.core.geometry.camera import CameraModel, write_kalibr_yaml
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame, ProjectedCRS
from birdseye.birdseye_qgis.core.plan.mission_files import parse_dji_kmz, parse_kml, parse_litchi_csv, parse_qgc_plan

LAT0, LON0 = 48.1371, 11.5754  # UTM zone 32N
UTM = "EPSG:32632"
TOL_DEG = 1e-7

def geotag_layer(xy_m, crs=UTM, ids=None, name="geotags"):
    """A memory point layer with an ``id`` field; ``xy_m`` are east/north metres from the site origin,
    placed exactly through the local frame and written in ``crs``."""
    frame = LocalFrame(LAT0, LON0, 0.0)
    lat, lon, _ = frame.to_geodetic(np.column_stack([xy_m, np.zeros(len(xy_m))]))
    lat, lon = np.atleast_1d(lat), np.atleast_1d(lon)
    layer = QgsVectorLayer(f"Point?crs={crs}", name, "memory")
    layer.dataProvider().addAttributes([QgsField("id", QVariant.Int)])
    layer.updateFields()
    if crs == "EPSG:4326":
        x, y = lon, lat
    else:
        x, y = ProjectedCRS(crs).from_geodetic(lat, lon)
    features = []
    for k, (px, py) in enumerate(zip(np.atleast_1d(x), np.atleast_1d(y))):
        f = QgsFeature(layer.fields())
        f.setAttributes([int(ids[k]) if ids is not None else 100 + k])
        f.setGeometry(QgsGeometry.fromPointXY(QgsPointXY(float(px), float(py))))
        features.append(f)
    layer.dataProvider().addFeatures(features)
    return layer


def run(params, feedback=None):
    import processing

    feedback = feedback or Recorder()
    context = QgsProcessingContext()
    context.setProject(QgsProject.instance())
    result = processing.run("birdseye:planflight", params, context=context, feedback=feedback)
    return result, context, feedback


def run_fails(params):
    """The message a user sees when the run is refused (the exception, and the log if any)."""
    feedback = Recorder()
    with pytest.raises(QgsProcessingException) as failure:
        run(params, feedback)
    return " ".join([str(failure.value)] + feedback.errors)


def features(layer_or_id, context):
    layer = layer_or_id if isinstance(layer_or_id, QgsVectorLayer) else context.getMapLayer(layer_or_id)
    return layer, list(layer.getFeatures())


@pytest.fixture
def camera_file(tmp_path):
    path = tmp_path / "camchain.yaml"
    write_kalibr_yaml(CameraModel(2000, 1500, 1500.0, 1500.0, 999.5, 749.5,
                                  dist=(-0.12, 0.03, 0.0, 0.0, 0.0)), path)
    return path


def test_plan_with_home_camera_and_split_writes_matching_mission_files(birdseye_provider, tmp_path,
                                                                       camera_file):
    rng = np.random.default_rng(8)
    xy = np.concatenate([rng.uniform(0, 300, (30, 2)), rng.normal([150, 150], 0.6, (6, 2))])
    layer = geotag_layer(xy)
    home_xy = ProjectedCRS(UTM).from_geodetic(LAT0, LON0)
    params = {"GEOTAGS": layer, "HOME": f"{float(home_xy[0])},{float(home_xy[1])} [{UTM}]",
              "ALTITUDE_M": 15.0, "SPEED_MS": 4.0, "MERGE_RADIUS_M": 2.0, "CAMERA": str(camera_file),
              "HOVER_S": 1.0, "MAX_WAYPOINTS": 8, "MAX_FLIGHT_MIN": 15.0,
              "OUTPUT_WAYPOINTS": "memory:", "OUTPUT_ROUTE": "memory:",
              "OUTPUT_KMZ": str(tmp_path / "survey.kmz"), "OUTPUT_PLAN": str(tmp_path / "survey.plan"),
              "OUTPUT_LITCHI": str(tmp_path / "survey.csv"), "OUTPUT_KML": str(tmp_path / "survey.kml")}
    result, context, feedback = run(params)
    wp_layer, wps = features(result["OUTPUT_WAYPOINTS"], context)
    assert QgsWkbTypes.hasZ(wp_layer.wkbType()) and wp_layer.crs().authid() == UTM
    n_missions = int(result["MISSION_COUNT"])
    assert result["WAYPOINT_COUNT"] == len(wps) and result["GEOTAG_COUNT"] == 36
    assert n_missions >= max(3, int(np.ceil(len(wps) / 8)))
    # The tight cluster of six merged; every geotag listed exactly once.
    ids = sorted(int(g) for f in wps for g in f["geotag_ids"].split(";"))
    assert ids == list(range(100, 136)) and len(wps) < 36
    to_wgs84 = QgsCoordinateTransform(wp_layer.crs(), QgsCoordinateReferenceSystem("EPSG:4326"),
                                      QgsProject.instance())
    by_mission = {}
    for f in wps:
        p = to_wgs84.transform(f.geometry().asPoint())
        assert (p.y(), p.x()) == (pytest.approx(f["lat"], abs=1e-9), pytest.approx(f["lon"], abs=1e-9))
        assert f.geometry().constGet().z() == f["altitude"] == 15.0
        by_mission.setdefault(f["mission"], []).append((f["order"], f["lat"], f["lon"], f["altitude"]))
    assert sorted(by_mission) == list(range(1, n_missions + 1))
    for m, rows in by_mission.items():
        rows.sort()
        assert [r[0] for r in rows] == list(range(1, len(rows) + 1)) and 2 <= len(rows) <= 8
        lat, lon, alt = (np.array([r[k] for r in rows]) for k in (1, 2, 3))
        kmz = parse_dji_kmz(tmp_path / f"survey_m{m}.kmz")["waylines"]
        plan = parse_qgc_plan(tmp_path / f"survey_m{m}.plan")
        litchi = parse_litchi_csv(tmp_path / f"survey_m{m}.csv")
        for parsed, alt_key in ((kmz, "height"), (plan, "altitude"), (litchi, "altitude")):
            assert np.allclose(parsed["lat"], lat, atol=TOL_DEG, rtol=0)
            assert np.allclose(parsed["lon"], lon, atol=TOL_DEG, rtol=0)
            assert np.allclose(parsed[alt_key], alt)
        assert kmz["drone_enum"] == 89 and kmz["execute_height_mode"] == "relativeToStartPoint"
        assert plan["commands"][0] == 22 and plan["commands"][-1] == 20
    kml = parse_kml(tmp_path / "survey.kml")
    assert len(kml) == n_missions
    assert not (tmp_path / "survey.kmz").exists()  # several missions: suffixed files only
    written = result["MISSION_FILES"].split(";")
    assert len(written) == 3 * n_missions + 1 and all(Path(p).is_file() for p in written)

    route_layer, routes = features(result["OUTPUT_ROUTE"], context)
    assert len(routes) == n_missions
    home_utm = QgsPointXY(float(home_xy[0]), float(home_xy[1]))
    for f in routes:
        line = f.geometry().asPolyline()
        assert line[0].distance(home_utm) < 1e-3 and line[-1].distance(home_utm) < 1e-3
        assert len(line) == f["waypoints"] + 2
        assert f["length_m"] == pytest.approx(f.geometry().length(), rel=2e-3)  # UTM scale ≈ 1
        assert f["est_time_min"] <= 15.0
    # The layer rounds to cm and 0.01 min.
    assert result["ROUTE_LENGTH_M"] == pytest.approx(sum(f["length_m"] for f in routes), abs=0.01 * n_missions)
    assert result["FLIGHT_TIME_MIN"] == pytest.approx(sum(f["est_time_min"] for f in routes), abs=0.01)
    log = " ".join(feedback.infos)
    assert "geotag(s) →" in log and "forward overlap" in log and "mission 1:" in log


def test_selected_only_flies_the_selection(birdseye_provider):
    layer = geotag_layer(np.array([[0, 0], [40, 0], [80, 0], [120, 0]], dtype=float), ids=[1, 2, 3, 4])
    QgsProject.instance().addMapLayer(layer)
    try:
        message = run_fails({"GEOTAGS": layer, "SELECTED_ONLY": True, "OUTPUT_WAYPOINTS": "memory:",
                             "OUTPUT_ROUTE": "memory:"})
        assert "SELECTED_ONLY is set but no geotag" in message
        layer.selectByIds([f.id() for f in layer.getFeatures() if f["id"] in (2, 4)])
        result, context, _ = run({"GEOTAGS": layer, "SELECTED_ONLY": True, "MERGE_RADIUS_M": 0.5,
                                  "OUTPUT_WAYPOINTS": "memory:", "OUTPUT_ROUTE": "memory:"})
        _, wps = features(result["OUTPUT_WAYPOINTS"], context)
        assert sorted(f["geotag_ids"] for f in wps) == ["2", "4"]
    finally:
        QgsProject.instance().removeMapLayer(layer.id())


def test_geographic_crs_is_read_and_checked(birdseye_provider):
    xy = np.array([[0, 0], [30, 10], [60, 40]], dtype=float)
    result, context, _ = run({"GEOTAGS": geotag_layer(xy, crs="EPSG:4326"), "MERGE_RADIUS_M": 0.0,
                              "OUTPUT_WAYPOINTS": "memory:", "OUTPUT_ROUTE": "memory:"})
    _, wps = features(result["OUTPUT_WAYPOINTS"], context)
    frame = LocalFrame(LAT0, LON0, 0.0)
    enu = frame.from_geodetic([f["lat"] for f in wps], [f["lon"] for f in wps], np.zeros(3))
    assert np.allclose(np.sort(enu[:, 0]), [0, 30, 60], atol=1e-6)
    # Metres stored in a layer that claims degrees.
    wrong = QgsVectorLayer("Point?crs=EPSG:4326", "wrong", "memory")
    f = QgsFeature()
    f.setGeometry(QgsGeometry.fromPointXY(QgsPointXY(691_000.0, 5_334_000.0)))
    wrong.dataProvider().addFeatures([f])
    message = run_fails({"GEOTAGS": wrong, "OUTPUT_WAYPOINTS": "memory:", "OUTPUT_ROUTE": "memory:"})
    assert "not degrees" in message and "CRS" in message


@pytest.mark.parametrize("case,expected", [
    ("empty", "has no features"),
    ("altitude", "ALTITUDE_M = 150 m is outside 2–120 m"),
    ("spread", "span 25."),
    ("single_kmz", "needs at least 2"),
    ("litchi_limit", "Litchi holds at most 99"),
])
def test_bad_input_messages(birdseye_provider, tmp_path, case, expected):
    params = {"OUTPUT_WAYPOINTS": "memory:", "OUTPUT_ROUTE": "memory:"}
    if case == "empty":
        params["GEOTAGS"] = QgsVectorLayer(f"Point?crs={UTM}", "empty", "memory")
    elif case == "altitude":
        params.update(GEOTAGS=geotag_layer(np.zeros((2, 2))), ALTITUDE_M=150.0)
    elif case == "spread":
        params["GEOTAGS"] = geotag_layer(np.array([[0, 0], [50, 0], [25_000, 3_000]], dtype=float))
    elif case == "single_kmz":
        params.update(GEOTAGS=geotag_layer(np.array([[5.0, 5.0]])), OUTPUT_KMZ=str(tmp_path / "one.kmz"))
    else:
        grid = np.stack(np.meshgrid(np.arange(11), np.arange(11)), -1).reshape(-1, 2) * 20.0
        params.update(GEOTAGS=geotag_layer(grid), MERGE_RADIUS_M=0.0, MAX_WAYPOINTS=150,
                      MAX_FLIGHT_MIN=600.0, OUTPUT_LITCHI=str(tmp_path / "big.csv"))
    assert expected in run_fails(params)
    assert not list(tmp_path.glob("*.kmz")) and not list(tmp_path.glob("*.csv"))


def test_spread_is_planned_when_forced(birdseye_provider):
    layer = geotag_layer(np.array([[0, 0], [50, 0], [25_000, 3_000]], dtype=float))
    result, _, _ = run({"GEOTAGS": layer, "FORCE": True, "MAX_FLIGHT_MIN": 600.0,
                        "OUTPUT_WAYPOINTS": "memory:", "OUTPUT_ROUTE": "memory:"})
    assert result["WAYPOINT_COUNT"] == 3


def test_single_geotag_is_a_one_waypoint_mission(birdseye_provider, tmp_path):
    result, context, feedback = run({"GEOTAGS": geotag_layer(np.array([[5.0, 5.0]])),
                                     "OUTPUT_WAYPOINTS": "memory:", "OUTPUT_ROUTE": "memory:",
                                     "OUTPUT_PLAN": str(tmp_path / "one.plan"),
                                     "OUTPUT_KML": str(tmp_path / "one.kml")})
    assert result["WAYPOINT_COUNT"] == 1 and result["MISSION_COUNT"] == 1
    assert len(parse_qgc_plan(tmp_path / "one.plan")["lat"]) == 1
    assert any("no HOME given" in w for w in feedback.warnings)


def test_styles_load_on_the_output_layers(birdseye_provider):
    from birdseye.birdseye_qgis.qgis_io.layers import STYLE_DIR

    result, context, _ = run({"GEOTAGS": geotag_layer(np.array([[0, 0], [30, 0], [30, 30]], dtype=float)),
                              "OUTPUT_WAYPOINTS": "memory:", "OUTPUT_ROUTE": "memory:"})
    for output, style in (("OUTPUT_WAYPOINTS", "waypoints.qml"), ("OUTPUT_ROUTE", "route.qml")):
        layer, _ = features(result[output], context)
        message, ok = layer.loadNamedStyle(str(STYLE_DIR / style))
        assert ok, message
        assert layer.labelsEnabled() and layer.renderer().type() == "RuleRenderer"


def polygon_layer(rings_xy, crs=UTM, name="surveyed"):
    """A memory polygon layer of one feature whose rings (exterior, holes) are east/north metres from the site."""
    frame = LocalFrame(LAT0, LON0, 0.0)
    layer = QgsVectorLayer(f"Polygon?crs={crs}", name, "memory")
    rings = []
    for ring in rings_xy:
        lat, lon, _ = frame.to_geodetic(np.column_stack([ring, np.zeros(len(ring))]))
        x, y = ProjectedCRS(crs).from_geodetic(lat, lon)
        rings.append([QgsPointXY(float(a), float(b)) for a, b in zip(x, y)])
    f = QgsFeature()
    f.setGeometry(QgsGeometry.fromPolygonXY(rings))
    layer.dataProvider().addFeatures([f])
    return layer


def test_each_waypoint_says_how_much_of_its_photo_lies_outside_the_surveyed_area(birdseye_provider, tmp_path):
    """A drawn area, the half-plane east ≥ 0 of the site (a 200 m square from there): the photo of the waypoint at
    (−30, 0) lies wholly outside it, the one at (30, 0) wholly inside. Without SURVEYED_AREA the hull of the three
    geotags grown by SURVEY_MARGIN_M is used; without CAMERA there is no photo to measure (NULL)."""
    camera = tmp_path / "camchain.yaml"
    write_kalibr_yaml(CameraModel(800, 500, 800.0, 800.0, 399.5, 249.5), camera)  # 10 × 6.25 m at 10 m
    layer = geotag_layer(np.array([[-30.0, 0.0], [30.0, 0.0], [60.0, 0.0]]), ids=[1, 2, 3])
    area = polygon_layer([np.array([[0.0, -100.0], [200.0, -100.0], [200.0, 100.0], [0.0, 100.0]])])
    params = {"GEOTAGS": layer, "CAMERA": str(camera), "MERGE_RADIUS_M": 0.5, "OUTPUT_WAYPOINTS": "memory:",
              "OUTPUT_ROUTE": "memory:"}
    result, context, feedback = run({**params, "SURVEYED_AREA": area})
    _, wps = features(result["OUTPUT_WAYPOINTS"], context)
    assert {f["geotag_ids"]: f["outside_pct"] for f in wps} == {"1": 100.0, "2": 0.0, "3": 0.0}
    log = " ".join(feedback.infos + feedback.warnings)
    assert "Surveyed area: the drawn polygons (1 ring(s)). 1 of 3 planned photo(s) see ground outside it" in log
    # The hull of the geotags (a line) grown by 1 m is a strip 2 m wide: every 6.25 m photo reaches past it.
    result, context, feedback = run(params)
    _, wps = features(result["OUTPUT_WAYPOINTS"], context)
    assert all(50.0 < f["outside_pct"] < 100.0 for f in wps)
    assert any("the hull of the 3 geotag(s) grown by 1 m" in w for w in feedback.warnings)
    result, context, feedback = run({k: v for k, v in params.items() if k != "CAMERA"})
    _, wps = features(result["OUTPUT_WAYPOINTS"], context)
    assert all(f["outside_pct"] == NULL for f in wps)
    assert any("Give CAMERA to see how much" in i for i in feedback.infos)
