"""Frames of a flight: ground heights from the altimeter, the frame table, footprints and frame records."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import check_cancel
from ..geometry.geodesy import LocalFrame, ProjectedCRS
from ..geometry.ground import LevelPlaneGround
from ..geometry.heights import ALTIMETER, ELLIPSOIDAL_REFERENCE, NO_GROUND, VerticalReference
from ..geometry.poses import FrameGeometry, FramePoses, ground_height_from_altimeter, indices_by_camera
from ..geometry.projection import footprints
from .frame_records import FRAME_FIELDS, euler_degrees
from .pose_log import RTK_FIXED, RTK_FLOAT

#: A strobe row whose altimeter reading is bad takes the ground height interpolated from good
#: readings at most this far (s) before and after it; beyond, the frame has no ground height.
RADALT_WINDOW_S = 1.0
#: Terrain slope (deg) up to which the method measured the level-plane ground model to hold.
FLAT_ENVELOPE_DEG = 10.0
#: Frame-layer fields beyond :data:`.frame_records.FRAME_FIELDS` (DJI RTK accuracy; NULL otherwise).
FRAME_EXTRA_FIELDS = [
    ("rtk_std_lon_m", "double", "RTK standard deviation east-west (m), DJI RtkStdLon"),
    ("rtk_std_lat_m", "double", "RTK standard deviation north-south (m), DJI RtkStdLat"),
    ("rtk_std_hgt_m", "double", "RTK standard deviation of height (m), DJI RtkStdHgt"),
    ("terrain_slope_deg", "double", "terrain slope under the footprint from the DEM (deg; NULL without a DEM)"),
]
FRAME_LAYER_FIELDS = FRAME_FIELDS + FRAME_EXTRA_FIELDS


def ground_heights(time_s, height, quat, radalt, good, query, t_imu_rad=None,
                   window_s: float = RADALT_WINDOW_S):
    """Ellipsoidal ground heights (m) at rows ``query`` and whether each was interpolated.

    Rows with a ``good`` altimeter reading give the tilt-corrected ground height
    (:func:`.poses.ground_height_from_altimeter`); a queried row without one takes the linear
    interpolation in time between the nearest good readings before and after it, or the nearer one
    alone, provided they lie within ``window_s``; otherwise NaN.
    """
    time_s = np.asarray(time_s, dtype=float)
    query = np.asarray(query, dtype=np.int64)
    good_idx = np.flatnonzero(good)
    out = np.full(len(query), np.nan)
    interpolated = np.zeros(len(query), dtype=bool)
    if len(good_idx) == 0 or len(query) == 0:
        return out, interpolated
    g_t = time_s[good_idx]
    g_h = ground_height_from_altimeter(height[good_idx], quat[good_idx], radalt[good_idx], t_imu_rad)
    own = np.asarray(good)[query]
    own_pos = np.searchsorted(good_idx, query[own])
    out[own] = g_h[own_pos]
    need = np.flatnonzero(~own)
    if len(need):
        t = time_s[query[need]]
        after = np.searchsorted(g_t, t, side="left")
        before = after - 1
        has_b = before >= 0
        has_a = after < len(g_t)
        tb = np.where(has_b, g_t[np.clip(before, 0, None)], -np.inf)
        ta = np.where(has_a, g_t[np.clip(after, None, len(g_t) - 1)], np.inf)
        ok_b = has_b & (t - tb <= window_s)
        ok_a = has_a & (ta - t <= window_s)
        hb = g_h[np.clip(before, 0, None)]
        ha = g_h[np.clip(after, None, len(g_t) - 1)]
        with np.errstate(invalid="ignore", divide="ignore"):
            w = np.where(ta > tb, (t - tb) / (ta - tb), 0.5)
        both = ok_b & ok_a
        value = np.where(both, hb + w * (ha - hb), np.where(ok_b, hb, np.where(ok_a, ha, np.nan)))
        out[need] = value
        interpolated[need] = np.isfinite(value)
    return out, interpolated

@dataclass
class Frames:
    """F frames, everything the frame layer carries (arrays of length F; heights in m).

    ``cameras[f]`` is the camera model of frame f (frames of one camera share the object);
    ``euler_deg`` (F, 3) overrides the roll/pitch/yaw derived from ``quat`` (DJI writes the gimbal
    angles exactly, where a nadir gimbal sits at the ZYX singularity); ``extra`` holds
    :data:`FRAME_EXTRA_FIELDS` columns. ``reference``: what ``height`` and ``ground_h`` are measured from;
    ``ground_source``: per frame, where ``ground_h`` came from (``heights.GROUND_SOURCES``; default: the
    altimeter where a ground height is known, none elsewhere).
    """

    frame_id: np.ndarray
    image: list
    time_s: np.ndarray
    lat: np.ndarray
    lon: np.ndarray
    height: np.ndarray
    quat: np.ndarray
    ground_h: np.ndarray
    rtk_status: np.ndarray
    sync_offset_s: np.ndarray
    cameras: list
    flags: list
    euler_deg: np.ndarray | None = None
    extra: dict = field(default_factory=dict)
    reference: VerticalReference = ELLIPSOIDAL_REFERENCE
    ground_source: list | None = None

    def __post_init__(self):
        if self.ground_source is None:
            self.ground_source = [ALTIMETER if np.isfinite(g) else NO_GROUND for g in np.asarray(self.ground_h)]
        self.ground_source = list(self.ground_source)

    def __len__(self) -> int:
        return len(self.frame_id)

    def subset(self, index) -> "Frames":
        index = np.asarray(index)
        if index.dtype == bool:
            index = np.flatnonzero(index)
        return Frames(self.frame_id[index], [self.image[i] for i in index], self.time_s[index],
                      self.lat[index], self.lon[index], self.height[index], self.quat[index],
                      self.ground_h[index], self.rtk_status[index], self.sync_offset_s[index],
                      [self.cameras[i] for i in index], [list(self.flags[i]) for i in index],
                      None if self.euler_deg is None else self.euler_deg[index],
                      {k: v[index] for k, v in self.extra.items()}, self.reference,
                      [self.ground_source[i] for i in index])

    def poses(self, index) -> FramePoses:
        """The poses of frames ``index``, which all have one camera (:func:`.poses.indices_by_camera`)."""
        return FramePoses(self.frame_id[index], self.lat[index], self.lon[index], self.height[index],
                          self.quat[index], self.ground_h[index], self.cameras[index[0]], self.reference,
                          [self.ground_source[i] for i in index])

    def all_poses(self) -> FramePoses:
        """Every frame's pose as one :class:`FramePoses` (the first frame's camera stands for all: for checks
        over the whole flight that use positions and heights, not projections)."""
        return self.poses(np.arange(len(self)))


@dataclass
class Footprints:
    """Per frame: the border's ground ring (K, 3) as output-CRS x, y and ellipsoidal z, or None."""

    rings: list
    depth_m: np.ndarray
    gsd_cm: np.ndarray
    crs: ProjectedCRS
    slope_deg: np.ndarray | None = None


def compute_footprints(frames: Frames, crs: ProjectedCRS, per_edge: int = 4, block: int = 4096,
                       progress=None, is_canceled=None, ground=None) -> Footprints:
    """Ground footprints of every frame, in ``crs``: over its level ground, or draped on a DEM.

    Geometry runs in one :class:`.geodesy.LocalFrame` around all frames (true-north attitudes, no
    grid convergence); ring points go local → WGS84 → ``crs``. ``ground`` builds another ground model
    from a :class:`FrameGeometry` (a DEM's ``DemGround.from_dem``); with it every frame is placed and
    the terrain slope under each footprint is measured. A frame without a ground height (level plane),
    or whose border rays do not all reach the ground (past the DEM, or above the horizon), gets no ring and the
    flag ``no_ground_height`` / ``footprint_unbounded`` (added to ``frames.flags``).
    """
    n = len(frames)
    rings: list = [None] * n
    depth = np.full(n, np.nan)
    gsd = np.full(n, np.nan)
    slope = np.full(n, np.nan)
    if n == 0:
        return Footprints(rings, depth, gsd, crs, slope)
    local = LocalFrame.around(frames.lat, frames.lon, frames.height)
    placeable = np.isfinite(frames.ground_h) | (ground is not None)
    for i in np.flatnonzero(~placeable):
        frames.flags[i].append("no_ground_height")
    placed = np.flatnonzero(placeable)
    total, done = max(len(placed), 1), 0
    for members in indices_by_camera([frames.cameras[i] for i in placed]):
        members = placed[members]
        camera = frames.cameras[members[0]]
        for start in range(0, len(members), block):
            check_cancel(is_canceled)
            idx = members[start:start + block]
            geometry = FrameGeometry(frames.poses(idx), local)
            model = LevelPlaneGround(geometry) if ground is None else ground(geometry)
            pts, complete = footprints(geometry, model, per_edge)
            if ground is None:
                depth[idx] = geometry.depth_below()
            else:
                depth[idx], slope[idx] = _terrain_depth_and_slope(geometry, model)
                for f in idx[np.nan_to_num(slope[idx]) > FLAT_ENVELOPE_DEG]:
                    frames.flags[f].append("steep_terrain")
            gsd[idx] = depth[idx] / np.sqrt(camera.fx * camera.fy) * 100.0
            k = pts.shape[1]
            ok = np.flatnonzero(complete)
            if len(ok):
                lat, lon, h = local.to_geodetic(pts[ok].reshape(-1, 3))
                x, y = crs.from_geodetic(lat, lon)
                xyz = np.stack([x, y, h], axis=-1).reshape(len(ok), k, 3)
                for j, f in enumerate(idx[ok]):
                    rings[f] = xyz[j]
            for f in idx[~complete]:
                frames.flags[f].append("footprint_unbounded")
            done += len(idx)
            if progress is not None:
                progress(done / total)
    return Footprints(rings, depth, gsd, crs, slope)


def _terrain_depth_and_slope(geometry: FrameGeometry, model):
    """Depth along the local vertical to the terrain under each camera, and the footprint's slope."""
    from ..geometry.dem import frame_terrain_slope

    below, valid = model.intersect(np.arange(len(geometry)), geometry.C, -geometry.up)
    depth = np.where(valid, np.einsum("fi,fi->f", geometry.C - below, geometry.up), np.nan)
    return depth, frame_terrain_slope(geometry, model).slope_deg


def frame_records(frames: Frames, fp: Footprints):
    """One dict per frame with the :data:`FRAME_LAYER_FIELDS` names (None for unknown values)."""
    if frames.euler_deg is not None:
        roll, pitch, yaw = frames.euler_deg.T
    else:
        roll, pitch, yaw = euler_degrees(frames.quat) if len(frames) else (np.empty(0),) * 3
    quat = frames.quat / np.linalg.norm(frames.quat, axis=1, keepdims=True)
    json_of: dict[int, str] = {}
    for i in range(len(frames)):
        cam = frames.cameras[i]
        if id(cam) not in json_of:
            json_of[id(cam)] = cam.to_json()
        rec = {"frame_id": int(frames.frame_id[i]), "image": frames.image[i],
               "time_s": _value(frames.time_s[i]), "lat": float(frames.lat[i]), "lon": float(frames.lon[i]),
               "height_m": float(frames.height[i]),
               "qw": float(quat[i, 0]), "qx": float(quat[i, 1]), "qy": float(quat[i, 2]), "qz": float(quat[i, 3]),
               "roll_deg": float(roll[i]), "pitch_deg": float(pitch[i]), "yaw_deg": float(yaw[i]),
               "ground_h_m": _value(frames.ground_h[i]), "depth_m": _value(fp.depth_m[i]),
               "height_ref": frames.reference.text, "ground_src": frames.ground_source[i],
               "rtk_status": int(frames.rtk_status[i]), "sync_offset_s": _value(frames.sync_offset_s[i]),
               "gsd_cm": _value(fp.gsd_cm[i]), "camera": json_of[id(cam)],
               "flags": ",".join(dict.fromkeys(frames.flags[i]))}
        for name, _, _ in FRAME_EXTRA_FIELDS:
            rec[name] = _value(frames.extra[name][i]) if name in frames.extra else None
        if fp.slope_deg is not None:
            rec["terrain_slope_deg"] = _value(fp.slope_deg[i])
        yield rec


def _value(x):
    x = float(x)
    return None if math.isnan(x) else x


def rtk_flags(rtk_status: np.ndarray) -> list[list[str]]:
    return [["rtk_float"] if s == RTK_FLOAT else ([] if s == RTK_FIXED else ["rtk_none"])
            for s in np.asarray(rtk_status).tolist()]


def dem_ground_for(frames: Frames, dem, report=None):
    """The DEM ground-model factory for ``frames``' footprints (None without a DEM): the DEM converted into the
    frames' vertical reference and checked once against their ground over the whole flight
    (:func:`..geometry.dem.check_vertical_datum`), the check's result a finding of ``report``."""
    from ..geometry.dem import DemGroundFactory, check_vertical_datum

    if dem is None:
        return None
    check = check_vertical_datum(dem, frames.all_poses())
    if report is not None:
        report.findings.append(f"DEM: {check.describe()}")
    return DemGroundFactory(dem, vertical_offset_m=check.offset_m)


def frames_from_records(records, source: str = "frame layer") -> Frames:
    """The :class:`Frames` of frame-layer records (as a frame layer was written), in record order."""
    from .frame_records import poses_from_records

    records = list(records)
    n = len(records)
    lat, lon, height, ground = (np.full(n, np.nan) for _ in range(4))
    quat = np.zeros((n, 4))
    cameras: list = [None] * n
    ground_source: list = [NO_GROUND] * n
    frame_id = np.zeros(n, dtype=np.int64)
    reference = ELLIPSOIDAL_REFERENCE
    for poses, idx in poses_from_records(records, source):
        lat[idx], lon[idx], height[idx], quat[idx], ground[idx] = (poses.lat, poses.lon, poses.height, poses.quat,
                                                                   poses.ground_height)
        frame_id[idx] = poses.frame_id
        reference = poses.reference
        for i, s in zip(idx, poses.ground_source):
            cameras[i] = poses.camera
            ground_source[i] = s

    def column(name, default=np.nan):
        return np.array([default if r.get(name) is None else float(r[name]) for r in records], dtype=float)

    return Frames(frame_id, [r.get("image") or "" for r in records], column("time_s"), lat, lon, height, quat,
                  ground, column("rtk_status", 1).astype(int), column("sync_offset_s"), cameras,
                  [[f for f in (r.get("flags") or "").split(",") if f] for r in records],
                  np.column_stack([column("roll_deg"), column("pitch_deg"), column("yaw_deg")]),
                  {name: column(name) for name, _, _ in FRAME_EXTRA_FIELDS if name != "terrain_slope_deg"},
                  reference, ground_source)
