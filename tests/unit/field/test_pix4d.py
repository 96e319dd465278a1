"""Pix4D calibrated camera parameters, tested against files Pix4D itself wrote (../shared/data/real_solutions,
see its SOURCE.md): every image's K [R | −Rt] is Pix4D's own P-matrix, and the imported frames — through the
CRS, ECEF, our poses and our camera — project project-CRS points where that P-matrix does.
"""
import shutil
from pathlib import Path

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.frame_records import GEOTAG_HEIGHTS_FLAG
from birdseye.birdseye_qgis.core.field.solutions import (
    SOLUTION_FLAG,
    import_camera_solution,
    read_camera_solution,
    solution_frames,
)
from birdseye.birdseye_qgis.core.field.solutions.pix4d import read_parameters
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame, ProjectedCRS
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses

REAL = Path(__file__).resolve().parents[4] / "shared" / "data" / "real_solutions" / "pix4d_phantom4pro"
PARAMS = "test_calibrated_camera_parameters.txt"
UTM54N = ProjectedCRS(32654)  # SOURCE.md: the offset is in UTM zone 54 N metres
N_IMAGES = 168
HEADER = ("fileName imageWidth imageHeight \ncamera matrix K [3x3]\nradial distortion [3x1]\ntangential distortion "
          "[2x1]\ncamera position t [3x1]\ncamera rotation R [3x3]\ncamera model m = K [R|-Rt] X\n\n")


@pytest.fixture
def real() -> Path:
    """The folder of the real Pix4D files; CI keeps ../shared beside the clone, so its absence is a failure."""
    assert (REAL / PARAMS).is_file(), f"{REAL} is missing: the shared data must lie beside the repository"
    return REAL


def pmatrices(folder: Path) -> dict:
    rows = (line.split() for line in (folder / "test_pmatrix.txt").read_text().splitlines() if line.strip())
    return {r[0]: np.array(r[1:], dtype=float).reshape(3, 4) for r in rows}


def unit(p: np.ndarray) -> np.ndarray:
    """A projection matrix scaled to unit Frobenius norm and a positive depth row: P is defined up to scale."""
    return p / np.linalg.norm(p) * np.sign(p[2, 3])


def test_every_camera_composes_to_pix4ds_own_pmatrix(real):
    images = read_parameters(real / PARAMS)
    expected = pmatrices(real)
    assert len(images) == N_IMAGES and {im.name for im in images} == set(expected)
    worst = 0.0
    for im in images:
        composed = im.K @ np.hstack([im.R, -(im.R @ im.t)[:, None]])
        worst = max(worst, float(np.abs(unit(composed) - unit(expected[im.name])).max()))
    # Pix4D prints P with 6 decimals (the largest entries are ~1e5): 5.6e-11 measured.
    assert worst < 1e-6, worst


def test_frames_project_project_crs_points_where_pix4ds_pmatrix_does(real):
    """The whole chain — UTM → WGS 84 → ECEF, grid convergence and scale, our pose, our camera — against P."""
    images = {im.name: im for im in read_parameters(real / PARAMS)}
    expected_p = pmatrices(real)
    offset = np.array((real / "test_offset.xyz").read_text().split(), dtype=float)
    solution = read_camera_solution(real, solution_crs=UTM54N)
    assert len(solution.cameras) == N_IMAGES
    frames = solution_frames(solution, {})
    local = LocalFrame.around(frames.lat, frames.lon, frames.height)
    # Pixels spanning the whole image, corners included, at depths from 5 to 40 m (the flight is ~15 m up).
    u, v = np.meshgrid(np.linspace(0, 5472, 7), np.linspace(0, 3648, 5))
    rays = np.stack([u.ravel(), v.ravel(), np.ones(u.size)], axis=1)
    worst = 0.0
    for f, cam in enumerate(solution.cameras):
        im = images[cam.name]
        x_cam = np.concatenate([(np.linalg.solve(im.K, rays.T)).T * d for d in (5.0, 15.0, 40.0)])
        x_rel = x_cam @ im.R + im.t  # project coordinates relative to the offset
        m = np.hstack([x_rel, np.ones((len(x_rel), 1))]) @ expected_p[cam.name].T
        pix4d_uv = m[:, :2] / m[:, 2:]
        lat, lon = UTM54N.to_geodetic(x_rel[:, 0] + offset[0], x_rel[:, 1] + offset[1])
        points = local.from_geodetic(lat, lon, x_rel[:, 2] + offset[2])
        pinhole = CameraModel.from_dict({**frames.cameras[f].to_dict(), "dist": [0.0] * 5})
        poses = FramePoses([0], frames.lat[[f]], frames.lon[[f]], frames.height[[f]], frames.quat[[f]],
                           frames.ground_h[[f]], pinhole)
        ours = pinhole.project(FrameGeometry(poses, local).to_camera(np.zeros(len(points), dtype=int), points))
        # Pix4D counts pixels from the image corner, we from the centre of the first pixel.
        worst = max(worst, float(np.hypot(*(ours + 0.5 - pix4d_uv).T).max()))
    # Pix4D's grid is Cartesian, the world is not: the focal length takes the grid's scale at the cameras'
    # height, so a point d m below them is off by d/R (R: the Earth's radius) of its distance from the principal
    # point (0.025 px at the corners 40 m down), and a tilted camera's rays mix in unscaled heights (0.006 px at
    # 0.6°): measured 0.034 px. Without that scale: 0.69 px (1.1 px inverted); without the meridian convergence
    # (0.9° here): 51 px.
    assert worst < 0.05, worst


def test_tangential_terms_follow_pix4ds_formula(tmp_path):
    """Pix4D: xd = x(1 + R1r² + R2r⁴ + R3r⁶) + 2T1xy + T2(r² + 2x²), yd = y(…) + T1(r² + 2y²) + 2T2xy."""
    write_parameters(tmp_path / "syn_calibrated_camera_parameters.txt",
                     k=[[1000.0, 0, 600.0], [0, 1000.0, 400.0], [0, 0, 1]], radial=(0.1, 0.01, 0.001),
                     tangential=(0.002, -0.003))
    (tmp_path / "syn_offset.xyz").write_text("368109.000 3956043.000 96.000")
    cam = read_camera_solution(tmp_path / "syn_calibrated_camera_parameters.txt", solution_crs=UTM54N).cameras[0]
    # x = 0.3, y = −0.2: r² = 0.13, radial factor 1 + 0.013 + 0.000169 + 0.000002197 = 1.013171197;
    # xd = 0.3039513591 + 2·0.002·0.3·(−0.2) + (−0.003)(0.13 + 0.18) = 0.3027813591,
    # yd = −0.2026342394 + 0.002(0.13 + 0.08) + 2(−0.003)(0.3)(−0.2) = −0.2018542394.
    np.testing.assert_allclose(cam.camera.distort(np.array([0.3, -0.2])), [0.3027813591, -0.2018542394],
                               rtol=0, atol=1e-10)
    k = cam.camera.fx / 1000.0  # the CRS's scale factor, applied to the focal length alone
    assert abs(k - 1) < 1e-3 and cam.camera.fy == cam.camera.fx
    assert (cam.camera.cx, cam.camera.cy) == (599.5, 399.5)


def write_parameters(path: Path, k, radial, tangential, name="IMG_1.JPG", t=(1.0, 2.0, 30.0),
                     r=((1, 0, 0), (0, -1, 0), (0, 0, -1))):
    rows = [f"{name} 1200 800", *(" ".join(map(str, row)) for row in k), " ".join(map(str, radial)),
            " ".join(map(str, tangential)), " ".join(map(str, t)), *(" ".join(map(str, row)) for row in r)]
    path.write_text(HEADER + "\n".join(rows) + "\n")


def copy_real(real: Path, folder: Path, with_offset=True) -> Path:
    shutil.copy(real / PARAMS, folder / PARAMS)
    if with_offset:
        shutil.copy(real / "test_offset.xyz", folder / "test_offset.xyz")
    return folder / PARAMS


def test_a_broken_row_is_named_with_its_field(real, tmp_path):
    path = copy_real(real, tmp_path)
    lines = path.read_text().splitlines()
    # The third image starts on line 29 (7 header lines, a blank one, 10 lines per image): its position is line 35.
    assert lines[28].startswith("DJI_0174.JPG")
    lines[34] = "15.12695280806216224789 n/a 15.21074870252876820587"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(InputError, match=r"calibrated_camera_parameters.txt, row 35, field 'camera position t': "
                                         r"expected 3 numbers"):
        read_camera_solution(path, solution_crs=UTM54N)


def test_a_truncated_file_names_the_last_image(real, tmp_path):
    path = copy_real(real, tmp_path)
    path.write_text("\n".join(path.read_text().splitlines()[:-3]) + "\n")
    with pytest.raises(InputError, match=r"row 1679: image 'DJI_0339.JPG' has 7 of its 10 lines"):
        read_camera_solution(path, solution_crs=UTM54N)


def test_a_matrix_that_is_no_rotation_is_refused(tmp_path):
    write_parameters(tmp_path / "p_calibrated_camera_parameters.txt", k=[[1000.0, 0, 600.0], [0, 1000.0, 400.0],
                                                                          [0, 0, 1]],
                     radial=(0, 0, 0), tangential=(0, 0), r=((1, 0, 0), (0, 1, 0), (0, 0, -1)))
    (tmp_path / "p_offset.xyz").write_text("368109 3956043 96")
    with pytest.raises(InputError, match=r"row 16, field 'camera rotation R': image 'IMG_1.JPG': expected a rotation"):
        read_camera_solution(tmp_path / "p_calibrated_camera_parameters.txt", solution_crs=UTM54N)


def test_missing_offset_file_is_named(real, tmp_path):
    path = copy_real(real, tmp_path, with_offset=False)
    with pytest.raises(InputError, match=r"test_offset.xyz: not found"):
        read_camera_solution(path, solution_crs=UTM54N)


def test_missing_crs_says_what_to_set(real):
    with pytest.raises(InputError, match=r"field 'SOLUTION_CRS': .*set SOLUTION_CRS to that projected CRS"):
        read_camera_solution(real / PARAMS)


def test_a_crs_whose_area_the_cameras_lie_outside_is_refused(real):
    """British National Grid read as UTM 54 N coordinates would put the flight near the North Pole."""
    with pytest.raises(InputError, match=r"field 'SOLUTION_CRS': .*inside its area of use; is SOLUTION_CRS the "
                                         r"project's output CRS\?"):
        read_camera_solution(real / PARAMS, solution_crs=ProjectedCRS(27700))


def test_import_places_frames_at_the_solved_positions_without_geotag_heights(real):
    result = import_camera_solution(real, solution_crs=UTM54N, ground_height=96.0)
    frames = result.frames
    assert len(frames) == N_IMAGES and result.report.counts["format"] == "pix4d"
    assert all(SOLUTION_FLAG in f and GEOTAG_HEIGHTS_FLAG not in f for f in frames.flags)
    first = read_parameters(real / PARAMS)[0]
    x, y = UTM54N.from_geodetic(frames.lat[0], frames.lon[0])
    np.testing.assert_allclose([x, y, frames.height[0]], first.t + [368109.0, 3956043.0, 96.0], atol=1e-6)
    assert all(ring is not None for ring in result.footprints.rings)
