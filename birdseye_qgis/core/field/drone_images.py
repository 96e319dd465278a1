"""Images from any drone → frames: DJI XMP, other makers' XMP attitude, or EXIF GPS alone.

Each image is placed from the best its metadata holds (:func:`import_drone_images` dispatches per image):

1. **DJI** ``drone-dji:`` tags: :mod:`.dji`, unchanged.
2. **Other makers' camera attitude in XMP** (the tags OpenDroneMap's photo reader knows, and Parrot's):

   * ``drone-parrot:CameraRollDegree/CameraPitchDegree/CameraYawDegree`` — Parrot documents them as
     the camera's orientation "in NED", which is DJI's gimbal convention (pitch −90° = nadir); Parrot's
     own example pairs ``CameraPitchDegree`` −51.988888 with ``Camera:Pitch`` 38.011101 (sum −90°).
   * ``Camera:Yaw/Pitch/Roll`` (Parrot, senseFly, MicaSense, Sentera, Pix4D-style writers) — Pix4D's
     convention: a nadir camera with the image top towards the aircraft's nose is pitch 0; the angles
     are aerospace ZYX, ``R_ned_body = Rz(yaw) Ry(pitch) Rx(roll)``, with the camera looking along body
     down (camera x = body right, camera y = −body forward). In our gimbal frame (x optical axis, y
     image right, z image down) that is ``R_ned_gimbal = R_ned_body · Ry(−90°)``: with zero roll, gimbal
     pitch = pitch − 90°, yaw unchanged. senseFly writes the roll with the opposite sign (OpenDroneMap
     negates it for make "senseFly"). Parrot's example photo, documented in both conventions, settles
     this for Parrot: the conversion reproduces its ``drone-parrot:`` angles to 1e-5°, the opposite roll
     sign misses by 0.08°. Ambiguous: the roll sign of other makers' ``Camera:Roll`` (senseFly shows
     they differ), and whether a rigidly mounted multispectral camera's angles are the camera's or the
     aircraft's; yaw and pitch are certain.
   * ``Camera:AboveGroundAltitude`` (Parrot: "altitude above the ground") sets a level ground under the
     frame, as DJI's ``RelativeAltitude`` does.

   ``DLS:Yaw/Pitch/Roll`` (MicaSense) are the sun sensor's attitude, not the camera's, and are ignored.
3. **EXIF only**: position from EXIF GPS, height from ``GPSAltitude`` (``GPSAltitudeRef`` 1 = below sea
   level), a nominal camera from EXIF (:func:`.dji.dji_camera` with :data:`SENSOR_WIDTH_MM` as the last
   resort), no distortion, principal point at the centre, and a **nadir** attitude whose heading follows
   the flight track (:func:`track_headings`): the image top is assumed to face the direction of travel,
   as a drone flying nose-first with its camera straight down takes it. Flags ``attitude_from_track``
   (and ``approx_intrinsics``): footprints are approximate; labels need **Refine frame poses**.

Heights above ground. A frame without a relative altitude (EXIF only, or XMP attitude without
``AboveGroundAltitude``) gets its ground, in order: from ``flight_height_m`` — the flight's take-off
ground is the median GPS altitude of that camera's frames minus the height the flight was flown at
(flag ``ground_from_flight_height``, ground source ``flight_height``; the median, because a stray frame shot
during climb-out or landing must not move the ground of a whole flight, and per camera, because each drone's
GPS altitude has its own bias); else from the DEM under the camera (flag ``ground_from_dem``, source ``dem``:
the footprint drapes on the terrain, and the frame's ground height is the terrain under it, the DEM converted
into the frames' heights); else the frame is imported without a ground (flag ``no_ground_height``, no
footprint), which Refine frame poses can give it from its tie points. EXIF's ``GPSAltitude`` is "above sea
level" by the EXIF standard, like DJI's ``AbsoluteAltitude`` (:data:`.dji.DJI_HEIGHT_REFERENCE`, EGM96), so one
folder has one vertical reference.
"""
from __future__ import annotations

import math
import re

import numpy as np

from ..errors import InputError, check_cancel, detached
from ..geometry.camera import CameraModel
from ..geometry.dem import DemRaster
from ..geometry.geodesy import LocalFrame, ProjectedCRS
from ..geometry.heights import DEM_GROUND, FLIGHT_HEIGHT, NO_GROUND, TAKEOFF
from ..geometry.rotations import euler_zyx_to_rotmat, rotmat_to_euler_zyx
from .dji import (
    DJI_HEIGHT_REFERENCE,
    NADIR_PITCH_LIMIT_DEG,
    YAW_MISMATCH_DEG,
    DjiMetadata,
    DjiPose,
    dji_camera,
    dji_pose,
    gps_position,
    list_jpegs,
    read_dji_metadata,
)
from .frames import Frames, compute_footprints, dem_ground_for
from .import_report import UNBOUNDED_NOTE, FlightImport, ImportReport
from .pose_log import RTK_NONE

#: Pix4D's camera frame (body FRD of a nadir camera, image top to the nose) → our gimbal frame: Ry(−90°).
R_BODY_GIMBAL_PIX4D = np.array([[0.0, 0.0, -1.0],
                                [0.0, 1.0, 0.0],
                                [1.0, 0.0, 0.0]])
#: Track bearings come from images at least this far apart (m); closer ones (hovering) are skipped.
TRACK_MIN_BASE_M = 1.0
#: A frame whose incoming and outgoing legs turn by more than this (deg) is flagged ``track_turn``.
TRACK_TURN_DEG = 30.0
#: Sensor width (mm, the long side) by lower-case EXIF "make model", for images whose EXIF has a focal
#: length but neither the sensor resolution nor a 35 mm equivalent (manufacturers' sensor formats:
#: 1/2.3" = 6.17 mm, 1" = 13.2 mm).
SENSOR_WIDTH_MM = {
    "dji fc300s": 6.17, "dji fc300x": 6.17, "dji fc300c": 6.17,   # Phantom 3 Professional/4K/Standard
    "dji fc330": 6.17,                                            # Phantom 4
    "dji fc220": 6.17,                                            # Mavic Pro
    "dji fc6310": 13.2, "dji fc6310s": 13.2, "dji fc6310r": 13.2,  # Phantom 4 Pro, Pro V2.0, RTK
    "hasselblad l1d-20c": 13.2,                                   # Mavic 2 Pro
}
#: Flags of frames whose footprints rest on assumptions, with what the report says about them.
FLAG_NOTES = (
    ("yaw_mismatch", f"gimbal and flight yaw differ by more than {YAW_MISMATCH_DEG:g}°"),
    ("dewarped", "the drone already removed the lens distortion (DewarpFlag 1); no distortion is applied to them"),
    ("non_nadir", f"gimbal pitch above {NADIR_PITCH_LIMIT_DEG:g}° (not looking down)"),
    ("yaw_from_flight", "no gimbal yaw; the flight yaw was used"),
    ("attitude_from_track", "no attitude in the metadata: a nadir camera is assumed, heading along the flight "
                            "track (image top towards the direction of travel); footprints are approximate, "
                            "refine the poses (Refine frame poses) before writing labels"),
    ("heading_unknown", "a lone image or one with no movement around it: heading 0° (north) assumed"),
    ("track_turn", f"the track turns by more than {TRACK_TURN_DEG:g}° at the image: its heading is least sure"),
    ("ground_from_flight_height", "no relative altitude: the ground is the camera's median GPS altitude minus "
                                  "the flight height given"),
    ("ground_from_dem", "no relative altitude: the ground is the DEM under the camera (the DEM converted into the "
                        "GPS altitudes' reference, EGM96; it cannot be checked against them)"),
    ("no_ground_height", "no relative altitude, flight height or DEM: the height above the ground is unknown, so "
                         "these frames have no footprint and get no labels or detections. Give FLIGHT_HEIGHT_M or "
                         "a DEM, or refine their poses (Refine frame poses gives them the ground their tie points "
                         "see)"),
    ("approx_intrinsics", "intrinsics from the nominal focal length; give a CALIBRATION for precise labels"),
)


# ---------------------------------------------------------------------------------------- XMP
def xmp_tags(text: str, prefix: str) -> dict:
    """Simple XMP properties ``prefix:Name`` of an XMP packet (attribute or element form) → text."""
    name = re.escape(prefix)
    tags = {k: v.strip() for k, v in re.findall(rf"(?<![\w-]){name}:(\w+)\s*=\s*\"([^\"]*)\"", text)}
    tags.update({k: v.strip() for k, v in re.findall(rf"<{name}:(\w+)>([^<]*)</{name}:\1>", text)})
    return tags


def _number(tags: dict, name: str, meta: DjiMetadata, prefix: str) -> float | None:
    """A tag as a number; XMP rationals ("11485529/262144") allowed; None if absent."""
    if name not in tags:
        return None
    text = tags[name]
    try:
        num, _, den = text.partition("/")
        value = float(num) / float(den) if den else float(num)
    except (ValueError, ZeroDivisionError):
        raise InputError(f"{text!r} is not a number", source=meta.path, field=f"{prefix}:{name}") from None
    return value if math.isfinite(value) else None


def pix4d_to_gimbal(yaw: float, pitch: float, roll: float) -> tuple[float, float, float]:
    """(roll, pitch, yaw) of our gimbal frame (deg, ZYX, pitch −90° = nadir) from Pix4D-convention camera
    angles (deg, pitch 0 = nadir)."""
    r = euler_zyx_to_rotmat(*np.radians([roll, pitch, yaw])) @ R_BODY_GIMBAL_PIX4D
    # Straight down (Pix4D pitch and roll 0) is gimbal lock: rotmat_to_euler_zyx then gives roll 0 and the
    # whole turn as yaw, as DJI writes a nadir gimbal.
    roll_g, pitch_g, yaw_g = (math.degrees(float(a)) for a in rotmat_to_euler_zyx(r))
    return roll_g, pitch_g, yaw_g % 360.0


def maker_attitude(meta: DjiMetadata) -> tuple[float, float, float] | None:
    """Gimbal (roll, pitch, yaw) in degrees from another maker's XMP, or None when it writes none."""
    parrot = xmp_tags(meta.xmp_text, "drone-parrot")
    angles = [_number(parrot, f"Camera{a}Degree", meta, "drone-parrot") for a in ("Roll", "Pitch", "Yaw")]
    if None not in angles:
        return angles[0], angles[1], angles[2] % 360.0
    camera = xmp_tags(meta.xmp_text, "Camera")
    yaw, pitch, roll = (_number(camera, a, meta, "Camera") for a in ("Yaw", "Pitch", "Roll"))
    if yaw is None or pitch is None or roll is None:
        return None
    if meta.make.lower() == "sensefly":
        roll = -roll
    return pix4d_to_gimbal(yaw, pitch, roll)


# ---------------------------------------------------------------------------------------- pose
def other_pose(meta: DjiMetadata) -> tuple[DjiPose, bool]:
    """Pose of an image without DJI tags and whether its heading is still to come from the track.

    The ground height is NaN where the image has no relative altitude (:func:`import_drone_images`
    places it); InputError if the image has no GPS fix or no height at all.
    """
    lat, lon = gps_position(meta)
    above_ground = _number(xmp_tags(meta.xmp_text, "Camera"), "AboveGroundAltitude", meta, "Camera")
    if above_ground is not None and above_ground <= 0.5:
        raise InputError(f"AboveGroundAltitude {above_ground:g} m: the drone is on or below the take-off point",
                         source=meta.path, field="Camera:AboveGroundAltitude")
    height = meta.exif_alt if meta.exif_alt is not None else above_ground
    if height is None:
        raise InputError("has no GPS altitude (EXIF GPSAltitude): its height cannot be placed", source=meta.path,
                         field="GPSAltitude")
    ground = height - above_ground if above_ground is not None else math.nan
    source = TAKEOFF if above_ground is not None else NO_GROUND
    attitude = maker_attitude(meta)
    flags = ["rtk_none"]
    if attitude is None:
        roll, pitch, yaw = 0.0, -90.0, math.nan
        flags.append("attitude_from_track")
    else:
        roll, pitch, yaw = attitude
        if pitch > NADIR_PITCH_LIMIT_DEG:
            flags.append("non_nadir")
    pose = DjiPose(lat, lon, height, ground, roll, pitch, yaw, RTK_NONE, (math.nan,) * 3, flags, source)
    return pose, attitude is None


def track_headings(lat, lon, time_s) -> tuple[np.ndarray, list[list[str]]]:
    """Heading (deg from true north) of each frame of one camera along its flight track, and flags.

    Frames are taken in capture-time order (name order, i.e. input order, breaks ties and stands in
    when a time is missing). A frame's heading is the bearing from the previous frame to the next (the
    first and last use their one neighbour); where those lie less than :data:`TRACK_MIN_BASE_M` apart
    (hovering) the window widens. A lone frame, or one with no movement around it, gets heading 0 and
    ``heading_unknown``; one where the track turns by more than :data:`TRACK_TURN_DEG` gets ``track_turn``.
    """
    lat, lon, time_s = (np.asarray(a, dtype=float) for a in (lat, lon, time_s))
    n = len(lat)
    heading = np.zeros(n)
    flags: list[list[str]] = [[] for _ in range(n)]
    if n == 0:
        return heading, flags
    index = np.arange(n)
    order = index if np.isnan(time_s).any() else np.lexsort((index, time_s))
    enu = LocalFrame.around(lat, lon).from_geodetic(lat[order], lon[order], np.zeros(n))[:, :2]

    def base(a, b):
        return float(np.hypot(*(enu[b] - enu[a])))

    def bearing(a, b):
        east, north = enu[b] - enu[a]
        return math.degrees(math.atan2(east, north)) % 360.0

    for k in range(n):
        lo, hi = max(k - 1, 0), min(k + 1, n - 1)
        while base(lo, hi) < TRACK_MIN_BASE_M and (lo > 0 or hi < n - 1):
            lo, hi = max(lo - 1, 0), min(hi + 1, n - 1)
        frame = order[k]
        if base(lo, hi) < TRACK_MIN_BASE_M:
            flags[frame].append("heading_unknown")
            continue
        heading[frame] = bearing(lo, hi)
        if 0 < k < n - 1 and min(base(k - 1, k), base(k, k + 1)) >= TRACK_MIN_BASE_M:
            turn = (bearing(k, k + 1) - bearing(k - 1, k) + 180.0) % 360.0 - 180.0
            if abs(turn) > TRACK_TURN_DEG:
                flags[frame].append("track_turn")
    return heading, flags


def drone_camera(meta: DjiMetadata, calibration: CameraModel | None = None) -> tuple[CameraModel, list]:
    """:func:`.dji.dji_camera` with :data:`SENSOR_WIDTH_MM` for cameras whose EXIF lacks the sensor size."""
    width = SENSOR_WIDTH_MM.get(f"{meta.make} {meta.model}".lower())
    return dji_camera(meta, calibration, sensor_width_mm=width)


# ---------------------------------------------------------------------------------------- import
def import_drone_images(folder, calibration: CameraModel | None = None, crs: ProjectedCRS | None = None,
                        progress=None, is_canceled=None, dem: DemRaster | None = None,
                        flight_height_m: float | None = None) -> FlightImport:
    """Frames with footprints from a folder of drone JPEGs; images that cannot be placed are reported.

    ``frame_id`` is the image's index in the name-sorted folder listing (stable across re-imports).
    ``flight_height_m``: the height above the take-off ground the flight was flown at, for images
    without a relative altitude (module docstring). With a ``dem`` the footprints drape on the terrain;
    it is converted into the frames' heights (:data:`.dji.DJI_HEIGHT_REFERENCE`) and checked once against the
    take-off heights the flight has.
    """
    if flight_height_m is not None and not flight_height_m > 0.5:
        raise InputError(f"the flight height above the ground must be more than 0.5 m, not {flight_height_m:g}",
                         field="FLIGHT_HEIGHT_M")
    paths = list_jpegs(folder)
    if not paths:
        raise InputError("holds no JPEG images (.jpg/.jpeg)", source=str(folder))
    report = ImportReport(str(folder))
    cameras: dict[str, CameraModel] = {}
    rows, unplaced = [], []
    for i, path in enumerate(paths):
        check_cancel(is_canceled)
        try:
            meta = read_dji_metadata(path)
            if meta.orientation not in (0, 1):
                raise InputError(f"EXIF Orientation is {meta.orientation} (a rotated image); only unrotated "
                                 "drone images are supported", source=str(path), field="Orientation")
            pose, from_track = (dji_pose(meta), False) if meta.has_dji_tags else other_pose(meta)
            camera, cam_flags = drone_camera(meta, calibration)
        except InputError as exc:
            unplaced.append(detached(exc))
            continue
        camera = cameras.setdefault(camera.to_json(), camera)
        rows.append([i, str(path.resolve()), meta.time_s, pose, camera, pose.flags + cam_flags, from_track])
        if progress is not None:
            progress(0.5 * (i + 1) / len(paths))
    _place_grounds(rows, flight_height_m, dem is not None)
    _head_along_tracks(rows)
    report.counts.update(images=len(paths), placed=len(rows), unplaced=len(unplaced))
    report.unplaced = unplaced
    if unplaced:
        report.errors.append(f"{len(unplaced)} of {len(paths)} image(s) cannot be placed: "
                             + "; ".join(str(e) for e in unplaced[:5]))
    if not rows:
        raise InputError(f"none of its {len(paths)} JPEG image(s) can be placed; the first: {unplaced[0]}",
                         source=str(folder))
    ids, images, times, poses, cams, flags, _ = zip(*rows)
    frames = Frames(
        frame_id=np.asarray(ids, dtype=np.int64), image=list(images), time_s=np.asarray(times, dtype=float),
        lat=np.array([p.lat for p in poses]), lon=np.array([p.lon for p in poses]),
        height=np.array([p.height for p in poses]), quat=np.array([p.quat for p in poses]),
        ground_h=np.array([p.ground_h for p in poses]), rtk_status=np.array([p.rtk_status for p in poses]),
        sync_offset_s=np.full(len(rows), np.nan), cameras=list(cams), flags=[list(f) for f in flags],
        euler_deg=np.array([[p.roll_deg, p.pitch_deg, p.yaw_deg] for p in poses]),
        extra={name: np.array([p.rtk_std[k] for p in poses])
               for k, name in enumerate(("rtk_std_lon_m", "rtk_std_lat_m", "rtk_std_hgt_m"))},
        reference=DJI_HEIGHT_REFERENCE, ground_source=[p.ground_source for p in poses])
    crs = crs or ProjectedCRS.for_site(frames.lat, frames.lon)
    sub = None if progress is None else (lambda f: progress(0.5 + 0.5 * f))
    ground = dem_ground_for(frames, dem, report)
    fp = compute_footprints(frames, crs, progress=sub, is_canceled=is_canceled, ground=ground)
    on_dem = np.array(["ground_from_dem" in f for f in frames.flags])
    frames.ground_h[on_dem] = frames.height[on_dem] - fp.depth_m[on_dem]
    for i in np.flatnonzero(on_dem & np.isfinite(frames.ground_h)):
        frames.ground_source[i] = DEM_GROUND
    for flag, text in FLAG_NOTES:
        n = sum(flag in f for f in frames.flags)
        report.counts[flag] = n
        if n:
            report.notes.append(f"{n} frame(s) flagged {flag}: {text}")
    n = sum("footprint_unbounded" in f for f in frames.flags)
    if n:
        report.notes.append(f"{n} frame(s) {UNBOUNDED_NOTE} (flag footprint_unbounded)")
    return FlightImport(frames, fp, [], report)


def _place_grounds(rows, flight_height_m, has_dem) -> None:
    """Give frames without a relative altitude their ground: from the flight height, else the DEM's (after the
    footprints); without either they keep none (``compute_footprints`` flags them ``no_ground_height``)."""
    need = [r for r in rows if math.isnan(r[3].ground_h)]
    if not need or (flight_height_m is None and not has_dem):
        return
    if flight_height_m is None:
        for r in need:
            r[5].append("ground_from_dem")
        return
    for camera in {id(r[4]): r[4] for r in need}.values():
        mine = [r for r in need if r[4] is camera]
        takeoff = float(np.median([r[3].height for r in mine])) - flight_height_m
        for r in mine:
            r[3].ground_h = takeoff
            r[3].ground_source = FLIGHT_HEIGHT
            r[5].append("ground_from_flight_height")


def _head_along_tracks(rows) -> None:
    """Give frames without an attitude the heading of their camera's track (all its frames count)."""
    for camera in {id(r[4]): r[4] for r in rows if r[6]}.values():
        mine = [r for r in rows if r[4] is camera]
        heading, flags = track_headings([r[3].lat for r in mine], [r[3].lon for r in mine], [r[2] for r in mine])
        for r, h, f in zip(mine, heading, flags):
            if r[6]:
                r[3].yaw_deg = float(h)
                r[5].extend(f)
