"""The simulator's consumer-drone mode: DJI JPEGs that the DJI importer reads back with the metadata
(and the errors) the simulator meant, frames that overlap and match for photogrammetry."""
from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.dji import (
    T_CAM_GIMBAL,
    dji_camera,
    dji_pose,
    import_dji_images,
    read_dji_metadata,
)
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import footprints
from birdseye.birdseye_qgis.core.geometry.rotations import quat_to_rotmat
from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign
from birdseye.birdseye_qgis.core.sim.dji_images import DjiMetadataErrors, dji_camera_model, write_dji_jpeg, xmp_packet

# One line of 640 × 480 frames at 8 m over a 6 × 4 m field: fast to render, enough frames for statistics.
SMALL = dict(seed=7, n_targets=4, field_width_m=6.0, field_length_m=4.0, altitude_m=8.0, image_width=640,
             image_height=480, platform="dji")


def so3_log(r):
    """Rotation vector of a rotation matrix (SciPy's, independent of the code under test)."""
    from scipy.spatial.transform import Rotation

    return Rotation.from_matrix(r).as_rotvec()


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def column(rows, name):
    return np.array([float(r[name]) for r in rows])


@pytest.fixture(scope="module")
def flight(tmp_path_factory):
    folder = tmp_path_factory.mktemp("dji")
    result = simulate_campaign(CampaignConfig(**SMALL), folder)
    return folder, result


@pytest.fixture(scope="module")
def exact(tmp_path_factory):
    folder = tmp_path_factory.mktemp("dji_exact")
    simulate_campaign(CampaignConfig(noise_off=True, dji_dewarped=True, **SMALL), folder)
    return folder


def true_rotations(folder):
    rows = read_csv(folder / "truth" / "frames_true.csv")
    return rows, quat_to_rotmat(np.stack([column(rows, k) for k in ("qw", "qx", "qy", "qz")], -1))


def test_the_files_of_a_dji_flight(flight):
    folder, result = flight
    names = sorted(p.name for p in (folder / "frames").iterdir())
    assert names == [f"DJI_{i:04d}.JPG" for i in range(1, result.n_frames + 1)] and result.n_frames >= 8
    assert not (folder / "poses.csv").exists() and not (folder / "images.csv").exists()
    assert not (folder / "calibration.yaml").exists() and result.files["frames"] == folder / "frames"
    record = json.loads((folder / "truth" / "campaign.json").read_text())
    assert record["platform"] == "dji" and record["dji"]["camera"]["model"] == "M3E"
    assert record["parameters"]["side_overlap"] == 0.7 and record["dji"]["forward_overlap"] == 0.8
    data = (folder / "frames" / "DJI_0001.JPG").read_bytes()
    # DJI's header: EXIF APP1 right after the start of image, then the XMP packet; no JFIF APP0.
    assert data[:4] == b"\xff\xd8\xff\xe1" and data[6:12] == b"Exif\x00\x00"
    second = 4 + int.from_bytes(data[4:6], "big")
    assert data[second:second + 2] == b"\xff\xe1"
    assert data[second + 4:second + 33] == b"http://ns.adobe.com/xap/1.0/\x00"
    assert b"\xff\xe0" not in data[:second]


def test_the_importer_reads_back_the_metadata_the_simulator_meant(flight):
    folder, result = flight
    record = json.loads((folder / "truth" / "campaign.json").read_text())
    n_geoid, takeoff = record["geoid_undulation_m"], record["dji"]["takeoff"]["height_m"]
    truth, r_true = true_rotations(folder)
    errors = read_csv(folder / "truth" / "dji_metadata_errors.csv")
    simulated = dji_camera_model(640, 480)
    local = LocalFrame(float(truth[0]["lat_deg"]), float(truth[0]["lon_deg"]), 0.0)
    for row, r_t, err in zip(truth, r_true, errors):
        meta = read_dji_metadata(folder / row["image"])
        pose = dji_pose(meta)
        camera, flags = dji_camera(meta)
        # The camera: DewarpData is the rendering lens, for the image as written.
        assert flags == [] and camera.source == "dji:DewarpData DJI M3E SIM-M3E-0001"
        for name in ("fx", "fy", "cx", "cy"):
            assert getattr(camera, name) == pytest.approx(getattr(simulated, name), abs=1e-6)
        np.testing.assert_allclose(camera.dist, simulated.dist, atol=1e-9)
        assert meta.time_s == pytest.approx(float(row["time_s"]), abs=1e-3)
        # Position: RTK noise only; heights: the height error, MSL, and above the take-off point.
        h_err = float(err["height_error_m"])
        offset = local.from_geodetic(pose.lat, pose.lon, 0.0) - local.from_geodetic(
            float(row["lat_deg"]), float(row["lon_deg"]), 0.0)
        assert np.hypot(*np.ravel(offset)[:2]) == pytest.approx(float(err["horizontal_error_m"]), abs=1e-3)
        assert pose.height == pytest.approx(float(row["height_m"]) + h_err - n_geoid, abs=1e-3)
        assert pose.height - pose.ground_h == pytest.approx(float(row["height_m"]) + h_err - takeoff, abs=2e-3)
        assert pose.rtk_status == 3 and 0.005 < pose.rtk_std[0] < 0.02 and pose.flags == []
        # Attitude: the metadata's is the truth turned by the drone's error rotation E (NED):
        # its down component is the heading error, its level part the tilt of the true optical axis.
        e = so3_log(quat_to_rotmat(pose.quat) @ r_t.T)
        jitter = 0.05
        assert math.degrees(e[2]) == pytest.approx(float(err["heading_error_deg"]), abs=jitter)
        tilt_true = math.degrees(math.acos(r_t[2, 0]))   # the optical axis (gimbal x) against down
        assert math.degrees(np.hypot(e[0], e[1])) == pytest.approx(tilt_true, abs=jitter)
        assert tilt_true == pytest.approx(float(err["tilt_error_deg"]), abs=1e-4)
    # One camera model for the whole flight.
    cams = import_dji_images(folder / "frames").frames.cameras
    assert len(cams) == result.n_frames and all(c is cams[0] for c in cams)


def test_the_metadata_errors_follow_the_documented_model(flight):
    folder, _ = flight
    errors = read_csv(folder / "truth" / "dji_metadata_errors.csv")
    model = DjiMetadataErrors()
    drawn = json.loads((folder / "truth" / "campaign.json").read_text())["dji"]["drawn"]
    assert model.heading_bias_deg[0] <= abs(drawn["heading_bias_deg"]) <= model.heading_bias_deg[1]
    assert model.tilt_bias_deg[0] <= drawn["tilt_bias_deg"] <= model.tilt_bias_deg[1]
    heading = column(errors, "heading_error_deg")
    # A short flight: the slow drift moves the heading error little from its bias.
    assert np.all(np.abs(heading - drawn["heading_bias_deg"]) < 4 * model.heading_drift_deg)
    assert np.all(np.abs(column(errors, "tilt_error_deg") - drawn["tilt_bias_deg"]) < 4 * model.tilt_drift_deg)
    height = column(errors, "height_error_m")
    assert np.all(np.abs(height - model.height_bias_m) < 4 * model.height_sigma_m)
    assert np.all(column(errors, "horizontal_error_m") < 5 * model.rtk_sigma_m)


def test_noise_off_metadata_tells_the_truth_and_a_dewarped_frame_has_no_distortion(exact):
    truth, r_true = true_rotations(exact)
    record = json.loads((exact / "truth" / "campaign.json").read_text())
    for row, r_t in zip(truth, r_true):
        meta = read_dji_metadata(exact / row["image"])
        pose = dji_pose(meta)
        camera, flags = dji_camera(meta)
        # Written to 0.01° and 1 mm: the metadata pose is the true pose.
        assert math.degrees(np.linalg.norm(so3_log(quat_to_rotmat(pose.quat) @ r_t.T))) < 0.01
        assert pose.height == pytest.approx(float(row["height_m"]) - record["geoid_undulation_m"], abs=1e-3)
        # DewarpFlag 1: the frames were rendered without distortion and are read back so.
        assert flags == ["dewarped"] and camera.dist == (0.0,) * 5
        assert meta.xmp["DewarpData"].split(",")[-1] == f"{dji_camera_model(640, 480).dist[-1]:.8f}"
        np.testing.assert_array_equal(camera.T_cam_imu, T_CAM_GIMBAL)


def test_frames_overlap_for_photogrammetry(tmp_path):
    """Neighbouring photos on a line share ≥ FORWARD_OVERLAP of their footprint, neighbouring lines
    ≥ the side overlap; and the rendered soil has features SIFT matches between neighbours."""
    import cv2

    folder = tmp_path / "sfm"
    # 640 × 480 px from 4 m: the ground sampling of 1280 × 960 px from 8 m (8.9 mm), a quarter of the pixels.
    cfg = CampaignConfig(seed=3, n_targets=4, field_width_m=8.0, field_length_m=9.0, altitude_m=4.0,
                         image_width=640, image_height=480, platform="dji")
    simulate_campaign(cfg, folder)
    truth, _ = true_rotations(folder)
    camera = dji_camera_model(640, 480)
    quat = np.stack([column(truth, k) for k in ("qw", "qx", "qy", "qz")], -1)
    poses = FramePoses(np.arange(len(truth)), column(truth, "lat_deg"), column(truth, "lon_deg"),
                       column(truth, "height_m"), quat, column(truth, "ground_h_m"), camera)
    geometry = FrameGeometry(poses, LocalFrame.around(poses.lat, poses.lon, poses.height))
    corners, _ = footprints(geometry, LevelPlaneGround(geometry), per_edge=1)
    centre = corners[:, :, :2].mean(axis=1)
    along = np.linalg.norm(corners[:, 0, :2] - corners[:, 3, :2], axis=1)   # image height on the ground
    across = np.linalg.norm(corners[:, 0, :2] - corners[:, 1, :2], axis=1)
    line = column(truth, "line").astype(int)
    assert len(set(line)) >= 3
    for k in set(line):
        c = centre[line == k]
        step = np.linalg.norm(np.diff(c, axis=0), axis=1)
        assert np.all(1.0 - step / along[line == k][1:] >= 0.8 - 0.03)
    spacing = [np.median(centre[line == k + 1], axis=0) - np.median(centre[line == k], axis=0)
               for k in sorted(set(line))[:-1]]
    side = 1.0 - np.abs(np.array(spacing)[:, 0]) / np.median(across)   # lines run north-south here
    # As planned, give or take the few centimetres the track wanders and the camera's tilt moves them.
    plan = json.loads((folder / "truth" / "campaign.json").read_text())["flight"]
    assert 1.0 - plan["line_spacing_m"] / plan["footprint_across_m"] == pytest.approx(0.7, abs=1e-4)  # rounded
    assert np.all(side >= 0.7 - 0.05), side

    sift = cv2.SIFT_create()
    first = np.flatnonzero(line == line[0])

    def features(i):
        return sift.detectAndCompute(cv2.imread(str(folder / truth[i]["image"]), cv2.IMREAD_GRAYSCALE), None)

    beside = np.flatnonzero(line == line[0] + 1)
    beside = beside[np.argmin(np.linalg.norm(centre[beside] - centre[first[2]], axis=1))]
    (ka, da), (kb, db), (kc, dc) = features(first[2]), features(first[3]), features(beside)
    # The next photo on the line (80 % overlap) and the one beside it on the next line (70 %, turned
    # by 180°): far more epipolar inliers than the 15 COLMAP needs to register a pair.
    for kp, des, least in ((kb, db, 150), (kc, dc, 60)):
        pairs = cv2.BFMatcher().knnMatch(da, des, k=2)
        good = [m for m, n in pairs if m.distance < 0.8 * n.distance]
        pa = np.float32([ka[m.queryIdx].pt for m in good])
        pb = np.float32([kp[m.trainIdx].pt for m in good])
        _, inliers = cv2.findFundamentalMat(pa, pb, cv2.FM_RANSAC, 1.0, 0.999)
        assert int(inliers.sum()) >= least, f"{int(inliers.sum())} SIFT inliers"


def test_dji_parameters_are_checked(tmp_path):
    with pytest.raises(InputError, match="PLATFORM"):
        CampaignConfig(platform="mavic").validated()
    with pytest.raises(InputError, match="FORWARD_OVERLAP"):
        CampaignConfig(platform="dji", forward_overlap=0.99).validated()


def test_the_jpeg_writer_keeps_the_pixels_and_limits_segments(tmp_path):
    import cv2
    from PIL import Image

    image = np.random.default_rng(0).integers(0, 255, (48, 64, 3), dtype=np.uint8)
    exif = Image.Exif()
    exif[0x0110] = "M3E"
    path = write_dji_jpeg(tmp_path / "a.jpg", image, exif.tobytes(), xmp_packet({"RelativeAltitude": "+8.000"}), 92)
    plain = cv2.imdecode(cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, 92])[1], cv2.IMREAD_COLOR)
    np.testing.assert_array_equal(cv2.imread(str(path)), plain)
    meta = read_dji_metadata(path)
    assert meta.tag("RelativeAltitude") == 8.0 and meta.model == "M3E"
    with pytest.raises(ValueError, match="65533"):
        write_dji_jpeg(tmp_path / "b.jpg", image, b"x" * 70000, b"", 92)


def test_same_seed_same_dji_files(flight, tmp_path):
    folder, _ = flight
    simulate_campaign(CampaignConfig(**SMALL), tmp_path)
    for path in sorted((folder / "frames").iterdir()) + [folder / "truth" / "dji_metadata_errors.csv"]:
        assert (tmp_path / path.relative_to(folder)).read_bytes() == path.read_bytes(), path.name
