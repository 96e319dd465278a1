"""The simulated campaign: determinism, file contracts, rendered targets where the projection puts
them, pose/altimeter/geotag noise as configured, coverage and conventions."""
from __future__ import annotations

import csv
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import Cancelled, InputError
from birdseye.birdseye_qgis.core.geometry.camera import load_calibration
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses, ground_height_from_altimeter
from birdseye.birdseye_qgis.core.geometry.projection import project_all
from birdseye.birdseye_qgis.core.geometry.rotations import quat_to_rotmat
from birdseye.birdseye_qgis.core.sim.render import blur_kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "data"))
from rendered_holes import dark_core_centroid

from birdseye.birdseye_qgis.core.sim.campaign import (
    NADIR_ROTATION,
    POSE_HEADER,
    CampaignConfig,
    parse_sigmas,
    simulate_campaign,
)

# A small rendered campaign (noise off): 3 × 3 m, 5 targets, 18 frames of 480 × 300 px from 4 m.
SMALL = dict(seed=5, n_targets=5, field_width_m=3.0, field_length_m=3.0, altitude_m=4.0, fps=2.0,
             image_width=480, image_height=300)
# A larger flight without frames for noise statistics (≈ 2,700 pose rows).
STATS = dict(seed=11, n_targets=12, field_width_m=20.0, field_length_m=12.0, render=False)


def read_csv(path: Path, header=True):
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh)) if header else list(csv.reader(fh))


def column(rows, name, kind=float):
    return np.array([kind(r[name]) for r in rows])


def pose_arrays(rows):
    return (column(rows, "lat_deg"), column(rows, "lon_deg"), column(rows, "height_m"),
            np.stack([column(rows, k) for k in ("qw", "qx", "qy", "qz")], -1))


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    folder = tmp_path_factory.mktemp("small")
    fractions = []
    result = simulate_campaign(CampaignConfig(noise_off=True, **SMALL), folder, progress=fractions.append)
    return folder, result, fractions


@pytest.fixture(scope="module")
def noisy(tmp_path_factory):
    folder = tmp_path_factory.mktemp("noisy")
    simulate_campaign(CampaignConfig(**STATS), folder)
    return folder


@pytest.fixture(scope="module")
def ideal(tmp_path_factory):
    """The same flight as ``noisy`` with noise off: the flight's randomness is its own stream, so
    the two logs differ by the measurement noise alone."""
    folder = tmp_path_factory.mktemp("ideal")
    simulate_campaign(CampaignConfig(noise_off=True, **STATS), folder)
    return folder


def all_files(folder: Path) -> dict:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


# ------------------------------------------------------------------------------ determinism
def test_same_seed_gives_identical_files_and_another_seed_does_not(small, tmp_path):
    folder, result, _ = small
    again = tmp_path / "again"
    simulate_campaign(CampaignConfig(noise_off=True, **SMALL), again)
    first, second = all_files(folder), all_files(again)
    assert sorted(first) == sorted(second)
    assert len([n for n in first if n.endswith(".jpg")]) == result.n_frames > 0
    different = [name for name in first if first[name] != second[name]]
    assert different == []

    other = tmp_path / "other"
    simulate_campaign(CampaignConfig(noise_off=True, **{**SMALL, "seed": 6}), other)
    third = all_files(other)
    for name in ("poses.csv", "geotags.csv", "truth/targets.csv"):
        assert third[name] != first[name]
    frames_a = sorted(n for n in first if n.endswith(".jpg"))
    frames_b = sorted(n for n in third if n.endswith(".jpg"))
    assert first[frames_a[0]] != third[frames_b[0]]


# ------------------------------------------------------------------------------ file contracts
def test_files_follow_the_contracts(small):
    folder, result, fractions = small
    cfg = CampaignConfig(**SMALL)
    with open(folder / "poses.csv", encoding="utf-8") as fh:
        assert fh.readline().strip() == ",".join(POSE_HEADER)
    poses = read_csv(folder / "poses.csv")
    assert len(poses) == result.n_poses
    time_s = column(poses, "time_s")
    assert np.all(np.diff(time_s) > 0)
    # Every INS message at INS_RATE_HZ, strobes at FPS (here on INS ticks).
    assert np.allclose(np.diff(time_s), 1 / cfg.ins_rate_hz, atol=1e-6)
    strobe = column(poses, "strobe", int)
    assert set(strobe) == {0, 1}
    assert np.allclose(np.diff(time_s[strobe == 1]), 1 / cfg.fps, atol=1e-6)
    assert set(column(poses, "rtk_status", int)) <= {1, 2, 3}
    radalt = column(poses, "radalt_m")
    assert np.all((radalt > cfg.altitude_m - 0.6) & (radalt < cfg.altitude_m + 0.6))
    q = pose_arrays(poses)[3]
    assert np.allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-8)

    geotags = read_csv(folder / "geotags.csv", header=False)
    assert len(geotags) == result.n_geotags == cfg.n_targets - cfg.n_missed + cfg.n_spurious
    for row in geotags:
        assert len(row) == 6
        lat, lon, alt_wgs, alt_msl = (float(v) for v in row[:4])
        assert abs(lat - cfg.site_lat) < 1e-3 and abs(lon - cfg.site_lon) < 1e-3
        assert alt_wgs - alt_msl == pytest.approx(41.54, abs=0.5)   # EGM96 at the site
        assert row[4] in ("4", "5") and row[5] == "burrow"

    images = read_csv(folder / "images.csv")
    assert len(images) == int(strobe.sum()) == result.n_frames
    strobe_times = time_s[strobe == 1]
    for strobe_t, row in zip(strobe_times, images):
        name = Path(row["file"]).name
        assert re.fullmatch(r"\d+\.\d{9}\.jpg", name)
        assert name[:-4] == row["time_s"]
        assert 0.0 <= float(row["time_s"]) - strobe_t < 0.25 / cfg.fps
        assert (folder / row["file"]).is_file()
    import cv2
    frame = cv2.imread(str(folder / images[0]["file"]))
    assert frame.shape == (cfg.image_height, cfg.image_width, 3)

    camera = load_calibration(folder / "calibration.yaml")
    assert (camera.width, camera.height) == (cfg.image_width, cfg.image_height)
    assert camera.fx == pytest.approx(4264.4945 * cfg.image_width / 1920)
    assert camera.has_distortion
    # Nadir mounting (image up = forward) within a degree, with a lever arm; altimeter lever arm read.
    angle = np.degrees(np.arccos(np.clip((np.trace(NADIR_ROTATION.T @ camera.T_cam_imu[:3, :3]) - 1) / 2, -1, 1)))
    assert 0.0 < angle < 1.0
    assert 0.05 < np.linalg.norm(camera.T_imu_cam[:3, 3]) < 0.2
    assert camera.t_imu_rad is not None and np.linalg.norm(camera.t_imu_rad) > 0.05

    truth = read_csv(folder / "truth" / "frames_true.csv")
    assert len(truth) == result.n_frames
    assert [r["image"] for r in truth] == [r["file"] for r in images]
    targets = read_csv(folder / "truth" / "targets.csv")
    assert len(targets) == cfg.n_targets
    import json
    metadata = (Path(__file__).resolve().parents[3] / "metadata.txt").read_text(encoding="utf-8")
    version = re.search(r"^version=(.+)$", metadata, flags=re.M).group(1).strip()
    assert json.loads((folder / "truth" / "campaign.json").read_text())["versions"]["birdseye"] == version
    assert fractions and fractions[-1] == pytest.approx(1.0) and np.all(np.diff(fractions) > 0)


def test_noise_off_logs_the_true_poses(small):
    folder, _, _ = small
    poses = read_csv(folder / "poses.csv")
    logged = [r for r in poses if r["strobe"] == "1"]
    truth = read_csv(folder / "truth" / "frames_true.csv")
    for name, tol in (("lat_deg", 1e-10), ("lon_deg", 1e-10), ("height_m", 1e-5), ("qw", 1e-9), ("qz", 1e-9)):
        np.testing.assert_allclose(column(logged, name), column(truth, name), atol=tol)
    assert all(r["rtk_status"] == "3" for r in poses)


# ------------------------------------------------------------------------------ rendered targets
def test_rendered_targets_appear_where_the_logged_pose_projects_them(small):
    """Noise off: the core projection from the LOGGED pose (frame layer inputs: pose log, tilt-
    corrected altimeter ground, calibration file) lands on the rendered hole within 0.5 px."""
    import cv2

    folder, _, _ = small
    camera = load_calibration(folder / "calibration.yaml")
    poses = [r for r in read_csv(folder / "poses.csv") if r["strobe"] == "1"]
    images = read_csv(folder / "images.csv")
    lat, lon, height, quat = pose_arrays(poses)
    ground = ground_height_from_altimeter(height, quat, column(poses, "radalt_m"), camera.t_imu_rad)
    frames = FramePoses(np.arange(len(poses)), lat, lon, height, quat, ground, camera)
    geometry = FrameGeometry(frames, LocalFrame.around(lat, lon, ground))
    targets = read_csv(folder / "truth" / "targets.csv")
    points = geometry.local.from_geodetic(column(targets, "lat"), column(targets, "lon"), column(targets, "h_ground"))
    proj = project_all(geometry, points, LevelPlaneGround(geometry))
    gsd = geometry.gsd_m()
    errors = []
    for k in np.flatnonzero(proj.in_view):
        f, t = proj.frame_idx[k], proj.point_idx[k]
        radius = float(targets[t]["radius_m"]) / gsd[f]
        outer = float(targets[t]["mound_radius_m"]) / gsd[f]
        if proj.margin_px[k] < 1.8 * outer:
            continue
        gray = cv2.imread(str(folder / images[f]["file"])).astype(float).mean(axis=2)
        errors.append(dark_core_centroid(gray, proj.uv[k], radius, outer) - proj.uv[k])
    errors = np.asarray(errors)
    assert len(errors) >= 3
    assert np.max(np.hypot(errors[:, 0], errors[:, 1])) < 0.5


def test_blur_kernels_are_normalised_and_symmetric():
    """Blur must not move a target: each 1-D kernel sums to 1 and has its centroid on its centre."""
    kx, ky = blur_kernels(0.6, (0.4, -1.3))
    for k in (kx, ky):
        assert len(k) % 2 == 1 and k.sum() == pytest.approx(1.0, abs=1e-6)
        np.testing.assert_allclose(k, k[::-1], atol=1e-8)
    # The motion streak lies along the motion: more spread along v than along u.
    x, y = np.arange(len(kx)) - len(kx) // 2, np.arange(len(ky)) - len(ky) // 2
    assert (ky * y ** 2).sum() > (kx * x ** 2).sum() > 0.3 ** 2


# ------------------------------------------------------------------------------ noise statistics
def local_and_rotations(rows, local):
    lat, lon, height, quat = pose_arrays(rows)
    return local.from_geodetic(lat, lon, height), local.rotation_from_ned(lat, lon) @ quat_to_rotmat(quat)


def test_pose_noise_has_the_configured_sigmas(noisy, ideal):
    noisy_rows, ideal_rows = read_csv(noisy / "poses.csv"), read_csv(ideal / "poses.csv")
    assert len(noisy_rows) == len(ideal_rows) > 2000
    fixed = column(noisy_rows, "rtk_status", int) == 3
    assert 0 < np.sum(~fixed) < 0.1 * len(fixed)       # one RTK-float episode of 2–5 s
    local = LocalFrame(-27.55, 151.95, 400.0)
    p_noisy, r_noisy = local_and_rotations(noisy_rows, local)
    p_ideal, r_ideal = local_and_rotations(ideal_rows, local)
    position_error = (p_noisy - p_ideal)[fixed]
    # Attitude error as a body-frame rotation vector: R_logged = R_true exp(φ^).
    delta = np.swapaxes(r_ideal, -1, -2) @ r_noisy
    phi = 0.5 * np.stack([delta[:, 2, 1] - delta[:, 1, 2], delta[:, 0, 2] - delta[:, 2, 0],
                          delta[:, 1, 0] - delta[:, 0, 1]], -1)
    sigmas = np.asarray(CampaignConfig().sigmas)
    measured = np.concatenate([position_error.std(axis=0), np.degrees(phi.std(axis=0))])
    n = fixed.sum()
    # The sample std of n Gaussian draws has a relative standard error of 1/√(2n) (≈ 1 % here).
    np.testing.assert_allclose(measured, sigmas, rtol=5.0 / math.sqrt(2 * n))
    assert np.all(np.abs(np.concatenate([position_error.mean(0), np.degrees(phi.mean(0))]))
                  < 5 * sigmas / math.sqrt(n))


def test_altimeter_ranges_agree_with_the_geometry(noisy, ideal):
    camera = load_calibration(ideal / "calibration.yaml")
    for folder, sigma in ((ideal, 0.0), (noisy, CampaignConfig().radalt_sigma_m)):
        rows = read_csv(folder / "poses.csv")
        _, _, height, quat = pose_arrays(read_csv(ideal / "poses.csv"))   # the true poses
        snr = column(rows, "radalt_snr")
        ground = ground_height_from_altimeter(height, quat, column(rows, "radalt_m"), camera.t_imu_rad)
        good = snr >= 13.0
        residual = ground[good] - 400.0
        if sigma == 0.0:
            assert np.all(good)
            assert np.max(np.abs(residual)) < 2e-4        # the log's 0.1 mm rounding
        else:
            assert 0 < np.sum(~good) < 0.05 * len(good)  # a short low-SNR burst
            # Tilt ≤ a few degrees: the vertical error is the range error times cos(tilt) ≈ 1.
            assert np.std(residual) == pytest.approx(sigma, rel=0.1)
            assert np.std(ground[~good] - 400.0) > 3 * sigma


def test_geotags_lie_within_rtk_noise_of_their_targets(noisy):
    cfg = CampaignConfig(**STATS)
    geotags = read_csv(noisy / "geotags.csv", header=False)
    targets = read_csv(noisy / "truth" / "targets.csv")
    surveyed = [t for t in targets if t["surveyed"] == "1"]
    assert len(targets) - len(surveyed) == cfg.n_missed
    referenced = {int(t["geotag_row"]) for t in surveyed}
    spurious = [i + 1 for i in range(len(geotags)) if i + 1 not in referenced]
    assert len(spurious) == cfg.n_spurious
    local = LocalFrame(cfg.site_lat, cfg.site_lon, cfg.ground_height_m)

    def enu(lat, lon, h):
        return local.from_geodetic(np.atleast_1d(lat), np.atleast_1d(lon), np.atleast_1d(h))[0]

    truth = {int(t["geotag_row"]): enu(float(t["lat"]), float(t["lon"]), float(t["h_ground"])) for t in surveyed}
    errors = []
    for row, t_enu in truth.items():
        g = geotags[row - 1]
        err = enu(float(g[0]), float(g[1]), float(g[2])) - t_enu
        bound = 0.06 * 5 if g[4] == "5" else cfg.rtk_sigma_m * 5
        assert np.all(np.abs(err[:2]) < bound) and abs(err[2]) < 2 * bound
        if g[4] == "4":
            errors.append(err)
    errors = np.asarray(errors)
    assert 0.4 * cfg.rtk_sigma_m < errors[:, :2].std() < 1.6 * cfg.rtk_sigma_m
    all_targets = np.array([enu(float(t["lat"]), float(t["lon"]), 400.0) for t in targets])
    for row in spurious:
        g = geotags[row - 1]
        p = enu(float(g[0]), float(g[1]), float(g[2]))
        assert np.min(np.hypot(*(all_targets[:, :2] - p[:2]).T)) > 0.4


# ------------------------------------------------------------------------------ flight
def test_every_target_is_seen_from_several_frames(ideal):
    camera = load_calibration(ideal / "calibration.yaml")
    truth = read_csv(ideal / "truth" / "frames_true.csv")
    lat, lon, height, quat = pose_arrays(truth)
    frames = FramePoses(np.arange(len(truth)), lat, lon, height, quat, column(truth, "ground_h_m"), camera)
    geometry = FrameGeometry(frames, LocalFrame.around(lat, lon, 400.0))
    targets = read_csv(ideal / "truth" / "targets.csv")
    points = geometry.local.from_geodetic(column(targets, "lat"), column(targets, "lon"), column(targets, "h_ground"))
    proj = project_all(geometry, points, edge_buffer_px=50)
    views = np.bincount(proj.point_idx[proj.in_view], minlength=len(targets))
    assert views.min() >= 3


def test_heading_follows_the_track_from_true_north(ideal):
    """On the lines the yaw (from true north) is the direction of travel, ± the wobble; the first
    line of a field wider than long runs east."""
    truth = read_csv(ideal / "truth" / "frames_true.csv")
    line = column(truth, "line", int)
    lat, lon, height, _ = pose_arrays(truth)
    local = LocalFrame(-27.55, 151.95, 400.0)
    p = local.from_geodetic(lat, lon, height)
    yaw = column(truth, "yaw_deg")
    assert np.median(yaw[line == 0]) == pytest.approx(90.0, abs=3.0)
    same = (line[1:] == line[:-1]) & (line[1:] >= 0)
    step = p[1:] - p[:-1]
    track = np.degrees(np.arctan2(step[:, 0], step[:, 1])) % 360
    diff = (yaw[1:] - track + 180) % 360 - 180
    assert np.all(np.abs(diff[same]) < 6.0)
    # A multirotor's attitude: wobble of a degree or two, tilted into the wind, braking at line ends.
    tilt = np.hypot(column(truth, "roll_deg"), column(truth, "pitch_deg"))
    assert 0.3 < np.median(tilt[line >= 0]) < 6.0 and np.max(tilt) < 15.0


def test_strobes_between_ins_messages_are_their_own_rows(tmp_path):
    """At 3 frames/s and 50 Hz most exposures fall between INS messages: each is a row of its own,
    at exactly k/3 s, and the regular messages stay 20 ms apart."""
    simulate_campaign(CampaignConfig(**{**SMALL, "fps": 3.0, "render": False}), tmp_path)
    rows = read_csv(tmp_path / "poses.csv")
    # Times to the nanosecond, exactly as written ("<sec>.<9 digits>").
    ns = np.array([int(r["time_s"].replace(".", "")) for r in rows], dtype=np.int64)
    ns -= ns[0]
    strobe = column(rows, "strobe", int) == 1
    k = np.arange(strobe.sum())
    assert np.all(np.abs(ns[strobe] - np.round(k * 1e9 / 3.0)) <= 1)
    on_tick = ns % 20_000_000 == 0
    assert np.all(on_tick | strobe)
    assert np.all(np.diff(ns[on_tick]) == 20_000_000)
    assert np.sum(strobe & ~on_tick) >= len(k) // 2
    assert np.all(np.diff(ns) > 0)


# ------------------------------------------------------------------------------ input and control
def test_bad_parameters_are_named():
    with pytest.raises(InputError, match="SIGMAS"):
        parse_sigmas("0.01, 0.01, 0.06")
    with pytest.raises(InputError, match="SIGMAS"):
        parse_sigmas("a,b,c,d,e,f")
    assert parse_sigmas("0,0,0,0,0,0") == (0.0,) * 6
    with pytest.raises(InputError, match="ALTITUDE_M"):
        CampaignConfig(altitude_m=0.0).validated()
    with pytest.raises(InputError, match="N_MISSED"):
        CampaignConfig(n_targets=3, n_missed=4).validated()


def test_too_many_targets_for_the_field_is_an_input_error(tmp_path):
    with pytest.raises(InputError, match="N_TARGETS"):
        simulate_campaign(CampaignConfig(n_targets=60, field_width_m=2.0, field_length_m=2.0, render=False),
                          tmp_path)


def test_cancel_stops_between_frames_and_a_rerun_clears_the_old_frames(tmp_path):
    calls = []

    def cancel_after_two():
        calls.append(1)
        return len(calls) > 2

    with pytest.raises(Cancelled):
        simulate_campaign(CampaignConfig(**{**SMALL, "image_width": 64, "image_height": 40}), tmp_path,
                          is_canceled=cancel_after_two)
    assert len(list((tmp_path / "frames").glob("*.jpg"))) == 2
    # A later run into the same folder does not leave those frames to be imported with its log.
    (tmp_path / "frames" / "notes.txt").write_text("mine")
    simulate_campaign(CampaignConfig(**{**SMALL, "render": False}), tmp_path)
    assert not (tmp_path / "images.csv").exists()
    assert [p.name for p in (tmp_path / "frames").iterdir()] == ["notes.txt"]


# ------------------------------------------------------------------------------ terrain
# A 20° slope facing east-south-east, flown terrain-following at 10 m (noise off, no frames).
SLOPE = dict(seed=8, n_targets=6, field_width_m=6.0, field_length_m=5.0, noise_off=True, n_spurious=2,
             render=False, terrain="plane", slope_deg=20.0, slope_aspect_deg=120.0)


def read_dem(path: Path):
    """The written GeoTIFF as a core DemRaster (read with GDAL), its EPSG code and its metadata."""
    from osgeo import gdal

    from birdseye.birdseye_qgis.core.geometry.dem import DemRaster

    dataset = gdal.Open(str(path))
    gt = dataset.GetGeoTransform()
    assert gt[2] == gt[4] == 0.0
    srs = dataset.GetSpatialRef()
    epsg = int(srs.GetAuthorityCode(None))
    heights = dataset.GetRasterBand(1).ReadAsArray().astype(float)
    return DemRaster(heights, (gt[0], gt[1], gt[3], gt[5]), epsg, "ellipsoidal"), epsg, dataset.GetMetadata()


@pytest.fixture(scope="module")
def slope(tmp_path_factory):
    folder = tmp_path_factory.mktemp("slope")
    simulate_campaign(CampaignConfig(**SLOPE), folder)
    return folder, read_dem(folder / "truth" / "dem.tif")


def test_the_terrain_is_written_as_a_dem_of_the_set_slope_and_aspect(slope):
    from birdseye.birdseye_qgis.core.geometry.geodesy import ProjectedCRS, utm_epsg

    folder, (dem, epsg, metadata) = slope
    cfg = CampaignConfig(**SLOPE)
    assert epsg == utm_epsg(cfg.site_lat, cfg.site_lon) and metadata["VERTICAL_DATUM"] == "WGS84 ellipsoid"
    assert 0.25 <= dem.cell_size_m <= 0.5 and not np.isnan(dem.heights).any()
    # A plane in the site's east/north/up frame (from the cells' own coordinates, through geodetic):
    # U = a + b·E + c·N, slope atan|∇U|, facing (downhill) towards the azimuth of −∇U from true north.
    x, y = dem.cell_centres()
    xx, yy = np.meshgrid(x, y)
    lat, lon = ProjectedCRS(epsg).to_geodetic(xx.ravel(), yy.ravel())
    local = LocalFrame(cfg.site_lat, cfg.site_lon, cfg.ground_height_m)
    enu = local.from_geodetic(lat, lon, dem.heights.ravel())
    (a, b, c), *_ = np.linalg.lstsq(np.c_[np.ones(len(enu)), enu[:, :2]], enu[:, 2], rcond=None)
    assert math.degrees(math.atan(math.hypot(b, c))) == pytest.approx(cfg.slope_deg, abs=0.02)
    assert math.degrees(math.atan2(-b, -c)) % 360 == pytest.approx(cfg.slope_aspect_deg, abs=0.02)
    assert a == pytest.approx(0.0, abs=1e-3)  # the site's ground height at the site
    # It covers the field and every frame's view with room to spare.
    truth = read_csv(folder / "truth" / "frames_true.csv")
    fx, fy = ProjectedCRS(epsg).from_geodetic(column(truth, "lat_deg"), column(truth, "lon_deg"))
    reach = 0.3 * cfg.altitude_m / (1 - 0.3 * math.tan(math.radians(cfg.slope_deg)))
    assert x.min() < fx.min() - reach and fx.max() + reach < x.max()
    assert y.min() < fy.min() - reach and fy.max() + reach < y.max()


def test_the_flight_follows_the_terrain_and_the_altimeter_ranges_to_it(slope):
    folder, (dem, _, _) = slope
    cfg = CampaignConfig(**SLOPE)
    camera = load_calibration(folder / "calibration.yaml")
    rows = read_csv(folder / "poses.csv")
    lat, lon, height, quat = pose_arrays(rows)
    below = dem.sample_geodetic(lat, lon)
    # Terrain following: a constant height above the terrain (± the cm-level wander) while it climbs.
    assert np.ptp(below) > 3.0
    assert np.mean(height - below) == pytest.approx(cfg.altitude_m, abs=0.1) and np.std(height - below) < 0.15
    # The altimeter's range along the body z axis ends on the DEM.
    local = LocalFrame(cfg.site_lat, cfg.site_lon, cfg.ground_height_m)
    r_local_body = local.rotation_from_ned(lat, lon) @ quat_to_rotmat(quat)
    origin = local.from_geodetic(lat, lon, height) + r_local_body @ np.asarray(camera.t_imu_rad)
    end = origin + column(rows, "radalt_m")[:, None] * r_local_body[:, :, 2]
    e_lat, e_lon, e_h = local.to_geodetic(end)
    assert np.max(np.abs(e_h - dem.sample_geodetic(e_lat, e_lon))) < 5e-4  # the log's 0.1 mm rounding
    truth = read_csv(folder / "truth" / "frames_true.csv")
    under = dem.sample_geodetic(column(truth, "lat_deg"), column(truth, "lon_deg"))
    assert np.max(np.abs(column(truth, "ground_h_m") - under)) < 2e-4


def test_targets_and_geotags_lie_on_the_terrain(slope):
    folder, (dem, _, _) = slope
    targets = read_csv(folder / "truth" / "targets.csv")
    terrain = dem.sample_geodetic(column(targets, "lat"), column(targets, "lon"))
    assert np.max(np.abs(column(targets, "h_ground") - terrain)) < 2e-4
    assert np.ptp(terrain) > 0.3
    geotags = np.array(read_csv(folder / "geotags.csv", header=False))[:, :3].astype(float)
    assert len(geotags) == SLOPE["n_targets"] - CampaignConfig().n_missed + SLOPE["n_spurious"]
    assert np.max(np.abs(geotags[:, 2] - dem.sample_geodetic(geotags[:, 0], geotags[:, 1]))) < 2e-4


def test_rendered_targets_sit_where_the_true_pose_projects_them_over_terrain(tmp_path):
    """Frames over a 20° slope show each hole where the true pose projects the target's point on the
    terrain (within 0.5 px), and far from where a level ground under the frame would put it."""
    import cv2

    simulate_campaign(CampaignConfig(noise_off=True, terrain="plane", slope_deg=20.0, slope_aspect_deg=300.0,
                                     **{**SMALL, "n_targets": 8, "field_width_m": 5.0, "field_length_m": 4.0,
                                        "altitude_m": 8.0}), tmp_path)
    camera = load_calibration(tmp_path / "calibration.yaml")
    truth = read_csv(tmp_path / "truth" / "frames_true.csv")
    lat, lon, height, quat = pose_arrays(truth)
    frames = FramePoses(np.arange(len(truth)), lat, lon, height, quat, column(truth, "ground_h_m"), camera)
    geometry = FrameGeometry(frames, LocalFrame.around(lat, lon, height))
    targets = read_csv(tmp_path / "truth" / "targets.csv")
    points = geometry.local.from_geodetic(column(targets, "lat"), column(targets, "lon"), column(targets, "h_ground"))
    proj = project_all(geometry, points)
    level = project_all(geometry, points, LevelPlaneGround(geometry))
    f_px = math.sqrt(camera.fx * camera.fy)
    errors, level_errors = [], []
    for k in np.flatnonzero(proj.in_view):
        f, t = proj.frame_idx[k], proj.point_idx[k]
        gsd = proj.depth[k] / f_px
        radius, outer = float(targets[t]["radius_m"]) / gsd, float(targets[t]["mound_radius_m"]) / gsd
        if proj.margin_px[k] < 1.8 * outer:
            continue
        gray = cv2.imread(str(tmp_path / truth[f]["image"])).astype(float).mean(axis=2)
        hole = dark_core_centroid(gray, proj.uv[k], radius, outer)
        errors.append(np.hypot(*(hole - proj.uv[k])))
        level_errors.append(np.hypot(*(hole - level.uv[k])))
    print(f"holes vs true projection over a 20° slope: {np.round(errors, 3)} px; level plane: "
          f"{np.round(level_errors, 1)} px")
    assert len(errors) >= 8
    assert max(errors) < 0.5
    assert max(level_errors) > 5.0


def test_dem_terrain_casts_rays_onto_the_dem():
    from birdseye.birdseye_qgis.core.sim.terrain import DemTerrain, synthetic_terrain

    lat0, lon0, h0 = -27.55, 151.95, 400.0
    local = LocalFrame(lat0, lon0, h0)
    extent = (-20.0, 20.0, -20.0, 20.0)
    plane = synthetic_terrain(lat0, lon0, "plane", slope_deg=25.0, aspect_deg=200.0, base_height_m=h0, size_m=50.0,
                              cell_m=0.5)
    hills = synthetic_terrain(lat0, lon0, "hills", slope_deg=10.0, aspect_deg=30.0, relief_m=3.0, base_height_m=h0,
                              size_m=50.0, cell_m=0.25, wavelength_m=30.0, seed=3)
    rng = np.random.default_rng(0)
    xn, yn = rng.uniform(-0.4, 0.4, (2, 50, 40)).astype(np.float32)
    r_local_cam = np.array([[0.0, -1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])  # nadir, image up = north
    centre = np.array([1.0, -2.0, 10.0])
    for dem in (plane, hills):
        terrain = DemTerrain(local, dem, extent)
        east, north = terrain.intersect_grid(centre, r_local_cam, xn, yn)
        rays = np.stack([xn.ravel(), yn.ravel(), np.ones(xn.size)], -1) @ r_local_cam.T
        t = terrain.intersect(np.broadcast_to(centre, rays.shape), rays)
        hits = centre + t[:, None] * rays
        np.testing.assert_allclose(east.ravel(), hits[:, 0], atol=1e-5)
        np.testing.assert_allclose(north.ravel(), hits[:, 1], atol=1e-5)
        # The hits lie on the DEM, read independently: local → geodetic → the DEM's UTM cells.
        h_lat, h_lon, h_h = local.to_geodetic(hits)
        # Planar: exact. Hills: the heightfield is the DEM's bilinear surface resampled on the local grid,
        # off by the interpolation error (cell²·curvature/8 ≈ |second difference|/8 per resampling).
        second_difference = max(np.abs(np.diff(dem.heights, 2, axis=axis)).max() for axis in (0, 1))
        tolerance = 1e-6 if dem is plane else 2 * second_difference / 8
        assert np.max(np.abs(h_h - dem.sample_geodetic(h_lat, h_lon))) < tolerance
        np.testing.assert_allclose(terrain.height_at(hits[:, 0], hits[:, 1]), h_h, atol=1e-6)
    # A ray leaving the terrain model is a miss, not a guess.
    assert np.isnan(terrain.intersect(centre[None], np.array([[1.0, 0.0, -0.05]])))[0]


def test_terrain_campaigns_are_deterministic_and_the_hills_follow_the_seed(tmp_path):
    hills = dict(seed=2, n_targets=4, field_width_m=6.0, field_length_m=4.0, render=False, terrain="hills",
                 relief_m=2.0, hill_wavelength_m=15.0)
    simulate_campaign(CampaignConfig(**hills), tmp_path / "a")
    simulate_campaign(CampaignConfig(**hills), tmp_path / "b")
    simulate_campaign(CampaignConfig(**{**hills, "seed": 3}), tmp_path / "c")
    first, second, third = (all_files(tmp_path / k) for k in "abc")
    assert first == second and "truth/dem.tif" in first
    assert third["truth/dem.tif"] != first["truth/dem.tif"]
    dem, _, _ = read_dem(tmp_path / "a" / "truth" / "dem.tif")
    assert np.ptp(dem.heights) == pytest.approx(2.0, abs=1e-6)  # no slope: the relief, peak to peak
    truth = read_csv(tmp_path / "a" / "truth" / "frames_true.csv")
    agl = column(truth, "height_m") - dem.sample_geodetic(column(truth, "lat_deg"), column(truth, "lon_deg"))
    assert np.std(agl) < 0.15 and np.ptp(column(truth, "ground_h_m")) > 0.3
    # A flat campaign into the same folder takes the old terrain away.
    simulate_campaign(CampaignConfig(**{**hills, "terrain": "flat"}), tmp_path / "a")
    assert not (tmp_path / "a" / "truth" / "dem.tif").exists()


def test_bad_terrain_parameters_are_named(tmp_path):
    with pytest.raises(InputError, match="TERRAIN"):
        CampaignConfig(terrain="mountains").validated()
    with pytest.raises(InputError, match="SLOPE_DEG"):
        CampaignConfig(terrain="plane", slope_deg=60.0).validated()
    with pytest.raises(InputError, match="RELIEF_M"):
        CampaignConfig(terrain="hills", relief_m=-1.0).validated()
    with pytest.raises(InputError, match="SLOPE_DEG.*too steep"):
        simulate_campaign(CampaignConfig(terrain="hills", slope_deg=40.0, relief_m=10.0, hill_wavelength_m=20.0,
                                         render=False, **{k: SMALL[k] for k in ("field_width_m", "field_length_m")}),
                          tmp_path)
