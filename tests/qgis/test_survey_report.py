"""``birdseye:surveyreport`` and ``birdseye:partitionfield`` through the Processing registry: the worked example's
figures from a geotag layer, equal-area partitions of a concave field, and bad input refused."""
from __future__ import annotations

import json

import pytest
from qgis.core import (
    QgsFeature,
    QgsField,
    QgsGeometry,
    QgsPointXY,
    QgsProcessingException,
    QgsVectorLayer,
)
from qgis.PyQt.QtCore import QDate, QDateTime, Qt, QTime, QVariant
from registry import run

UTM = "EPSG:32632"
X0, Y0 = 690_000.0, 5_334_000.0


def square(x0, y0, x1, y1):
    return QgsGeometry.fromPolygonXY([[QgsPointXY(X0 + x, Y0 + y) for x, y in
                                       ((x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0))]])


def polygon_layer(geometries, name="area", fields=()):
    layer = QgsVectorLayer(f"Polygon?crs={UTM}", name, "memory")
    layer.dataProvider().addAttributes([QgsField(n, QVariant.String) for n in fields])
    layer.updateFields()
    features = []
    for geometry in geometries:
        feature = QgsFeature(layer.fields())
        feature.setGeometry(geometry)
        features.append(feature)
    layer.dataProvider().addFeatures(features)
    return layer


def at(minutes_after_eight: int) -> QDateTime:
    return QDateTime(QDate(2026, 5, 20), QTime(8, 0).addSecs(60 * minutes_after_eight), Qt.TimeSpec.UTC)


def morning_layer(with_time=True):
    """The worked example of tests/unit/field/test_survey_report.py as a layer, time_utc a DateTime field (as the
    field package's): worker A every 2 min 08:00–08:58 in partition 1 and 09:30–09:58 in partition 2; worker B every
    3 min 08:10–09:07 and 09:40–10:07 in partition 3; one geotag of B without a time, outside the partitions."""
    layer = QgsVectorLayer(f"Point?crs={UTM}", "survey", "memory")
    fields = [QgsField("worker", QVariant.String)]
    if with_time:
        fields.append(QgsField("time_utc", QVariant.DateTime))
    layer.dataProvider().addAttributes(fields)
    layer.updateFields()
    rows = ([("A", at(2 * k), 0, k) for k in range(30)] + [("A", at(90 + 2 * k), 100, k) for k in range(15)]
            + [("B", at(10 + 3 * k), 200, k) for k in range(20)] + [("B", at(100 + 3 * k), 200, 20 + k)
                                                                   for k in range(10)]
            + [("B", None, 0, -6)])
    features = []
    for worker, time, x, k in rows:
        feature = QgsFeature(layer.fields())
        feature.setGeometry(QgsGeometry.fromPointXY(QgsPointXY(X0 + x + 10 + (k % 8) * 10, Y0 + 10 + (k // 8) * 10)))
        feature["worker"] = worker
        if with_time:
            feature["time_utc"] = time
        features.append(feature)
    layer.dataProvider().addFeatures(features)
    return layer


def test_the_worked_example_through_the_toolbox(birdseye_provider, tmp_path):
    partitions = polygon_layer([square(100 * k, 0, 100 * (k + 1), 100) for k in range(4)])
    flight = polygon_layer([square(1, 1, 99, 99), square(201, 1, 299, 99)], "flight 1")
    result = run("surveyreport", {"GEOTAGS": morning_layer(), "AREA": partitions, "FRAMES": [flight],
                                  "LABEL_COUNT": 150, "OUTPUT_JSON": str(tmp_path / "report.json"),
                                  "OUTPUT_HTML": str(tmp_path / "report.html")})
    # By hand (tests/unit/field/test_survey_report.py): A 45 geotags in 1.5 h, B 30 timed in 1.5 h → 75 / 3 h.
    assert result["GEOTAGS_PER_WORKER_HOUR"] == pytest.approx(25.0)
    assert result["WORKER_HOURS"] == pytest.approx(3.0)
    assert result["PEOPLE"] == 2
    assert result["ELAPSED_HOURS"] == pytest.approx(127 / 60)
    assert result["LABELS_PER_WORKER_HOUR"] == pytest.approx(50.0)  # 150 labels / 3 worker-hours
    assert result["FRAMES_PER_WORKER_HOUR"] is None
    report = json.loads((tmp_path / "report.json").read_text(encoding="utf-8"))
    assert [(w["name"], w["sessions"], round(w["worker_hours"], 6), w["typical_interval_s"])
            for w in report["workers"]] == [("A", 2, 1.5, 120.0), ("B", 2, 1.5, 180.0)]
    assert [round(p["worker_hours"], 6) for p in report["partitions"]] == [1.0, 0.5, 1.5, 0.0]
    assert report["coverage"] == {"partitions": 4, "partitions_with_geotags": 3, "geotags_outside_partitions": 1}
    [f] = report["flights"]
    assert (f["name"], f["geotags"], round(f["worker_hours"], 6)) == ("flight 1", 60, 2.5)
    html = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "Geotags per worker-hour" in html and "Worker-hours [h]" in html and "typical interval" in html


def test_a_layer_without_workers_is_one_unnamed_worker(birdseye_provider, tmp_path):
    layer = morning_layer()
    layer.dataProvider().deleteAttributes([layer.fields().indexOf("worker")])
    layer.updateFields()
    result = run("surveyreport", {"GEOTAGS": layer, "OUTPUT_JSON": str(tmp_path / "r.json")})
    report = json.loads((tmp_path / "r.json").read_text(encoding="utf-8"))
    assert result["PEOPLE"] == 1 and [w["name"] for w in report["workers"]] == [""]
    # An empty WORKER_FIELD reads every geotag as the unnamed worker's too, the worker field there or not.
    result = run("surveyreport", {"GEOTAGS": morning_layer(), "WORKER_FIELD": "",
                                  "OUTPUT_JSON": str(tmp_path / "r.json")})
    assert result["PEOPLE"] == 1


def test_bad_geotag_layers_are_refused_saying_why(birdseye_provider, tmp_path):
    with pytest.raises(QgsProcessingException, match="no time_utc field"):
        run("surveyreport", {"GEOTAGS": morning_layer(with_time=False), "OUTPUT_JSON": str(tmp_path / "r.json")})
    empty = QgsVectorLayer(f"Point?crs={UTM}&field=time_utc:string", "empty", "memory")
    with pytest.raises(QgsProcessingException, match="has no geotags"):
        run("surveyreport", {"GEOTAGS": empty, "OUTPUT_JSON": str(tmp_path / "r.json")})


# ------------------------------------------------------------------------------------------ partitions
def l_field():
    """300 m × 200 m less its 200 m × 100 m north-east quarter: 4 ha, concave."""
    return QgsGeometry.fromPolygonXY([[QgsPointXY(X0 + x, Y0 + y) for x, y in
                                       ((0, 0), (300, 0), (300, 100), (100, 100), (100, 200), (0, 200), (0, 0))]])


@pytest.mark.parametrize("people, hours, pieces", [(2, 1.0, 4), (2, 0.5, 8), (3, 1.0, 6)])
def test_partitions_of_a_concave_field(birdseye_provider, people, hours, pieces):
    # 100 geotags per hour at 100 targets per ha: 1 ha an hour; 4 ha → 4 one-hour pieces (2 people), 8 half-hour
    # pieces, or 4 rounded up to 6 for 3 people (0.667 h each).
    field = l_field()
    result = run("partitionfield", {"AREA": polygon_layer([field]), "N_PEOPLE": people, "HOURS_PER_PIECE": hours,
                                    "GEOTAGS_PER_HOUR": 100, "TARGETS_PER_HA": 100, "OUTPUT": "TEMPORARY_OUTPUT"})
    layer = result["OUTPUT"]
    features = sorted(layer.getFeatures(), key=lambda f: f["partition"])
    assert result["PIECES"] == len(features) == pieces and pieces % people == 0
    areas = [f.geometry().area() for f in features]
    assert sum(areas) == pytest.approx(field.area(), rel=1e-3)
    assert areas == pytest.approx([field.area() / pieces] * pieces, rel=1e-3)
    assert [f["area_ha"] for f in features] == pytest.approx([a / 1e4 for a in areas], rel=1e-3)
    assert all(f["expected_hours"] <= hours + 1e-9 for f in features)
    assert [f["expected_hours"] for f in features] == pytest.approx([4.0 / pieces] * pieces, abs=1e-3)
    assert [f["expected_geotags"] for f in features] == pytest.approx([400 / pieces] * pieces, abs=0.1)
    # The pieces do not overlap, and each worker's pieces form one connected block walked in order.
    union = QgsGeometry.unaryUnion([f.geometry() for f in features])
    assert union.area() == pytest.approx(field.area(), rel=1e-3)
    for worker in range(1, people + 1):
        own = [f for f in features if f["worker"] == worker]
        assert len(own) == pieces // people
        assert [f["order"] for f in own] == list(range(1, len(own) + 1))
        block = QgsGeometry.unaryUnion([f.geometry().buffer(0.01, 2) for f in own])
        assert not block.isMultipart() or len(block.asMultiPolygon()) == 1, f"worker {worker}'s pieces are apart"


def test_a_geographic_field_is_cut_in_its_utm_zone(birdseye_provider):
    layer = QgsVectorLayer("Polygon?crs=EPSG:4326", "field", "memory")
    feature = QgsFeature()
    feature.setGeometry(QgsGeometry.fromRect(QgsGeometry.fromPointXY(QgsPointXY(11.5, 48.1)).buffer(0.002, 1)
                                             .boundingBox()))
    layer.dataProvider().addFeatures([feature])
    result = run("partitionfield", {"AREA": layer, "OUTPUT": "TEMPORARY_OUTPUT"})
    assert result["OUTPUT"].crs().authid() == "EPSG:32632"
    assert result["PIECES"] % 2 == 0 and result["AREA_HA"] > 0


def test_partition_bad_input(birdseye_provider):
    empty = QgsVectorLayer(f"Polygon?crs={UTM}", "empty", "memory")
    with pytest.raises(QgsProcessingException, match="no polygon to partition"):
        run("partitionfield", {"AREA": empty, "OUTPUT": "TEMPORARY_OUTPUT"})
