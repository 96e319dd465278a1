"""``birdseye:simulatecampaign`` through the Processing registry, and its output through the importers."""
from __future__ import annotations

import csv
from pathlib import Path

import pytest
from qgis.core import QgsProcessingException

SMALL = {"SEED": 4, "N_TARGETS": 3, "FIELD_WIDTH_M": 6.0, "FIELD_LENGTH_M": 4.0, "IMAGE_WIDTH": 160,
         "IMAGE_HEIGHT": 100, "FPS": 2.0, "N_MISSED": 1, "N_SPURIOUS": 1}


@pytest.fixture(scope="module")
def campaign(birdseye_provider, tmp_path_factory):
    import processing

    folder = tmp_path_factory.mktemp("campaign")
    result = processing.run("birdseye:simulatecampaign", {**SMALL, "OUTPUT_FOLDER": str(folder)})
    return folder, result


def test_algorithm_is_registered_with_help(birdseye_provider):
    from qgis.core import QgsApplication

    alg = QgsApplication.processingRegistry().algorithmById("birdseye:simulatecampaign")
    assert alg is not None and alg.group()
    names = {p.name() for p in alg.parameterDefinitions()}
    for name in ("SEED", "OUTPUT_FOLDER", "N_TARGETS", "FIELD_WIDTH_M", "FIELD_LENGTH_M", "SITE_LAT", "SITE_LON",
                 "GROUND_HEIGHT_M", "ALTITUDE_M", "SPEED_MS", "FPS", "INS_RATE_HZ", "IMAGE_WIDTH", "IMAGE_HEIGHT",
                 "SIGMAS", "RADALT_SIGMA_M", "RTK_SIGMA_M", "N_MISSED", "N_SPURIOUS", "RENDER", "NOISE_OFF",
                 "ORTHO_PIXEL_M"):
        assert name in names
        assert name in alg.shortHelpString()


def test_outputs_are_written_and_returned(campaign):
    folder, result = campaign
    assert Path(result["OUTPUT_FOLDER"]) == folder
    for key in ("GEOTAGS", "POSES", "IMAGES", "CALIBRATION"):
        assert Path(result[key]).is_file() and Path(result[key]).parent == folder
    with open(result["IMAGES"], encoding="utf-8") as fh:
        images = list(csv.DictReader(fh))
    assert len(images) == result["FRAME_COUNT"] > 0
    assert all((folder / row["file"]).is_file() for row in images)
    with open(result["GEOTAGS"], encoding="utf-8") as fh:
        assert len(list(csv.reader(fh))) == SMALL["N_TARGETS"] - SMALL["N_MISSED"] + SMALL["N_SPURIOUS"]
    assert (folder / "truth" / "campaign.json").is_file()
    assert Path(result["ORTHOMOSAIC"]) == folder / "orthomosaic.tif"


def test_orthomosaic_loads_as_a_map_layer_under_the_geotags(campaign):
    """QGIS opens the map in the site's UTM zone, and it holds every geotag the importer reads."""
    import processing
    from qgis.core import QgsCoordinateTransform, QgsProject, QgsRasterLayer

    _, result = campaign
    layer = QgsRasterLayer(result["ORTHOMOSAIC"], "orthomosaic")
    assert layer.isValid() and layer.bandCount() == 4
    assert layer.crs().authid() == "EPSG:32756"  # UTM 56 S at the default site
    geotags = processing.run("birdseye:importgeotags", {"INPUT": result["GEOTAGS"], "OUTPUT": "memory:geotags"})
    points = geotags["OUTPUT"]
    to_map = QgsCoordinateTransform(points.crs(), layer.crs(), QgsProject.instance())
    assert points.featureCount() > 0
    for feature in points.getFeatures():
        assert layer.extent().contains(to_map.transform(feature.geometry().asPoint()))


def test_campaign_imports_through_the_importers(campaign):
    """The contract, end to end: every strobe finds its image and every geotag row is read."""
    import processing

    folder, result = campaign
    frames = processing.run("birdseye:importflightlog", {
        "POSE_LOG": result["POSES"], "IMAGES": str(folder), "CALIBRATION": result["CALIBRATION"],
        "FPS": SMALL["FPS"], "OUTPUT": "memory:frames"})
    assert frames["FRAME_COUNT"] == result["FRAME_COUNT"]
    assert frames["UNMATCHED_STROBES"] == 0 and frames["UNMATCHED_IMAGES"] == 0 and frames["BAD_ROWS"] == 0
    geotags = processing.run("birdseye:importgeotags", {"INPUT": result["GEOTAGS"], "OUTPUT": "memory:geotags"})
    assert geotags["GEOTAG_COUNT"] == SMALL["N_TARGETS"] - SMALL["N_MISSED"] + SMALL["N_SPURIOUS"]
    assert geotags["BAD_ROWS"] == 0


def test_poses_only_and_bad_sigmas(birdseye_provider, tmp_path):
    import processing

    result = processing.run("birdseye:simulatecampaign", {
        **SMALL, "RENDER": False, "NOISE_OFF": True, "OUTPUT_FOLDER": str(tmp_path / "poses_only")})
    assert result["FRAME_COUNT"] > 0 and not (tmp_path / "poses_only" / "frames").exists()
    assert Path(result["POSES"]).is_file()
    with pytest.raises(QgsProcessingException, match="SIGMAS"):
        processing.run("birdseye:simulatecampaign", {**SMALL, "SIGMAS": "0.01,0.01", "RENDER": False,
                                                      "OUTPUT_FOLDER": str(tmp_path / "bad")})
