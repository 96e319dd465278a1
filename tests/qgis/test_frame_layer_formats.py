"""The frame layer in the formats users save to (§4.6): a copy saved as GeoPackage, Shapefile, GeoJSON,
FlatGeobuf or CSV reads back as the original and gives every algorithm the original's result; a Shapefile
output keeps the whole camera model in ``camera``, ``camera_2``, …; a camera cut by a later Save Features
As… is refused with what to do."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest
from qgis.core import (
    QgsCoordinateTransformContext,
    QgsProcessingContext,
    QgsProcessingException,
    QgsProcessingFeedback,
    QgsProject,
    QgsVectorFileWriter,
    QgsVectorLayer,
)
from registry import run

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.frame_records import poses_from_records
from birdseye.birdseye_qgis.core.field.frames import frames_from_records
from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign
from birdseye.birdseye_qgis.qgis_enums import GEOMETRY_POINT
from birdseye.birdseye_qgis.qgis_io import layers


def as_layer(output) -> QgsVectorLayer:
    layer = output if isinstance(output, QgsVectorLayer) else QgsVectorLayer(str(output), Path(output).stem, "ogr")
    assert layer.isValid()
    return layer


def save_as(layer, path, driver, layer_options=()) -> QgsVectorLayer:
    """What the user's Export › Save Features As… does."""
    options = QgsVectorFileWriter.SaveVectorOptions()
    options.driverName = driver
    options.layerOptions = list(layer_options)
    error, message, _, _ = QgsVectorFileWriter.writeAsVectorFormatV3(layer, str(path),
                                                                     QgsCoordinateTransformContext(), options)
    assert error == QgsVectorFileWriter.NoError, message
    return as_layer(path)


@pytest.fixture(scope="module")
def campaign(birdseye_provider, tmp_path_factory):
    """A simulated campaign imported twice: frame layers written to a GeoPackage and to a Shapefile."""
    folder = tmp_path_factory.mktemp("campaign")
    simulate_campaign(CampaignConfig(seed=3, n_targets=6, field_width_m=8.0, field_length_m=6.0, image_width=480,
                                     image_height=300, n_missed=1, n_spurious=1), folder)
    geotags = run("importgeotags", {"INPUT": str(folder / "geotags.csv"), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    imported = {}
    for ext in ("gpkg", "shp"):
        imported[ext] = as_layer(run("importflightlog", {
            "POSE_LOG": str(folder / "poses.csv"), "IMAGES": str(folder / "frames"),
            "CALIBRATION": str(folder / "calibration.yaml"), "OUTPUT": str(folder / f"frames.{ext}")})["OUTPUT"])
    return folder, geotags, imported


class Log(QgsProcessingFeedback):
    """Feedback that keeps the log's lines."""

    def __init__(self):
        super().__init__()
        self.lines = []

    def pushInfo(self, info):
        self.lines.append(info)

    def reportError(self, error, fatalError=False):
        self.lines.append(error)


def labels(geotags, frames, folder):
    run("writelabels", {"GEOTAGS": geotags, "FRAMES": frames, "WRITE_RASTERS": False, "OUTPUT_FOLDER": str(folder),
                        "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None})
    with open(folder / "labels.csv") as f:
        return list(csv.DictReader(f))


def test_a_shapefile_frame_layer_reads_back_as_the_geopackage(campaign, tmp_path):
    _, geotags, imported = campaign
    gpkg, shp = imported["gpkg"], imported["shp"]
    assert gpkg.storageType() == "GPKG" and shp.storageType() == "ESRI Shapefile"
    # The GeoPackage keeps the camera inline; the Shapefile continues it in camera_2, … of 254 characters.
    assert "camera_2" not in gpkg.fields().names() and len(next(gpkg.getFeatures())["camera"]) > 254
    assert shp.fields().field("camera").length() == 254 and "camera_2" in shp.fields().names()
    records = {ext: layers.read_frame_layer(layer) for ext, layer in imported.items()}
    assert [r["camera"] for r in records["shp"]] == [r["camera"] for r in records["gpkg"]]
    # A name dBase cut to 10 characters is read as the field it stands for (numbers: 15 decimals in dBase).
    assert [r["sync_offset_s"] for r in records["shp"]] == pytest.approx(
        [r["sync_offset_s"] for r in records["gpkg"]], abs=1e-12)
    # Epoch times keep their 10 digits before the point (refineposes orders frames by them).
    assert all(r["time_s"] > 1e9 for r in records["gpkg"])
    assert [r["time_s"] for r in records["shp"]] == pytest.approx([r["time_s"] for r in records["gpkg"]], abs=1e-9)
    (a, _), = poses_from_records(records["gpkg"])
    (b, _), = poses_from_records(records["shp"])
    assert a.camera == b.camera
    # A later step gives the same result from either.
    from_gpkg = labels(geotags, gpkg, tmp_path / "gpkg")
    assert len(from_gpkg) > 10 and labels(geotags, shp, tmp_path / "shp") == from_gpkg
    # Saved on by the user to another format (here back to a GeoPackage), the parts travel with the frames.
    again = save_as(shp, tmp_path / "again.gpkg", "GPKG")
    assert [r["camera"] for r in layers.read_frame_layer(again)] == [r["camera"] for r in records["gpkg"]]


def test_a_camera_cut_by_save_as_shapefile_is_refused_with_the_fix(campaign, tmp_path):
    _, geotags, imported = campaign
    cut = save_as(imported["gpkg"], tmp_path / "exported.shp", "ESRI Shapefile")
    first = next(imported["gpkg"].getFeatures())["frame_id"]
    with pytest.raises(InputError) as err:
        layers.read_frame_layer(cut)
    message = str(err.value)
    assert "exported" in message and "row 1, field 'camera'" in message and f"frame {first}" in message
    assert "cut at 254 characters" in message and "ESRI Shapefile keeps at most 254" in message
    assert "GeoPackage" in message and "run the import again" in message
    # Through an algorithm (a Processing source, whose format is not known): the same advice.
    with pytest.raises(QgsProcessingException, match="cut at 254 characters.*GeoPackage"):
        labels(geotags, cut, tmp_path / "labels")


def test_a_shapefile_output_loads_once_and_says_where_the_camera_goes(campaign, tmp_path):
    import processing

    folder = campaign[0]
    project, log = QgsProject.instance(), Log()
    before = set(project.mapLayers())
    context = QgsProcessingContext()
    context.setProject(project)
    processing.runAndLoadResults("birdseye:importflightlog", {
        "POSE_LOG": str(folder / "poses.csv"), "IMAGES": str(folder / "frames"),
        "CALIBRATION": str(folder / "calibration.yaml"), "OUTPUT": str(tmp_path / "frames.shp")},
        context=context, feedback=log)
    added = [project.mapLayer(i) for i in set(project.mapLayers()) - before]
    assert len(added) == 1 and added[0].storageType() == "ESRI Shapefile"
    assert any("at most 254 characters" in line and "camera_2" in line for line in log.lines)
    assert not any("not correctly generated" in line for line in log.lines)
    project.removeMapLayers([layer.id() for layer in added])


# ------------------------------------------------------------------ every format QGIS saves to
@pytest.fixture(scope="module")
def drone_images(birdseye_provider, tmp_path_factory):
    """A simulated DJI RTK flight (RTK standard deviations, EGM96 heights, NULL sync offsets) imported by
    importdjiimages, as a GeoPackage and as a Shapefile."""
    folder = tmp_path_factory.mktemp("drone_images")
    simulate_campaign(CampaignConfig(seed=5, platform="dji", n_targets=4, field_width_m=20.0, field_length_m=15.0,
                                     image_width=320, image_height=240, n_missed=0, n_spurious=0), folder)
    return {ext: as_layer(run("importdjiimages", {"IMAGES": str(folder / "frames"),
                                                  "OUTPUT": str(folder / f"frames.{ext}")})["OUTPUT"])
            for ext in ("gpkg", "shp")}


def delimited_text(path: Path, crs) -> QgsVectorLayer:
    """A CSV with its geometry as WKT, added as QGIS's Add Delimited Text Layer does (field types detected)."""
    layer = QgsVectorLayer(f"{path.as_uri()}?type=csv&detectTypes=yes&wktField=WKT&crs={crs.authid()}",
                           path.stem, "delimitedtext")
    assert layer.isValid()
    return layer


def saved_copy(imported: dict, kind: str, folder: Path) -> QgsVectorLayer:
    """The frame layer ``imported["gpkg"]`` saved by the user as ``kind``; a Shapefile copy is the import's
    Shapefile output saved on (a GeoPackage's camera saved as a Shapefile is cut: refused, test above)."""
    gpkg = imported["gpkg"]
    if kind == "Shapefile":
        return save_as(imported["shp"], folder / "copy.shp", "ESRI Shapefile")
    if kind in ("CSV", "CSV, delimited text"):
        copy = save_as(gpkg, folder / "copy.csv", "CSV", ["GEOMETRY=AS_WKT"])
        return copy if kind == "CSV" else delimited_text(folder / "copy.csv", gpkg.crs())
    suffix, driver = {"GeoJSON": (".geojson", "GeoJSON"), "FlatGeobuf": (".fgb", "FlatGeobuf")}[kind]
    return save_as(gpkg, folder / f"copy{suffix}", driver)


def by_frame(records) -> dict:
    out = {r["frame_id"]: r for r in records}
    assert len(out) == len(records)
    return out


def sorted_by_frame(frames):
    return frames.subset(np.argsort(frames.frame_id, kind="stable"))


# What each format hands back for the camera: GeoJSON a dict (QGIS parses the JSON object GDAL wrote).
CAMERA_AS = {"GeoJSON": dict}
# CSV keeps 15 significant digits (OGR's %.15g), a Shapefile 15 decimals, GeoJSON trims some last digits;
# GeoPackage and FlatGeobuf keep every bit.
RELATIVE, ABSOLUTE = 1e-14, 1e-12


def assert_close(values, expected):
    np.testing.assert_allclose(values, expected, rtol=RELATIVE, atol=ABSOLUTE)


@pytest.mark.parametrize("kind", ["Shapefile", "GeoJSON", "FlatGeobuf", "CSV", "CSV, delimited text"])
@pytest.mark.parametrize("source", ["flight log", "drone images"])
def test_a_saved_copy_reads_back_as_the_geopackage(request, source, kind, tmp_path):
    imported = request.getfixturevalue("campaign")[2] if source == "flight log" else \
        request.getfixturevalue("drone_images")
    copy = saved_copy(imported, kind, tmp_path)
    assert isinstance(next(copy.getFeatures())["camera"], CAMERA_AS.get(kind, str))
    original, records = layers.read_frame_layer(imported["gpkg"]), layers.read_frame_layer(copy)
    # The same frames with the same values and types (a FlatGeobuf lists them in its spatial index's order).
    want, got = by_frame(original), by_frame(records)
    assert got.keys() == want.keys()
    for frame_id, rec in want.items():
        assert got[frame_id].keys() == rec.keys()
        for name, value in rec.items():
            assert type(got[frame_id][name]) is type(value), (frame_id, name, got[frame_id][name])
            if isinstance(value, float):
                assert got[frame_id][name] == pytest.approx(value, rel=RELATIVE, abs=ABSOLUTE), (frame_id, name)
            else:
                assert got[frame_id][name] == value, (frame_id, name)
    # The same camera groups, camera models and poses.
    groups = {tuple(sorted(p.frame_id.tolist())): p for p, _ in poses_from_records(records)}
    for poses, _ in poses_from_records(original):
        again = groups.pop(tuple(sorted(poses.frame_id.tolist())))
        assert again.camera == poses.camera and again.reference == poses.reference
        mine, theirs = np.argsort(again.frame_id), np.argsort(poses.frame_id)
        for name in ("lat", "lon", "height", "quat", "ground_height"):
            assert_close(getattr(again, name)[mine], getattr(poses, name)[theirs])
        assert list(again.ground_source[mine]) == list(poses.ground_source[theirs])
    assert not groups
    # refineposes' reader: the same frames, RTK accuracy and flags included.
    frames, expected = sorted_by_frame(frames_from_records(records)), sorted_by_frame(frames_from_records(original))
    for name in ("time_s", "sync_offset_s", "rtk_status", "euler_deg"):
        assert_close(getattr(frames, name), getattr(expected, name))
    assert frames.extra.keys() == expected.extra.keys()
    for name, values in expected.extra.items():
        assert_close(frames.extra[name], values)
    assert (frames.image, frames.flags, frames.cameras, frames.ground_source, frames.reference) == \
        (expected.image, expected.flags, expected.cameras, expected.ground_source, expected.reference)
    if source == "drone images":
        assert np.isfinite(expected.extra["rtk_std_lon_m"]).all()


def test_values_of_the_wrong_type_are_refused_with_row_and_field(campaign, tmp_path):
    layer = save_as(campaign[2]["gpkg"], tmp_path / "frames.csv", "CSV", ["GEOMETRY=AS_WKT"])
    layer.startEditing()
    second = [f.id() for f in layer.getFeatures()][1]
    layer.changeAttributeValue(second, layer.fields().indexOf("lat"), "north")
    assert layer.commitChanges()
    with pytest.raises(InputError, match=r"row 2, field 'lat': 'north' is not a number"):
        layers.read_frame_layer(layer)
    layer.startEditing()
    layer.changeAttributeValue(second, layer.fields().indexOf("lat"), "-27.5")
    layer.changeAttributeValue(second, layer.fields().indexOf("frame_id"), "2.5")
    assert layer.commitChanges()
    with pytest.raises(InputError, match=r"row 2, field 'frame_id': '2.5' is not a whole number"):
        layers.read_frame_layer(layer)


# ------------------------------------------------------------------ every algorithm on GeoJSON and FlatGeobuf
@pytest.fixture(scope="module")
def burrows(birdseye_provider, tmp_path_factory):
    """A low flight over three burrows the bundled model finds (as in test_detect's end-to-end campaign): its
    geotags, and its frame layer as the import's GeoPackage and saved as GeoJSON, FlatGeobuf and CSV."""

    folder = tmp_path_factory.mktemp("burrows")
    simulate_campaign(CampaignConfig(seed=404, n_targets=3, field_width_m=3.0, field_length_m=2.0, altitude_m=2.5,
                                     image_width=480, image_height=300, n_missed=0, n_spurious=0), folder)
    geotags = run("importgeotags", {"INPUT": str(folder / "geotags.csv"), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    gpkg = as_layer(run("importflightlog", {
        "POSE_LOG": str(folder / "poses.csv"), "IMAGES": str(folder / "frames"),
        "CALIBRATION": str(folder / "calibration.yaml"), "OUTPUT": str(folder / "frames.gpkg")})["OUTPUT"])
    copies = {"GeoJSON": save_as(gpkg, folder / "frames.geojson", "GeoJSON"),
              "FlatGeobuf": save_as(gpkg, folder / "frames.fgb", "FlatGeobuf"),
              # Read back through OGR, a CSV names no CRS: Detect writes in the site's UTM zone, the GeoPackage's.
              "CSV": save_as(gpkg, folder / "frames.csv", "CSV", ["GEOMETRY=AS_WKT"])}
    return geotags, gpkg, copies


def plain(value):
    """An attribute, None for NULL (a QVariant under Qt 5)."""
    return None if hasattr(value, "isNull") and value.isNull() else value


def feature_rows(layer, skip=()) -> list[list]:
    """Each feature's attributes (less ``skip``) and where it is (a point's x, y, z; a polygon's centroid and
    area: a hull may start at another vertex), sorted: the order follows the frames', a format's choice."""
    names = [n for n in layer.fields().names() if n not in skip]
    rows = []
    for f in layer.getFeatures():
        g = f.geometry()
        if g.type() == GEOMETRY_POINT:
            where = [g.constGet().x(), g.constGet().y(), g.constGet().z()]
        else:
            where = [g.centroid().asPoint().x(), g.centroid().asPoint().y(), g.area()]
        rows.append([plain(f[n]) for n in names] + where)
    return sorted(rows, key=lambda row: [(1, 0) if v is None else (0, v) for v in row])


def csv_rows(path) -> list[list]:
    """A CSV file's rows, numbers as numbers, sorted."""
    def value(text):
        try:
            return float(text)
        except ValueError:
            return text
    with open(path, encoding="utf-8") as f:
        return sorted([value(v) for v in row.values()] for row in csv.DictReader(f))


def assert_same_rows(rows, expected, tolerance):
    """Rows equal; numbers within ``tolerance``."""
    assert len(rows) == len(expected)
    for row, want in zip(rows, expected):
        assert row == [v if v is None or isinstance(v, str) else pytest.approx(v, abs=tolerance) for v in want]


def algorithm_results(geotags, frames, folder) -> dict:
    """writelabels, detect (the bundled model), clusterdetections and evaluatedetections on ``frames``."""
    run("writelabels", {"GEOTAGS": geotags, "FRAMES": frames, "WRITE_RASTERS": False,
                        "OUTPUT_FOLDER": str(folder / "labels"), "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None})
    detections = run("detect", {"FRAMES": frames, "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    clusters = run("clusterdetections", {"DETECTIONS": detections, "GEOTAGS": geotags, "FRAMES": frames,
                                         "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    scores = run("evaluatedetections", {"DETECTIONS": [detections], "GEOTAGS": geotags, "FRAMES": [frames],
                                        "OUTPUT_JSON": str(folder / "scores.json"), "OUTPUT_REPORT": None})
    return {"labels": csv_rows(folder / "labels" / "labels.csv"), "detections": feature_rows(detections),
            "clusters": feature_rows(clusters, skip=("cluster_id",)),  # numbered in the detections' order
            "scores": {k: v for k, v in scores.items() if k.startswith(("N_", "RECALL", "GMCF"))}}


@pytest.fixture(scope="module")
def from_the_geopackage(burrows, tmp_path_factory):
    geotags, gpkg, _ = burrows
    return algorithm_results(geotags, gpkg, tmp_path_factory.mktemp("from_gpkg"))


@pytest.mark.parametrize("kind", ["GeoJSON", "FlatGeobuf", "CSV"])
def test_geojson_and_flatgeobuf_copies_give_every_algorithm_the_geopackage_result(burrows, from_the_geopackage,
                                                                                  kind, tmp_path):
    geotags, _, copies = burrows
    got, want = algorithm_results(geotags, copies[kind], tmp_path), from_the_geopackage
    assert len(want["labels"]) >= 5 and len(want["detections"]) >= 5 and want["scores"]["N_HIT_CLUSTERS"] >= 2
    assert_same_rows(got["labels"], want["labels"], 1.5e-3)  # u, v are written to 0.001 px
    assert_same_rows(got["detections"], want["detections"], 1e-6)
    assert_same_rows(got["clusters"], want["clusters"], 1e-6)
    assert got["scores"] == want["scores"]


@pytest.mark.parametrize("kind", ["GeoJSON", "FlatGeobuf"])
def test_the_frames_with_label_counts_of_a_copy_are_the_geopackage_counts(burrows, kind, tmp_path):
    geotags, gpkg, copies = burrows

    def counts(frames, folder):
        written = run("writelabels", {"GEOTAGS": geotags, "FRAMES": frames, "WRITE_RASTERS": False,
                                      "OUTPUT_FOLDER": str(folder), "OUTPUT_FRAMES": "TEMPORARY_OUTPUT",
                                      "OUTPUT_GEOTAGS": None})["OUTPUT_FRAMES"]
        return {f["frame_id"]: f["n_labels"] for f in written.getFeatures()}

    want = counts(gpkg, tmp_path / "gpkg")
    assert len(want) == gpkg.featureCount() and sum(want.values()) >= 5
    assert counts(copies[kind], tmp_path / kind) == want  # each frame its own count, in the copy's order
