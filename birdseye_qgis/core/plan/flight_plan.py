"""Survey flight planning over geotags: merge → order (TSP) → split into missions → estimate.

Frames and units (docs/design.md#world):

* Geotags and home come in as WGS84 latitude/longitude (degrees). All geometry runs in a
  :class:`~.geodesy.LocalFrame` (east-north-up, metres) centred on the site; distances are
  therefore ground metres at any latitude, never degrees.
* The plan is made over a level plane through the geotags (ellipsoidal height 0 in the local
  frame): waypoints are ``altitude_m`` above it. Mission altitudes are relative to the take-off
  point, which is assumed to stand on the same level ground.
* The camera, when given, looks straight down from a gimbal at −90° with the image top towards the
  aircraft's nose; the aircraft may face any heading (DJI "follow wayline"), so the footprint check
  holds for every heading.

Pipeline (:func:`plan_flight`):

1. **Merge** geotags into waypoints: a greedy disc cover (each chosen disc of radius
   ``merge_radius_m`` covers the most geotags still uncovered; candidate centres are the geotags and
   the midpoints of pairs within two radii), each waypoint at the centre of the smallest circle
   enclosing its geotags. Every geotag is thus within ``merge_radius_m`` of its waypoint. With a
   camera the radius is also capped by the footprint's inscribed radius at ``altitude_m`` (with the
   edge margin), and every geotag is projected into its waypoint's nadir frame at headings every
   :data:`HEADING_STEP_DEG`; a geotag that misses (a strongly distorted lens) gets its own waypoint.
2. **Order**: one tour over home and all waypoints by fast-tsp (distances in metres, scaled to
   its 16-bit integers), never worse than nearest-neighbour. Without a home the route is the
   shortest open path.
3. **Split** the tour into consecutive missions that respect ``max_waypoints`` and
   ``max_flight_min``, each from home back to home: an exact dynamic programme over the cut points
   (fewest missions, then shortest total route), then each mission re-ordered on its own.
4. **Estimate** flight time: climb and descent, each leg flown stop-to-stop with a trapezoidal speed
   profile, hover and photo time at each waypoint.
5. **Surveyed area** (with a camera and a :class:`~..field.surveyed_area.SurveyedArea`): the share of each
   waypoint's photo whose ground lies outside the area (:func:`photo_outside_share`) — ground Write labels
   takes no negative tiles from, since an unsurveyed target may lie there.
"""
from __future__ import annotations

import heapq
import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import Cancelled, InputError
from ..field.surveyed_area import PlacedArea, SurveyedArea
from ..geometry.camera import NADIR_ROTATION, CameraModel
from ..geometry.geodesy import LocalFrame
from ..geometry.rigid import RigidTransform
from .mission_files import CAPTURE_PHOTO, CAPTURE_TIMED, MissionSpec

ALTITUDE_LIMITS_M = (2.0, 120.0)
SPEED_LIMITS_MS = (0.5, 15.0)
#: Geotags (and home) spread wider than this are refused unless forced: a farm partition is a few
#: hundred metres across; tens of kilometres mean a wrong CRS or bad rows.
MAX_SPREAD_M = 10_000.0
#: Flight-time model of a multirotor on a waypoint mission (typical DJI mission defaults).
CLIMB_RATE_MS = 3.0
DESCENT_RATE_MS = 2.0
ACCELERATION_MS2 = 2.0
PHOTO_ACTION_S = 1.0
#: Ground-height spread (fraction of the altitude) beyond which the level-field assumption is flagged.
LEVEL_GROUND_FRACTION = 0.1
#: Headings at which the footprint check projects each geotag.
HEADING_STEP_DEG = 5.0
#: Headings at which the share of a photo outside the surveyed area is measured (the worst is reported).
OUTSIDE_HEADING_STEP_DEG = 15.0
#: Pixels sampled along the image's longer side for that share (the shorter side in proportion).
OUTSIDE_SAMPLES_LONG_SIDE = 40
#: fast-tsp works on unsigned 16-bit distances.
_TSP_INT_MAX = 65535
SURVEY_ORIGIN = "survey"


@dataclass(frozen=True)
class FlightSettings:
    """What the user chose. Metres, seconds, m/s; ``forward_overlap`` is a fraction (0–1).

    The altitude defaults to the method's flying height, 10 m, where the sensor bound accepts the
    deployed platform's pose noise.
    """

    altitude_m: float = 10.0
    speed_ms: float = 3.0
    merge_radius_m: float = 2.0
    hover_s: float = 2.0
    max_waypoints: int = 99
    max_flight_min: float = 20.0
    capture: str = CAPTURE_PHOTO
    capture_interval_s: float = 2.0
    forward_overlap: float = 0.8
    footprint_margin_px: float = 50.0
    force: bool = False
    tsp_seconds: float | None = None

    def validate(self) -> None:
        lo, hi = ALTITUDE_LIMITS_M
        if not (lo <= self.altitude_m <= hi):
            raise InputError(f"ALTITUDE_M = {self.altitude_m:g} m is outside {lo:g}–{hi:g} m: below"
                             f" {lo:g} m the rotor wash disturbs the crop and the drone cannot hold"
                             f" height; above {hi:g} m is beyond the usual legal ceiling")
        lo, hi = SPEED_LIMITS_MS
        if not (lo <= self.speed_ms <= hi):
            raise InputError(f"SPEED_MS = {self.speed_ms:g} m/s is outside {lo:g}–{hi:g} m/s"
                             " (DJI waypoint missions fly at most 15 m/s)")
        if not self.merge_radius_m >= 0:
            raise InputError(f"MERGE_RADIUS_M = {self.merge_radius_m:g} m must be zero or positive")
        if not self.hover_s >= 0:
            raise InputError(f"HOVER_S = {self.hover_s:g} s must be zero or positive")
        if self.max_waypoints < 1:
            raise InputError(f"MAX_WAYPOINTS = {self.max_waypoints} must be at least 1")
        if not self.max_flight_min > 0:
            raise InputError(f"MAX_FLIGHT_MIN = {self.max_flight_min:g} min must be positive")
        if self.capture not in (CAPTURE_PHOTO, CAPTURE_TIMED):
            raise InputError(f"CAPTURE must be '{CAPTURE_PHOTO}' or '{CAPTURE_TIMED}'")
        if not self.capture_interval_s >= 0:
            raise InputError(f"CAPTURE_INTERVAL_S = {self.capture_interval_s:g} s must be zero"
                             " (derive it from the camera) or positive")
        if not (0.0 <= self.forward_overlap < 1.0):
            raise InputError(f"FORWARD_OVERLAP_PCT = {100 * self.forward_overlap:g} % must be in"
                             " 0–99 %")
        if not self.footprint_margin_px >= 0:
            raise InputError(f"FOOTPRINT_MARGIN_PX = {self.footprint_margin_px:g} px must be zero"
                             " or positive")

    @property
    def per_waypoint_s(self) -> float:
        """Time spent at each waypoint: hover, plus the photo action when shooting per waypoint."""
        return self.hover_s + (PHOTO_ACTION_S if self.capture == CAPTURE_PHOTO else 0.0)


@dataclass
class Mission:
    """One flight: waypoint indices (into :attr:`FlightPlan.waypoint_xy`) in flight order."""

    number: int
    waypoints: np.ndarray
    length_m: float
    time_s: float


@dataclass
class FlightPlan:
    """The planned flight. Local coordinates are metres in :attr:`local` (east, north)."""

    local: LocalFrame
    settings: FlightSettings
    geotag_xy: np.ndarray
    geotag_ids: list
    waypoint_xy: np.ndarray
    waypoint_lat: np.ndarray
    waypoint_lon: np.ndarray
    members: list
    missions: list
    home_xy: np.ndarray | None = None
    home_latlon: tuple | None = None
    capture_interval_s: float | None = None
    suggested_interval_s: float | None = None
    footprint_radius_m: float | None = None
    warnings: list = field(default_factory=list)
    #: Where each target came from: ``survey`` (a geotag) or ``review:<outcome>`` (a cluster the review
    #: left unresolved, ``core.scoring.reviewed_clusters``); None: every target is a geotag.
    geotag_origins: list | None = None
    #: Per waypoint, the share (0–1) of its photo whose ground lies outside the surveyed area at the worst
    #: heading; None without a camera or a surveyed area.
    outside_share: np.ndarray | None = None
    surveyed: SurveyedArea | None = None

    def waypoint_origins(self, w: int) -> tuple[str, str]:
        """(provenance, review outcomes) of a waypoint's targets, each ';'-joined and sorted."""
        origins = [SURVEY_ORIGIN if self.geotag_origins is None else self.geotag_origins[g] for g in self.members[w]]
        provenance = sorted({o.split(":", 1)[0] for o in origins})
        outcomes = sorted({o.split(":", 1)[1] for o in origins if ":" in o})
        return ";".join(provenance), ";".join(outcomes)

    @property
    def waypoint_count(self) -> int:
        return len(self.waypoint_xy)

    @property
    def total_length_m(self) -> float:
        return float(sum(m.length_m for m in self.missions))

    @property
    def total_time_s(self) -> float:
        return float(sum(m.time_s for m in self.missions))

    def mission_of_waypoint(self) -> np.ndarray:
        """(mission number, order within mission) per waypoint, both 1-based, shape (W, 2)."""
        out = np.zeros((self.waypoint_count, 2), dtype=int)
        for mission in self.missions:
            out[mission.waypoints, 0] = mission.number
            out[mission.waypoints, 1] = np.arange(1, len(mission.waypoints) + 1)
        return out

    def max_offset_m(self) -> np.ndarray:
        """Ground distance (m) from each waypoint to its farthest geotag."""
        return np.array([np.max(np.linalg.norm(self.geotag_xy[m] - self.waypoint_xy[w], axis=1))
                         for w, m in enumerate(self.members)])

    def route_latlon(self, mission: Mission):
        """(lat, lon) arrays of a mission's route line: home → waypoints → home when home is set."""
        lat = self.waypoint_lat[mission.waypoints]
        lon = self.waypoint_lon[mission.waypoints]
        if self.home_latlon is not None:
            lat = np.concatenate([[self.home_latlon[0]], lat, [self.home_latlon[0]]])
            lon = np.concatenate([[self.home_latlon[1]], lon, [self.home_latlon[1]]])
        return lat, lon

    def mission_specs(self, name: str) -> list[MissionSpec]:
        """One :class:`~.mission_files.MissionSpec` per mission, named ``<name>_m<k>`` when split."""
        specs = []
        for mission in self.missions:
            w = mission.waypoints
            specs.append(MissionSpec(
                name=name if len(self.missions) == 1 else f"{name}_m{mission.number}",
                lat=self.waypoint_lat[w], lon=self.waypoint_lon[w],
                altitude_m=np.full(len(w), self.settings.altitude_m),
                speed_ms=self.settings.speed_ms, hover_s=self.settings.hover_s,
                capture=self.settings.capture, capture_interval_s=self.capture_interval_s,
                home=self.home_latlon,
                geotag_ids=[[self.geotag_ids[g] for g in self.members[k]] for k in w]))
        return specs


#: Output schemas (name, type, description) of the waypoint and route layers.
WAYPOINT_FIELDS = [
    ("mission", "int", "mission (one flight, one battery) number, 1.."),
    ("order", "int", "order of the waypoint within its mission, 1.."),
    ("altitude", "double", "flight altitude relative to the take-off point (m)"),
    ("geotag_count", "int", "number of geotags this waypoint photographs"),
    ("geotag_ids", "string", "ids of those geotags, ';'-separated"),
    ("max_offset_m", "double", "ground distance from the waypoint to its farthest geotag (m)"),
    ("lat", "double", "latitude, WGS84 (deg), as written to the mission files"),
    ("lon", "double", "longitude, WGS84 (deg), as written to the mission files"),
    ("provenance", "string", "where its targets came from: survey (geotags), review (unresolved clusters), "
                             "';'-separated"),
    ("review_outcomes", "string", "what the review left open at its clusters: conflicting, uncertain, "
                                  "unreviewed (';'-separated; empty for geotags)"),
    ("outside_pct", "double", "share of the photo (% of its pixels) whose ground lies outside the surveyed area, "
                              "at the worst heading; empty without a camera"),
]
ROUTE_FIELDS = [
    ("mission", "int", "mission number, 1.."),
    ("waypoints", "int", "number of waypoints flown"),
    ("length_m", "double", "horizontal route length (m), from home back to home when HOME is given"),
    ("est_time_min", "double", "estimated flight time (min): climb, legs, hover and photos, descent"),
]


def waypoint_records(plan: "FlightPlan") -> list[dict]:
    """One record per waypoint (fields :data:`WAYPOINT_FIELDS`), in mission and flight order."""
    numbers, offsets = plan.mission_of_waypoint(), plan.max_offset_m()
    records = []
    for mission in plan.missions:
        for w in mission.waypoints:
            provenance, outcomes = plan.waypoint_origins(w)
            records.append({
                "mission": int(numbers[w, 0]), "order": int(numbers[w, 1]),
                "altitude": float(plan.settings.altitude_m), "geotag_count": len(plan.members[w]),
                "geotag_ids": ";".join(plan.geotag_ids[g] for g in plan.members[w]),
                "max_offset_m": round(float(offsets[w]), 4),
                "lat": float(plan.waypoint_lat[w]), "lon": float(plan.waypoint_lon[w]),
                "provenance": provenance, "review_outcomes": outcomes,
                "outside_pct": None if plan.outside_share is None else round(100.0 * float(plan.outside_share[w]), 1)})
    return records


def route_records(plan: "FlightPlan") -> list[dict]:
    """One record per mission (fields :data:`ROUTE_FIELDS`)."""
    return [{"mission": m.number, "waypoints": len(m.waypoints), "length_m": round(m.length_m, 2),
             "est_time_min": round(m.time_s / 60.0, 2)} for m in plan.missions]


# ---------------------------------------------------------------------- input checks
def check_coordinates(lat, lon, ids, source: str = "geotags") -> None:
    """Refuse coordinates that cannot be WGS84 degrees: missing, out of range, or exactly 0°/0°.

    A layer whose CRS claims degrees while holding metres is read as impossible latitudes here.
    """
    lat, lon = np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)
    missing = ~(np.isfinite(lat) & np.isfinite(lon))
    if np.any(missing):
        k = int(np.flatnonzero(missing)[0])
        raise InputError(f"feature {ids[k]} has no position (empty geometry); remove it or fix it",
                         source=source)
    bad_range = (np.abs(lat) > 90) | (np.abs(lon) > 180)
    if np.any(bad_range):
        k = int(np.flatnonzero(bad_range)[0])
        raise InputError(f"feature {ids[k]} has latitude {lat[k]:.6g}, longitude {lon[k]:.6g}, which"
                         " are not degrees: check the layer's CRS (metres read as degrees?)",
                         source=source)
    null_island = (np.abs(lat) < 1e-9) & (np.abs(lon) < 1e-9)
    if np.any(null_island):
        k = int(np.flatnonzero(null_island)[0])
        raise InputError(f"feature {ids[k]} lies at 0°, 0° — an empty or failed GNSS fix, not a"
                         " surveyed point; remove it", source=source)


def check_spread(xy: np.ndarray, ids, force: bool, source: str = "geotags") -> float:
    """Span (m) of the points; refused above :data:`MAX_SPREAD_M` unless ``force``."""
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    span = float(np.hypot(*(hi - lo)))
    if span > MAX_SPREAD_M and not force:
        median = np.median(xy, axis=0)
        far = int(np.argmax(np.linalg.norm(xy - median, axis=1)))
        raise InputError(
            f"the points span {span / 1000:.1f} km; a surveyed partition is usually under 2 km."
            f" The point farthest from the others is {ids[far]}"
            f" ({np.linalg.norm(xy[far] - median) / 1000:.1f} km from the median). Check the layer's CRS"
            " and for bad rows, or set FORCE to plan anyway", source=source)
    return span


# ---------------------------------------------------------------------- merging
def min_enclosing_circle(points: np.ndarray):
    """Centre (2,) and radius of the smallest circle enclosing 2-D points (Welzl, iterative)."""
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    if len(pts) == 1:
        return pts[0].copy(), 0.0
    pts = pts[np.random.default_rng(0).permutation(len(pts))]
    tol = 1e-9 * (1.0 + float(np.max(np.abs(pts))))

    def outside(p, c, r):
        return math.hypot(p[0] - c[0], p[1] - c[1]) > r + tol

    def two(a, b):
        return (a + b) / 2.0, math.hypot(*(a - b)) / 2.0

    def three(a, b, c):
        d = 2.0 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]))
        if abs(d) < 1e-18:  # collinear: the farthest pair spans the circle
            return max((two(a, b), two(a, c), two(b, c)), key=lambda cr: cr[1])
        sa, sb, sc = a @ a, b @ b, c @ c
        centre = np.array([sa * (b[1] - c[1]) + sb * (c[1] - a[1]) + sc * (a[1] - b[1]),
                           sa * (c[0] - b[0]) + sb * (a[0] - c[0]) + sc * (b[0] - a[0])]) / d
        return centre, max(math.hypot(*(centre - p)) for p in (a, b, c))

    c, r = pts[0].copy(), 0.0
    for i in range(1, len(pts)):
        if outside(pts[i], c, r):
            c, r = pts[i].copy(), 0.0
            for j in range(i):
                if outside(pts[j], c, r):
                    c, r = two(pts[i], pts[j])
                    for k in range(j):
                        if outside(pts[k], c, r):
                            c, r = three(pts[i], pts[j], pts[k])
    return c, float(r)


def merge_geotags(xy: np.ndarray, radius_m: float):
    """Group 2-D points (m) into discs of ``radius_m``: (centres (W, 2), labels (N,)).

    Greedy set cover: repeatedly take the candidate disc that covers the most points not yet
    covered. Candidate centres are the points themselves and the midpoints of pairs within
    ``2·radius_m`` (a pair further apart can share no disc). Each group's centre is then moved to the
    centre of its smallest enclosing circle, which is never farther than ``radius_m`` from any member.
    """
    from scipy.spatial import cKDTree

    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    n = len(xy)
    if radius_m <= 0 or n == 1:
        return xy.copy(), np.arange(n)
    tree = cKDTree(xy)
    candidates = [xy]
    pairs = tree.query_pairs(2.0 * radius_m, output_type="ndarray")
    if 0 < len(pairs) <= 50 * n:  # dense swarms: the points alone are candidates enough
        candidates.append(0.5 * (xy[pairs[:, 0]] + xy[pairs[:, 1]]))
    candidates = np.concatenate(candidates)
    covers = tree.query_ball_point(candidates, radius_m)
    labels = np.full(n, -1)
    heap = [(-len(c), k) for k, c in enumerate(covers)]
    heapq.heapify(heap)
    centres = []
    while heap:
        neg, k = heapq.heappop(heap)
        fresh = [p for p in covers[k] if labels[p] < 0]
        if not fresh:
            continue
        if len(fresh) < -neg:  # stale count: re-queue with the true gain (lazy greedy)
            heapq.heappush(heap, (-len(fresh), k))
            continue
        labels[fresh] = len(centres)
        centre, r = min_enclosing_circle(xy[fresh])
        centres.append(centre if r <= radius_m else candidates[k])
    return np.array(centres), labels


def nadir_camera(camera: CameraModel) -> CameraModel:
    """The calibrated lens on a gimbal at −90°, image top towards the nose."""
    return replace(camera, T_cam_imu=RigidTransform(NADIR_ROTATION, np.zeros(3)).matrix, t_imu_rad=None)


def _nadir_geometry(local: LocalFrame, camera: CameraModel, xy: np.ndarray, altitude_m: float,
                    yaw_rad: np.ndarray):
    """Frames of a level aircraft at local positions ``xy`` (F, 2), ``altitude_m`` above the level
    ground (ellipsoidal height 0), heading ``yaw_rad`` (F,) from true north."""
    from ..geometry.poses import FrameGeometry, FramePoses
    from ..geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat

    xy = np.atleast_2d(xy)
    lat, lon, _ = local.to_geodetic(np.column_stack([xy, np.zeros(len(xy))]))
    yaw = np.broadcast_to(np.asarray(yaw_rad, dtype=float), (len(xy),))
    quat = rotmat_to_quat(euler_zyx_to_rotmat(np.zeros(len(xy)), np.zeros(len(xy)), yaw))
    poses = FramePoses(np.arange(len(xy)), np.atleast_1d(lat), np.atleast_1d(lon),
                       np.full(len(xy), float(altitude_m)), quat, np.zeros(len(xy)),
                       nadir_camera(camera))
    return FrameGeometry(poses, local)


def footprint_radius_m(camera: CameraModel, altitude_m: float, margin_px: float,
                       local: LocalFrame | None = None) -> float:
    """Radius (m) of the largest ground circle around the nadir point that stays inside the image,
    ``margin_px`` from its edges, at any heading: the distance from the nadir point to the ground
    outline of the margin-inset image border (back-projected onto the level ground)."""
    from ..geometry.ground import LevelPlaneGround
    from ..geometry.projection import pixel_to_ground

    b = float(margin_px)
    x0, y0, x1, y1 = -0.5 + b, -0.5 + b, camera.width - 0.5 - b, camera.height - 0.5 - b
    if x0 >= x1 or y0 >= y1:
        raise InputError(f"FOOTPRINT_MARGIN_PX = {b:g} px leaves nothing of a {camera.width}×"
                         f"{camera.height} px image: use less than half the shorter side")
    local = local or LocalFrame(0.0, 0.0, 0.0)
    geometry = _nadir_geometry(local, camera, np.zeros((1, 2)), altitude_m, np.zeros(1))
    t = np.linspace(0.0, 1.0, 64, endpoint=False)[:, None]
    corners = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
    border = np.concatenate([a + t * (c - a) for a, c in zip(corners, np.roll(corners, -1, axis=0))])
    pts, valid = pixel_to_ground(geometry, LevelPlaneGround(geometry), np.zeros(len(border), int), border)
    if not np.all(valid):
        raise InputError("the camera's image border does not reach the ground from a nadir view;"
                         " check the calibration")
    outline = pts[:, :2] - geometry.ground_point[0, :2]
    a, c = outline, np.roll(outline, -1, axis=0)
    seg = c - a
    s = np.clip(np.einsum("ij,ij->i", -a, seg) / np.einsum("ij,ij->i", seg, seg), 0.0, 1.0)
    return float(np.min(np.linalg.norm(a + s[:, None] * seg, axis=1)))


def footprint_misses(local: LocalFrame, camera: CameraModel, altitude_m: float, margin_px: float,
                     waypoint_xy: np.ndarray, geotag_enu: np.ndarray, labels: np.ndarray,
                     step_deg: float = HEADING_STEP_DEG) -> np.ndarray:
    """Mask (N,) of geotags outside their waypoint's nadir image (by ``margin_px``) at some heading.

    Each geotag is projected with the core projection into a level, nadir frame at its waypoint,
    ``altitude_m`` above the level ground, at headings every ``step_deg``.
    """
    from ..geometry.projection import project_pairs

    headings = np.radians(np.arange(0.0, 360.0, step_deg))
    k = len(headings)
    geometry = _nadir_geometry(local, camera, np.repeat(waypoint_xy, k, axis=0), altitude_m,
                               np.tile(headings, len(waypoint_xy)))
    frame_idx = (np.repeat(labels, k) * k + np.tile(np.arange(k), len(labels)))
    proj = project_pairs(geometry, frame_idx, np.repeat(geotag_enu, k, axis=0),
                         edge_buffer_px=margin_px)
    return ~proj.in_view.reshape(len(labels), k).all(axis=1)


def along_track_footprint_m(camera: CameraModel, altitude_m: float) -> float:
    """Ground length (m) of the image's centre column (nose to tail) from a nadir view."""
    from ..geometry.ground import LevelPlaneGround
    from ..geometry.projection import pixel_to_ground

    geometry = _nadir_geometry(LocalFrame(0.0, 0.0, 0.0), camera, np.zeros((1, 2)), altitude_m,
                               np.zeros(1))
    uv = np.array([[camera.cx, -0.5], [camera.cx, camera.height - 0.5]])
    pts, valid = pixel_to_ground(geometry, LevelPlaneGround(geometry), np.zeros(2, int), uv)
    if not np.all(valid):
        raise InputError("the camera's image border does not reach the ground from a nadir view;"
                         " check the calibration")
    return float(np.linalg.norm(pts[1] - pts[0]))


def photo_outside_share(local: LocalFrame, camera: CameraModel, altitude_m: float, waypoint_xy: np.ndarray,
                        area: PlacedArea, step_deg: float = OUTSIDE_HEADING_STEP_DEG) -> np.ndarray:
    """Share (W,) of each waypoint's nadir photo, ``altitude_m`` above the level ground, whose ground lies outside
    ``area``, at the worst of the headings every ``step_deg``: the fraction of a regular grid of pixels
    (:data:`OUTSIDE_SAMPLES_LONG_SIDE` along the longer side) whose rays meet the ground outside it.

    A photo whose ground disc (around the waypoint, out to its farthest sample) lies wholly inside or wholly
    outside the area is 0 or 1 without sampling.
    """
    from ..geometry.ground import LevelPlaneGround
    from ..geometry.projection import pixel_to_ground

    waypoint_xy = np.asarray(waypoint_xy, dtype=float).reshape(-1, 2)
    long_side = max(camera.width, camera.height)
    n_u = max(2, round(OUTSIDE_SAMPLES_LONG_SIDE * camera.width / long_side))
    n_v = max(2, round(OUTSIDE_SAMPLES_LONG_SIDE * camera.height / long_side))
    u = (np.arange(n_u) + 0.5) * camera.width / n_u - 0.5
    v = (np.arange(n_v) + 0.5) * camera.height / n_v - 0.5
    uv = np.stack(np.meshgrid(u, v), axis=-1).reshape(-1, 2)
    headings = np.radians(np.arange(0.0, 360.0, step_deg))
    k, s = len(headings), len(uv)
    geometry = _nadir_geometry(local, camera, np.zeros((k, 2)), altitude_m, headings)
    pts, valid = pixel_to_ground(geometry, LevelPlaneGround(geometry), np.repeat(np.arange(k), s), np.tile(uv, (k, 1)))
    if not np.all(valid):
        raise InputError("the camera's image does not reach the ground from a nadir view; check the calibration")
    offsets = (pts[:, :2] - np.repeat(geometry.ground_point[:, :2], s, axis=0)).reshape(k, s, 2)
    reach = float(np.max(np.linalg.norm(offsets, axis=2)))
    inside = area.contains(waypoint_xy)
    share = np.where(inside, 0.0, 1.0)
    near = np.flatnonzero(area.boundary_distance(waypoint_xy) < reach)
    for w in near:
        outside = ~area.contains((waypoint_xy[w] + offsets).reshape(-1, 2)).reshape(k, s)
        share[w] = float(outside.mean(axis=1).max())
    return share


def suggested_capture_interval_s(camera: CameraModel, altitude_m: float, speed_ms: float,
                                 forward_overlap: float) -> float:
    """Interval (s) between photos giving ``forward_overlap`` (fraction) at ``speed_ms``."""
    return (1.0 - forward_overlap) * along_track_footprint_m(camera, altitude_m) / speed_ms


# ---------------------------------------------------------------------- ordering
def distance_matrix(xy: np.ndarray) -> np.ndarray:
    """Euclidean distances (m) between local points (n, 2)."""
    d = xy[:, None, :] - xy[None, :, :]
    return np.sqrt(np.einsum("ijk,ijk->ij", d, d))


def tour_length(dist: np.ndarray, order, closed: bool = True) -> float:
    order = np.asarray(order)
    length = float(dist[order[:-1], order[1:]].sum())
    return length + float(dist[order[-1], order[0]]) if closed and len(order) > 1 else length


def nearest_neighbour_tour(dist: np.ndarray, start: int = 0) -> np.ndarray:
    """The nearest-neighbour tour from ``start`` (the baseline the solver must never lose to)."""
    n = len(dist)
    visited = np.zeros(n, dtype=bool)
    order = np.empty(n, dtype=int)
    order[0], visited[start] = start, True
    for k in range(1, n):
        row = np.where(visited, np.inf, dist[order[k - 1]])
        order[k] = int(np.argmin(row))
        visited[order[k]] = True
    return order


def default_tsp_seconds(n: int) -> float:
    """fast-tsp's CPU budget (s): 1.2 ms per node, 0.05–1.2 s (small tours are solved exactly).

    Measured on 1,000 random points against LKH (benchmarks/bench_flight_plan.py): 0.8 s of search
    lands 0.9–1.7 % above, 1 s 1.1–1.8 %, 1.5 s 0.8–1.3 % (fast-tsp is randomised). With its
    fixed set-up cost (≈0.2 s) 1.2 s keeps the solver near 1.4 s of CPU, inside the 2 s goal.
    """
    return float(np.clip(0.0012 * n, 0.05, 1.2))


def solve_tour(dist: np.ndarray, seconds: float | None = None) -> np.ndarray:
    """A short closed tour (node order) over a symmetric distance matrix in metres.

    fast-tsp (exact for small instances, local search otherwise) runs on the distances scaled to
    its unsigned 16-bit integers, i.e. to 1/65 535 of the longest distance; the result is kept
    only if it beats nearest-neighbour on the real (float) distances.
    """
    dist = np.asarray(dist, dtype=float)
    n = len(dist)
    if n <= 3:
        return np.arange(n)
    import fast_tsp

    scale = _TSP_INT_MAX / max(float(dist.max()), 1e-9)
    ints = np.rint(dist * scale).astype(np.int64)
    budget = default_tsp_seconds(n) if seconds is None else float(seconds)
    tour = np.asarray(fast_tsp.find_tour(ints, budget), dtype=int)
    baseline = nearest_neighbour_tour(dist)
    return tour if tour_length(dist, tour) <= tour_length(dist, baseline) else baseline


def order_route(xy: np.ndarray, home_xy: np.ndarray | None, seconds: float | None = None) -> np.ndarray:
    """Indices of ``xy`` in flight order: the shortest closed tour from home back to home, or
    without home the shortest open path (a dummy node at zero distance from all closes the tour)."""
    n = len(xy)
    if n == 1:
        return np.zeros(1, dtype=int)
    if home_xy is not None:
        dist = distance_matrix(np.vstack([home_xy, xy]))
        tour = solve_tour(dist, seconds)
        start = int(np.flatnonzero(tour == 0)[0])
        return np.roll(tour, -start)[1:] - 1
    dist = np.zeros((n + 1, n + 1))
    dist[:n, :n] = distance_matrix(xy)
    tour = solve_tour(dist, seconds)
    start = int(np.flatnonzero(tour == n)[0])
    return np.roll(tour, -start)[1:]


# ---------------------------------------------------------------------- time and splitting
def leg_time_s(length_m, speed_ms: float, acceleration_ms2: float = ACCELERATION_MS2):
    """Time (s) to fly legs of ``length_m`` from standstill to standstill: trapezoidal speed
    profile with ``acceleration_ms2``, or triangular when the leg is too short to reach speed."""
    length = np.asarray(length_m, dtype=float)
    ramp = speed_ms * speed_ms / acceleration_ms2  # distance spent accelerating + braking
    return np.where(length >= ramp, length / speed_ms + speed_ms / acceleration_ms2,
                    2.0 * np.sqrt(length / acceleration_ms2))


def mission_metrics(xy: np.ndarray, home_xy: np.ndarray | None, settings: FlightSettings):
    """(route length m, flight time s) of one mission flying ``xy`` (k, 2) in order."""
    pts = xy if home_xy is None else np.vstack([home_xy, xy, home_xy])
    legs = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    time_s = (settings.altitude_m / CLIMB_RATE_MS + settings.altitude_m / DESCENT_RATE_MS
              + float(leg_time_s(legs, settings.speed_ms).sum()) + len(xy) * settings.per_waypoint_s)
    return float(legs.sum()), time_s


def split_route(seq_xy: np.ndarray, home_xy: np.ndarray | None, settings: FlightSettings,
                min_size: int = 1) -> list[tuple[int, int]]:
    """Cut a flight-ordered sequence into consecutive missions ``[(start, stop), …]`` (stop
    exclusive), each within ``settings.max_waypoints`` and ``settings.max_flight_min``.

    Exact dynamic programme over the cut points: fewest missions first, then shortest total route.
    Mission cost from home: home → first + the inner legs + last → home.
    """
    n = len(seq_xy)
    limit_s = 60.0 * settings.max_flight_min
    legs = np.linalg.norm(np.diff(seq_xy, axis=0), axis=1)
    inner_len = np.concatenate([[0.0], np.cumsum(legs)])
    inner_time = np.concatenate([[0.0], np.cumsum(leg_time_s(legs, settings.speed_ms))])
    if home_xy is not None:
        to_home = np.linalg.norm(seq_xy - home_xy, axis=1)
        home_time = leg_time_s(to_home, settings.speed_ms)
    else:
        to_home = home_time = np.zeros(n)
    overhead = settings.altitude_m / CLIMB_RATE_MS + settings.altitude_m / DESCENT_RATE_MS
    mission_weight = 1e12  # lexicographic: one more mission outweighs any route length
    best = np.full(n + 1, np.inf)
    best[0] = 0.0
    cut = np.zeros(n + 1, dtype=int)
    for stop in range(1, n + 1):
        last = stop - 1
        first = np.arange(max(0, stop - settings.max_waypoints), stop - min_size + 1)
        if len(first) == 0:
            continue
        length = to_home[first] + inner_len[last] - inner_len[first] + to_home[last]
        time_s = (overhead + home_time[first] + inner_time[last] - inner_time[first] + home_time[last]
                  + (stop - first) * settings.per_waypoint_s)
        cost = np.where(time_s <= limit_s, best[first] + mission_weight + length, np.inf)
        k = int(np.argmin(cost))
        best[stop], cut[stop] = cost[k], first[k]
    if not np.isfinite(best[n]):
        return []
    bounds, stop = [], n
    while stop > 0:
        bounds.append((int(cut[stop]), stop))
        stop = int(cut[stop])
    return bounds[::-1]


def _split_or_explain(seq_xy, home_xy, settings: FlightSettings, describe):
    """Split the ordered waypoints into missions of two or more waypoints when the limits allow
    (DJI Pilot 2 and Litchi need two), else of one or more; explain when even one does not fit."""
    if len(seq_xy) >= 2 and settings.max_waypoints >= 2:
        bounds = split_route(seq_xy, home_xy, settings, min_size=2)
        if bounds:
            return bounds
    bounds = split_route(seq_xy, home_xy, settings, min_size=1)
    if bounds:
        return bounds
    times = [mission_metrics(seq_xy[k:k + 1], home_xy, settings)[1] for k in range(len(seq_xy))]
    k = int(np.argmax(times))
    where = ("" if home_xy is None
             else f"{np.linalg.norm(seq_xy[k] - home_xy):.0f} m from HOME and back, ")
    raise InputError(
        f"even a flight to the single waypoint of geotag(s) {describe(k)} takes {times[k] / 60:.1f} min"
        f" ({where}at {settings.speed_ms:g} m/s, climbing to {settings.altitude_m:g} m), more than"
        f" MAX_FLIGHT_MIN = {settings.max_flight_min:g} min: move HOME closer, fly faster or allow"
        " longer flights")


# ---------------------------------------------------------------------- the whole plan
def plan_flight(lat, lon, ids=None, home=None, settings: FlightSettings | None = None,
                camera: CameraModel | None = None, source: str = "geotags",
                progress=None, is_canceled=None, ground_heights=None, origins=None,
                surveyed: SurveyedArea | None = None) -> FlightPlan:
    """Plan the survey flight over geotags at WGS84 ``lat``/``lon`` (degrees).

    ``ids`` name the geotags in messages and outputs (default: 1, 2, …); ``home`` is an optional
    (lat, lon) take-off and landing point; ``camera`` enables the footprint check and the
    capture-interval suggestion; ``ground_heights`` (m, NaN where unknown) only feed a warning when
    the ground is far from level, since altitudes are relative to take-off over a level field.
    ``origins`` says where each target came from (:attr:`FlightPlan.geotag_origins`). ``surveyed``: the
    surveyed area; with a camera, :attr:`FlightPlan.outside_share` tells how much of each photo lies outside it.
    """
    settings = settings or FlightSettings()
    settings.validate()
    progress = progress or (lambda fraction: None)
    is_canceled = is_canceled or (lambda: False)
    lat, lon = np.asarray(lat, dtype=float).reshape(-1), np.asarray(lon, dtype=float).reshape(-1)
    ids = [str(i) for i in (range(1, len(lat) + 1) if ids is None else ids)]
    if len(lat) == 0:
        raise InputError("there are no geotags to fly over (the layer or the selection is empty)",
                         source=source)
    check_coordinates(lat, lon, ids, source)
    if home is not None:
        check_coordinates([home[0]], [home[1]], ["HOME"], "HOME")
    all_lat = np.append(lat, home[0]) if home is not None else lat
    all_lon = np.append(lon, home[1]) if home is not None else lon
    local = LocalFrame.around(all_lat, all_lon)
    enu = local.from_geodetic(lat, lon, np.zeros(len(lat)))
    xy = enu[:, :2]
    home_xy = None
    if home is not None:
        home_xy = local.from_geodetic(home[0], home[1], 0.0).reshape(3)[:2]
    check_spread(np.vstack([xy, home_xy]) if home_xy is not None else xy,
                 ids + (["HOME"] if home_xy is not None else []), settings.force, source)
    warnings = []
    heights = np.asarray([] if ground_heights is None else ground_heights, dtype=float)
    heights = heights[np.isfinite(heights)]
    if len(heights) and np.ptp(heights) > LEVEL_GROUND_FRACTION * settings.altitude_m:
        warnings.append(
            f"the geotags' ground heights vary by {np.ptp(heights):.1f} m, more than"
            f" {100 * LEVEL_GROUND_FRACTION:g} % of ALTITUDE_M = {settings.altitude_m:g} m: altitudes are"
            " relative to take-off over a level field, so the camera will be lower over high ground and"
            " higher over low ground; footprints and the merge check assume level ground")

    radius = settings.merge_radius_m
    fp_radius = suggested = None
    if camera is not None:
        fp_radius = footprint_radius_m(camera, settings.altitude_m, settings.footprint_margin_px, local)
        if fp_radius < radius:
            warnings.append(
                f"the camera footprint at {settings.altitude_m:g} m keeps geotags in view (with"
                f" {settings.footprint_margin_px:g} px margin, at any heading) only within"
                f" {fp_radius:.2f} m of the waypoint, so geotags are merged within {fp_radius:.2f} m"
                f" instead of MERGE_RADIUS_M = {radius:g} m")
            radius = fp_radius
        suggested = suggested_capture_interval_s(camera, settings.altitude_m, settings.speed_ms,
                                                 settings.forward_overlap)
    centres, labels = merge_geotags(xy, radius)
    if camera is not None:
        labels, centres = _enforce_footprint(local, camera, settings, centres, labels, xy, enu, warnings)
    members = [np.flatnonzero(labels == w) for w in range(len(centres))]
    progress(0.3)
    if is_canceled():
        raise Cancelled()

    interval = None
    if settings.capture == CAPTURE_TIMED:
        if settings.capture_interval_s > 0:
            interval = settings.capture_interval_s
        elif suggested is not None:
            interval = round(suggested, 1) or 0.1
        else:
            raise InputError("CAPTURE_INTERVAL_S = 0 asks for the interval to be derived from the"
                             " camera, but no CAMERA calibration is given: give one or set the"
                             " interval in seconds")

    order = order_route(centres, home_xy, settings.tsp_seconds)
    progress(0.7)
    if is_canceled():
        raise Cancelled()
    seq = centres[order]
    bounds = _split_or_explain(seq, home_xy, settings,
                               lambda k: ", ".join(ids[g] for g in members[order[k]]))
    missions = []
    for number, (a, b) in enumerate(bounds, start=1):
        chunk = order[a:b]
        length, time_s = mission_metrics(centres[chunk], home_xy, settings)
        reordered = chunk[order_route(centres[chunk], home_xy, settings.tsp_seconds)]
        new_length, new_time = mission_metrics(centres[reordered], home_xy, settings)
        if new_length < length and new_time <= 60.0 * settings.max_flight_min:
            chunk, length, time_s = reordered, new_length, new_time
        missions.append(Mission(number, chunk, length, time_s))
    progress(1.0)

    if home_xy is None:
        warnings.append("no HOME given: each mission's route and time run from its first to its last"
                        " waypoint; the flights to and from the take-off point are not included")
    wlat, wlon, _ = local.to_geodetic(np.column_stack([centres, np.zeros(len(centres))]))
    outside = None
    if camera is not None and surveyed is not None:
        outside = photo_outside_share(local, camera, settings.altitude_m, centres, surveyed.placed(local))
    return FlightPlan(local=local, settings=settings, geotag_xy=xy, geotag_ids=ids,
                      waypoint_xy=centres, waypoint_lat=np.atleast_1d(wlat),
                      waypoint_lon=np.atleast_1d(wlon), members=members, missions=missions,
                      home_xy=home_xy, home_latlon=None if home is None else (float(home[0]), float(home[1])),
                      capture_interval_s=interval, suggested_interval_s=suggested,
                      footprint_radius_m=fp_radius, warnings=warnings,
                      geotag_origins=None if origins is None else [str(o) for o in origins],
                      outside_share=outside, surveyed=surveyed)


def _enforce_footprint(local, camera, settings, centres, labels, xy, enu, warnings):
    """Give every geotag that falls outside its waypoint's image (at some heading) its own waypoint.

    The remaining members of a waypoint that lost some are re-centred and checked again; a geotag
    at its own waypoint's nadir point is always in view, so the loop ends.
    """
    labels, centres = labels.copy(), [np.asarray(c, dtype=float) for c in centres]
    moved = 0
    while True:
        misses = footprint_misses(local, camera, settings.altitude_m, settings.footprint_margin_px,
                                  np.array(centres), enu, labels)
        if not np.any(misses):
            break
        sizes = np.bincount(labels, minlength=len(centres))
        if np.all(sizes[labels[misses]] == 1):
            raise InputError("a geotag falls outside the image even straight below the camera:"
                             " lower FOOTPRINT_MARGIN_PX")
        touched = set(labels[misses].tolist())
        for g in np.flatnonzero(misses):
            labels[g] = len(centres)
            centres.append(xy[g].copy())
            moved += 1
        for w in touched:
            left = np.flatnonzero(labels == w)
            if len(left):
                centres[w] = min_enclosing_circle(xy[left])[0]
    used = np.unique(labels)  # drop waypoints left empty, renumber in order
    remap = np.full(len(centres), -1)
    remap[used] = np.arange(len(used))
    if moved:
        warnings.append(f"{moved} geotag(s) fell outside the camera image of their merged waypoint"
                        " at some heading and got their own waypoint")
    return remap[labels], np.array(centres)[used]
