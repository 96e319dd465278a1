"""The frame layer in the formats users save to (§4.6): a Shapefile output keeps the whole camera model in
``camera``, ``camera_2``, …; a camera cut by a later Save Features As… is refused with what to do."""
from __future__ import annotations

import csv
from pathlib import Path

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
from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign
from birdseye.birdseye_qgis.qgis_io import layers


def as_layer(output) -> QgsVectorLayer:
    layer = output if isinstance(output, QgsVectorLayer) else QgsVectorLayer(str(output), Path(output).stem, "ogr")
    assert layer.isValid()
    return layer


def save_as(layer, path, driver) -> QgsVectorLayer:
    """What the user's Export › Save Features As… does."""
    options = QgsVectorFileWriter.SaveVectorOptions()
    options.driverName = driver
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
