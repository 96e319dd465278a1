"""The simulated survey flight: lawnmower lines over the field, flown by a multirotor.

Frames (docs/design.md#frames): positions in the site's :class:`~.geodesy.LocalFrame` (east, north, up; metres),
attitudes as body (forward-right-down) → local rotations, converted to the pose log's body → NED
quaternions at each pose's own position (so yaw is measured from *true* north there).

The plan: lines parallel to the field's longer side, spaced by the camera's across-track footprint
times (1 − side overlap), extended past the field by half a footprint plus a run-in so targets at the
ends are seen as often as the others, joined by semicircular turns. The aircraft flies the path at
the set speed on the lines, slows where the turns' lateral acceleration would exceed 1 m/s², and
accelerates at most 0.8 m/s². Its attitude follows from the forces: the thrust axis tilts to produce
the path's acceleration and to hold against the drag of the wind (plus gusts), the heading follows the
track, and small random wobble (correlated over fractions of a second) is added about every axis.
The height above the ground and the track wander by centimetres, as a GNSS-guided aircraft does.

Over terrain the aircraft follows it (a terrain-following mode, as survey drones fly at ~10 m above
the crop): its height is the terrain height directly beneath it plus the set height above ground
(plus that wander), so the climb and descent enter its velocity, acceleration and hence attitude. The
alternative, a constant altitude above take-off, would bring a 10 m flight down to 3 m over the upper
edge of a 40 m field on a 20° slope.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..geometry.camera import CameraModel
from ..geometry.geodesy import LocalFrame
from ..geometry.rotations import rotmat_to_quat, so3_exp

GRAVITY = 9.80665
LATERAL_ACCEL_MAX = 1.0      # m/s², in turns
LONGITUDINAL_ACCEL_MAX = 0.8  # m/s²
DRAG_PER_S = 0.12            # drag acceleration per m/s of airspeed (1/s)
RUN_IN_M = 1.0               # straight flight past the footprint at each end of a line
RUN_OUT_M = 5.0              # straight flight before the log starts and after it ends
PATH_STEP_M = 0.01


@dataclass
class SurveyPlan:
    """Survey lines (L, 2, 2): start and end (east, north) in metres, flown in order."""

    lines: np.ndarray
    spacing_m: float
    footprint_across_m: float
    footprint_along_m: float

    @property
    def extent(self):
        """(east_min, east_max, north_min, north_max) of the lines."""
        pts = self.lines.reshape(-1, 2)
        return pts[:, 0].min(), pts[:, 0].max(), pts[:, 1].min(), pts[:, 1].max()


def footprint(camera: CameraModel, altitude_m: float) -> tuple[float, float]:
    """Ground size (m) of a nadir image at ``altitude_m``: across track (image width), along track
    (image height), measured through the lens at the principal point's row and column."""
    w, h = camera.width - 0.5, camera.height - 0.5
    rays = camera.pixel_rays(np.array([[-0.5, camera.cy], [w, camera.cy], [camera.cx, -0.5], [camera.cx, h]]))
    return altitude_m * (rays[1, 0] - rays[0, 0]), altitude_m * (rays[3, 1] - rays[2, 1])


def plan_survey(camera: CameraModel, altitude_m: float, field_width_m: float, field_length_m: float,
                side_overlap: float) -> SurveyPlan:
    """Lawnmower lines covering a field centred on the local origin (width east, length north).

    The camera's image width lies across track (image up = forward)."""
    across, along = footprint(camera, altitude_m)
    spacing = across * (1.0 - side_overlap)
    along_east = field_width_m >= field_length_m
    line_len, cover_len = (field_width_m, field_length_m) if along_east else (field_length_m, field_width_m)
    n_lines = max(1, int(math.ceil(max(cover_len - across, 0.0) / spacing - 1e-9)) + 1)
    offsets = (np.arange(n_lines) - 0.5 * (n_lines - 1)) * spacing
    half = 0.5 * line_len + 0.5 * along + RUN_IN_M
    lines = []
    for i, off in enumerate(offsets):
        a, b = (-half, half) if i % 2 == 0 else (half, -half)
        lines.append([[a, off], [b, off]] if along_east else [[off, a], [off, b]])
    return SurveyPlan(np.asarray(lines, float), spacing, across, along)


def _path(plan: SurveyPlan):
    """Sampled path: points (P, 2), arc length (P,), curvature (P,), line index (P,) (−1 in turns)."""
    pts, curv, line_idx = [], [], []
    lines = plan.lines
    for i, (a, b) in enumerate(lines):
        n = max(2, int(math.ceil(np.linalg.norm(b - a) / PATH_STEP_M)) + 1)
        t = np.linspace(0.0, 1.0, n)[:-1] if i + 1 < len(lines) else np.linspace(0.0, 1.0, n)
        pts.append(a + t[:, None] * (b - a))
        curv.append(np.zeros(len(t)))
        line_idx.append(np.full(len(t), i))
        if i + 1 == len(lines):
            break
        c = lines[i + 1][0]
        centre = 0.5 * (b + c)
        radius = 0.5 * np.linalg.norm(c - b)
        start = math.atan2(*(b - centre)[::-1])
        direction = (b - a) / np.linalg.norm(b - a)
        # Turn towards the next line: the sign of the turn is that of (direction × (c − b)).
        sense = np.sign(direction[0] * (c - b)[1] - direction[1] * (c - b)[0])
        n_arc = max(4, int(math.ceil(math.pi * radius / PATH_STEP_M)))
        ang = start + sense * np.linspace(0.0, math.pi, n_arc, endpoint=False)
        pts.append(centre + radius * np.stack([np.cos(ang), np.sin(ang)], -1))
        curv.append(np.full(n_arc, 1.0 / max(radius, 1e-6)))
        line_idx.append(np.full(n_arc, -1))
    # Straight run-out before the first and after the last line: the aircraft is already flying
    # when the log starts and still flying when it ends.
    first, last = lines[0], lines[-1]
    t = np.linspace(1.0, 0.0, int(RUN_OUT_M / PATH_STEP_M), endpoint=False)[:, None]
    d0 = (first[1] - first[0]) / np.linalg.norm(first[1] - first[0])
    d1 = (last[1] - last[0]) / np.linalg.norm(last[1] - last[0])
    pts = [first[0] - t * RUN_OUT_M * d0] + pts + [last[1] + t[::-1] * RUN_OUT_M * d1]
    curv = [np.zeros(len(t))] + curv + [np.zeros(len(t))]
    line_idx = [np.full(len(t), -1)] + line_idx + [np.full(len(t), -1)]
    pts = np.concatenate(pts)
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    return pts, s, np.concatenate(curv), np.concatenate(line_idx)


def _speed_profile(s, curvature, speed):
    """Speed (m/s) along the path: the set speed, slowed for turns, acceleration-limited."""
    v = np.minimum(speed, np.sqrt(LATERAL_ACCEL_MAX / np.maximum(curvature, 1e-9)))
    ds = np.diff(s)
    for i in range(1, len(v)):
        v[i] = min(v[i], math.sqrt(v[i - 1] ** 2 + 2 * LONGITUDINAL_ACCEL_MAX * ds[i - 1]))
    for i in range(len(v) - 2, -1, -1):
        v[i] = min(v[i], math.sqrt(v[i + 1] ** 2 + 2 * LONGITUDINAL_ACCEL_MAX * ds[i]))
    return v


def correlated_noise(rng: np.random.Generator, n: int, dt: float, tau_s: float, sigma: float,
                     dims: int = 1) -> np.ndarray:
    """(n, dims) stationary Gaussian noise of std ``sigma`` on a grid of step ``dt``, correlated over
    ``tau_s`` (white noise through a Gaussian kernel of that width). Slow noise is drawn on a grid of
    tau/4 and interpolated, which keeps long correlation times cheap."""
    from scipy.ndimage import gaussian_filter1d

    step = max(1, int(tau_s / dt / 4.0))
    m = (n - 1) // step + 2
    width = max(tau_s / (dt * step), 0.5)
    pad = int(4 * width) + 1
    white = rng.standard_normal((m + 2 * pad, dims))
    smooth = gaussian_filter1d(white, width, axis=0, mode="nearest")[pad:pad + m]
    # Std of white noise through a unit-sum Gaussian kernel of width w: (2 √π w)^-1/2.
    smooth *= sigma * math.sqrt(2.0 * math.sqrt(math.pi) * width)
    if step == 1:
        return smooth[:n]
    fine = np.arange(n) / step
    return np.stack([np.interp(fine, np.arange(m), smooth[:, i]) for i in range(dims)], -1)


@dataclass
class FlightTruth:
    """True states at the log's times. Lengths N; positions of the IMU."""

    time_ns: np.ndarray        # (N,) since the start of the flight
    lat: np.ndarray
    lon: np.ndarray
    height: np.ndarray         # ellipsoidal (m)
    local: np.ndarray          # (N, 3) east, north, up in the site frame (m)
    r_local_body: np.ndarray   # (N, 3, 3)
    quat: np.ndarray           # (N, 4) body → NED at the pose, (w, x, y, z)
    velocity: np.ndarray       # (N, 3) local (m/s)
    line: np.ndarray           # (N,) survey line index, −1 in turns


class SimulatedFlight:
    """One flight of a plan: the path, its timing and the random disturbances (seeded)."""

    def __init__(self, plan: SurveyPlan, altitude_m: float, speed_ms: float, rng: np.random.Generator,
                 terrain_rise=None):
        """``terrain_rise(east, north)``: height (m) of the terrain above the site's ground height under
        local horizontal positions, which the aircraft follows; None: level ground."""
        from scipy.ndimage import gaussian_filter1d

        pts, s, curv, self._line_idx = _path(plan)
        v = _speed_profile(s, curv, speed_ms)
        self._s = s
        t_path = np.concatenate([[0.0], np.cumsum(np.diff(s) / (0.5 * (v[1:] + v[:-1])))])
        # The log runs from the first line's start to the last line's end (time 0 = first start).
        t_start, t_end = np.interp([RUN_OUT_M, s[-1] - RUN_OUT_M], s, t_path)
        self._t_path = t_path - t_start
        self.duration_s = float(t_end - t_start)

        # States on a uniform 100 Hz grid over the whole path, interpolated to the log's times.
        dt = 0.01
        grid = np.arange(-t_start, self._t_path[-1], dt)
        n = len(grid)
        wind = rng.uniform(0.0, 3.0) * np.array([*_unit(rng.uniform(0, 2 * math.pi)), 0.0])
        gust = correlated_noise(rng, n, dt, 1.5, 0.6, 3) * np.array([1.0, 1.0, 0.3])
        track_err = correlated_noise(rng, n, dt, 2.0, 0.03, 2)
        height_err = (correlated_noise(rng, n, dt, 3.0, 0.06, 1)[:, 0]
                      + correlated_noise(rng, n, dt, 20.0, 0.05, 1)[:, 0])
        wobble = correlated_noise(rng, n, dt, 0.35, 1.0, 3) * np.radians([0.7, 0.7, 0.4])
        yaw_err = correlated_noise(rng, n, dt, 3.0, math.radians(1.2), 1)[:, 0]

        s_grid = np.interp(grid, self._t_path, s)
        track = np.stack([np.interp(s_grid, s, pts[:, 0]), np.interp(s_grid, s, pts[:, 1])], -1)
        pos = np.concatenate([track + track_err, (altitude_m + height_err)[:, None]], axis=1)
        if terrain_rise is not None:
            pos[:, 2] += terrain_rise(pos[:, 0], pos[:, 1])
        vel = np.gradient(pos, dt, axis=0)
        acc = gaussian_filter1d(np.gradient(vel, dt, axis=0), 0.15 / dt, axis=0, mode="nearest")
        tangent = np.gradient(track, axis=0)
        heading = np.unwrap(np.arctan2(tangent[:, 0], tangent[:, 1])) + yaw_err  # from north, clockwise

        # Thrust direction (body up) = acceleration − gravity + drag of the airflow.
        thrust = acc + DRAG_PER_S * (vel - (wind + gust)) + np.array([0.0, 0.0, GRAVITY])
        z_body = -thrust / np.linalg.norm(thrust, axis=1, keepdims=True)
        h_dir = np.stack([np.sin(heading), np.cos(heading), np.zeros(n)], -1)
        x_body = h_dir - np.sum(h_dir * z_body, axis=1, keepdims=True) * z_body
        x_body /= np.linalg.norm(x_body, axis=1, keepdims=True)
        y_body = np.cross(z_body, x_body)
        self._grid = grid
        self._pos = pos
        self._vel = vel
        self._r = np.stack([x_body, y_body, z_body], axis=-1) @ so3_exp(wobble)
        self.wind = wind

    def states(self, times_ns, local: LocalFrame, ground_height_m: float) -> FlightTruth:
        """True IMU states at ``times_ns`` (int64 ns from the start of the path); heights are
        ``ground_height_m`` (ellipsoidal, the site's ground) plus the flight's height above it (terrain
        rise included), along the ellipsoid normal."""
        times_ns = np.asarray(times_ns, np.int64)
        t = times_ns * 1e-9
        if t[0] < 0.0 or t[-1] > self.duration_s + 1e-9:
            raise ValueError("log times run past the ends of the flight")
        pos = np.stack([np.interp(t, self._grid, self._pos[:, i]) for i in range(3)], -1)
        vel = np.stack([np.interp(t, self._grid, self._vel[:, i]) for i in range(3)], -1)
        r_local_body = _interp_rotations(t, self._grid, self._r)
        s_t = np.interp(t, self._t_path, self._s)
        line = self._line_idx[np.clip(np.searchsorted(self._s, s_t), 0, len(self._s) - 1)]
        lat, lon, _ = local.to_geodetic(pos * np.array([1.0, 1.0, 0.0]))
        lat, lon = np.asarray(lat), np.asarray(lon)
        height = ground_height_m + pos[:, 2]
        local_pos = local.from_geodetic(lat, lon, height)
        r_ned_body = np.swapaxes(local.rotation_from_ned(lat, lon), -1, -2) @ r_local_body
        return FlightTruth(times_ns, lat, lon, height, local_pos, r_local_body, rotmat_to_quat(r_ned_body),
                           vel, line)


def _unit(angle):
    return math.sin(angle), math.cos(angle)


def _interp_rotations(t, grid, r_grid):
    """Rotations at times t, interpolated on the geodesic between grid samples (10 ms apart, so the
    relative rotation is small and its vee form exact to its cube)."""
    idx = np.clip(np.searchsorted(grid, t) - 1, 0, len(grid) - 2)
    frac = ((t - grid[idx]) / (grid[idx + 1] - grid[idx]))[:, None]
    r0, r1 = r_grid[idx], r_grid[idx + 1]
    delta = np.swapaxes(r0, -1, -2) @ r1
    vec = 0.5 * np.stack([delta[:, 2, 1] - delta[:, 1, 2], delta[:, 0, 2] - delta[:, 2, 0],
                          delta[:, 1, 0] - delta[:, 0, 1]], -1)
    return r0 @ so3_exp(vec * frac)
