"""Import geotags through the Processing registry on a real Emlid Flow export in US survey feet: positions,
ellipsoidal heights in metres, fixes, accuracies, capture times, the log, and the accuracy filter.

Oracles: the file's own numbers (Longitude, Latitude; 461.923 ftUS × 1200/3937 = 140.7946 m for TCU1).
"""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest
from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsFeature,
    QgsGeometry,
    QgsPointXY,
    QgsProcessingException,
    QgsProject,
    QgsVectorLayer,
)
from registry import Recorder

from birdseye.birdseye_qgis.core.field.geotags import GEOTAG_FIELD_NAMES

EMLID = Path(__file__).resolve().parents[1] / "data" / "rover" / "emlid_flow_reach_rs4_ftus.csv"
US_FT = 1200.0 / 3937.0

def run(params, feedback=None):
    import processing

    return processing.run("birdseye:importgeotags", {**params, "OUTPUT": "TEMPORARY_OUTPUT"},
                          feedback=feedback or Recorder())


def file_rows():
    with EMLID.open(newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def test_emlid_flow_export_through_the_registry(birdseye_provider):
    feedback = Recorder()
    result = run({"INPUT": str(EMLID)}, feedback)
    layer = result["OUTPUT"]
    assert [f.name() for f in layer.fields()] == GEOTAG_FIELD_NAMES
    assert layer.crs().authid() == "EPSG:32616"  # UTM 16N: Peoria, Illinois
    feats = list(layer.getFeatures())
    rows = file_rows()
    assert [f["label"] for f in feats] == [r["Name"] for r in rows]
    assert [f["lat"] for f in feats] == [float(r["Latitude"]) for r in rows]
    assert [f["lon"] for f in feats] == [float(r["Longitude"]) for r in rows]
    assert [f["fix_quality"] for f in feats] == [1, 4, 4]
    assert [f["flags"] for f in feats] == ["no_rtk", "", ""]
    tcu1 = feats[1]
    assert tcu1["h_ellipsoid"] == pytest.approx(140.7946, abs=0.01)
    assert tcu1.geometry().constGet().z() == pytest.approx(140.7946, abs=0.01)
    assert tcu1["h_msl"] == pytest.approx(570.143 * US_FT, abs=1e-6)
    np.testing.assert_allclose([f["h_acc_m"] for f in feats], [float(r["Lateral RMS"]) * US_FT for r in rows])
    np.testing.assert_allclose([f["v_acc_m"] for f in feats], [float(r["Elevation RMS"]) * US_FT for r in rows])
    assert tcu1["time_utc"] == "2026-05-20T15:27:09.400Z"
    back = QgsCoordinateTransform(layer.crs(), QgsCoordinateReferenceSystem("EPSG:4326"), QgsProject.instance())
    p = back.transform(tcu1.geometry().asPoint())
    assert (p.y(), p.x()) == (pytest.approx(40.71672295, abs=1e-9), pytest.approx(-89.67023838, abs=1e-9))
    log = "\n".join(feedback.infos)
    assert "Reading: read as an Emlid Flow export (42 columns)" in log
    assert "Reading: height: 'Ellipsoidal height', ellipsoidal by its name" in log
    assert "Reading: lengths in US survey feet" in log
    assert "Horizontal accuracy of the input: median 0.017 m, worst 0.183 m (3 of 3 geotags give one)" in log
    assert result["GEOTAG_COUNT"] == 3 and result["BAD_ROWS"] == 0 and result["ACCURACY_DROPPED"] == 0


def test_accuracy_filter_and_units_override(birdseye_provider):
    feedback = Recorder()
    result = run({"INPUT": str(EMLID), "MAX_H_ACCURACY_M": 0.05}, feedback)
    assert result["GEOTAG_COUNT"] == 2 and result["ACCURACY_DROPPED"] == 1
    assert [f["id"] for f in result["OUTPUT"].getFeatures()] == [2, 3]   # ids count before the filter
    assert any("1 geotag(s) with a horizontal accuracy worse than 0.05 m" in w for w in feedback.warnings)
    feet = run({"INPUT": str(EMLID), "UNITS": 2})  # international feet, as asked
    heights = [f["h_ellipsoid"] for f in feet["OUTPUT"].getFeatures()]
    np.testing.assert_allclose(heights, [float(r["Ellipsoidal height"]) * 0.3048 for r in file_rows()])


def test_a_pole_height_on_ground_heights_and_a_bad_row_are_explained(birdseye_provider, tmp_path):
    import processing

    with pytest.raises(QgsProcessingException, match="ground point already.*set the pole height to 0"):
        processing.run("birdseye:importgeotags", {"INPUT": str(EMLID), "POLE_HEIGHT_M": 2.0,
                                                  "OUTPUT": "TEMPORARY_OUTPUT"}, feedback=Recorder())
    lines = EMLID.read_text(encoding="utf-8").splitlines()
    lines[2] = lines[2].replace(",461.923,", ",n/a,")
    bad = tmp_path / "export.csv"
    bad.write_text("\n".join(lines) + "\n", encoding="utf-8")
    feedback = Recorder()
    result = run({"INPUT": str(bad)}, feedback)
    assert result["GEOTAG_COUNT"] == 2 and result["BAD_ROWS"] == 1
    assert any("row 3, field 'Ellipsoidal height': 'n/a' is not a number; expected ellipsoidal height in US "
               "survey feet" in e for e in feedback.warnings) and feedback.errors == []


def test_a_point_layer_with_accuracy_fields(birdseye_provider):
    layer = QgsVectorLayer("Point?crs=EPSG:4326&field=name:string&field=hrms:double&field=h:double",
                           "qfield survey", "memory")
    feats = []
    for name, lat, lon, hrms, h in (("a", 52.0, 5.0, 0.012, 45.0), ("b", 52.001, 5.001, 0.8, 46.0)):
        f = QgsFeature(layer.fields())
        f.setGeometry(QgsGeometry.fromPointXY(QgsPointXY(lon, lat)))
        f.setAttributes([name, hrms, h])
        feats.append(f)
    layer.dataProvider().addFeatures(feats)
    result = run({"INPUT_LAYER": layer, "HEIGHT_FIELD": "h", "LABEL_FIELD": "name", "MAX_H_ACCURACY_M": 0.1})
    out = list(result["OUTPUT"].getFeatures())
    assert [f["label"] for f in out] == ["a"] and out[0]["h_acc_m"] == pytest.approx(0.012)
    assert result["ACCURACY_DROPPED"] == 1
