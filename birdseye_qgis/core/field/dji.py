"""DJI drone images → frames: XMP ``drone-dji:`` tags and EXIF, camera model, gimbal pose, footprints.

Orientation. DJI writes the gimbal attitude as ``GimbalRoll/Pitch/YawDegree``: aerospace ZYX Euler
angles of the *gimbal* frame (x along the optical axis, y to the image right, z to the image bottom)
relative to local NED, yaw from north, pitch −90° = looking straight down. The camera orientation *is*
the gimbal orientation, so a DJI frame's "body" is the gimbal frame: ``q = q(ZYX(roll, pitch, yaw))``
and :data:`T_CAM_GIMBAL` maps gimbal axes to the OpenCV camera axes (camera x = gimbal y,
camera y = gimbal z, camera z = gimbal x). Check: pitch −90°, yaw 0 → the camera z axis points down and
the image top (−y) points north; yaw 90° turns the image top east.

Depth. ``RelativeAltitude`` is the height above the take-off point, so the ground is a level plane at
the take-off height: ``ground_h = AbsoluteAltitude − RelativeAltitude`` (ground source ``takeoff``). DJI's
``AbsoluteAltitude`` is above mean sea level (:data:`DJI_HEIGHT_REFERENCE`, EGM96, as GNSS receivers report
it; barometric on models without RTK, and then often tens of metres off); because camera height and ground
height come from the same source the depth (= ``RelativeAltitude``) is right whatever the bias. Terrain that
rises or falls from the take-off point scales footprints accordingly (a DEM ground model fixes that). A DEM
is converted into EGM96 heights and checked once for the whole flight: the take-off height must be one the
terrain around the frames has (:func:`.dem.check_vertical_datum`), so honest relief between the take-off
point and the field passes while a datum mix-up larger than the relief does not.

Intrinsics, best first: a calibration file; ``DewarpData`` (:func:`.camera.camera_from_dji_dewarp`);
``CalibratedFocalLength`` + ``CalibratedOpticalCenterX/Y`` (pixels); EXIF ``FocalLength`` (mm) with
``FocalPlaneXResolution`` (the sensor size); EXIF ``FocalLengthIn35mmFilm``, read like OpenSfM/ODM
as relative to the 36 mm long side of the 35 mm frame (fx = f35 · max(W, H) / 36 px); EXIF
``FocalLength`` with the sensor width the caller knows for the camera model
(:data:`.drone_images.SENSOR_WIDTH_MM`). The last three are nominal values, a few per cent off (frames
flagged ``approx_intrinsics``). A resized copy of an image (fewer pixels than EXIF ``ExifImageWidth``)
has its pixel intrinsics scaled to its size.

Images without DJI tags are read by :mod:`.drone_images`, which also holds the folder importer.

One camera, one model. The frames of one camera — same model, serial number (XMP
``CameraSerialNumber``, else EXIF ``BodySerialNumber``) and ``DewarpData`` — share one
:class:`~.camera.CameraModel`, named after the camera rather than a file, so everything that works per
camera (footprints, the DEM check, labels) sees the flight as one.

``DewarpFlag`` 1 says the drone has already removed the lens distortion from the JPEG (the focal
length and principal point stay those of ``DewarpData``): such frames get a camera with zero
distortion, or the distortion would be removed twice, and the flag ``dewarped``.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace
from datetime import datetime, timedelta, timezone
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..geometry.camera import CalibrationError, CameraModel, camera_from_dji_dewarp
from ..geometry.dem import DemRaster
from ..geometry.geodesy import ProjectedCRS
from ..geometry.heights import EGM96_REFERENCE, TAKEOFF
from ..geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from .import_report import FlightImport
from .pose_log import RTK_FIXED, RTK_FLOAT, RTK_NONE

#: Gimbal frame (x optical axis, y image right, z image down) → OpenCV camera frame.
T_CAM_GIMBAL = np.array([[0.0, 1.0, 0.0, 0.0],
                         [0.0, 0.0, 1.0, 0.0],
                         [1.0, 0.0, 0.0, 0.0],
                         [0.0, 0.0, 0.0, 1.0]])
#: DJI ``RtkFlag`` → frame-layer ``rtk_status`` (50 fixed, 34 float, 16 single point, 0 none).
RTK_FLAG_STATUS = {50: RTK_FIXED, 34: RTK_FLOAT}
#: Frames whose gimbal and flight yaw differ by more than this (deg) are flagged ``yaw_mismatch``.
YAW_MISMATCH_DEG = 5.0
#: Frames with a gimbal pitch above this (deg; −90 = nadir) are flagged ``non_nadir``.
NADIR_PITCH_LIMIT_DEG = -80.0
#: Long side (mm) of the 35 mm film frame the EXIF 35 mm-equivalent focal length refers to.
FILM_LONG_SIDE_MM = 36.0
#: What DJI's ``AbsoluteAltitude`` and EXIF's ``GPSAltitude`` ("above sea level", by the EXIF standard) are
#: measured from: mean sea level, as GNSS receivers report it with the EGM96 geoid.
DJI_HEIGHT_REFERENCE = EGM96_REFERENCE

_JPEG_SUFFIXES = (".jpg", ".jpeg")
_XMP_HEADER = b"http://ns.adobe.com/xap/1.0/\x00"
_XMP_ATTR = re.compile(r"drone-dji:(\w+)\s*=\s*\"([^\"]*)\"")
_XMP_ELEM = re.compile(r"<drone-dji:(\w+)>([^<]*)</drone-dji:\1>")


@dataclass
class DjiMetadata:
    """What a DJI JPEG says about itself (None where a tag is absent). Angles deg, lengths m."""

    path: str
    width: int
    height: int
    xmp: dict = field(default_factory=dict)
    exif_width: int | None = None
    exif_height: int | None = None
    make: str = ""
    model: str = ""
    time_s: float = math.nan
    exif_lat: float | None = None
    exif_lon: float | None = None
    exif_alt: float | None = None
    focal_mm: float | None = None
    focal_35mm: float | None = None
    focal_plane_px_per_mm: float | None = None
    orientation: int = 1
    serial: str = ""
    xmp_text: str = ""

    def tag(self, *names) -> float | None:
        """First of the XMP tags ``names`` present, as a number (None if absent or not a number)."""
        for name in names:
            if name in self.xmp:
                try:
                    value = float(self.xmp[name])
                except ValueError:
                    raise InputError(f"{self.xmp[name]!r} is not a number", source=self.path,
                                     field=f"drone-dji:{name}") from None
                return value if math.isfinite(value) else None
        return None

    @property
    def has_dji_tags(self) -> bool:
        return bool(self.xmp)

    @property
    def gps_lat_lon(self) -> tuple:
        """(lat, lon) from XMP ``GpsLatitude/GpsLongitude``, else EXIF GPS; Nones without either."""
        lat = self.tag("GpsLatitude", "GPSLatitude")
        lon = self.tag("GpsLongitude", "GpsLongtitude", "GPSLongitude")
        if lat is None or lon is None:
            return self.exif_lat, self.exif_lon
        return lat, lon

    @property
    def gps_height(self) -> float | None:
        """XMP ``AbsoluteAltitude``, else the EXIF GPS altitude (:data:`DJI_HEIGHT_REFERENCE`); None without either."""
        absolute = self.tag("AbsoluteAltitude")
        return absolute if absolute is not None else self.exif_alt

    @property
    def dewarped(self) -> bool:
        """``DewarpFlag`` 1: the drone already removed the lens distortion from the pixels."""
        return self.tag("DewarpFlag") == 1.0

    @property
    def camera_name(self) -> str:
        """Model and serial number: the same for every frame of one camera."""
        return " ".join(part for part in (self.make, self.model, self.serial) if part) or "unnamed camera"


def _jpeg_segments(path: Path):
    """(marker, payload) of the JPEG's header segments, up to the start of the image data."""
    with open(path, "rb") as f:
        if f.read(2) != b"\xff\xd8":
            raise InputError("is not a JPEG file", source=str(path))
        while True:
            byte = f.read(1)
            if byte != b"\xff":
                return
            marker = f.read(1)
            while marker == b"\xff":
                marker = f.read(1)
            if not marker:
                return
            m = marker[0]
            if m in (0xD8, 0x01) or 0xD0 <= m <= 0xD7:
                continue
            if m in (0xDA, 0xD9):
                return
            size = f.read(2)
            if len(size) < 2:
                return
            yield m, f.read(int.from_bytes(size, "big") - 2)


def read_dji_metadata(path) -> DjiMetadata:
    """XMP ``drone-dji:`` tags and the EXIF fields the importer uses, without decoding pixels."""
    from PIL import Image, UnidentifiedImageError

    path = Path(path)
    xmp_text = "".join(data[len(_XMP_HEADER):].decode("utf-8", errors="replace")
                       for m, data in _jpeg_segments(path) if m == 0xE1 and data.startswith(_XMP_HEADER))
    xmp = {k: v.strip() for k, v in _XMP_ATTR.findall(xmp_text)}
    xmp.update({k: v.strip() for k, v in _XMP_ELEM.findall(xmp_text)})
    try:
        with Image.open(path) as im:
            width, height = im.size
            exif = im.getexif()
    except (UnidentifiedImageError, OSError) as exc:
        raise InputError(f"cannot be read as an image ({exc})", source=str(path)) from exc
    ifd = exif.get_ifd(0x8769)
    gps = exif.get_ifd(0x8825)
    meta = DjiMetadata(str(path), int(width), int(height), xmp, xmp_text=xmp_text)
    meta.make = _text(exif.get(0x010F))
    meta.model = _text(exif.get(0x0110))
    meta.orientation = int(exif.get(0x0112, 1) or 1)
    meta.serial = xmp.get("CameraSerialNumber") or _text(ifd.get(0xA431))
    meta.exif_width = _int(ifd.get(0xA002))
    meta.exif_height = _int(ifd.get(0xA003))
    meta.focal_mm = _float(ifd.get(0x920A))
    meta.focal_35mm = _float(ifd.get(0xA405))
    res, unit = _float(ifd.get(0xA20E)), _int(ifd.get(0xA210))
    mm_per_unit = {2: 25.4, 3: 10.0, 4: 1.0}.get(unit or 2)
    if res and mm_per_unit:
        meta.focal_plane_px_per_mm = res / mm_per_unit
    meta.time_s = _exif_time(ifd.get(0x9003), ifd.get(0x9291), ifd.get(0x9011))
    if 2 in gps and 4 in gps:
        lat, lon = _dms(gps.get(2)), _dms(gps.get(4))
        if lat is not None and lon is not None:
            meta.exif_lat = -lat if _text(gps.get(1)).upper().startswith("S") else lat
            meta.exif_lon = -lon if _text(gps.get(3)).upper().startswith("W") else lon
    alt = _float(gps.get(6))
    if alt is not None:
        meta.exif_alt = -alt if gps.get(5) in (1, b"\x01") else alt
    return meta


def _text(value) -> str:
    if value is None:
        return ""
    if isinstance(value, bytes):
        value = value.decode("utf-8", errors="replace")
    return str(value).replace("\x00", "").strip()


def _float(value) -> float | None:
    try:
        out = float(value)
    except (TypeError, ValueError, ZeroDivisionError):
        return None
    return out if math.isfinite(out) and out != 0.0 else None


def _int(value) -> int | None:
    out = _float(value)
    return None if out is None else int(out)


def _dms(value) -> float | None:
    try:
        d, m, s = (float(v) for v in value)
    except (TypeError, ValueError, ZeroDivisionError):
        return None
    return d + m / 60.0 + s / 3600.0 if all(map(math.isfinite, (d, m, s))) else None


def _exif_time(original, subsec, offset) -> float:
    """POSIX seconds of EXIF DateTimeOriginal (+ sub-seconds); UTC unless OffsetTimeOriginal says."""
    text = _text(original)
    try:
        stamp = datetime.strptime(text, "%Y:%m:%d %H:%M:%S")
    except ValueError:
        return math.nan
    tz = timezone.utc
    match = re.fullmatch(r"([+-])(\d\d):(\d\d)", _text(offset))
    if match:
        delta = timedelta(hours=int(match.group(2)), minutes=int(match.group(3)))
        tz = timezone(delta if match.group(1) == "+" else -delta)
    digits = re.sub(r"\D", "", _text(subsec))
    return stamp.replace(tzinfo=tz).timestamp() + (float("0." + digits) if digits else 0.0)


# ---------------------------------------------------------------------------------------- camera
def dji_camera(meta: DjiMetadata, calibration: CameraModel | None = None,
               sensor_width_mm: float | None = None) -> tuple[CameraModel, list]:
    """Camera model of a DJI image (mounted by :data:`T_CAM_GIMBAL`) and flags about its origin; an
    image the drone already undistorted (``DewarpFlag`` 1) gets zero distortion. ``sensor_width_mm``
    (the long side of the sensor) is the last resort for the focal length in pixels."""
    cam, flags = _lens_camera(meta, calibration, sensor_width_mm)
    if meta.dewarped:
        return replace(cam, dist=(0.0,) * 5, source=f"{cam.source} (dewarped)"), flags + ["dewarped"]
    return cam, flags


def _lens_camera(meta: DjiMetadata, calibration: CameraModel | None,
                 sensor_width_mm: float | None) -> tuple[CameraModel, list]:
    w, h = meta.width, meta.height
    full_w, full_h = meta.exif_width or w, meta.exif_height or h
    flags = ["resized"] if (full_w, full_h) != (w, h) else []
    if calibration is not None:
        if (calibration.width, calibration.height) == (w, h):
            cam = calibration
        elif (calibration.width, calibration.height) == (full_w, full_h):
            cam = calibration.resized(w, h)
        else:
            raise InputError(f"is {w}×{h} px but the calibration ({calibration.source}) is for "
                             f"{calibration.width}×{calibration.height} px", source=meta.path)
        return replace(cam, T_cam_imu=T_CAM_GIMBAL), flags
    dewarp = meta.xmp.get("DewarpData")
    if dewarp:
        try:
            cam = camera_from_dji_dewarp(dewarp, full_w, full_h, source=f"DewarpData {meta.camera_name}",
                                         T_cam_imu=T_CAM_GIMBAL)
        except CalibrationError as exc:
            raise InputError(f"DewarpData cannot be used ({exc})", source=meta.path,
                             field="drone-dji:DewarpData") from exc
        return cam.resized(w, h), flags
    focal_px = meta.tag("CalibratedFocalLength")
    if focal_px:
        ox = meta.tag("CalibratedOpticalCenterX")
        oy = meta.tag("CalibratedOpticalCenterY")
        # DJI's optical centre is measured from the image's outer edge; OpenCV counts pixel centres.
        cx = (full_w / 2.0 if ox is None else ox) - 0.5
        cy = (full_h / 2.0 if oy is None else oy) - 0.5
        cam = CameraModel(full_w, full_h, focal_px, focal_px, cx, cy, T_cam_imu=T_CAM_GIMBAL,
                          source="dji:CalibratedFocalLength")
        return cam.resized(w, h), flags
    if meta.focal_mm and meta.focal_plane_px_per_mm:
        f = meta.focal_mm * meta.focal_plane_px_per_mm
        cam = CameraModel(full_w, full_h, f, f, (full_w - 1) / 2.0, (full_h - 1) / 2.0, T_cam_imu=T_CAM_GIMBAL,
                          source=f"exif:FocalLength+FocalPlaneXResolution {meta.camera_name}")
        return cam.resized(w, h), flags + ["approx_intrinsics"]
    if meta.focal_35mm:
        f = meta.focal_35mm * max(w, h) / FILM_LONG_SIDE_MM
        cam = CameraModel(w, h, f, f, (w - 1) / 2.0, (h - 1) / 2.0, T_cam_imu=T_CAM_GIMBAL,
                          source=f"exif:FocalLengthIn35mmFilm {meta.camera_name}")
        return cam, flags + ["approx_intrinsics"]
    if meta.focal_mm and sensor_width_mm:
        f = meta.focal_mm * max(full_w, full_h) / sensor_width_mm
        cam = CameraModel(full_w, full_h, f, f, (full_w - 1) / 2.0, (full_h - 1) / 2.0, T_cam_imu=T_CAM_GIMBAL,
                          source=f"exif:FocalLength+sensor width {sensor_width_mm:g} mm {meta.camera_name}")
        return cam.resized(w, h), flags + ["approx_intrinsics"]
    raise InputError("has no camera intrinsics: no DewarpData, CalibratedFocalLength, EXIF FocalLength "
                     "with FocalPlaneXResolution or a known sensor width, or FocalLengthIn35mmFilm; give a "
                     "CALIBRATION file", source=meta.path, field="FocalLengthIn35mmFilm")


# ---------------------------------------------------------------------------------------- pose
@dataclass
class DjiPose:
    lat: float
    lon: float
    height: float
    ground_h: float
    roll_deg: float
    pitch_deg: float
    yaw_deg: float
    rtk_status: int
    rtk_std: tuple
    flags: list
    #: Where ``ground_h`` came from (``heights.GROUND_SOURCES``): the take-off point for DJI's relative altitude.
    ground_source: str = TAKEOFF

    @property
    def quat(self) -> np.ndarray:
        """Gimbal frame → NED quaternion (w, x, y, z)."""
        r = euler_zyx_to_rotmat(*np.radians([self.roll_deg, self.pitch_deg, self.yaw_deg]))
        return rotmat_to_quat(r)


def _wrap180(angle: float) -> float:
    return (angle + 180.0) % 360.0 - 180.0


def gps_position(meta: DjiMetadata) -> tuple[float, float]:
    """(lat, lon) of an image (XMP, else EXIF GPS); InputError without a GPS fix."""
    lat, lon = meta.gps_lat_lon
    if lat is None or lon is None:
        raise InputError("has no GPS position (XMP GpsLatitude/GpsLongitude or EXIF GPS)", source=meta.path,
                         field="GPSLatitude")
    if (lat == 0.0 and lon == 0.0) or abs(lat) > 90 or abs(lon) > 180:
        raise InputError(f"GPS position ({lat}, {lon}) is not a fix", source=meta.path, field="GPSLatitude")
    return lat, lon


def dji_pose(meta: DjiMetadata) -> DjiPose:
    """Position, level ground and gimbal attitude of a DJI image; InputError if it cannot be placed."""
    if not meta.has_dji_tags:
        raise InputError("has no DJI XMP tags (drone-dji:RelativeAltitude, GimbalPitchDegree, …); is it a "
                         "DJI drone image with its metadata intact?", source=meta.path, field="XMP drone-dji")
    lat, lon = gps_position(meta)
    relative = meta.tag("RelativeAltitude")
    if relative is None:
        raise InputError("has no RelativeAltitude: the height above the ground is unknown", source=meta.path,
                         field="drone-dji:RelativeAltitude")
    if relative <= 0.5:
        raise InputError(f"RelativeAltitude {relative:g} m: the drone is on or below the take-off point",
                         source=meta.path, field="drone-dji:RelativeAltitude")
    height = meta.gps_height if meta.gps_height is not None else relative
    flags = []
    pitch = meta.tag("GimbalPitchDegree")
    if pitch is None:
        pitch = -90.0
        flags.append("gimbal_pitch_missing")
    roll = meta.tag("GimbalRollDegree") or 0.0
    gimbal_yaw = meta.tag("GimbalYawDegree")
    flight_yaw = meta.tag("FlightYawDegree")
    if gimbal_yaw is None:
        if flight_yaw is None:
            raise InputError("has neither GimbalYawDegree nor FlightYawDegree: the image heading is unknown",
                             source=meta.path, field="drone-dji:GimbalYawDegree")
        yaw = flight_yaw
        flags.append("yaw_from_flight")
    else:
        yaw = gimbal_yaw
        if flight_yaw is not None and abs(_wrap180(gimbal_yaw - flight_yaw)) > YAW_MISMATCH_DEG:
            flags.append("yaw_mismatch")
    if pitch > NADIR_PITCH_LIMIT_DEG:
        flags.append("non_nadir")
    rtk_flag = meta.tag("RtkFlag")
    rtk_status = RTK_FLAG_STATUS.get(int(rtk_flag), RTK_NONE) if rtk_flag is not None else RTK_NONE
    flags.append({RTK_FIXED: "", RTK_FLOAT: "rtk_float"}.get(rtk_status, "rtk_none"))
    rtk_std = tuple(math.nan if v is None else v for v in
                    (meta.tag("RtkStdLon"), meta.tag("RtkStdLat"), meta.tag("RtkStdHgt")))
    return DjiPose(lat, lon, height, height - relative, roll, pitch, yaw % 360.0, rtk_status, rtk_std,
                   [f for f in flags if f])


# ---------------------------------------------------------------------------------------- import
def list_jpegs(folder) -> list[Path]:
    folder = Path(folder)
    if not folder.is_dir():
        raise InputError("image folder not found", source=str(folder))
    return sorted(p for p in folder.iterdir() if p.is_file() and p.suffix.lower() in _JPEG_SUFFIXES)


def import_dji_images(folder, calibration: CameraModel | None = None, crs: ProjectedCRS | None = None,
                      progress=None, is_canceled=None, dem: DemRaster | None = None,
                      flight_height_m: float | None = None) -> FlightImport:
    """Frames with footprints from a folder of drone JPEGs, DJI or not: the name callers and saved
    Processing models know; see :func:`.drone_images.import_drone_images`."""
    from .drone_images import import_drone_images

    return import_drone_images(folder, calibration, crs, progress=progress, is_canceled=is_canceled, dem=dem,
                               flight_height_m=flight_height_m)
