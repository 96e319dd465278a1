"""Camera model: projection against OpenCV, distortion round trips, calibration loaders."""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.geometry.camera import (
    CalibrationError,
    CameraModel,
    camera_from_dji_dewarp,
    load_calibration,
    write_kalibr_yaml,
)

DEPLOYED = dict(width=1920, height=1200, fx=4264.4945, fy=4262.8927, cx=958.4594, cy=592.5033)
# A strongly distorted lens, so the round trips are tested where fixed-point iteration would fail.
STRONG = (-0.28, 0.12, 1.2e-3, -8e-4, -0.03)


def camera(dist=STRONG, **kw):
    params = {**DEPLOYED, **kw}
    return CameraModel(dist=dist, **params)


def test_projection_matches_opencv_project_points():
    import cv2
    cam = camera(fx=1400.0, fy=1390.0)  # short lens: large normalised coordinates, distortion matters
    rng = np.random.default_rng(3)
    pts = np.column_stack([rng.uniform(-4, 4, 500), rng.uniform(-3, 3, 500), rng.uniform(6, 15, 500)])
    expected, _ = cv2.projectPoints(pts, np.zeros(3), np.zeros(3), cam.K, np.array(cam.dist))
    np.testing.assert_allclose(cam.project(pts), expected[:, 0, :], atol=1e-6, rtol=0)


def test_undistort_inverts_distort_over_whole_frame():
    cam = camera()
    u, v = np.meshgrid(np.arange(-0.5, cam.width, 7.0), np.arange(-0.5, cam.height, 7.0))
    u = np.append(u.ravel(), [cam.width - 0.5, -0.5, cam.width - 0.5])
    v = np.append(v.ravel(), [cam.height - 0.5, cam.height - 0.5, -0.5])
    uv = np.column_stack([u, v])
    back = cam.normalized_to_pixel(cam.pixel_to_normalized(uv))
    assert np.max(np.abs(back - uv)) < 1e-3


def test_undistort_agrees_with_opencv_where_it_converges():
    import cv2
    cam = camera(dist=(-0.08, 0.12, 4e-4, -3e-4, 0.0))
    rng = np.random.default_rng(0)
    uv = np.column_stack([rng.uniform(0, cam.width, 200), rng.uniform(0, cam.height, 200)])
    crit = (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 200, 1e-14)
    if hasattr(cv2, "undistortPointsIter"):  # OpenCV 4; OpenCV 5 folded it into undistortPoints
        ref = cv2.undistortPointsIter(uv[:, None, :], cam.K, np.array(cam.dist), None, None, crit)[:, 0, :]
    else:
        ref = cv2.undistortPoints(uv[:, None, :], cam.K, np.array(cam.dist), criteria=crit)[:, 0, :]
    np.testing.assert_allclose(cam.pixel_to_normalized(uv), ref, atol=1e-9)


def test_pixel_convention_principal_point_and_in_frame_buffer():
    cam = camera(dist=(0, 0, 0, 0, 0))
    assert np.allclose(cam.project(np.array([0.0, 0.0, 5.0])), [cam.cx, cam.cy])
    # A point 1 m right and 0.5 m down at 10 m depth lands right of and below the principal point.
    u, v = cam.project(np.array([1.0, 0.5, 10.0]))
    assert u == pytest.approx(cam.cx + cam.fx * 0.1) and v == pytest.approx(cam.cy + cam.fy * 0.05)
    uv = np.array([[5.0, 600.0], [15.0, 600.0], [1914.0, 600.0], [-0.6, 600.0]])
    assert cam.in_frame(uv).tolist() == [True, True, True, False]
    assert cam.in_frame(uv, edge_buffer_px=10).tolist() == [False, True, False, False]
    np.testing.assert_allclose(cam.edge_margin(uv)[:3], [5.5, 15.5, 5.5])
    assert np.isnan(cam.project(np.array([0.0, 0.0, -1.0]))).all()


def test_camera_json_round_trip():
    t = np.eye(4)
    t[:3, 3] = [0.05, -0.02, 0.1]
    cam = camera(T_cam_imu=t, t_imu_rad=(0.1, 0.0, 0.2))
    back = CameraModel.from_json(cam.to_json())
    assert back.dist == cam.dist and back.t_imu_rad == cam.t_imu_rad
    np.testing.assert_array_equal(back.T_cam_imu, cam.T_cam_imu)


def test_kalibr_round_trip_with_lever_arms(tmp_path):
    t = np.eye(4)
    t[:3, :3] = [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]
    t[:3, 3] = [0.02, 0.07, -0.01]
    cam = camera(T_cam_imu=t, t_imu_rad=(0.15, -0.05, 0.12))
    path = tmp_path / "camchain-imucam.yaml"
    write_kalibr_yaml(cam, path)
    back = load_calibration(path)
    assert (back.fx, back.fy, back.cx, back.cy, back.width, back.height) == (
        cam.fx, cam.fy, cam.cx, cam.cy, cam.width, cam.height)
    np.testing.assert_allclose(back.dist, cam.dist)
    np.testing.assert_allclose(back.T_cam_imu, t)
    np.testing.assert_allclose(back.t_imu_rad, cam.t_imu_rad)


def test_opencv_filestorage_yaml(tmp_path):
    path = tmp_path / "cam.yml"
    path.write_text("""%YAML:1.0
---
image_width: 1920
image_height: 1200
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 4264.4945, 0., 958.4594, 0., 4262.8927, 592.5033, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.08, 0.12, 4.0e-4, -3.0e-4, 0. ]
""")
    cam = load_calibration(path)
    assert (cam.fx, cam.cy, cam.width) == (4264.4945, 592.5033, 1920)
    assert cam.dist == (-0.08, 0.12, 4e-4, -3e-4, 0.0)


@pytest.mark.parametrize("text, field", [
    ("cam0:\n  resolution: [1920, 1200]\n", "cam0.intrinsics"),
    ("cam0:\n  intrinsics: [1, 2, 3]\n  resolution: [1920, 1200]\n", "cam0.intrinsics"),
    ("cam0:\n  intrinsics: [100, 100, 50, 50]\n  resolution: [1920, 1200]\n"
     "  distortion_model: fov\n", "cam0.distortion_model"),
    ("cam0:\n  intrinsics: [100, 100, 50, 50]\n  resolution: [100, 100]\n"
     "  T_cam_imu: [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]\n", "cam0.T_cam_imu"),
    ("cam0:\n  intrinsics: [100, abc, 50, 50]\n  resolution: [100, 100]\n", "cam0.intrinsics"),
])
def test_bad_kalibr_files_name_file_and_field(tmp_path, text, field):
    path = tmp_path / "bad-camchain.yaml"
    path.write_text(text)
    with pytest.raises(CalibrationError) as err:
        load_calibration(path)
    assert "bad-camchain.yaml" in str(err.value) and field in str(err.value)


def test_bad_opencv_and_unknown_files(tmp_path):
    path = tmp_path / "cv.yml"
    path.write_text("camera_matrix:\n  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]\nimage_width: 10\nimage_height: 10\n")
    with pytest.raises(CalibrationError, match=r"cv\.yml.*distortion_coefficients"):
        load_calibration(path)
    other = tmp_path / "notes.yaml"
    other.write_text("hello: world\n")
    with pytest.raises(CalibrationError, match="notes.yaml: not a recognised calibration"):
        load_calibration(other)
    with pytest.raises(CalibrationError, match="not found"):
        load_calibration(tmp_path / "missing.yaml")


def test_principal_point_outside_image_is_rejected(tmp_path):
    path = tmp_path / "c.yaml"
    path.write_text("cam0:\n  intrinsics: [100, 100, 500, 50]\n  resolution: [100, 100]\n")
    with pytest.raises(CalibrationError, match="principal point"):
        load_calibration(path)


def test_dji_dewarp_offsets_are_from_image_centre():
    cam = camera_from_dji_dewarp(
        "2018-09-04;3678.21,3678.21,11.5,-20.25,-0.27,0.11,0.0004,-0.0002,-0.03", 5472, 3648)
    assert cam.cx == pytest.approx(2735.5 + 11.5) and cam.cy == pytest.approx(1823.5 - 20.25)
    assert cam.dist == (-0.27, 0.11, 0.0004, -0.0002, -0.03)
    with pytest.raises(CalibrationError, match="expected 9"):
        camera_from_dji_dewarp("2018;1,2,3", 100, 100)


# ---------------------------------------------------------------- terms of photogrammetry packages
def test_r8_radial_term_and_skew_project_as_written():
    """k4 multiplies r⁸ and skew enters u only: checked against the formula evaluated by hand."""
    cam = camera(dist=(0.01, -0.02, 1e-3, 2e-3, 0.03), k4=-0.05, skew=1.5, fx=1400.0, fy=1390.0)
    x, y, z = 1.2, -0.7, 4.0
    xn, yn = x / z, y / z
    r2 = xn * xn + yn * yn
    radial = 1 + 0.01 * r2 - 0.02 * r2 ** 2 + 0.03 * r2 ** 3 - 0.05 * r2 ** 4
    xd = xn * radial + 2 * 1e-3 * xn * yn + 2e-3 * (r2 + 2 * xn * xn)
    yd = yn * radial + 1e-3 * (r2 + 2 * yn * yn) + 2 * 2e-3 * xn * yn
    expected = [1400.0 * xd + 1.5 * yd + cam.cx, 1390.0 * yd + cam.cy]
    np.testing.assert_allclose(cam.project(np.array([x, y, z])), expected, rtol=0, atol=1e-9)


def test_skewed_camera_adds_skew_times_distorted_y_to_opencv():
    """cv2.projectPoints ignores K[0, 1]; the skewed pixel is OpenCV's plus skew · y_d, y_d = (v − cy)/fy."""
    import cv2
    cam = camera(fx=1400.0, fy=1390.0, skew=2.5)
    rng = np.random.default_rng(5)
    pts = np.column_stack([rng.uniform(-4, 4, 300), rng.uniform(-3, 3, 300), rng.uniform(6, 15, 300)])
    unskewed, _ = cv2.projectPoints(pts, np.zeros(3), np.zeros(3), camera(fx=1400.0, fy=1390.0).K,
                                    np.array(cam.dist))
    expected = unskewed[:, 0, :].copy()
    expected[:, 0] += 2.5 * (expected[:, 1] - cam.cy) / cam.fy
    np.testing.assert_allclose(cam.project(pts), expected, atol=1e-6, rtol=0)


def test_fisheye_matches_opencv_fisheye_project_points():
    import cv2
    cam = CameraModel(1280, 960, 520.0, 521.0, 641.2, 478.9, dist=(0.05, -0.012, 0.004, -0.0007), fisheye=True)
    rng = np.random.default_rng(8)
    pts = np.column_stack([rng.uniform(-4, 4, 400), rng.uniform(-3, 3, 400), rng.uniform(1, 8, 400)])
    expected, _ = cv2.fisheye.projectPoints(pts[:, None, :], np.zeros(3), np.zeros(3), cam.K,
                                           np.array(cam.dist[:4]))
    np.testing.assert_allclose(cam.project(pts), expected[:, 0, :], atol=1e-6, rtol=0)


@pytest.mark.parametrize("extra", [dict(k4=-0.02, skew=0.8), dict(dist=(0.05, -0.012, 0.004, -0.0007), fisheye=True)])
def test_round_trip_over_the_frame_with_new_terms(extra):
    cam = camera(**{"dist": STRONG, **extra, "fx": 1400.0, "fy": 1390.0})
    u, v = np.meshgrid(np.arange(-0.5, cam.width, 11.0), np.arange(-0.5, cam.height, 11.0))
    uv = np.column_stack([u.ravel(), v.ravel()])
    back = cam.normalized_to_pixel(cam.pixel_to_normalized(uv))
    assert np.max(np.abs(back - uv)) < 1e-6
    again = CameraModel.from_json(cam.to_json())
    assert again == cam and again.fisheye == cam.fisheye and again.k4 == cam.k4 and again.skew == cam.skew


def test_plain_camera_json_carries_no_new_keys():
    """Frame layers written before the photogrammetry terms existed keep their camera JSON byte for byte."""
    assert not {"k4", "skew", "fisheye"} & set(camera().to_dict())


def test_resized_camera_sees_the_same_rays():
    cam = camera(skew=1.2, k4=0.01)
    small = cam.resized(cam.width // 4, cam.height // 4)
    pts = np.array([[0.3, -0.2, 10.0], [-0.9, 0.6, 12.0]])
    # A pixel centre of the small image covers 4×4 full pixels: u_small = (u + 0.5)/4 - 0.5.
    np.testing.assert_allclose(small.project(pts), (cam.project(pts) + 0.5) / 4.0 - 0.5, atol=1e-9)


def test_kalibr_equidistant_round_trip_and_refusal_of_r8(tmp_path):
    fish = CameraModel(1280, 960, 520.0, 521.0, 641.2, 478.9, dist=(0.05, -0.012, 0.004, -0.0007), fisheye=True)
    write_kalibr_yaml(fish, tmp_path / "fish.yaml")
    assert load_calibration(tmp_path / "fish.yaml").fisheye
    np.testing.assert_allclose(load_calibration(tmp_path / "fish.yaml").dist, fish.dist)
    with pytest.raises(CalibrationError, match="k4"):
        write_kalibr_yaml(camera(k4=0.1), tmp_path / "r8.yaml")
