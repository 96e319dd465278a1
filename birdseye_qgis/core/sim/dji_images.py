"""Consumer-drone frames for the simulator: JPEGs that say about themselves what a DJI drone's say.

A DJI drone writes no pose log: each JPEG carries its own pose in EXIF (GPS) and in an XMP packet of
``drone-dji:`` tags, which :mod:`..field.dji` reads. This module makes those files for simulated
frames: the pixels are rendered through the *true* pose, the metadata carries the errors a real
drone's has. Those errors, as measured on a real RTK flight (labels from the metadata missed by
~160 px there):

* the gimbal attitude is only as good as the aircraft's attitude and heading estimate, because the
  gimbal stabilises the camera against that estimate and reports it. The metadata says "nadir,
  heading ψ"; the camera truly looks a little off: a heading error (a bias of
  :attr:`DjiMetadataErrors.heading_bias_deg` in magnitude, random sign, plus a slow drift) and a tilt
  (a bias of :attr:`~DjiMetadataErrors.tilt_bias_deg` in a random direction fixed in the aircraft
  body — an accelerometer bias turns with the aircraft — plus a slow drift);
* heights: one height estimate feeds ``AbsoluteAltitude`` (above mean sea level), EXIF
  ``GPSAltitude`` and ``RelativeAltitude`` (above the take-off point), and it reads
  :attr:`~DjiMetadataErrors.height_bias_m` low, so the depth the importer takes (``RelativeAltitude``)
  is short by that much;
* positions carry an RTK fix's noise (σ :attr:`~DjiMetadataErrors.rtk_sigma_m`), and the reported
  gimbal angles the gimbal's own angular jitter.

In one picture: the drone's belief is the truth rotated by a small error rotation ``E = exp([e]^)``
(``e`` = tilt about north, tilt about east, heading about down; NED, radians): for the gimbal and the
aircraft alike, ``R_metadata = E · R_true``. Every draw comes from the generator given (seeded by the
campaign).

The camera (:func:`dji_camera_model`) is the Mavic 3 Enterprise wide camera of the sensor-bound
preset (:data:`..design.platforms.DJI_METADATA`: 5280 × 3956 px, 84° diagonal field of view) with a
principal point offset and a lens distortion of the size DJI's ``DewarpData`` shows; those are the
simulator's, not a calibration. Smaller images are the
same sensor scaled and, for another aspect ratio, cropped (as the drone's 16:9 mode crops the 4:3
sensor). ``DewarpData`` and the calibrated focal length are written for the image as written, so
the importer needs no calibration file.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from ..design.platforms import DJI_METADATA
from ..errors import InputError
from ..field.dji import T_CAM_GIMBAL
from ..geometry.camera import CameraModel
from ..geometry.rotations import euler_zyx_to_rotmat, rotmat_to_euler_zyx, rotmat_to_quat, so3_exp
from .flight import correlated_noise

DJI_MAKE = "DJI"
DJI_MODEL = "M3E"
DJI_SERIAL = "SIM-M3E-0001"
DJI_DEWARP_DATE = "2024-01-01"
#: Full sensor (px), focal length (px; square pixels), principal point offset from the image centre (px).
DJI_SENSOR_PX = (DJI_METADATA.camera.width, DJI_METADATA.camera.height)
DJI_FOCAL_PX = DJI_METADATA.camera.fx
DJI_CENTRE_OFFSET_PX = (11.2, -7.8)
#: Brown–Conrady k1, k2, p1, p2, k3 as ``DewarpData`` gives them (OpenCV's order).
DJI_DISTORTION = (-0.1105, 0.0135, 0.00035, -0.00028, -0.0092)
DJI_FOCAL_35MM = 24
#: ``RtkFlag`` of an RTK fixed solution.
DJI_RTK_FIXED = 50


@dataclass(frozen=True)
class DjiMetadataErrors:
    """What the metadata gets wrong (see the module docstring): angles in degrees, lengths in metres,
    correlation times in seconds. ``height_bias_m`` < 0: the heights read low."""

    heading_bias_deg: tuple = (1.0, 2.0)
    heading_drift_deg: float = 0.2
    heading_tau_s: float = 60.0
    tilt_bias_deg: tuple = (0.5, 1.0)
    tilt_drift_deg: float = 0.1
    tilt_tau_s: float = 20.0
    height_bias_m: float = -1.5
    height_sigma_m: float = 0.015
    rtk_sigma_m: float = 0.01
    gimbal_jitter_deg: float = 0.01

    @classmethod
    def none(cls) -> "DjiMetadataErrors":
        """Metadata that tells the truth (to the precision it is written with)."""
        return cls(heading_bias_deg=(0.0, 0.0), heading_drift_deg=0.0, tilt_bias_deg=(0.0, 0.0), tilt_drift_deg=0.0,
                   height_bias_m=0.0, height_sigma_m=0.0, rtk_sigma_m=0.0, gimbal_jitter_deg=0.0)

    def to_dict(self) -> dict:
        return {k: list(v) if isinstance(v, tuple) else v for k, v in asdict(self).items()}


def dji_camera_model(width: int, height: int, dewarped: bool = False) -> CameraModel:
    """The simulated DJI camera for ``width × height`` images, mounted on its gimbal (:data:`T_CAM_GIMBAL`).

    The image is the sensor scaled so that it fits the image, cropped to the image's aspect ratio.
    ``dewarped``: the camera of a JPEG the drone has already undistorted (zero distortion)."""
    scale = max(width / DJI_SENSOR_PX[0], height / DJI_SENSOR_PX[1])
    f = DJI_FOCAL_PX * scale
    cx = (width - 1) / 2.0 + DJI_CENTRE_OFFSET_PX[0] * scale
    cy = (height - 1) / 2.0 + DJI_CENTRE_OFFSET_PX[1] * scale
    return CameraModel(width, height, f, f, cx, cy, (0.0,) * 5 if dewarped else DJI_DISTORTION, T_CAM_GIMBAL,
                       source="simulated DJI camera" + (" (dewarped)" if dewarped else ""))


# ---------------------------------------------------------------------------------------- metadata
@dataclass
class DjiFrames:
    """Per frame (length F): the true gimbal orientation the frames are rendered with, what the
    metadata says, and its errors. Angles in degrees, heights in metres."""

    quat_true: np.ndarray          # (F, 4) gimbal → NED, (w, x, y, z)
    lat: np.ndarray                # metadata position (deg)
    lon: np.ndarray
    absolute_altitude: np.ndarray  # above mean sea level
    relative_altitude: np.ndarray  # above the take-off point
    gimbal_rpy: np.ndarray         # (F, 3) roll, pitch, yaw
    flight_rpy: np.ndarray         # (F, 3)
    rtk_std: np.ndarray            # (F, 3) lon, lat, height σ the drone reports (m)
    heading_error_deg: np.ndarray  # metadata − true heading
    tilt_error_deg: np.ndarray     # angle between the true optical axis and the metadata's (nadir)
    height_error_m: np.ndarray     # metadata − true height
    horizontal_error_m: np.ndarray
    biases: dict


def dji_frame_metadata(rng: np.random.Generator, time_s, local_true, r_ned_body, height_true, takeoff_height,
                       undulation_m: float, local, errors: DjiMetadataErrors = DjiMetadataErrors()) -> DjiFrames:
    """The true gimbal poses and the DJI metadata of frames taken at ``time_s`` (s).

    ``local_true`` (F, 3): true camera positions in the site's local frame; ``r_ned_body`` (F, 3, 3):
    the aircraft's true attitude (body forward-right-down → NED); ``height_true`` (F,) and
    ``takeoff_height``: ellipsoidal heights (m); ``undulation_m``: the geoid undulation N (MSL = h − N).
    """
    t = np.asarray(time_s, float)
    n = len(t)
    heading = np.asarray(rotmat_to_euler_zyx(r_ned_body)[2])

    # The drone's attitude error e (NED, rad): a heading bias and drift, and a tilt fixed in the body.
    # The drifts run on a 0.1 s clock over the flight (frames are not evenly spaced: none in the turns).
    heading_bias = math.radians(rng.uniform(*errors.heading_bias_deg)) * rng.choice([-1.0, 1.0])
    tilt_bias = math.radians(rng.uniform(*errors.tilt_bias_deg))
    tilt_dir = rng.uniform(0.0, 2.0 * math.pi)
    clock = np.arange(t.min(), t.max() + 0.2, 0.1) if n else np.zeros(1)

    def drift(tau_s, sigma_deg, dims):
        noise = correlated_noise(rng, len(clock), 0.1, tau_s, math.radians(sigma_deg), dims)
        return np.stack([np.interp(t, clock, noise[:, k]) for k in range(dims)], axis=-1)

    e_heading = heading_bias + drift(errors.heading_tau_s, errors.heading_drift_deg, 1)[:, 0]
    tilt_body = (tilt_bias * np.array([math.cos(tilt_dir), math.sin(tilt_dir)])
                 + drift(errors.tilt_tau_s, errors.tilt_drift_deg, 2))
    c, s = np.cos(heading), np.sin(heading)
    # Body forward is (cos ψ, sin ψ) in north/east, body right (−sin ψ, cos ψ).
    e = np.stack([c * tilt_body[:, 0] - s * tilt_body[:, 1], s * tilt_body[:, 0] + c * tilt_body[:, 1],
                  e_heading], axis=-1)
    belief = so3_exp(e)

    # What the gimbal reports: nadir along the believed heading, within its jitter.
    jitter = rng.standard_normal((n, 3)) * errors.gimbal_jitter_deg
    gimbal_rpy = np.column_stack([jitter[:, 0], -90.0 + jitter[:, 1],
                                  _wrap180(np.degrees(heading + e_heading) + jitter[:, 2])])
    r_meta = euler_zyx_to_rotmat(*np.radians(gimbal_rpy.T))
    r_true = np.swapaxes(belief, -1, -2) @ r_meta
    flight_rpy = np.degrees(np.column_stack(rotmat_to_euler_zyx(belief @ r_ned_body)))
    flight_rpy[:, 2] = _wrap180(flight_rpy[:, 2])

    height_error = errors.height_bias_m + rng.standard_normal(n) * errors.height_sigma_m
    horizontal = rng.standard_normal((n, 2)) * errors.rtk_sigma_m
    believed = np.asarray(local_true, float) + np.column_stack([horizontal, np.zeros(n)])
    lat, lon, _ = local.to_geodetic(believed)
    height_meta = np.asarray(height_true, float) + height_error
    # Angle between the true optical axis (gimbal x) and straight down, which the metadata claims.
    axis_true = r_true[:, :, 0]
    tilt = np.degrees(np.arccos(np.clip(axis_true[:, 2], -1.0, 1.0)))
    rtk_std = np.abs(np.column_stack([np.full(n, errors.rtk_sigma_m), np.full(n, errors.rtk_sigma_m),
                                      np.full(n, 1.5 * errors.rtk_sigma_m)])
                     * (1.0 + 0.1 * rng.standard_normal((n, 3))))
    return DjiFrames(
        quat_true=rotmat_to_quat(r_true), lat=np.asarray(lat), lon=np.asarray(lon),
        absolute_altitude=height_meta - undulation_m, relative_altitude=height_meta - takeoff_height,
        gimbal_rpy=gimbal_rpy, flight_rpy=flight_rpy, rtk_std=rtk_std,
        heading_error_deg=np.degrees(e_heading), tilt_error_deg=tilt, height_error_m=height_error,
        horizontal_error_m=np.hypot(*horizontal.T),
        biases={"heading_bias_deg": math.degrees(heading_bias), "tilt_bias_deg": math.degrees(tilt_bias),
                "tilt_bias_direction_deg": math.degrees(tilt_dir),
                "tilt_bias_frame": "aircraft body (0° forward, 90° right)",
                "height_bias_m": errors.height_bias_m})


def _wrap180(angle):
    return (np.asarray(angle, float) + 180.0) % 360.0 - 180.0


# ---------------------------------------------------------------------------------------- files
@dataclass(frozen=True)
class DjiCamera:
    """The camera-level tags: the lens in the written image's pixels, and whether the drone
    undistorted the image (``dewarped``: ``DewarpFlag`` 1, the distortion is that of the raw lens)."""

    lens: CameraModel
    dewarped: bool = False
    make: str = DJI_MAKE
    model: str = DJI_MODEL
    serial: str = DJI_SERIAL

    def xmp_tags(self) -> dict:
        w, h = self.lens.width, self.lens.height
        fx, fy, cx, cy = self.lens.fx, self.lens.fy, self.lens.cx, self.lens.cy
        # DewarpData gives cx, cy from the image centre, (W − 1)/2 in pixel-centre coordinates;
        # CalibratedOpticalCenterX/Y from the outer edge (pixel-centre coordinate + 0.5).
        numbers = [fx, fy, cx - (w - 1) / 2.0, cy - (h - 1) / 2.0, *self.lens.dist]
        return {"CalibratedFocalLength": f"{fx:.4f}", "CalibratedOpticalCenterX": f"{cx + 0.5:.4f}",
                "CalibratedOpticalCenterY": f"{cy + 0.5:.4f}",
                "DewarpData": DJI_DEWARP_DATE + ";" + ",".join(f"{v:.8f}" for v in numbers),
                "DewarpFlag": "1" if self.dewarped else "0",
                "CameraSerialNumber": self.serial, "DroneModel": self.model}


def frame_xmp_tags(frames: DjiFrames, i: int) -> dict:
    """One frame's pose tags, formatted as DJI writes them (signed, fixed decimals)."""
    g, f, std = frames.gimbal_rpy[i], frames.flight_rpy[i], frames.rtk_std[i]
    return {"GpsLatitude": f"{frames.lat[i]:+.10f}", "GpsLongitude": f"{frames.lon[i]:+.10f}",
            "AbsoluteAltitude": f"{frames.absolute_altitude[i]:+.3f}",
            "RelativeAltitude": f"{frames.relative_altitude[i]:+.3f}",
            "GimbalRollDegree": f"{g[0]:+.2f}", "GimbalYawDegree": f"{g[2]:+.2f}",
            "GimbalPitchDegree": f"{g[1]:+.2f}", "FlightRollDegree": f"{f[0]:+.2f}",
            "FlightYawDegree": f"{f[2]:+.2f}", "FlightPitchDegree": f"{f[1]:+.2f}",
            "RtkFlag": str(DJI_RTK_FIXED), "RtkStdLon": f"{std[0]:.5f}", "RtkStdLat": f"{std[1]:.5f}",
            "RtkStdHgt": f"{std[2]:.5f}"}


def xmp_packet(tags: dict) -> bytes:
    """The APP1 payload of an XMP packet with ``drone-dji:`` attributes, as DJI lays it out."""
    attrs = "\n".join(f'    drone-dji:{name}="{value}"' for name, value in tags.items())
    text = ('<?xpacket begin="\ufeff" id="W5M0MpCehiHzreSzNTczkc9d"?>\n'
            '<x:xmpmeta xmlns:x="adobe:ns:meta/">\n'
            ' <rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#">\n'
            '  <rdf:Description rdf:about="DJI Meta Data"\n'
            '    xmlns:drone-dji="http://www.dji.com/drone-dji/1.0/"\n'
            f"{attrs}>\n"
            "  </rdf:Description>\n"
            " </rdf:RDF>\n"
            "</x:xmpmeta>\n"
            '<?xpacket end="w"?>')
    return b"http://ns.adobe.com/xap/1.0/\x00" + text.encode("utf-8")


def exif_payload(camera: DjiCamera, frames: DjiFrames, i: int, time_s: float) -> bytes:
    """The APP1 payload of the EXIF block: make, model, serial, size, 35 mm focal length, time and GPS."""
    from PIL import Image
    from PIL.TiffImagePlugin import IFDRational

    stamp = datetime.fromtimestamp(float(time_s), tz=timezone.utc)
    exif = Image.Exif()
    exif[0x010F], exif[0x0110], exif[0x0112] = camera.make, camera.model, 1
    exif[0x8769] = {0x9003: stamp.strftime("%Y:%m:%d %H:%M:%S"), 0x9291: f"{stamp.microsecond // 1000:03d}",
                    0x9011: "+00:00", 0xA002: camera.lens.width, 0xA003: camera.lens.height,
                    0xA405: DJI_FOCAL_35MM,
                    0xA431: camera.serial}

    def dms(value):
        value = abs(float(value))
        d = int(value)
        m = int((value - d) * 60.0)
        seconds = ((value - d) * 60.0 - m) * 60.0
        return IFDRational(d, 1), IFDRational(m, 1), IFDRational(round(seconds * 1e6), 1_000_000)

    alt = float(frames.absolute_altitude[i])
    exif[0x8825] = {0: b"\x02\x03\x00\x00", 1: "N" if frames.lat[i] >= 0 else "S", 2: dms(frames.lat[i]),
                    3: "E" if frames.lon[i] >= 0 else "W", 4: dms(frames.lon[i]),
                    5: b"\x01" if alt < 0 else b"\x00", 6: IFDRational(round(abs(alt) * 1000), 1000)}
    return exif.tobytes()


def write_dji_jpeg(path, image_bgr: np.ndarray, exif: bytes, xmp: bytes, quality: int) -> Path:
    """Encode ``image_bgr`` as a JPEG whose header is the DJI one: EXIF APP1, then XMP APP1 (OpenCV's
    JFIF APP0 is dropped, as DJI's files have none)."""
    import cv2

    ok, encoded = cv2.imencode(".jpg", image_bgr, [cv2.IMWRITE_JPEG_QUALITY, int(quality)])
    if not ok:
        raise InputError("cannot encode the frame as JPEG", source=str(path))
    data = encoded.tobytes()
    rest = data[2:]
    if rest[:2] == b"\xff\xe0":
        rest = rest[2 + int.from_bytes(rest[2:4], "big"):]
    if any(len(p) + 2 > 0xFFFF for p in (exif, xmp)):
        raise ValueError("an APP1 segment holds at most 65533 bytes")
    segments = b"".join(b"\xff\xe1" + (len(p) + 2).to_bytes(2, "big") + p for p in (exif, xmp))
    try:
        Path(path).write_bytes(data[:2] + segments + rest)
    except OSError as exc:
        raise InputError(f"cannot write the frame ({exc})", source=str(path)) from exc
    return Path(path)


def write_frame(path, image_bgr, camera: DjiCamera, frames: DjiFrames, i: int, time_s: float,
                quality: int) -> Path:
    """Frame ``i`` as a DJI JPEG with its EXIF and XMP metadata."""
    tags = {**frame_xmp_tags(frames, i), **camera.xmp_tags()}
    return write_dji_jpeg(path, image_bgr, exif_payload(camera, frames, i, time_s), xmp_packet(tags), quality)


def lens_for(camera: CameraModel, dewarped: bool) -> DjiCamera:
    """The tags' camera for frames rendered with ``camera``: a dewarped frame is rendered without
    distortion but its ``DewarpData`` still gives the raw lens's."""
    return DjiCamera(replace(camera, dist=DJI_DISTORTION) if dewarped else camera, dewarped)
