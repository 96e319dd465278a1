"""Camera solutions of Metashape, OpenSfM/ODM and COLMAP: each file is written from the format's
documented conventions (tests/data/camera_solutions.py), and the pixel each format's *own* projection
formula gives for a ground point must be where the imported frame projects it: within 0.01 px over the
whole frame.
"""
import json
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "data"))
from camera_solutions import (
    MS_CAL,
    SITE,
    assert_same_pixels,
    camera_coordinates,
    colmap_pixel,
    imported_pixels,
    metashape_pixel,
    opensfm_pixel,
    truth,
    write_colmap_text,
    write_metashape,
    write_opensfm,
)

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.frame_records import GEOTAG_HEIGHTS_FLAG
from birdseye.birdseye_qgis.core.field.solutions import (
    SOLUTION_FLAG,
    import_camera_solution,
    read_camera_solution,
)


# ---------------------------------------------------------------------------------------------- Metashape
@pytest.mark.parametrize("components", [True, False])
def test_metashape_export_lands_within_a_hundredth_of_a_pixel(tmp_path, components):
    r, c, g = truth()
    write_metashape(tmp_path / "cameras.xml", r, c, components=components)
    result = import_camera_solution(tmp_path / "cameras.xml")
    expected = [metashape_pixel(camera_coordinates(r[f], c[f], g)) for f in range(len(c))]
    assert_same_pixels(expected, imported_pixels(result, r, c, g))
    assert result.report.counts["not_aligned"] == 1 and "IMG_9999" in " ".join(result.report.notes)
    assert all(SOLUTION_FLAG in f and GEOTAG_HEIGHTS_FLAG in f for f in result.frames.flags)
    np.testing.assert_allclose(result.frames.height, SITE[2] + c[:, 2], atol=1e-3)


def test_metashape_camera_takes_its_components_similarity_once(tmp_path):
    """A camera in a component is placed by that component's similarity alone: a chunk transform that
    differs from it (a stale one) changes nothing, and it is never composed with the component's."""
    r, c, g = truth()
    write_metashape(tmp_path / "cameras.xml", r, c, components=True)
    tree = ET.parse(tmp_path / "cameras.xml")
    tree.getroot().find("chunk").find("transform").find("scale").text = "3.0"
    tree.write(tmp_path / "cameras.xml")
    result = import_camera_solution(tmp_path / "cameras.xml")
    expected = [metashape_pixel(camera_coordinates(r[f], c[f], g)) for f in range(len(c))]
    assert_same_pixels(expected, imported_pixels(result, r, c, g))


def test_metashape_fisheye_sensor(tmp_path):
    r, c, g = truth(seed=3)
    cal = {**MS_CAL, "p1": 0.0, "p2": 0.0, "b1": 0.0, "b2": 0.0, "f": 1300.0}
    write_metashape(tmp_path / "fish.xml", r, c, cal=cal, kind="fisheye")
    result = import_camera_solution(tmp_path / "fish.xml")
    expected = [metashape_pixel(camera_coordinates(r[f], c[f], g), cal, fisheye=True) for f in range(len(c))]
    assert_same_pixels(expected, imported_pixels(result, r, c, g))


def test_metashape_without_geographic_reference_is_refused(tmp_path):
    r, c, _ = truth()
    write_metashape(tmp_path / "local.xml", r, c)
    tree = ET.parse(tmp_path / "local.xml")
    tree.getroot().find("chunk").find("reference").text = 'LOCAL_CS["Local Coordinates (m)"]'
    tree.write(tmp_path / "local.xml")
    with pytest.raises(InputError, match="local.xml.*names no geographic reference"):
        read_camera_solution(tmp_path / "local.xml")


# ---------------------------------------------------------------------------------------------- OpenSfM
@pytest.mark.parametrize("reference_in_file", [True, False])
def test_opensfm_reconstruction_lands_within_a_hundredth_of_a_pixel(tmp_path, reference_in_file):
    r, c, g = truth(seed=1)
    write_opensfm(tmp_path / "reconstruction.json", r, c, g, reference_in_file)
    result = import_camera_solution(tmp_path)
    expected = [opensfm_pixel(camera_coordinates(r[f], c[f], g)) for f in range(len(c))]
    assert_same_pixels(expected, imported_pixels(result, r, c, g))
    # Tie points lie within ±1 m of the site height: each frame's ground is their median in view.
    assert np.all(np.abs(result.frames.ground_h - SITE[2]) < 0.3)
    assert all(GEOTAG_HEIGHTS_FLAG not in f for f in result.frames.flags)


def test_odm_topocentric_copy_is_preferred(tmp_path):
    r, c, g = truth(seed=1)
    write_opensfm(tmp_path / "reconstruction.topocentric.json", r, c, g)
    (tmp_path / "reconstruction.json").write_text(json.dumps([{"cameras": {}, "shots": {}}]))
    result = import_camera_solution(tmp_path / "reconstruction.json")
    assert len(result.frames) == len(c) and "topocentric" in " ".join(result.report.findings)
    assert not result.report.notes, "reading the topocentric copy is a finding, nothing to check"


def test_opensfm_without_reference_is_refused(tmp_path):
    r, c, g = truth(seed=1)
    write_opensfm(tmp_path / "reconstruction.json", r, c, g, reference_in_file=False)
    (tmp_path / "reference_lla.json").unlink()
    with pytest.raises(InputError, match="names no geographic reference"):
        read_camera_solution(tmp_path / "reconstruction.json")


# ---------------------------------------------------------------------------------------------- COLMAP
@pytest.mark.parametrize("frame", ["enu", "ecef"])
def test_colmap_model_lands_within_a_hundredth_of_a_pixel(tmp_path, frame):
    import pycolmap  # noqa: F401  (the reader needs it: a missing install fails here, not skips)
    r, c, g = truth(seed=2)
    write_colmap_text(tmp_path / "sparse" / "0", r, c, g, frame)
    reference = f"enu:{SITE[0]},{SITE[1]},{SITE[2]}" if frame == "enu" else "ecef"
    result = import_camera_solution(tmp_path, colmap_reference=reference)
    expected = [colmap_pixel(camera_coordinates(r[f], c[f], g)) for f in range(len(c))]
    assert_same_pixels(expected, imported_pixels(result, r, c, g))


def test_colmap_without_reference_or_images_is_refused(tmp_path):
    import pycolmap  # noqa: F401  (the reader needs it: a missing install fails here, not skips)
    r, c, g = truth(seed=2)
    write_colmap_text(tmp_path / "model", r, c, g)
    with pytest.raises(InputError, match="names no geographic reference"):
        read_camera_solution(tmp_path / "model")


def test_unknown_files_say_what_is_expected(tmp_path):
    (tmp_path / "notes.txt").write_text("hello")
    with pytest.raises(InputError, match="holds no camera solution"):
        read_camera_solution(tmp_path)
    bad = tmp_path / "cams.xml"
    bad.write_text("<document><chunk><cameras/>")
    with pytest.raises(InputError, match="cams.xml: is not valid XML"):
        read_camera_solution(bad)


@pytest.mark.parametrize("camera", [
    dict(dist=(-0.1, 0.05, 1e-3, -2e-3, 0.0)),
    dict(dist=(-0.1, 0.05, 1e-3, -2e-3, 0.02)),
    dict(dist=(0.03, -0.01, 0.002, -0.0004), fisheye=True),
])
def test_colmap_camera_parameters_round_trip(camera):
    from birdseye.birdseye_qgis.core.field.solutions.colmap import camera_from_colmap, colmap_camera
    from birdseye.birdseye_qgis.core.geometry.camera import CameraModel

    cam = CameraModel(1280, 960, 1000.0, 1001.0, 641.3, 478.2, **camera)
    model, params = colmap_camera(cam)
    back = camera_from_colmap(model, 1280, 960, params, "test")
    assert back.dist == cam.dist and back.fisheye == cam.fisheye
    assert (back.fx, back.fy, back.cx, back.cy) == pytest.approx((cam.fx, cam.fy, cam.cx, cam.cy), abs=1e-12)
