"""A synthetic BirdsEye flight with known truth: pose log, image folder and calibration.

Used by the flight-log tests and the import benchmark. The drone flies straight legs (a lawnmower) at
constant height over level ground; INS rows at ``ins_hz`` with a strobe every ``ins_hz / fps`` rows;
images named ``<sec>.<nsec>.png`` (empty files: the importer never opens them) or listed in
``images.csv``. Radar ranges are consistent with the tilt-corrected ground model, so the true ground
height is ``ground_h`` everywhere.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

HEADER = "time_s,lat_deg,lon_deg,height_m,qw,qx,qy,qz,rtk_status,radalt_m,radalt_snr,strobe"

CALIBRATION_YAML = """cam0:
  camera_model: pinhole
  intrinsics: [800.0, 800.0, 319.5, 239.5]
  distortion_model: radtan
  distortion_coeffs: [0.0, 0.0, 0.0, 0.0]
  resolution: [640, 480]
  T_cam_imu:
  - [0.0, 1.0, 0.0, 0.0]
  - [-1.0, 0.0, 0.0, 0.0]
  - [0.0, 0.0, 1.0, 0.0]
  - [0.0, 0.0, 0.0, 1.0]
"""


def flight_poses(n_frames: int, ins_hz: float = 50.0, fps: float = 5.0, lat0: float = 52.0,
                 lon0: float = 5.0, ground_h: float = 45.0, altitude: float = 12.0, speed: float = 3.0,
                 leg_m: float = 60.0, t0: float = 1_700_000_000.0, attitude_noise_deg: float = 2.0,
                 seed: int = 1) -> dict:
    """Pose-log columns (dict of arrays) for ``n_frames`` strobes; vectorised, any size."""
    from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
    from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat

    rng = np.random.default_rng(seed)
    per_frame = int(round(ins_hz / fps))
    n = n_frames * per_frame
    t = t0 + np.arange(n) / ins_hz
    s = speed * (t - t0)  # distance flown
    leg = np.floor(s / leg_m).astype(np.int64)
    along = s - leg * leg_m
    forward = leg % 2 == 0
    north = np.where(forward, along, leg_m - along)
    east = leg * 8.0
    yaw = np.where(forward, 0.0, np.pi)
    roll, pitch = np.radians(attitude_noise_deg) * rng.standard_normal((2, n))
    local = LocalFrame(lat0, lon0, ground_h)
    lat, lon, h = local.to_geodetic(np.stack([east, north, np.full(n, altitude)], axis=1))
    quat = rotmat_to_quat(euler_zyx_to_rotmat(roll, pitch, yaw))
    radalt = (h - ground_h) / (np.cos(roll) * np.cos(pitch))
    strobe = (np.arange(n) % per_frame == 0).astype(int)
    return {"time_s": t, "lat_deg": lat, "lon_deg": lon, "height_m": h, "qw": quat[:, 0], "qx": quat[:, 1],
            "qy": quat[:, 2], "qz": quat[:, 3], "rtk_status": np.full(n, 3), "radalt_m": radalt,
            "radalt_snr": np.full(n, 25.0), "strobe": strobe}


def write_pose_log(path: Path, cols: dict) -> None:
    """Write pose-log columns as CSV (fixed-point text, as a logger writes it)."""
    fmt = ["%.6f", "%.9f", "%.9f", "%.4f", "%.8f", "%.8f", "%.8f", "%.8f", "%d", "%.3f", "%.1f", "%d"]
    data = np.column_stack([cols[name] for name in HEADER.split(",")])
    np.savetxt(path, data, fmt=fmt, delimiter=",", header=HEADER, comments="")


def image_name(t: float) -> str:
    sec = int(np.floor(t))
    return f"{sec}.{int(round((t - sec) * 1e9)):09d}.png"


def write_images(folder: Path, times, images_csv: bool = False) -> list[Path]:
    """Empty image files for ``times`` (named by timestamp, or listed in images.csv)."""
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    if images_csv:
        lines = ["time_s,file"]
        for k, t in enumerate(times):
            name = f"frame_{k:06d}.jpg"
            (folder / name).touch()
            lines.append(f"{t:.6f},{name}")
            paths.append(folder / name)
        (folder / "images.csv").write_text("\n".join(lines) + "\n")
    else:
        for t in times:
            p = folder / image_name(t)
            p.touch()
            paths.append(p)
    return paths


def make_flight(folder: Path, n_frames: int = 40, image_offset_s: float = 0.004, images_csv: bool = False,
                **kwargs) -> dict:
    """Pose log + images + calibration in ``folder``; returns paths and the truth."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    cols = flight_poses(n_frames, **kwargs)
    write_pose_log(folder / "pose_log.csv", cols)
    strobe_t = cols["time_s"][cols["strobe"] == 1]
    write_images(folder / "images", strobe_t + image_offset_s, images_csv)
    (folder / "camchain.yaml").write_text(CALIBRATION_YAML)
    return {"pose_log": folder / "pose_log.csv", "images": folder / "images",
            "calibration": folder / "camchain.yaml", "cols": cols, "strobe_t": strobe_t}
