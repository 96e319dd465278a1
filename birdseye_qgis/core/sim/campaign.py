"""A deterministic synthetic survey campaign, written in the file contracts of docs/design.md#files.

What it simulates (every random draw from the SEED; same seed → identical files):

* a field (:mod:`.field`) centred on the site, with burrow targets and look-alikes, on level
  ground or on terrain (:mod:`.terrain`): a tilted plane or a plane with smooth hills, given as a
  DEM (ellipsoidal heights, the site's UTM zone) that is written with the campaign;
* the rover survey: a geotag per target (RTK noise, a few float fixes), a few targets missed and a
  few spurious points;
* the flight (:mod:`.flight`): lawnmower lines at the set speed and height above the ground
  (following the terrain), a multirotor's attitude, an INS log at ``ins_rate_hz`` with Σ0 noise
  (position in the local east/north/up axes, attitude as small body rotations about roll/pitch/yaw),
  a radar altimeter ranging along the body z axis to the terrain, and strobe rows at the camera's
  exposures;
* the frames (:mod:`.render`): every pixel's ray through the *true* pose and the lens onto the
  field's terrain, with a real camera's photometry, written as timestamped JPEGs.
* the orthomosaic (:mod:`.orthomosaic`): the same field seen straight down, a map GeoTIFF to
  draw the survey over.

Two platforms (``platform``):

* ``ins`` — the BirdsEye payload: an RTK INS pose log, a radar altimeter and the nadir camera,
  triggered at ``fps`` (the files below);
* ``dji`` — a consumer drone (:mod:`.dji_images`): no pose log; a mapping mission's photos on the
  survey lines, spaced for ``forward_overlap``, from a gimbal-stabilised camera, each a DJI JPEG
  whose EXIF and XMP ``drone-dji:`` tags hold its pose as the drone believes it — with the heading,
  tilt and height errors real drones have — while the pixels are rendered through the true pose.
  The drone takes off at the site centre (``ground_height_m``); its camera centre is the position.

Written to the output folder::

    geotags.csv          rover CSV, no header: lat, lon, altWGS84, altMSL, gpsStatus, label
    poses.csv            time_s, lat_deg, lon_deg, height_m, qw, qx, qy, qz, rtk_status,
                         radalt_m, radalt_snr, strobe
    images.csv           time_s, file             (only when frames are rendered)
    frames/<sec>.<nsec>.jpg
    calibration.yaml     Kalibr camchain-imucam (+ T_rad_imu, the altimeter lever arm)
    truth/targets.csv, truth/distractors.csv, truth/frames_true.csv, truth/campaign.json
    truth/dem.tif        the terrain (GeoTIFF; not written for level ground)
    orthomosaic.tif      the field seen straight down, a map GeoTIFF (RGBA, the site's UTM zone;
                         only when frames are rendered)

and with ``platform="dji"`` instead of the pose log, image list and calibration::

    frames/DJI_0001.JPG …            DJI JPEGs: EXIF GPS, XMP drone-dji: pose, DewarpData
    truth/dji_metadata_errors.csv    per frame: the metadata's heading, tilt, height and position errors

(``frames_true.csv`` then holds the true *gimbal* poses: quaternion gimbal → NED, x along the optical
axis, y image right, z image down.)

Heights are ellipsoidal (WGS84); ``altMSL = altWGS84 − N`` with N the geoid undulation stated in
``campaign.json`` (EGM96 at the site unless given). Times are seconds on the log's clock (a Unix-like
epoch), written exactly from integer nanoseconds.
"""
from __future__ import annotations

import csv
import json
import math
import platform
import re
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Callable, Optional

import numpy as np

from ..errors import InputError, check_cancel
from ..geometry.camera import NADIR_ROTATION, CameraModel, write_kalibr_yaml
from ..geometry.geodesy import LocalFrame, meridian_convergence_deg, proj_version, utm_epsg
from ..geometry.heights import geoid_undulation
from ..geometry.poses import FrameGeometry, FramePoses
from ..geometry.projection import footprints
from ..geometry.rigid import RigidTransform
from ..geometry.rotations import quat_to_rotmat, rotmat_to_euler_zyx, rotmat_to_quat, so3_exp
from .dji_images import DjiMetadataErrors, dji_camera_model, dji_frame_metadata, lens_for, write_frame
from .field import FEATURE_NAMES, P_CONTRAST, P_OUTER, P_R, FieldScene
from .flight import RUN_OUT_M, SimulatedFlight, correlated_noise, plan_survey
from .orthomosaic import ORTHO_PIXEL_M, ortho_grid, render_orthomosaic
from .render import FrameRenderer, Photometry, base_exposure_gain, motion_blur_px
from .terrain import DemTerrain, FlatTerrain, Terrain, synthetic_terrain, write_dem_geotiff

# The deployed payload camera (1920 × 1200) and its mounting; other image sizes scale the intrinsics.
DEPLOYED_SIZE = (1920, 1200)
DEPLOYED_INTRINSICS = (4264.4945, 4262.8927, 958.4594, 592.5033)
DEPLOYED_DISTORTION = (-0.08, 0.12, 4e-4, -3e-4, 0.0)
# The nadir camera (NADIR_ROTATION) is mounted with a small boresight misalignment (rad, about camera x, y, z)
# and a lever arm (body forward, right, down; m). The radar altimeter sits behind and below the IMU.
CAMERA_BORESIGHT_RAD = (0.004, -0.003, 0.006)
CAMERA_LEVER_ARM_M = (0.07, 0.02, 0.09)
RADAR_LEVER_ARM_M = (-0.05, 0.0, 0.12)

START_TIME_NS = 1_700_000_000 * 1_000_000_000   # the log clock's start (2023-11-14, a Unix time)
EXPOSURE_S = 0.001
JPEG_QUALITY = 92
IMAGE_DELAY_S = (0.003, 0.001)       # image time − strobe time: mean, std (s)
SNR_NORMAL = (19.0, 2.5)             # altimeter SNR (dB): mean, std, floored at 13.5 …
SNR_LOW = (4.0, 12.0)                # … except in short low-SNR bursts, about one a minute
LOW_SNR_BURSTS_PER_MINUTE = 1.0
LOW_SNR_RANGE_SIGMA_M = 0.25
RTK_FLOAT_SIGMA_M = (0.05, 0.05, 0.12)   # extra position error while the INS is in RTK float
GEOTAG_FLOAT_FRACTION = 0.05
GEOTAG_FLOAT_SIGMA_M = 0.06
DISTRACTOR_CLEARANCE_M = 0.5         # spurious geotags are at least this far from every target
TERRAIN_KINDS = ("flat", "plane", "hills")
PLATFORMS = ("ins", "dji")
#: Side overlap of neighbouring lines when none is given: the payload's, and a mapping mission's.
DEFAULT_SIDE_OVERLAP = {"ins": 0.3, "dji": 0.7}
DEM_CELL_M = 0.25                    # the written DEM's cell size, doubled while it would exceed …
DEM_MAX_CELLS = 2_000_000            # … this many cells
MAX_TILT_DEG = 15.0                  # the aircraft's largest tilt, which the terrain's extent allows for
DJI_ERRORS = DjiMetadataErrors()     # what a DJI drone's metadata gets wrong (see dji_images)
ORTHO_PIXEL_RANGE_M = (0.005, 1.0)   # the orthomosaic's pixel: from finer than a burrow to a farm overview
ORTHO_NAME = "orthomosaic.tif"

POSE_HEADER = ["time_s", "lat_deg", "lon_deg", "height_m", "qw", "qx", "qy", "qz", "rtk_status",
               "radalt_m", "radalt_snr", "strobe"]
DJI_ERRORS_HEADER = ["frame_index", "image", "heading_error_deg", "tilt_error_deg", "height_error_m",
                     "horizontal_error_m"]
FRAMES_TRUE_HEADER = ["frame_index", "image", "pose_row", "time_s", "image_time_s", "lat_deg", "lon_deg",
                      "height_m", "qw", "qx", "qy", "qz", "roll_deg", "pitch_deg", "yaw_deg", "radalt_m",
                      "ground_h_m", "line", "speed_ms", "exposure_gain"]
TARGETS_HEADER = ["id", "lat", "lon", "h_ground", "radius_m", "contrast", "surveyed", "geotag_row",
                  "mound_radius_m", "east_m", "north_m"]
SIGMA_NAMES = ("x (m)", "y (m)", "z (m)", "roll (deg)", "pitch (deg)", "yaw (deg)")


@dataclass
class CampaignConfig:
    """Parameters of a simulated campaign (units in the names; sigmas: x, y, z in m, roll, pitch,
    yaw in degrees). ``noise_off`` turns every measurement error off (Σ0, altimeter, RTK of the
    geotags, RTK-float episodes, low-SNR bursts, a DJI drone's metadata errors); the images keep their
    photometric realism.

    Terrain: ``terrain`` is ``flat`` (level ground at ``ground_height_m``), ``plane`` (rising at
    ``slope_deg`` away from ``slope_aspect_deg``, the direction the slope faces = downhill, degrees
    clockwise from true north; ``ground_height_m`` at the site) or ``hills`` (that plane plus smooth
    random hills of ``relief_m`` peak to peak, one hill and valley every ``hill_wavelength_m``). The
    aircraft keeps ``altitude_m`` above the terrain beneath it.

    Platform: ``platform`` is ``ins`` (pose log, altimeter, frames at ``fps``) or ``dji`` (DJI JPEGs
    with their own metadata, a photo every ``(1 − forward_overlap)`` footprint lengths on the lines;
    ``dji_dewarped``: the drone undistorts the JPEGs, ``DewarpFlag`` 1). ``side_overlap`` None: the
    platform's default (:data:`DEFAULT_SIDE_OVERLAP`).

    With ``render``, an orthomosaic of the field (:mod:`.orthomosaic`) is written too, with pixels of
    ``ortho_pixel_m``."""

    seed: int = 1
    n_targets: int = 40
    field_width_m: float = 40.0
    field_length_m: float = 30.0
    site_lat: float = -27.55
    site_lon: float = 151.95
    ground_height_m: float = 400.0
    altitude_m: float = 10.0
    speed_ms: float = 2.5
    fps: float = 5.0
    ins_rate_hz: float = 50.0
    image_width: int = 1920
    image_height: int = 1200
    sigmas: tuple = (0.01, 0.01, 0.06, 0.04, 0.04, 0.13)
    radalt_sigma_m: float = 0.03
    rtk_sigma_m: float = 0.015
    n_missed: int = 2
    n_spurious: int = 2
    render: bool = True
    noise_off: bool = False
    side_overlap: Optional[float] = None
    rtk_float_episodes: int = 1
    geoid_undulation_m: Optional[float] = None
    label: str = "burrow"
    terrain: str = "flat"
    slope_deg: float = 0.0
    slope_aspect_deg: float = 0.0
    relief_m: float = 0.0
    hill_wavelength_m: float = 40.0
    platform: str = "ins"
    forward_overlap: float = 0.8
    dji_dewarped: bool = False
    ortho_pixel_m: float = ORTHO_PIXEL_M
    look_alike_density: float = 1.0

    def validated(self) -> "CampaignConfig":
        """This configuration, checked; raises :class:`InputError` naming the parameter."""
        def need(ok, name, message):
            if not ok:
                raise InputError(message, field=name)

        need(self.n_targets >= 1, "N_TARGETS", f"must be at least 1, got {self.n_targets}")
        need(self.field_width_m >= 2 and self.field_length_m >= 2, "FIELD_WIDTH_M",
             "the field must be at least 2 m × 2 m")
        need(self.field_width_m * self.field_length_m <= 250_000, "FIELD_WIDTH_M",
             "the field is larger than 25 ha; simulate a part of it")
        need(-80 <= self.site_lat <= 84, "SITE_LAT", f"must lie in −80…84°, got {self.site_lat}")
        need(0 <= self.look_alike_density <= 20, "LOOK_ALIKE_DENSITY",
             f"must lie in 0…20 (times the default density), got {self.look_alike_density}")
        need(-180 <= self.site_lon <= 180, "SITE_LON", f"must lie in −180…180°, got {self.site_lon}")
        need(1.0 <= self.altitude_m <= 120.0, "ALTITUDE_M", f"must lie in 1…120 m, got {self.altitude_m}")
        need(0.2 <= self.speed_ms <= 20.0, "SPEED_MS", f"must lie in 0.2…20 m/s, got {self.speed_ms}")
        need(0.2 <= self.fps <= 60.0, "FPS", f"must lie in 0.2…60 frames/s, got {self.fps}")
        need(1.0 <= self.ins_rate_hz <= 1000.0, "INS_RATE_HZ", f"must lie in 1…1000 Hz, got {self.ins_rate_hz}")
        need(self.ins_rate_hz >= self.fps, "INS_RATE_HZ", "must be at least the camera rate FPS")
        need(32 <= self.image_width <= 8192 and 32 <= self.image_height <= 8192, "IMAGE_WIDTH",
             "image sizes must lie in 32…8192 px")
        need(len(self.sigmas) == 6 and all(s >= 0 and math.isfinite(s) for s in self.sigmas), "SIGMAS",
             "needs six non-negative numbers: x, y, z (m), roll, pitch, yaw (deg)")
        need(self.radalt_sigma_m >= 0, "RADALT_SIGMA_M", "must not be negative")
        need(self.rtk_sigma_m >= 0, "RTK_SIGMA_M", "must not be negative")
        need(0 <= self.n_missed <= self.n_targets, "N_MISSED", "must lie between 0 and N_TARGETS")
        need(self.n_spurious >= 0, "N_SPURIOUS", "must not be negative")
        need(self.side_overlap is None or 0.0 <= self.side_overlap <= 0.9, "SIDE_OVERLAP", "must lie in 0…0.9")
        need(self.platform in PLATFORMS, "PLATFORM",
             f"must be one of {', '.join(PLATFORMS)}, got {self.platform!r}")
        need(0.0 <= self.forward_overlap <= 0.95, "FORWARD_OVERLAP", "must lie in 0…0.95")
        need(self.rtk_float_episodes >= 0, "RTK_FLOAT_EPISODES", "must not be negative")
        need(self.terrain in TERRAIN_KINDS, "TERRAIN",
             f"must be one of {', '.join(TERRAIN_KINDS)}, got {self.terrain!r}")
        need(0.0 <= self.slope_deg <= 45.0, "SLOPE_DEG", f"must lie in 0…45°, got {self.slope_deg}")
        need(math.isfinite(self.slope_aspect_deg), "SLOPE_ASPECT_DEG", "must be a finite angle in degrees")
        need(0.0 <= self.relief_m <= 50.0, "RELIEF_M", f"must lie in 0…50 m, got {self.relief_m}")
        need(5.0 <= self.hill_wavelength_m <= 1000.0, "HILL_WAVELENGTH_M",
             f"must lie in 5…1000 m, got {self.hill_wavelength_m}")
        need(ORTHO_PIXEL_RANGE_M[0] <= self.ortho_pixel_m <= ORTHO_PIXEL_RANGE_M[1], "ORTHO_PIXEL_M",
             f"must lie in {ORTHO_PIXEL_RANGE_M[0]:g}…{ORTHO_PIXEL_RANGE_M[1]:g} m, got {self.ortho_pixel_m}")
        return self

    @property
    def effective_sigmas(self) -> np.ndarray:
        return np.zeros(6) if self.noise_off else np.asarray(self.sigmas, float)

    @property
    def effective_side_overlap(self) -> float:
        return DEFAULT_SIDE_OVERLAP[self.platform] if self.side_overlap is None else float(self.side_overlap)

    def frame_rate(self, plan) -> float:
        """Frames per second: ``fps`` on the payload; on a DJI mission a photo every
        (1 − forward_overlap) footprint lengths at the line speed."""
        if self.platform == "ins":
            return self.fps
        return self.speed_ms / max((1.0 - self.forward_overlap) * plan.footprint_along_m, 1e-3)


def parse_sigmas(text: str) -> tuple:
    """Σ0 standard deviations from "x, y, z, roll, pitch, yaw" (m and degrees)."""
    parts = [p for p in str(text).replace(";", ",").split(",") if p.strip()]
    try:
        values = tuple(float(p) for p in parts)
    except ValueError:
        raise InputError(f"'{text}' is not six comma-separated numbers "
                         "(x, y, z in m; roll, pitch, yaw in degrees)", field="SIGMAS") from None
    if len(values) != 6 or any(v < 0 or not math.isfinite(v) for v in values):
        raise InputError(f"'{text}' must be six non-negative numbers (x, y, z in m; roll, pitch, yaw "
                         "in degrees), e.g. 0.01,0.01,0.06,0.04,0.04,0.13", field="SIGMAS")
    return values


def deployed_camera(width: int = 1920, height: int = 1200) -> CameraModel:
    """The deployed payload camera scaled to ``width × height`` (same field of view), with its
    mounting: T_cam_imu (nadir, boresight, lever arm) and the radar altimeter's lever arm."""
    sx, sy = width / DEPLOYED_SIZE[0], height / DEPLOYED_SIZE[1]
    fx, fy, cx, cy = DEPLOYED_INTRINSICS
    r_cam_imu = so3_exp(np.asarray(CAMERA_BORESIGHT_RAD)) @ NADIR_ROTATION
    imu_from_cam = RigidTransform(r_cam_imu.T, CAMERA_LEVER_ARM_M)  # the camera's pose on the body
    return CameraModel(width, height, fx * sx, fy * sy, (cx + 0.5) * sx - 0.5, (cy + 0.5) * sy - 0.5,
                       DEPLOYED_DISTORTION, imu_from_cam.inverse().matrix, tuple(RADAR_LEVER_ARM_M),
                       source="simulated")


@dataclass
class CampaignResult:
    folder: Path
    n_frames: int
    n_poses: int
    n_geotags: int
    files: dict = field(default_factory=dict)


def simulate_campaign(config: CampaignConfig, output_folder, progress: Callable[[float], None] | None = None,
                      is_canceled: Callable[[], bool] | None = None) -> CampaignResult:
    """Simulate a campaign and write it to ``output_folder`` (see the module docstring)."""
    cfg = config.validated()
    out = Path(output_folder)
    (out / "truth").mkdir(parents=True, exist_ok=True)
    _remove_previous_frames(out)
    # Children 0–7 are those spawn(8) gave before terrain existed (level-ground campaigns are unchanged);
    # child 8 draws the hills, child 9 the DJI metadata's errors.
    seeds = np.random.SeedSequence(int(cfg.seed)).spawn(10)
    rng_flight, rng_pose, rng_radalt, rng_geotag, rng_photo, rng_time = (
        np.random.default_rng(s) for s in (seeds[1], seeds[2], seeds[3], seeds[4], seeds[5], seeds[6]))
    undulation = (float(geoid_undulation(cfg.site_lat, cfg.site_lon)) if cfg.geoid_undulation_m is None
                  else float(cfg.geoid_undulation_m))

    dji = cfg.platform == "dji"
    camera = (dji_camera_model(cfg.image_width, cfg.image_height, cfg.dji_dewarped) if dji
              else deployed_camera(cfg.image_width, cfg.image_height))
    local = LocalFrame(cfg.site_lat, cfg.site_lon, cfg.ground_height_m)
    plan = plan_survey(camera, cfg.altitude_m, cfg.field_width_m, cfg.field_length_m, cfg.effective_side_overlap)
    fps = cfg.frame_rate(plan)
    terrain, dem = _terrain(cfg, local, camera, plan, int(seeds[8].generate_state(1)[0]))
    rise = None if dem is None else (lambda east, north: terrain.height_at(east, north) - cfg.ground_height_m)
    flight = SimulatedFlight(plan, cfg.altitude_m, cfg.speed_ms, rng_flight, terrain_rise=rise)

    times_ns, strobe = _log_times(cfg, flight.duration_s, fps)
    truth = flight.states(times_ns, local, cfg.ground_height_m)
    frame_rows = np.flatnonzero(strobe)
    if dji:  # a mapping mission takes its photos on the survey lines, not in the turns
        frame_rows = frame_rows[truth.line[frame_rows] >= 0]
    n_frames = len(frame_rows)
    t_frames = times_ns[frame_rows] * 1e-9
    metadata = (dji_frame_metadata(np.random.default_rng(seeds[9]), t_frames, truth.local[frame_rows],
                                   quat_to_rotmat(truth.quat[frame_rows]), truth.height[frame_rows],
                                   cfg.ground_height_m, undulation, local, _dji_errors(cfg))
                if dji else None)
    frame_poses = FramePoses(np.arange(n_frames), truth.lat[frame_rows], truth.lon[frame_rows],
                             truth.height[frame_rows], metadata.quat_true if dji else truth.quat[frame_rows],
                             terrain.height_at(truth.local[frame_rows, 0], truth.local[frame_rows, 1]), camera)
    geometry = FrameGeometry(frame_poses, local)

    # The field covers everything a frame sees (its footprint on the ground, plus a margin).
    corners, complete = footprints(geometry, terrain.ground_model(geometry), per_edge=terrain.edge_samples)
    if not np.all(complete):
        raise InputError(f"{int(np.sum(~complete))} frames see past the simulated terrain; lower the slope or "
                         "relief, or fly higher", field="SLOPE_DEG")
    margin = 1.0
    domain = (np.nanmin(corners[..., 0]) - margin, np.nanmax(corners[..., 0]) + margin,
              np.nanmin(corners[..., 1]) - margin, np.nanmax(corners[..., 1]) + margin)
    along_east = cfg.field_width_m >= cfg.field_length_m
    try:
        scene = FieldScene(seeds[0], domain, (cfg.field_width_m / 2, cfg.field_length_m / 2), cfg.n_targets,
                           field_axis_azimuth=math.pi / 2 if along_east else 0.0,
                           distractor_density=cfg.look_alike_density)
    except ValueError as exc:
        raise InputError(str(exc), field="N_TARGETS") from exc
    feature_lat, feature_lon, _ = local.to_geodetic(np.c_[scene.features.xy, np.zeros(len(scene.features))])
    feature_h = terrain.height_at(scene.features.xy[:, 0], scene.features.xy[:, 1])
    feature_xyz = local.from_geodetic(feature_lat, feature_lon, feature_h)

    geotags, geotag_row = _geotags(cfg, scene, feature_lat, feature_lon, feature_h, undulation, local, terrain,
                                   rng_geotag)
    files = {}
    files["geotags"] = _write_csv(out / "geotags.csv", None, geotags)
    files["field"] = _write_field(out / "field.geojson", cfg, local)
    if dji:
        radalt_true = None
        image_ns = times_ns[frame_rows]
        image_names = [f"frames/DJI_{i + 1:04d}.JPG" for i in range(n_frames)]
        for stale in ("poses.csv", "calibration.yaml"):  # an earlier payload run's, not this drone's
            (out / stale).unlink(missing_ok=True)
        files["dji_errors"] = _write_csv(out / "truth" / "dji_metadata_errors.csv", DJI_ERRORS_HEADER,
                                         _dji_error_rows(image_names, metadata))
    else:
        logged = _logged_poses(cfg, truth, local, rng_pose)
        radalt_true, radalt, snr = _altimeter(cfg, camera, truth, terrain, rng_radalt)
        image_ns = _image_times(cfg, strobe_ns=times_ns[frame_rows], rng=rng_time)
        image_names = [f"frames/{_ns_text(START_TIME_NS + t)}.jpg" for t in image_ns]
        files["poses"] = _write_csv(out / "poses.csv", POSE_HEADER, _pose_rows(times_ns, logged, radalt, snr, strobe))
        files["calibration"] = out / "calibration.yaml"
        write_kalibr_yaml(camera, files["calibration"])
    if dem is not None:
        files["dem"] = Path(write_dem_geotiff(dem, out / "truth" / "dem.tif"))
    else:
        (out / "truth" / "dem.tif").unlink(missing_ok=True)  # an earlier run's terrain is not this one's
    files["targets"] = _write_csv(out / "truth" / "targets.csv", TARGETS_HEADER,
                                  _target_rows(scene, feature_lat, feature_lon, feature_h, geotag_row))
    files["distractors"] = _write_csv(
        out / "truth" / "distractors.csv", ["id", "kind", "lat", "lon", "radius_m", "east_m", "north_m"],
        [[i, FEATURE_NAMES[int(scene.features.kind[i])], f"{feature_lat[i]:.10f}", f"{feature_lon[i]:.10f}",
          f"{scene.features.params[i, P_R]:.4f}", f"{scene.features.xy[i, 0]:.4f}", f"{scene.features.xy[i, 1]:.4f}"]
         for i in range(scene.n_targets, len(scene.features))])

    # Per-frame camera state: exposure follows the clouds (auto exposure, partly), white balance and
    # focus drift slowly.
    photometry = (_photometry(fps, scene, geometry, truth.velocity[frame_rows], t_frames, rng_photo)
                  if cfg.render else [])
    files["frames_true"] = _write_csv(
        out / "truth" / "frames_true.csv", FRAMES_TRUE_HEADER,
        _frame_truth_rows(frame_rows, times_ns, image_ns, image_names, truth, radalt_true, frame_poses, photometry,
                          with_pose_log=not dji))
    files["campaign"] = out / "truth" / "campaign.json"
    record = _campaign_record(cfg, camera, local, undulation, plan, scene, n_frames, len(times_ns), len(geotags),
                              flight, dem, fps)
    if dji:
        record["dji"] = _dji_record(cfg, camera, metadata, fps, plan, undulation)
    grid = ortho_grid(scene, local, record["crs"], cfg.ortho_pixel_m) if cfg.render else None
    if grid is not None:
        record["orthomosaic"] = _ortho_record(grid, flight)
    files["campaign"].write_text(json.dumps(record, indent=2), encoding="utf-8")

    if cfg.render:
        files["frames"] = out / "frames"
        if not dji:
            image_rows = [[_ns_text(START_TIME_NS + t), name] for t, name in zip(image_ns, image_names)]
            files["images"] = _write_csv(out / "images.csv", ["time_s", "file"], image_rows)
        write = _dji_writer(lens_for(camera, cfg.dji_dewarped), metadata, image_ns) if dji else None
        renderer = FrameRenderer(camera, scene, terrain, int(seeds[7].generate_state(1)[0]), feature_xyz)
        # Progress in proportion to the pixels rendered: the frames, then the map.
        frames_share = n_frames * camera.width * camera.height / (
            n_frames * camera.width * camera.height + grid.width * grid.height)
        _render_frames(renderer, geometry, t_frames, photometry, seeds[7].spawn(n_frames),
                       [out / name for name in image_names], _progress_part(progress, 0.0, frames_share),
                       is_canceled, write)
        files["orthomosaic"] = Path(render_orthomosaic(
            out / ORTHO_NAME, scene, terrain, local, grid, (feature_lat, feature_lon), 0.5 * flight.duration_s,
            _progress_part(progress, frames_share, 1.0), is_canceled))
    else:
        (out / ORTHO_NAME).unlink(missing_ok=True)  # an earlier run's map would not show this field
        if progress is not None:
            progress(1.0)
    return CampaignResult(out, n_frames, len(times_ns), len(geotags), files)


def _progress_part(progress: Callable[[float], None] | None, start: float, end: float):
    """``progress`` for one stage: the stage's fractions 0…1 reported as ``start``…``end``."""
    if progress is None:
        return None
    return lambda fraction: progress(start + (end - start) * fraction)


def _ortho_record(grid, flight) -> dict:
    return {"file": ORTHO_NAME, **grid.to_dict(), "bands": "red, green, blue, alpha (0 off the simulated ground)",
            "rendered": "the field model seen straight down at the pixel centres (no frames mosaicked), "
                        "under the sky of the flight's middle moment",
            "cloud_time_s": round(0.5 * flight.duration_s, 3)}


def _terrain(cfg: CampaignConfig, local: LocalFrame, camera: CameraModel, plan, seed: int):
    """The simulated ground and, over terrain, the DEM behind it (None for level ground).

    The DEM is centred on the site in its UTM zone and covers every point a frame can see: the flight
    path (the survey lines, turns and run-outs) widened by the horizontal reach of the image corners,
    with the aircraft tilted by up to ``MAX_TILT_DEG``, over terrain falling away at its steepest. On a
    slope of gradient G below the aircraft a ray of horizontal ratio r from ``altitude_m`` above the
    ground reaches d = r·altitude / (1 − r·G). The hills' steepest gradient is taken as 2π·relief /
    wavelength, twice that of a sine of that height and wavelength; the footprints and the altimeter
    are checked against the terrain afterwards, so a rougher draw is reported, not rendered wrong.
    """
    if cfg.terrain == "flat":
        return FlatTerrain(local, cfg.ground_height_m), None
    corners = camera.pixel_rays(camera.corner_pixels())
    view = math.atan(float(np.max(np.hypot(corners[:, 0], corners[:, 1]))))
    ratio = math.tan(view + math.radians(MAX_TILT_DEG))
    steepest = math.tan(math.radians(cfg.slope_deg))
    if cfg.terrain == "hills":
        steepest += 2.0 * math.pi * cfg.relief_m / cfg.hill_wavelength_m
    if ratio * steepest >= 0.8:
        raise InputError(f"terrain rising up to {math.degrees(math.atan(steepest)):.0f}° is too steep for the "
                         f"camera's {math.degrees(view):.0f}° half field of view: the frames would look along it; "
                         "lower SLOPE_DEG or RELIEF_M, or lengthen HILL_WAVELENGTH_M", field="SLOPE_DEG")
    pad = RUN_OUT_M + 0.5 * plan.spacing_m + 0.5 + cfg.altitude_m * ratio / (1.0 - ratio * steepest) + 1.0
    e0, e1, n0, n1 = plan.extent
    extent = (e0 - pad, e1 + pad, n0 - pad, n1 + pad)
    # The DEM's north-up UTM grid is turned against the local frame by the meridian convergence γ
    # and scaled by the map's scale factor (< 1.001 in a UTM zone): its half sides must hold the
    # local box turned by γ, plus two cells.
    half_e, half_n = max(-extent[0], extent[1]), max(-extent[2], extent[3])
    gamma = math.radians(float(meridian_convergence_deg(cfg.site_lat, cfg.site_lon,
                                                        f"EPSG:{utm_epsg(cfg.site_lat, cfg.site_lon)}")))
    cos_g, sin_g = abs(math.cos(gamma)), abs(math.sin(gamma))
    cell = DEM_CELL_M
    while True:
        size = (2.0 * (1.001 * (half_e * cos_g + half_n * sin_g) + 2 * cell),
                2.0 * (1.001 * (half_e * sin_g + half_n * cos_g) + 2 * cell))
        if size[0] * size[1] / cell ** 2 <= DEM_MAX_CELLS:
            break
        cell *= 2.0
    dem = synthetic_terrain(cfg.site_lat, cfg.site_lon, kind=cfg.terrain, slope_deg=cfg.slope_deg,
                            aspect_deg=cfg.slope_aspect_deg, relief_m=cfg.relief_m,
                            base_height_m=cfg.ground_height_m, size_m=size, cell_m=cell,
                            wavelength_m=cfg.hill_wavelength_m, seed=seed, vertical_datum="ellipsoidal")
    dem.source = "simulated terrain (truth/dem.tif)"
    return DemTerrain(local, dem, extent), dem


def _log_times(cfg: CampaignConfig, duration_s: float, fps: float):
    """Times (int64 ns from the start) of the pose log's rows and its strobe mask: every INS message
    at INS_RATE_HZ, plus a row of its own for each exposure at ``fps`` that falls between messages."""
    ins_ns = np.round(np.arange(int(duration_s * cfg.ins_rate_hz) + 1) * (1e9 / cfg.ins_rate_hz)).astype(np.int64)
    strobe_ns = np.round(np.arange(int(duration_s * fps) + 1) * (1e9 / fps)).astype(np.int64)
    times_ns = np.union1d(ins_ns, strobe_ns)
    times_ns = times_ns[times_ns <= int(duration_s * 1e9)]
    return times_ns, np.isin(times_ns, strobe_ns)


def _render_frames(renderer: FrameRenderer, geometry: FrameGeometry, t_frames, photometry, frame_seeds, paths,
                   progress, is_canceled, write=None) -> None:
    """Render and write every frame (each with its own random stream), reporting progress per frame
    and stopping between frames when cancelled. ``write(i, path, image)`` writes a frame with its
    metadata; None: a plain JPEG."""
    import cv2

    if paths:
        paths[0].parent.mkdir(exist_ok=True)
    for i, path in enumerate(paths):
        check_cancel(is_canceled)
        image = renderer.render(geometry, i, t_frames[i], photometry[i], np.random.default_rng(frame_seeds[i]))
        if write is not None:
            write(i, path, image)
        elif not cv2.imwrite(str(path), image, [cv2.IMWRITE_JPEG_QUALITY, JPEG_QUALITY]):
            raise InputError("cannot write the frame (disk full or no permission?)", source=path)
        if progress is not None:
            progress((i + 1) / len(paths))


# ---------------------------------------------------------------------- measurements
def _logged_poses(cfg: CampaignConfig, truth, local: LocalFrame, rng):
    """Logged INS poses: truth + Σ0 noise (+ RTK-float episodes). Returns (lat, lon, h, quat, status)."""
    n = len(truth.time_ns)
    sig = cfg.effective_sigmas
    position = truth.local + rng.standard_normal((n, 3)) * sig[:3]
    # Attitude noise: small rotations about the body roll (x), pitch (y) and yaw (z) axes.
    attitude = rng.standard_normal((n, 3)) * np.radians(sig[3:])
    r_ned_body = quat_to_rotmat(truth.quat) @ so3_exp(attitude)
    status = np.full(n, 3)
    episodes = 0 if cfg.noise_off else cfg.rtk_float_episodes
    t = truth.time_ns * 1e-9
    for _ in range(episodes):
        start = rng.uniform(0.1, 0.85) * t[-1]
        rows = np.flatnonzero((t >= start) & (t < start + rng.uniform(2.0, 5.0)))
        status[rows] = 2
        dt = 1.0 / cfg.ins_rate_hz
        position[rows] += correlated_noise(rng, len(rows), dt, 1.0, 1.0, 3) * np.asarray(RTK_FLOAT_SIGMA_M)
    lat, lon, h = local.to_geodetic(position)
    return np.asarray(lat), np.asarray(lon), np.asarray(h), rotmat_to_quat(r_ned_body), status


def _altimeter(cfg: CampaignConfig, camera: CameraModel, truth, terrain, rng):
    """True range, logged range and SNR of the radar altimeter (ranging along the body z axis)."""
    n = len(truth.time_ns)
    origin = truth.local + np.einsum("nij,j->ni", truth.r_local_body, np.asarray(camera.t_imu_rad))
    true_range = terrain.intersect(origin, truth.r_local_body[:, :, 2])
    if np.any(np.isnan(true_range)):
        raise InputError("the radar altimeter's beam misses the simulated terrain; lower the slope or relief",
                         field="SLOPE_DEG")
    sigma = 0.0 if cfg.noise_off else cfg.radalt_sigma_m
    logged = true_range + rng.standard_normal(n) * sigma
    snr = np.maximum(SNR_NORMAL[0] + SNR_NORMAL[1] * rng.standard_normal(n), 13.5)
    if not cfg.noise_off:
        t = truth.time_ns * 1e-9
        for _ in range(max(1, int(round(LOW_SNR_BURSTS_PER_MINUTE * t[-1] / 60.0)))):
            start = rng.uniform(0.05, 0.95) * t[-1]
            rows = np.flatnonzero((t >= start) & (t < start + rng.uniform(0.2, 0.8)))
            snr[rows] = rng.uniform(*SNR_LOW, len(rows))
            logged[rows] = true_range[rows] + rng.standard_normal(len(rows)) * LOW_SNR_RANGE_SIGMA_M
    return true_range, logged, snr


def _geotags(cfg: CampaignConfig, scene: FieldScene, lat, lon, h, undulation, local: LocalFrame,
             terrain: Terrain, rng):
    """Rover rows in walking order, and each target's 1-based geotag row (0: missed)."""
    n = scene.n_targets
    xy = scene.features.xy[:n]
    missed = set(rng.choice(n, size=cfg.n_missed, replace=False).tolist()) if cfg.n_missed else set()
    surveyed = [i for i in range(n) if i not in missed]
    # The surveyor walks the field in 3 m strips, alternating direction.
    strip = np.floor((xy[surveyed, 1] + cfg.field_length_m / 2) / 3.0).astype(int)
    order = sorted(range(len(surveyed)),
                   key=lambda k: (strip[k], xy[surveyed[k], 0] * (1 if strip[k] % 2 == 0 else -1)))
    entries = [("target", surveyed[k]) for k in order]
    spurious = _spurious_points(cfg, xy, rng)
    for point in spurious:
        entries.insert(int(rng.integers(0, len(entries) + 1)), ("spurious", point))
    n_float = 0 if cfg.noise_off else int(round(GEOTAG_FLOAT_FRACTION * len(entries)))
    float_rows = set(rng.choice(len(entries), size=min(n_float, len(entries)), replace=False).tolist())
    rows, geotag_row = [], np.zeros(n, int)
    sigma = 0.0 if cfg.noise_off else cfg.rtk_sigma_m
    for r, (kind, item) in enumerate(entries):
        is_float = r in float_rows
        s = GEOTAG_FLOAT_SIGMA_M if is_float else sigma
        if kind == "target":
            geotag_row[item] = r + 1
            point = np.array([xy[item, 0], xy[item, 1]])
            ground = float(h[item])
        else:
            point = item
            ground = float(terrain.height_at(point[:1], point[1:])[0])
        err = rng.standard_normal(3) * np.array([s, s, 2 * s])
        g_lat, g_lon, _ = local.to_geodetic(np.array([point[0] + err[0], point[1] + err[1], 0.0]))
        alt = ground + err[2]
        rows.append([f"{float(g_lat):.10f}", f"{float(g_lon):.10f}", f"{alt:.4f}", f"{alt - undulation:.4f}",
                     5 if is_float else 4, cfg.label])
    return rows, geotag_row


def _spurious_points(cfg: CampaignConfig, targets_xy, rng):
    """Positions (east, north) in the field away from every target (a press with nothing there)."""
    points = []
    hw, hl = cfg.field_width_m / 2 - 0.3, cfg.field_length_m / 2 - 0.3
    for _ in range(cfg.n_spurious):
        for _attempt in range(10000):
            p = np.array([rng.uniform(-hw, hw), rng.uniform(-hl, hl)])
            if np.min(np.hypot(*(targets_xy - p).T)) > DISTRACTOR_CLEARANCE_M:
                break
        points.append(p)
    return points


def _image_times(cfg: CampaignConfig, strobe_ns, rng):
    """Image timestamps (ns): the strobe plus the camera's small, jittery delay (≪ 1/fps)."""
    delay = IMAGE_DELAY_S[0] + IMAGE_DELAY_S[1] * rng.standard_normal(len(strobe_ns))
    delay = np.clip(delay, 0.0, 0.2 / cfg.fps)
    return strobe_ns + np.round(delay * 1e9).astype(np.int64)


def _photometry(fps: float, scene: FieldScene, geometry: FrameGeometry, velocity, t_frames, rng):
    n = len(t_frames)
    if n == 0:
        return []
    st = scene.style
    dt = 1.0 / fps
    drift = correlated_noise(rng, n, dt, 8.0, 1.0, 5)
    nadir = geometry.ground_point
    cloud = scene.cloud_factor(nadir[:, 0], nadir[:, 1], t_frames)
    light = (1.0 - st.direct_fraction) + st.direct_fraction * cloud
    base = base_exposure_gain(scene)
    out = []
    for i in range(n):
        gain = base * light[i] ** -0.7 * math.exp(0.06 * drift[i, 0])
        wb = (1.0 + 0.03 * drift[i, 1], 1.0, 1.0 + 0.03 * drift[i, 2])
        defocus = float(np.clip(0.55 + 0.12 * drift[i, 3], 0.35, 0.9))
        motion = motion_blur_px(geometry, i, velocity[i], EXPOSURE_S)
        out.append(Photometry(gain, wb, defocus, motion))
    return out


# ---------------------------------------------------------------------- writing
FRAME_NAME = re.compile(r"^(\d+\.\d{9}\.jpg|DJI_\d{4}\.JPG)$")


def _remove_previous_frames(out: Path) -> None:
    """Frames and image list of an earlier run into the same folder, which would otherwise be
    imported with this run's pose log (only our own timestamped JPEGs are touched)."""
    (out / "images.csv").unlink(missing_ok=True)
    frames = out / "frames"
    if frames.is_dir():
        for path in frames.iterdir():
            if FRAME_NAME.match(path.name):
                path.unlink()


def _ns_text(ns: int) -> str:
    """Seconds with nine decimals, exact from integer nanoseconds (also the frame file stem)."""
    ns = int(ns)
    return f"{ns // 1_000_000_000}.{ns % 1_000_000_000:09d}"


def _write_field(path: Path, cfg: CampaignConfig, local: LocalFrame) -> Path:
    """The field's boundary (the rectangle the targets lie in, centred on the site) as a GeoJSON polygon in WGS84:
    what a farm map holds and Partition field cuts."""
    hw, hl = cfg.field_width_m / 2, cfg.field_length_m / 2
    corners = np.array([[-hw, -hl, 0.0], [hw, -hl, 0.0], [hw, hl, 0.0], [-hw, hl, 0.0], [-hw, -hl, 0.0]])
    lat, lon, _ = local.to_geodetic(corners)
    ring = [[round(float(x), 9), round(float(y), 9)] for x, y in zip(lon, lat)]
    feature = {"type": "Feature", "properties": {"name": "field"},
               "geometry": {"type": "Polygon", "coordinates": [ring]}}
    path.write_text(json.dumps({"type": "FeatureCollection", "features": [feature]}), encoding="utf-8")
    return path


def _write_csv(path: Path, header, rows) -> Path:
    with open(path, "w", newline="", encoding="utf-8") as fh:
        writer = csv.writer(fh, lineterminator="\n")
        if header:
            writer.writerow(header)
        writer.writerows(rows)
    return path


def _pose_rows(times_ns, logged, radalt, snr, strobe):
    lat, lon, h, quat, status = logged
    for i in range(len(times_ns)):
        q = quat[i]
        yield [_ns_text(START_TIME_NS + times_ns[i]), f"{lat[i]:.11f}", f"{lon[i]:.11f}", f"{h[i]:.5f}",
               f"{q[0]:.10f}", f"{q[1]:.10f}", f"{q[2]:.10f}", f"{q[3]:.10f}", int(status[i]),
               f"{radalt[i]:.4f}", f"{snr[i]:.1f}", int(strobe[i])]


def _target_rows(scene: FieldScene, lat, lon, h, geotag_row):
    f = scene.features
    for i in range(scene.n_targets):
        yield [i + 1, f"{lat[i]:.10f}", f"{lon[i]:.10f}", f"{h[i]:.4f}", f"{f.params[i, P_R]:.4f}",
               f"{f.params[i, P_CONTRAST]:.3f}", int(geotag_row[i] > 0), int(geotag_row[i]) or "",
               f"{f.params[i, P_OUTER]:.4f}", f"{f.xy[i, 0]:.4f}", f"{f.xy[i, 1]:.4f}"]


def _frame_truth_rows(frame_rows, times_ns, image_ns, image_names, truth, radalt_true, poses, photometry,
                      with_pose_log=True):
    roll, pitch, yaw = rotmat_to_euler_zyx(quat_to_rotmat(poses.quat))
    for i, row in enumerate(frame_rows):
        q = poses.quat[i]
        yield [i, image_names[i], row + 1 if with_pose_log else "", _ns_text(START_TIME_NS + times_ns[row]),
               _ns_text(START_TIME_NS + image_ns[i]), f"{poses.lat[i]:.11f}", f"{poses.lon[i]:.11f}",
               f"{poses.height[i]:.5f}", f"{q[0]:.10f}", f"{q[1]:.10f}", f"{q[2]:.10f}", f"{q[3]:.10f}",
               f"{math.degrees(roll[i]):.5f}", f"{math.degrees(pitch[i]):.5f}",
               f"{math.degrees(yaw[i]) % 360.0:.5f}", "" if radalt_true is None else f"{radalt_true[row]:.5f}",
               f"{poses.ground_height[i]:.4f}", int(truth.line[row]),
               f"{np.linalg.norm(truth.velocity[row]):.3f}", f"{photometry[i].gain:.4f}" if photometry else ""]


def _dji_errors(cfg: CampaignConfig) -> DjiMetadataErrors:
    return DjiMetadataErrors.none() if cfg.noise_off else DJI_ERRORS


def _dji_writer(tags_camera, metadata, image_ns):
    """``write(i, path, image)`` for :func:`_render_frames`: frame i as a DJI JPEG with its metadata."""
    def write(i, path, image):
        write_frame(path, image, tags_camera, metadata, i, (START_TIME_NS + int(image_ns[i])) * 1e-9, JPEG_QUALITY)
    return write


def _dji_error_rows(image_names, metadata):
    for i, name in enumerate(image_names):
        yield [i, name, f"{metadata.heading_error_deg[i]:.5f}", f"{metadata.tilt_error_deg[i]:.5f}",
               f"{metadata.height_error_m[i]:.4f}", f"{metadata.horizontal_error_m[i]:.4f}"]


def _dji_record(cfg, camera, metadata, fps, plan, undulation) -> dict:
    tags = lens_for(camera, cfg.dji_dewarped)
    return {"camera": {"make": tags.make, "model": tags.model, "serial": tags.serial,
                       "dewarp_flag": int(cfg.dji_dewarped), "lens": tags.lens.to_dict()},
            "photo_interval_s": round(1.0 / fps, 4),
            "photo_spacing_m": round(cfg.speed_ms / fps, 4),
            "forward_overlap": cfg.forward_overlap, "side_overlap": cfg.effective_side_overlap,
            "takeoff": {"east_m": 0.0, "north_m": 0.0, "height_m": cfg.ground_height_m,
                        "height_msl_m": round(cfg.ground_height_m - undulation, 4)},
            "heights": "AbsoluteAltitude and EXIF GPSAltitude above mean sea level (ellipsoidal − N); "
                       "RelativeAltitude above the take-off point",
            "error_model": _dji_errors(cfg).to_dict(), "drawn": metadata.biases,
            "errors_file": "truth/dji_metadata_errors.csv",
            "truth_orientation": "frames_true.csv quaternions: gimbal (x optical axis, y image right, z image "
                                 "down) → NED; the metadata's = exp([e]^)·true, e the drone's attitude error"}


def _campaign_record(cfg, camera, local, undulation, plan, scene, n_frames, n_poses, n_geotags, flight,
                     dem, fps) -> dict:
    import cv2
    import scipy

    params = asdict(cfg)
    params["sigmas"] = list(cfg.sigmas)
    params["side_overlap"] = cfg.effective_side_overlap
    kinds = scene.features.kind
    return {
        "generator": "birdseye:simulatecampaign",
        "seed": cfg.seed,
        "parameters": params,
        "site": {"lat": cfg.site_lat, "lon": cfg.site_lon, "ground_height_m": cfg.ground_height_m,
                 "height_reference": "WGS84 ellipsoid"},
        "local_frame": {**local.to_dict(), "axes": "east, north, up (m), tangent at the site"},
        "crs": f"EPSG:{utm_epsg(cfg.site_lat, cfg.site_lon)}",
        "geoid_undulation_m": round(undulation, 4),
        "geoid_source": "GEOID_UNDULATION_M" if cfg.geoid_undulation_m is not None else "EGM96 (PROJ egm96_15.gtx)",
        "altMSL": "altWGS84 - geoid_undulation_m",
        "log_clock_start_s": START_TIME_NS // 1_000_000_000,
        "conventions": {
            "quaternion": "(qw, qx, qy, qz), v_ned = R(q) v_body, body forward-right-down, NED at the pose",
            "pose_noise": "position: local east, north, up (m); attitude: R_logged = R_true·exp([δroll, "
                          "δpitch, δyaw]^) (body axes, rad); independent per log row",
            "radalt": "range (m) from the altimeter (T_rad_imu) along the body z axis to the ground",
            "strobe": "1 on rows at the camera's exposure (mid-exposure); frames_true.csv holds their true poses",
            "image_time": "strobe time + delay (mean %.1f ms, std %.1f ms)" % (IMAGE_DELAY_S[0] * 1e3,
                                                                                IMAGE_DELAY_S[1] * 1e3),
            "rtk_status": "3 fixed, 2 float (RTK-float episodes add correlated position error)",
            "gpsStatus": "4 RTK fixed, 5 float (geotags)",
        },
        "camera": camera.to_dict(),
        "platform": cfg.platform,
        "frame_rate_fps": round(fps, 6),
        "exposure_s": EXPOSURE_S,
        "jpeg_quality": JPEG_QUALITY,
        "flight": {"lines": np.round(plan.lines, 4).tolist(), "line_spacing_m": round(plan.spacing_m, 4),
                   "footprint_across_m": round(plan.footprint_across_m, 4),
                   "footprint_along_m": round(plan.footprint_along_m, 4),
                   "duration_s": round(flight.duration_s, 3), "wind_ms": np.round(flight.wind, 3).tolist()},
        "field": {"width_m": cfg.field_width_m, "length_m": cfg.field_length_m,
                  "domain_m": [round(v, 3) for v in scene.domain], "style": scene.style.to_dict(),
                  "features": {FEATURE_NAMES[k]: int(np.sum(kinds == k)) for k in FEATURE_NAMES}},
        "terrain": _terrain_record(cfg, dem),
        "counts": {"frames": n_frames, "pose_rows": n_poses, "targets": cfg.n_targets,
                   "geotags": n_geotags, "missed": cfg.n_missed, "spurious": cfg.n_spurious},
        "versions": {"python": platform.python_version(), "numpy": np.__version__, "scipy": scipy.__version__,
                     "opencv": cv2.__version__, "pyproj": proj_version(), "birdseye": _plugin_version()},
    }


def _terrain_record(cfg: CampaignConfig, dem) -> dict:
    if dem is None:
        return {"kind": "flat", "height_m": cfg.ground_height_m, "flight": "ALTITUDE_M above the level ground"}
    x0, dx, y0, dy = dem.geotransform
    rows, cols = dem.heights.shape
    record = {"kind": cfg.terrain, "slope_deg": cfg.slope_deg,
              "slope_aspect_deg": cfg.slope_aspect_deg,
              "aspect": "direction the slope faces (downhill), degrees clockwise from true north",
              "height_at_site_m": cfg.ground_height_m,
              "dem": "truth/dem.tif", "dem_crs": str(dem.crs), "dem_cell_m": dx,
              "dem_extent": {"xmin": x0, "ymin": y0 + rows * dy, "xmax": x0 + cols * dx, "ymax": y0},
              "dem_heights": "WGS84 ellipsoidal (m), bilinear between cell centres",
              "dem_height_range_m": [round(float(np.min(dem.heights)), 4), round(float(np.max(dem.heights)), 4)],
              "flight": "terrain following: ALTITUDE_M above the terrain beneath the aircraft"}
    if cfg.terrain == "hills":
        record.update(relief_m=cfg.relief_m, hill_wavelength_m=cfg.hill_wavelength_m)
    return record


def _plugin_version() -> str:
    meta = Path(__file__).resolve().parents[3] / "metadata.txt"
    try:
        for line in meta.read_text(encoding="utf-8").splitlines():
            if line.startswith("version="):
                return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return "unknown"
