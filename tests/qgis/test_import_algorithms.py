"""The three field-data importers through the Processing registry: outputs, CRS, styles, bad input."""
from __future__ import annotations

import shutil
import sys
from pathlib import Path

import numpy as np
import pytest
from qgis.core import (
    QgsCategorizedSymbolRenderer,
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsFeature,
    QgsGeometry,
    QgsPoint,
    QgsProcessingContext,
    QgsProcessingException,
    QgsProject,
    QgsVectorLayer,
    QgsWkbTypes,
)
from qgis.PyQt.QtCore import Qt
from registry import Recorder

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from strip_xmp import strip_xmp
from synthetic_flight import HEADER, make_flight

from birdseye.birdseye_qgis.core.field.flight_track import TRACK_FIELDS
from birdseye.birdseye_qgis.core.field.frame_records import poses_from_records
from birdseye.birdseye_qgis.core.field.frames import FRAME_LAYER_FIELDS
from birdseye.birdseye_qgis.core.field.geotags import GEOTAG_FIELD_NAMES
from birdseye.birdseye_qgis.qgis_io import layers

BRIGHTON = Path(__file__).resolve().parents[1] / "data" / "brighton_beach"

def run(alg_id, params, feedback=None):
    import processing

    return processing.run(f"birdseye:{alg_id}", {**params, "OUTPUT": "TEMPORARY_OUTPUT"},
                          feedback=feedback or Recorder())


def run_failing(alg_id, params):
    """The message a user sees in the log when the algorithm refuses its input."""
    import processing

    feedback = Recorder()
    with pytest.raises(QgsProcessingException) as err:
        processing.run(f"birdseye:{alg_id}", {**params, "OUTPUT": "TEMPORARY_OUTPUT"}, feedback=feedback)
    return " ".join([str(err.value)] + feedback.errors)


def field_names(layer):
    return [f.name() for f in layer.fields()]


@pytest.fixture(scope="module")
def flight(tmp_path_factory):
    return make_flight(tmp_path_factory.mktemp("flight"), n_frames=30, leg_m=15.0)


# ------------------------------------------------------------------------------------ geotags
def test_import_geotags_from_a_rover_file(birdseye_provider, tmp_path):
    path = tmp_path / "rover.csv"
    path.write_text("52.0000000,5.0000000,47.80,4.30,4,burrow\n"
                    "52.0000001,5.0000001,47.80,4.30,4,burrow\n"     # 1.3 cm away: duplicate
                    "52.0010000,5.0010000,47.90,4.40,5,gap\n"
                    "52.0020000,north,47.90,4.40,4,bad\n")
    feedback = Recorder()
    result = run("importgeotags", {"INPUT": str(path), "POLE_HEIGHT_M": 1.8}, feedback)
    layer = result["OUTPUT"]
    assert field_names(layer) == GEOTAG_FIELD_NAMES
    assert layer.crs().authid() == "EPSG:32631" and layer.wkbType() == QgsWkbTypes.PointZ
    feats = list(layer.getFeatures())
    assert [f["id"] for f in feats] == [1, 2, 3] and [f["source_row"] for f in feats] == [1, 2, 3]
    assert [f["flags"] for f in feats] == ["", "duplicate_2cm", "rtk_float"]
    assert feats[0]["h_ellipsoid"] == pytest.approx(46.0) and feats[0].geometry().constGet().z() == pytest.approx(46.0)
    back = QgsCoordinateTransform(layer.crs(), QgsCoordinateReferenceSystem("EPSG:4326"), QgsProject.instance())
    p = back.transform(feats[2].geometry().asPoint())
    assert (p.y(), p.x()) == (pytest.approx(52.001, abs=1e-9), pytest.approx(5.001, abs=1e-9))
    assert result["BAD_ROWS"] == 1 and result["DUPLICATES"] == 1
    assert any("row 4, field 'lon'" in e for e in feedback.warnings) and feedback.errors == []

    fixed = run("importgeotags", {"INPUT": str(path), "FIX_FILTER": 1})
    assert fixed["GEOTAG_COUNT"] == 2 and fixed["NOT_FIXED_DROPPED"] == 1


def test_import_geotags_from_a_point_layer_in_another_crs(birdseye_provider):
    layer = QgsVectorLayer("PointZ?crs=EPSG:3857&field=name:string&field=q:string", "survey", "memory")
    to_merc = QgsCoordinateTransform(QgsCoordinateReferenceSystem("EPSG:4326"), layer.crs(), QgsProject.instance())
    truth = [(-33.9, 18.4, 21.0, "fixed"), (-33.901, 18.401, 22.5, "float")]
    feats = []
    for lat, lon, h, q in truth:
        xy = to_merc.transform(lon, lat)
        f = QgsFeature(layer.fields())
        f.setGeometry(QgsGeometry(QgsPoint(xy.x(), xy.y(), h)))
        f.setAttributes([f"T{len(feats)}", q])
        feats.append(f)
    layer.dataProvider().addFeatures(feats)
    result = run("importgeotags", {"INPUT_LAYER": layer, "FIX_FIELD": "q", "LABEL_FIELD": "name",
                                   "OUTPUT_CRS": "EPSG:32734"})
    out = list(result["OUTPUT"].getFeatures())
    assert result["OUTPUT"].crs().authid() == "EPSG:32734"
    np.testing.assert_allclose([f["lat"] for f in out], [-33.9, -33.901], atol=1e-9)
    np.testing.assert_allclose([f["lon"] for f in out], [18.4, 18.401], atol=1e-9)
    assert [f["h_ellipsoid"] for f in out] == [21.0, 22.5]
    assert [f["fix_quality"] for f in out] == [4, 5] and [f["label"] for f in out] == ["T0", "T1"]


def test_import_geotags_refuses_unclear_input(birdseye_provider, tmp_path):
    path = tmp_path / "rover.csv"
    path.write_text("52.0,5.0,47.8,4.3,4,a\n")
    assert "either a geotag file" in run_failing("importgeotags", {})
    message = run_failing("importgeotags", {"INPUT": str(path), "OUTPUT_CRS": "EPSG:4326"})
    assert "geographic CRS" in message and "OUTPUT_CRS" in message
    path.write_text("a,b,c\n1,2,3\n")
    assert "no latitude column" in run_failing("importgeotags", {"INPUT": str(path), "FORMAT": 2})
    photo = tmp_path / "DJI_0018.JPG"
    photo.write_bytes((Path(__file__).resolve().parents[1] / "data" / "brighton_beach" / "DJI_0018.JPG").read_bytes())
    message = run_failing("importgeotags", {"INPUT": str(photo)})
    assert "DJI_0018.JPG" in message and "is not a text CSV (a JPEG image)" in message and "\ufffd" not in message


def test_geotag_style_is_applied_when_loaded(birdseye_provider, tmp_path):
    import processing

    path = tmp_path / "rover.csv"
    path.write_text("52.0,5.0,47.8,4.3,4,a\n52.001,5.001,47.8,4.3,5,b\n")
    project = QgsProject.instance()
    before = set(project.mapLayers())
    context = QgsProcessingContext()
    context.setProject(project)
    processing.runAndLoadResults("birdseye:importgeotags", {"INPUT": str(path), "OUTPUT": "TEMPORARY_OUTPUT"},
                                 context=context, feedback=Recorder())
    added = [project.mapLayer(i) for i in set(project.mapLayers()) - before]
    assert len(added) == 1
    renderer = added[0].renderer()
    assert isinstance(renderer, QgsCategorizedSymbolRenderer) and "fix_quality" in renderer.classAttribute()
    assert [c.label() for c in renderer.categories()] == ["RTK fixed, cm accurate", "RTK float, dm accurate",
                                                          "No RTK fix, m accurate", "Control point",
                                                          "Check point (not fitted)"]
    project.removeMapLayers([layer.id() for layer in added])


# ------------------------------------------------------------------------------------ flight log
def test_import_flight_log_writes_frames_and_track(birdseye_provider, flight):
    import processing

    feedback = Recorder()
    result = processing.run("birdseye:importflightlog", {
        "POSE_LOG": str(flight["pose_log"]), "IMAGES": str(flight["images"]),
        "CALIBRATION": str(flight["calibration"]), "OUTPUT": "TEMPORARY_OUTPUT",
        "OUTPUT_TRACK": "TEMPORARY_OUTPUT"}, feedback=feedback)
    frames, track = result["OUTPUT"], result["OUTPUT_TRACK"]
    assert field_names(frames) == [f[0] for f in FRAME_LAYER_FIELDS]
    assert frames.featureCount() == 30 == result["FRAME_COUNT"] and result["UNMATCHED_STROBES"] == 0
    assert frames.wkbType() == QgsWkbTypes.PolygonZ and frames.crs().authid() == "EPSG:32631"
    assert field_names(track) == [f[0] for f in TRACK_FIELDS] and track.featureCount() == 1
    assert next(track.getFeatures())["n_frames"] == 30
    # The layer alone is enough for later steps: read back, same poses as the log.
    (poses, idx), = poses_from_records(layers.read_frame_layer(frames))
    strobe = flight["cols"]["strobe"] == 1
    np.testing.assert_allclose(poses.lat, flight["cols"]["lat_deg"][strobe], atol=1e-9)
    np.testing.assert_allclose(poses.ground_height, 45.0, atol=2e-3)
    area = np.array([f.geometry().area() for f in frames.getFeatures()])
    np.testing.assert_allclose(area, (640 / 800 * 12.0) * (480 / 800 * 12.0), rtol=0.05)
    assert any("Output CRS: EPSG:32631" in i for i in feedback.infos)


def test_import_flight_log_reports_bad_rows_and_refuses_no_strobes(birdseye_provider, flight, tmp_path):
    import processing

    log = tmp_path / "log.csv"
    lines = flight["pose_log"].read_text().splitlines()
    lines[3] = lines[3].replace(",", ";", 2)
    log.write_text("\n".join(lines) + "\n")
    feedback = Recorder()
    result = processing.run("birdseye:importflightlog", {
        "POSE_LOG": str(log), "IMAGES": str(flight["images"]), "CALIBRATION": str(flight["calibration"]),
        "OUTPUT": "TEMPORARY_OUTPUT"}, feedback=feedback)
    assert result["BAD_ROWS"] == 1 and result["FRAME_COUNT"] == 30
    assert any("1 bad pose-log rows left out" in e and "row 4" in e for e in feedback.warnings)

    log.write_text(HEADER + "\n" + "\n".join(",".join(line.split(",")[:-1] + ["0"]) for line in lines[1:]))
    message = run_failing("importflightlog", {"POSE_LOG": str(log), "IMAGES": str(flight["images"]),
                                              "CALIBRATION": str(flight["calibration"])})
    assert "no strobe rows" in message and str(log) in message
    message = run_failing("importflightlog", {"POSE_LOG": str(flight["pose_log"]), "IMAGES": str(flight["images"]),
                                              "CALIBRATION": str(flight["calibration"]), "OUTPUT_CRS": "EPSG:4326"})
    assert "geographic CRS" in message
    message = run_failing("importflightlog", {"POSE_LOG": str(flight["pose_log"]), "IMAGES": str(flight["images"]),
                                              "CALIBRATION": str(flight["calibration"]), "OUTPUT_CRS": "EPSG:2056"})
    assert "outside the area of use of EPSG:2056" in message


def test_frame_style_is_applied_when_loaded(birdseye_provider, flight):
    import processing

    project = QgsProject.instance()
    before = set(project.mapLayers())
    context = QgsProcessingContext()
    context.setProject(project)
    processing.runAndLoadResults("birdseye:importflightlog", {
        "POSE_LOG": str(flight["pose_log"]), "IMAGES": str(flight["images"]),
        "CALIBRATION": str(flight["calibration"]), "OUTPUT": "TEMPORARY_OUTPUT",
        "OUTPUT_TRACK": "TEMPORARY_OUTPUT"}, context=context, feedback=Recorder())
    added = {project.mapLayer(i).geometryType(): project.mapLayer(i) for i in set(project.mapLayers()) - before}
    frames, track = added[QgsWkbTypes.PolygonGeometry], added[QgsWkbTypes.LineGeometry]
    assert "rtk_status" in frames.renderer().classAttribute()
    # Outlines only: the footprints never hide the geotags and detections under them.
    assert all(c.symbol().symbolLayer(0).brushStyle() == Qt.BrushStyle.NoBrush for c in frames.renderer().categories())
    assert track.labelsEnabled() and "@layer_name" in track.labeling().settings().fieldName
    project.removeMapLayers([layer.id() for layer in added.values()])


# ------------------------------------------------------------------------------------ DJI
def test_import_dji_images_brighton_beach(birdseye_provider, tmp_path):
    feedback = Recorder()
    result = run("importdjiimages", {"IMAGES": str(BRIGHTON)}, feedback)
    layer = result["OUTPUT"]
    assert result["FRAME_COUNT"] == 6 and result["UNPLACED_COUNT"] == 0
    assert layer.crs().authid() == "EPSG:32615" and field_names(layer) == [f[0] for f in FRAME_LAYER_FIELDS]
    first = next(layer.getFeatures())
    assert first["yaw_deg"] == 45.0 and first["depth_m"] == pytest.approx(39.8)
    assert "approx_intrinsics" in first["flags"]
    # 36 mm / 20 mm × 39.8 m wide, 2250/4000 of that high.
    assert first.geometry().area() == pytest.approx((1.8 * 39.8) ** 2 * 2250 / 4000, rel=0.01)

    folder = tmp_path / "mixed"
    folder.mkdir()
    shutil.copy(BRIGHTON / "DJI_0018.JPG", folder)
    (folder / "IMG_0001.jpg").write_bytes(b"\xff\xd8\xff\xd9")
    feedback = Recorder()
    result = run("importdjiimages", {"IMAGES": str(folder)}, feedback)
    assert result["FRAME_COUNT"] == 1 and result["UNPLACED_COUNT"] == 1
    assert any("IMG_0001.jpg" in e for e in feedback.warnings)
    (folder / "DJI_0018.JPG").unlink()
    assert "none of its 1 JPEG" in run_failing("importdjiimages", {"IMAGES": str(folder)})


def test_import_drone_images_exif_only(birdseye_provider, tmp_path):
    """The Brighton frames without their XMP (a drone writing only EXIF): without a flight height imported with
    their ground unknown (flagged, no footprint); placed with FLIGHT_HEIGHT_M."""
    from qgis.core import QgsApplication

    alg = QgsApplication.processingRegistry().algorithmById("birdseye:importdjiimages")
    assert alg.displayName() == "1.3 · Import drone images"
    folder = tmp_path / "exif"
    folder.mkdir()
    for path in sorted(BRIGHTON.glob("*.JPG")):
        strip_xmp(path, folder / path.name)
    unknown = Recorder()
    result = run("importdjiimages", {"IMAGES": str(folder)}, unknown)
    assert result["FRAME_COUNT"] == 6 and result["UNPLACED_COUNT"] == 0
    features = list(result["OUTPUT"].getFeatures())
    assert all(f.geometry().isNull() and "no_ground_height" in f["flags"] and f["ground_src"] == "" and
               f["height_ref"] == "EGM96" for f in features)
    assert any("no_ground_height" in w and "FLIGHT_HEIGHT_M" in w and "Refine frame poses" in w
               for w in unknown.warnings)
    feedback = Recorder()
    result = run("importdjiimages", {"IMAGES": str(folder), "FLIGHT_HEIGHT_M": 40.0}, feedback)
    assert result["FRAME_COUNT"] == 6 and result["UNPLACED_COUNT"] == 0
    features = list(result["OUTPUT"].getFeatures())
    assert all({"attitude_from_track", "approx_intrinsics", "ground_from_flight_height"}
               <= set(f["flags"].split(",")) for f in features)
    # Nadir, heading from DJI_0018 towards DJI_0019 (the gimbal said 45.0°); 40 m above the median.
    first = features[0]
    assert first["pitch_deg"] == -90.0 and first["yaw_deg"] == pytest.approx(47.43, abs=0.01)
    heights = sorted(f["height_m"] for f in features)
    assert first["depth_m"] == pytest.approx(first["height_m"] - (heights[2] + heights[3]) / 2 + 40.0)
    assert any("attitude_from_track" in w for w in feedback.warnings)
