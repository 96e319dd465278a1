"""Import geotags reads a field survey package's GeoPackage as QField left it: the geotags a worker recorded (QField's
quality descriptions as fixes, accuracies, UTC capture times as DateTime, an orthometric height by its field name,
the worker), and the decisions taken at the points to visit, appended to the review they came from.

The GeoPackage is written here by the contract (``core/field/field_survey.py``) and filled as QField fills it: the
GNSS fields hold QField's position variables (``@position_quality_description`` …), ``time_utc`` a DateTime in
UTC. Oracles: the values written; h_ellipsoid = h_msl + N with N given.
"""
from __future__ import annotations

import json

import pytest
from qgis.core import (
    QgsFeature,
    QgsGeometry,
    QgsPoint,
    QgsProcessingContext,
    QgsProcessingException,
    QgsProject,
    QgsVectorFileWriter,
    QgsVectorLayer,
)
from qgis.PyQt.QtCore import QDate, QDateTime, Qt, QTime
from registry import Recorder

from birdseye.birdseye_qgis.core.field.field_survey import (
    FIELD_REVIEWER_PREFIX,
    GEOTAG_TABLE,
    GNSS_FIELDS,
    HEIGHT_ELLIPSOIDAL,
    HEIGHT_FIELDS,
    HEIGHT_ORTHOMETRIC,
    META_HEIGHT_REFERENCE,
    META_REVIEW_LOG,
    META_TABLE,
    PACKAGE_GPKG,
    VISIT_TABLE,
)
from birdseye.birdseye_qgis.core.field.geotags import GEOTAG_FIELD_NAMES
from birdseye.birdseye_qgis.core.review.actions import PlannedRow
from birdseye.birdseye_qgis.core.scoring.verdicts import CONFIRMED, DIRECT, HARD_NEGATIVE, UNCERTAIN
from birdseye.birdseye_qgis.qgis_io.detections import read_verdicts
from birdseye.birdseye_qgis.qgis_io.review_store import RowMeta, VerdictStore

N_M = 47.25          # the geoid undulation given (GEOID_UNDULATION_M)
LAT0, LON0 = 52.0, 5.0
QGIS_TYPES = {"text": "string", "double": "double", "int": "integer", "datetime": "datetime"}


def utc(hour, minute, second, ms=0):
    return QDateTime(QDate(2026, 5, 20), QTime(hour, minute, second, ms), Qt.TimeSpec.UTC)


#: The worker's geotags: label, h_msl, worker, fix, h_acc_m, v_acc_m, time_utc (the other fields as QField fills
#: them). Whole seconds: QGIS 3.22's file writer keeps neither milliseconds nor the zone (it stores
#: 2026-05-20T15:27:09.000), so the zone-less reading of time_utc is what this file tests;
#: test_times_reach_the_core_as_iso_text tests milliseconds and zones.
GEOTAGS = [
    ("burrow", 12.5, "Ann", "Fixed RTK", 0.012, 0.02, utc(15, 27, 9)),
    ("nest", 12.75, "Bob", "Float RTK", 0.08, 0.15, utc(15, 30, 0)),
    ("burrow", 13.0, "Ann", "Unknown (4)", 0.014, 0.03, utc(15, 31, 2)),
]
TIMES = ["2026-05-20T15:27:09.000Z", "2026-05-20T15:30:00.000Z", "2026-05-20T15:31:02.000Z"]


def write_table(path, name, geometry, fields, rows, first):
    """Table ``name`` of the GeoPackage ``path``: ``fields`` (name, field_survey kind), one feature per
    (attributes, point) of ``rows``; ``first``: the GeoPackage is created with it."""
    spec = "&".join(f"field={n}:{QGIS_TYPES[kind]}" for n, kind in fields)
    layer = QgsVectorLayer(f"{geometry}?crs=EPSG:4326&{spec}" if geometry != "None" else f"None?{spec}",
                           name, "memory")
    features = []
    for attributes, point in rows:
        feature = QgsFeature(layer.fields())
        feature.setAttributes(list(attributes))
        if point is not None:
            feature.setGeometry(QgsGeometry(point))
        features.append(feature)
    assert layer.dataProvider().addFeatures(features)
    options = QgsVectorFileWriter.SaveVectorOptions()
    options.driverName, options.layerName = "GPKG", name
    if not first:
        options.actionOnExistingFile = QgsVectorFileWriter.ActionOnExistingFile.CreateOrOverwriteLayer
    error = QgsVectorFileWriter.writeAsVectorFormatV3(layer, str(path), QgsProject.instance().transformContext(),
                                                      options)
    assert error[0] == QgsVectorFileWriter.WriterError.NoError, error


def gnss(fix, h_acc, v_acc, time):
    """The GNSS fields' values as QField fills them from the receiver."""
    return [fix, h_acc, v_acc, 0.9, 0.5, 0.7, 23, 1, "Bluetooth: Reach RS4", time]


def collected_package(folder, visits=(), review_log="", reference=HEIGHT_ORTHOMETRIC):
    """A field package folder as QField hands it back: the worker's geotags (heights of the declared
    ``reference``), the points to visit ``visits`` ((visit_id, unit keys, decision, worker, lat, lon)) and the
    metadata; the GeoPackage's path."""
    gpkg = folder / PACKAGE_GPKG
    folder.mkdir(parents=True, exist_ok=True)
    gnss_fields = [(f.name, f.kind) for f in GNSS_FIELDS]
    height = HEIGHT_FIELDS[reference]
    geotag_fields = [("label", "text"), (height, "double"), ("radius_m", "double"), ("note", "text"),
                     ("worker", "text")] + gnss_fields
    rows = [([label, h_msl, 0.15, "", worker] + gnss(fix, h_acc, v_acc, time),
             QgsPoint(LON0 + 1e-5 * i, LAT0 + 1e-5 * i, h_msl))
            for i, (label, h_msl, worker, fix, h_acc, v_acc, time) in enumerate(GEOTAGS)]
    write_table(gpkg, GEOTAG_TABLE, "PointZ", geotag_fields, rows, first=True)
    visit_fields = [("visit_id", "text"), ("origin", "text"), ("unit_keys", "text"), ("question", "text"),
                    ("decision", "text"), ("note", "text"), ("worker", "text")] + gnss_fields
    rows = [([visit_id, "review:uncertain" if keys else "layer:checkpoints", json.dumps(keys), "Is it real?",
              decision, "", worker] + (gnss("Fixed RTK", 0.01, 0.02, utc(16, 0, 0)) if decision else [None] * 10),
             QgsPoint(lon, lat)) for visit_id, keys, decision, worker, lat, lon in visits]
    write_table(gpkg, VISIT_TABLE, "Point", visit_fields, rows, first=False)
    meta = [([k, v], None) for k, v in ((META_REVIEW_LOG, review_log), (META_HEIGHT_REFERENCE, reference))]
    write_table(gpkg, META_TABLE, "None", [("key", "text"), ("value", "text")], meta, first=False)
    return gpkg


def run(params, feedback=None):
    import processing

    return processing.run("birdseye:importgeotags", {"GEOID_UNDULATION_M": N_M, **params,
                                                     "OUTPUT": "TEMPORARY_OUTPUT"}, feedback=feedback or Recorder())


def test_the_collected_geotags_are_read_as_qfield_left_them(birdseye_provider, tmp_path):
    feedback = Recorder()
    result = run({"INPUT": str(collected_package(tmp_path / "survey"))}, feedback)
    layer = result["OUTPUT"]
    assert [f.name() for f in layer.fields()] == GEOTAG_FIELD_NAMES
    feats = list(layer.getFeatures())
    assert [f["fix_quality"] for f in feats] == [4, 5, 4]
    assert [f["flags"] for f in feats] == ["", "rtk_float", ""]
    assert [f["h_acc_m"] for f in feats] == [pytest.approx(g[4]) for g in GEOTAGS]
    assert [f["v_acc_m"] for f in feats] == [pytest.approx(g[5]) for g in GEOTAGS]
    assert [f["time_utc"] for f in feats] == TIMES
    assert [f["worker"] for f in feats] == ["Ann", "Bob", "Ann"]
    assert [f["label"] for f in feats] == ["burrow", "nest", "burrow"]
    assert [f["h_msl"] for f in feats] == [pytest.approx(g[1]) for g in GEOTAGS]
    assert [f["h_ellipsoid"] for f in feats] == [pytest.approx(g[1] + N_M, abs=1e-9) for g in GEOTAGS]
    assert feats[0].geometry().constGet().z() == pytest.approx(12.5 + N_M)
    assert result["GEOTAG_COUNT"] == 3 and result["BAD_ROWS"] == 0
    assert (result["DECISIONS_IMPORTED"], result["VISITS_UNDECIDED"]) == (0, 0)
    log = "\n".join(feedback.infos)
    assert "Reading: read as a BirdsEye field survey GeoPackage (QField)" in log
    assert "Field survey: 3 geotag(s), 2 RTK fixed, 3 with a horizontal accuracy, 3 with a capture time; " \
           "recorded by Ann, Bob" in log
    assert "Reading: height: from 'h_msl' (above mean sea level)" in log
    assert f"N = {N_M:g} m" in log or "h = H + N" in log
    assert feedback.warnings == []


def test_times_reach_the_core_as_iso_text():
    """A time with a zone as UTC to the millisecond; one without (OGR's local time) zone-less, for the core to
    judge by the field's name, never shifted by this computer's zone."""
    from birdseye.birdseye_qgis.qgis_io.layers import plain_value

    assert plain_value(utc(15, 27, 9, 400)) == "2026-05-20T15:27:09.400Z"
    offset = QDateTime(QDate(2026, 5, 20), QTime(17, 27, 9, 5), Qt.TimeSpec.OffsetFromUTC, 7200)
    assert plain_value(offset) == "2026-05-20T15:27:09.005Z"
    assert plain_value(QDateTime(QDate(2026, 5, 20), QTime(15, 27, 9), Qt.TimeSpec.LocalTime)) == \
        "2026-05-20T15:27:09.000"
    assert plain_value(QDate(2026, 5, 20)) == "2026-05-20"
    assert plain_value(QDateTime()) is None and plain_value(12.5) == 12.5


def test_an_ellipsoidal_height_field_is_the_height(birdseye_provider, tmp_path):
    gpkg = collected_package(tmp_path / "survey", reference=HEIGHT_ELLIPSOIDAL)
    feats = list(run({"INPUT": str(gpkg)})["OUTPUT"].getFeatures())
    assert [f["h_ellipsoid"] for f in feats] == [pytest.approx(g[1]) for g in GEOTAGS]   # N not added
    assert [f["h_msl"] for f in feats] == [None] * 3


def test_the_fix_and_accuracy_filters_work_on_qfields_figures(birdseye_provider, tmp_path):
    gpkg = str(collected_package(tmp_path / "survey"))
    fixed = run({"INPUT": gpkg, "FIX_FILTER": 1})
    assert [f["worker"] for f in fixed["OUTPUT"].getFeatures()] == ["Ann", "Ann"]
    assert fixed["NOT_FIXED_DROPPED"] == 1
    accurate = run({"INPUT": gpkg, "MAX_H_ACCURACY_M": 0.05})
    assert [f["id"] for f in accurate["OUTPUT"].getFeatures()] == [1, 3] and accurate["ACCURACY_DROPPED"] == 1
    assert run({"INPUT": gpkg, "MAX_H_ACCURACY_M": 0.013})["ACCURACY_DROPPED"] == 2


def test_the_project_file_reads_the_geopackage_beside_it(birdseye_provider, tmp_path):
    collected_package(tmp_path / "survey")
    (tmp_path / "survey" / "survey.qgz").write_bytes(b"PK\x03\x04 a zipped project")
    assert run({"INPUT": str(tmp_path / "survey" / "survey.qgz")})["GEOTAG_COUNT"] == 3


def test_a_geopackage_that_is_no_field_package_is_refused_naming_its_tables(birdseye_provider, tmp_path):
    other = tmp_path / "other.gpkg"
    write_table(other, "points", "Point", [("name", "text")], [(["a"], QgsPoint(LON0, LAT0))], first=True)
    with pytest.raises(QgsProcessingException, match=r"not a BirdsEye field survey package.*its tables: points"):
        run({"INPUT": str(other)})
    png = tmp_path / "photo.png"
    png.write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(64))
    with pytest.raises(QgsProcessingException, match=r"not a text CSV \(a PNG image\)"):
        run({"INPUT": str(png)})


def review_log(path, keys):
    """A review's verdict GeoPackage in which the office left ``keys`` uncertain."""
    store = VerdictStore(path)
    try:
        meta = RowMeta("office", json.dumps({"detections:det": "abc123"}), json.dumps({"eps_pred_m": 0.2}),
                       json.dumps({"dedup_cm": 3}))
        store.append([PlannedRow(k, UNCERTAIN, DIRECT, LAT0 + 1e-4 * i, LON0, ("det",)) for i, k in enumerate(keys)],
                     "verdict", meta)
        return store.layer_uri
    finally:
        store.close()


def latest_direct(uri):
    """{unit key: (verdict, reviewer)} of the latest direct verdicts, read back as evaluatedetections reads them."""
    layer = QgsVectorLayer(uri, "verdicts", "ogr")
    log = read_verdicts(layer, QgsProcessingContext())
    return {unit: (row.verdict, row.reviewer) for (unit, provenance), row in log.latest.items()
            if provenance == DIRECT}, layer.featureCount()


def test_decisions_at_the_visited_points_go_to_the_review_once(birdseye_provider, tmp_path):
    log_path = tmp_path / "review.gpkg"
    uri = review_log(log_path, ["u1", "u2", "u3", "u4"])
    visits = [("v1", ["u1", "u2"], CONFIRMED, "Ann", LAT0, LON0),
              ("v2", ["u3"], HARD_NEGATIVE, "Bob", LAT0 + 2e-4, LON0),
              ("v3", [], CONFIRMED, "Ann", LAT0 + 3e-4, LON0),          # a plain point: nothing to write
              ("v4", ["u4"], None, "", LAT0 + 4e-4, LON0),              # not visited
              ("v5", ["u4"], "definitely", "Bob", LAT0 + 5e-4, LON0)]   # not a decision: warned, skipped
    gpkg = collected_package(tmp_path / "survey", visits, str(log_path))
    feedback = Recorder()
    result = run({"INPUT": str(gpkg)}, feedback)
    assert (result["DECISIONS_IMPORTED"], result["VISITS_UNDECIDED"]) == (3, 1)
    latest, n_rows = latest_direct(uri)
    assert latest == {"u1": (CONFIRMED, FIELD_REVIEWER_PREFIX + "Ann"), "u2": (CONFIRMED, "field:Ann"),
                      "u3": (HARD_NEGATIVE, "field:Bob"), "u4": (UNCERTAIN, "office")}
    assert n_rows == 7
    store = VerdictStore(log_path, create=False)
    try:
        field_rows = store.rows()[4:]
    finally:
        store.close()
    assert len({r["action_id"] for r in field_rows}) == 1                     # one action, one transaction
    assert [(r["lat"], r["lon"]) for r in field_rows] == [(LAT0, LON0)] * 2 + [(LAT0 + 2e-4, LON0)]
    assert {r["input_digests"] for r in field_rows} == {json.dumps({"detections:det": "abc123"})}
    assert [json.loads(r["layers_fired"]) for r in field_rows] == [["det"]] * 3
    assert any("row 5, field 'decision': 'definitely' is not a field decision" in w for w in feedback.warnings)
    assert any("1 decided point(s) to visit are not review units" in i and "v3 (confirmed_real)" in i
               for i in feedback.infos)
    # The same package again appends nothing.
    feedback = Recorder()
    again = run({"INPUT": str(gpkg)}, feedback)
    assert again["DECISIONS_IMPORTED"] == 0 and latest_direct(uri)[1] == 7
    assert any("3 review unit(s) already hold the field's decision" in i for i in feedback.infos)


def test_review_log_parameter_wins_and_a_missing_package_log_is_a_warning(birdseye_provider, tmp_path):
    visits = [("v1", ["u1"], HARD_NEGATIVE, "Ann", LAT0, LON0)]
    gpkg = collected_package(tmp_path / "survey", visits, str(tmp_path / "moved.gpkg"))
    feedback = Recorder()
    assert run({"INPUT": str(gpkg)}, feedback)["DECISIONS_IMPORTED"] == 0
    assert any("moved.gpkg, is not there" in w for w in feedback.warnings)
    uri = review_log(tmp_path / "elsewhere.gpkg", ["u1"])
    assert run({"INPUT": str(gpkg), "REVIEW_LOG": str(tmp_path / "elsewhere.gpkg")})["DECISIONS_IMPORTED"] == 1
    assert latest_direct(uri)[0]["u1"] == (HARD_NEGATIVE, "field:Ann")
    unnamed = collected_package(tmp_path / "unnamed", visits)
    feedback = Recorder()
    assert run({"INPUT": str(unnamed)}, feedback)["DECISIONS_IMPORTED"] == 0
    assert any("the package names no review and REVIEW_LOG is empty" in w for w in feedback.warnings)
