"""birdseye:importcameras through the Processing registry: a Metashape export of a georeferenced block →
frames → writelabels; every label where Metashape's own camera model puts the surveyed point."""
from __future__ import annotations

import csv
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from qgis.core import QgsFeature, QgsGeometry, QgsPoint, QgsProcessingException, QgsVectorLayer

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from camera_solutions import camera_coordinates, metashape_pixel, to_ecef, truth, write_metashape
from registry import run

from birdseye.birdseye_qgis.core.geometry.geodesy import ecef_to_geodetic


def geotag_layer(ground_enu):
    lat, lon, h = ecef_to_geodetic(to_ecef(ground_enu))
    layer = QgsVectorLayer("PointZ?crs=EPSG:4326&field=id:integer&field=label:string", "geotags", "memory")
    features = []
    for k in range(len(lat)):
        f = QgsFeature(layer.fields())
        f.setAttributes([k, "burrow"])
        f.setGeometry(QgsGeometry(QgsPoint(float(lon[k]), float(lat[k]), float(h[k]))))
        features.append(f)
    layer.dataProvider().addFeatures(features)
    return layer


def test_metashape_solution_to_labels_at_the_surveyed_heights(birdseye_provider, tmp_path):
    r, c, ground = truth(n=4, seed=7)
    ground = ground[:300]  # targets on uneven ground (±1 m): their own heights matter
    write_metashape(tmp_path / "cameras.xml", r, c)
    result = run("importcameras", {"CAMERAS": str(tmp_path / "cameras.xml"), "OUTPUT": "TEMPORARY_OUTPUT"})
    assert result["FRAME_COUNT"] == 4 and result["NOT_ALIGNED_COUNT"] == 1
    frames = result["OUTPUT"]
    flags = {f["flags"] for f in frames.getFeatures()}
    assert flags == {"camera_solution,geotag_heights,no_ground_height"}
    # No tie points and no DEM: no footprints, yet labels come from the geotags' own heights.
    run("writelabels", {"GEOTAGS": geotag_layer(ground), "FRAMES": frames, "SIGMA_PX": 5.0, "WRITE_RASTERS": False,
                        "OUTPUT_FOLDER": str(tmp_path / "labels"), "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None})
    with open(tmp_path / "labels" / "labels.csv", newline="", encoding="utf-8") as fh:
        labels = list(csv.DictReader(fh))
    assert len(labels) > 40
    errors = []
    for row in labels:
        f, k = int(row["frame_id"]), int(row["geotag_id"])
        expected = metashape_pixel(camera_coordinates(r[f], c[f], ground[[k]]))[0]
        errors.append(np.hypot(float(row["u"]) - expected[0], float(row["v"]) - expected[1]))
    assert max(errors) < 0.01


def test_unreferenced_solution_is_refused_naming_the_file(birdseye_provider, tmp_path):
    r, c, _ = truth()
    write_metashape(tmp_path / "local.xml", r, c)
    tree = ET.parse(tmp_path / "local.xml")
    tree.getroot().find("chunk").find("reference").text = 'LOCAL_CS["Local Coordinates (m)"]'
    tree.write(tmp_path / "local.xml")
    with pytest.raises(QgsProcessingException, match="local.xml.*names no geographic reference"):
        run("importcameras", {"CAMERAS": str(tmp_path / "local.xml"), "OUTPUT": "TEMPORARY_OUTPUT"})


@pytest.fixture
def pix4d_params() -> Path:
    """Real PIX4Dmapper output (../shared/data beside the clone, as in CI: missing data is a failure)."""
    path = (Path(__file__).resolve().parents[2].parent / "shared" / "data" / "real_solutions" / "pix4d_phantom4pro"
            / "test_calibrated_camera_parameters.txt")
    assert path.is_file(), f"{path} is missing: the shared data must lie beside the repository"
    return path


def test_pix4d_solution_in_its_project_crs(birdseye_provider, pix4d_params):
    result = run("importcameras", {"CAMERAS": str(pix4d_params), "SOLUTION_CRS": "EPSG:32654",
                                   "GROUND_HEIGHT_M": 96.0, "OUTPUT": "TEMPORARY_OUTPUT"})
    assert result["FRAME_COUNT"] == 168 and result["NOT_ALIGNED_COUNT"] == 0
    frames = result["OUTPUT"]
    assert frames.crs().authid() == "EPSG:32654"  # the UTM zone of the site, as the Pix4D project's
    assert {f["flags"] for f in frames.getFeatures()} == {"camera_solution"}  # heights not known to be ellipsoidal
    # Footprints ~14 m under the cameras (±9 m wide) centre on the solved positions: offset + the middle of the
    # cameras' t range (0.94, −4.83).
    centre = frames.extent().center()
    assert abs(centre.x() - 368109.94) < 3 and abs(centre.y() - 3956038.17) < 3


@pytest.mark.parametrize("crs, message", [(None, "set SOLUTION_CRS to that projected CRS"),
                                          ("EPSG:4326", "SOLUTION_CRS: EPSG:4326 is not a projected CRS in metres")])
def test_pix4d_solution_without_a_projected_crs_is_refused(birdseye_provider, pix4d_params, crs, message):
    params = {"CAMERAS": str(pix4d_params), "OUTPUT": "TEMPORARY_OUTPUT"}
    if crs:
        params["SOLUTION_CRS"] = crs
    with pytest.raises(QgsProcessingException, match=message):
        run("importcameras", params)
