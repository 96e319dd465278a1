"""Geodesy: WGS84 ↔ a local metric frame ↔ the output CRS.

Frames (docs/design.md#world):

* Inputs are WGS84 latitude, longitude (degrees) and *ellipsoidal* height (metres).
* Geometry is computed in a :class:`LocalFrame`: an east-north-up tangent frame at a site origin,
  reached exactly through ECEF by closed-form WGS84 formulas (no PROJ, so it runs on any thread; see
  :func:`on_python_thread` for what does use PROJ). Attitudes are relative to the local NED frame *at
  each pose's own position* (true north there); :meth:`LocalFrame.rotation_from_ned` turns them into
  the local frame, so true-north yaw is honoured everywhere and no map-projection convergence enters
  the geometry.
* Outputs are written in a projected CRS, by default the UTM zone of the site (:func:`utm_epsg`).
  Grid north of a UTM zone differs from true north by the meridian convergence
  (:func:`meridian_convergence_deg`), 2–3° near zone edges; that only matters to code that works in
  grid coordinates directly, which this module's users never do for geometry.
"""
from __future__ import annotations

import functools
import os
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np

from .rotations import R_ENU_NED


def ensure_proj_data() -> None:
    """Point pyproj at Debian's PROJ data when it cannot find it (it does not look in a venv's parent)."""
    if os.environ.get("PROJ_DATA") or os.environ.get("PROJ_LIB"):
        return
    for candidate in ("/usr/share/proj", "/usr/local/share/proj"):
        if (Path(candidate) / "proj.db").is_file():
            os.environ["PROJ_DATA"] = candidate
            return


#: WGS84 (EPSG:7030): semi-major axis (m) and flattening; e² and e'² derived.
WGS84_A = 6378137.0
WGS84_F = 1.0 / 298.257223563
_B = WGS84_A * (1.0 - WGS84_F)
_E2 = WGS84_F * (2.0 - WGS84_F)
_EP2 = _E2 / (1.0 - WGS84_F) ** 2

_proj_executor: ThreadPoolExecutor | None = None
_proj_executor_lock = threading.Lock()


def _thread_made_by_python() -> bool:
    # Threads Python did not start (Qt's thread pools, QThread, QgsTask) appear as dummy threads.
    return not isinstance(threading.current_thread(), threading._DummyThread)


def on_python_thread(fn):
    """Run ``fn`` on a thread Python created when it is called from one Python did not.

    pyproj 3.7 keeps its PROJ context in thread-specific storage that needs a Python thread state, which
    threads started by Qt (the review dock's pool, Processing's QgsTask) lack: PROJ calls there crash
    QGIS (pyproj#1509, fixed by pyproj#1539; 3.7.1 and 3.7.2 crash here, Debian 12's 3.4 does not).
    Every function that uses pyproj is wrapped here (tests/unit/geometry/test_geodesy_closed_form.py
    checks), so it runs on one dedicated Python thread instead; on threads Python made (the main thread,
    ``threading``) it runs in place, and on that dedicated thread nested calls do too.
    """
    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        if _thread_made_by_python():
            return fn(*args, **kwargs)
        global _proj_executor
        with _proj_executor_lock:
            if _proj_executor is None:
                _proj_executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="birdseye-proj")
        return _proj_executor.submit(fn, *args, **kwargs).result()

    return wrapper


@on_python_thread
@functools.lru_cache(maxsize=None)
def _transformer(src: str, dst: str):
    ensure_proj_data()
    import pyproj

    return pyproj.Transformer.from_crs(src, dst, always_xy=True)


@on_python_thread
def proj_version() -> str:
    """pyproj's version (importing pyproj the first time already calls PROJ)."""
    ensure_proj_data()
    import pyproj

    return pyproj.__version__


def geodetic_to_ecef(lat, lon, h) -> np.ndarray:
    """ECEF coordinates (N, 3) in metres of WGS84 latitude/longitude (deg) and ellipsoidal height (m).

    Closed form, the same numbers as PROJ's EPSG:4979 → EPSG:4978 to well under a millimetre
    (tests/unit/geometry/test_geodesy_closed_form.py), and free of pyproj on any thread."""
    la = np.radians(np.asarray(lat, dtype=float))
    lo = np.radians(np.asarray(lon, dtype=float))
    h = np.asarray(h, dtype=float)
    sla = np.sin(la)
    n = WGS84_A / np.sqrt(1.0 - _E2 * sla * sla)
    x = (n + h) * np.cos(la) * np.cos(lo)
    y = (n + h) * np.cos(la) * np.sin(lo)
    z = (n * (1.0 - _E2) + h) * sla
    return np.stack(np.broadcast_arrays(x, y, z), axis=-1)


def ecef_to_geodetic(xyz: np.ndarray):
    """(lat, lon, h) arrays from ECEF coordinates (..., 3), the inverse of :func:`geodetic_to_ecef`.

    Bowring's latitude iterated three times, which round-trips :func:`geodetic_to_ecef` to nanometres
    from the geoid to orbital heights (PROJ's own inverse is off by up to 0.1 mm at 100 km); the height
    comes from a form that is stable at the poles."""
    xyz = np.asarray(xyz, dtype=float)
    x, y, z = xyz[..., 0], xyz[..., 1], xyz[..., 2]
    p = np.hypot(x, y)
    beta = np.arctan2(z, (1.0 - WGS84_F) * p)
    for _ in range(3):
        sb, cb = np.sin(beta), np.cos(beta)
        lat = np.arctan2(z + _EP2 * _B * sb ** 3, p - _E2 * WGS84_A * cb ** 3)
        beta = np.arctan2((1.0 - WGS84_F) * np.sin(lat), np.cos(lat))
    sla, cla = np.sin(lat), np.cos(lat)
    h = p * cla + z * sla - WGS84_A * np.sqrt(1.0 - _E2 * sla * sla)
    return np.degrees(lat), np.degrees(np.arctan2(y, x)), h


def rotation_ecef_enu(lat, lon) -> np.ndarray:
    """Rotations (..., 3, 3) whose columns are the local east, north, up unit vectors in ECEF."""
    la, lo = np.radians(np.asarray(lat, dtype=float)), np.radians(np.asarray(lon, dtype=float))
    sla, cla, slo, clo = np.sin(la), np.cos(la), np.sin(lo), np.cos(lo)
    r = np.empty(np.broadcast(la, lo).shape + (3, 3))
    r[..., :, 0] = np.stack(np.broadcast_arrays(-slo, clo, np.zeros_like(la)), -1)
    r[..., :, 1] = np.stack(np.broadcast_arrays(-sla * clo, -sla * slo, cla), -1)
    r[..., :, 2] = np.stack(np.broadcast_arrays(cla * clo, cla * slo, sla), -1)
    return r


class LocalFrame:
    """East-north-up tangent frame at a WGS84 origin: the metric frame all geometry runs in."""

    def __init__(self, lat0: float, lon0: float, h0: float = 0.0):
        self.lat0, self.lon0, self.h0 = float(lat0), float(lon0), float(h0)
        self._origin = geodetic_to_ecef(self.lat0, self.lon0, self.h0).reshape(3)
        self._r_ecef_enu0 = rotation_ecef_enu(self.lat0, self.lon0)

    @classmethod
    def around(cls, lat, lon, h=None) -> "LocalFrame":
        """A frame at the centre of the given positions (mid-range, so it is robust to outliers)."""
        lat, lon = np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)
        h0 = 0.0 if h is None else float(np.nanmedian(h))
        return cls(0.5 * (np.nanmin(lat) + np.nanmax(lat)), 0.5 * (np.nanmin(lon) + np.nanmax(lon)), h0)

    def to_dict(self) -> dict:
        return {"lat0": self.lat0, "lon0": self.lon0, "h0": self.h0}

    def from_geodetic(self, lat, lon, h) -> np.ndarray:
        """Local ENU coordinates (N, 3) in metres."""
        ecef = geodetic_to_ecef(lat, lon, h)
        return (ecef - self._origin) @ self._r_ecef_enu0

    def to_geodetic(self, enu: np.ndarray):
        """(lat, lon, h) of local ENU coordinates (..., 3)."""
        enu = np.asarray(enu, dtype=float)
        return ecef_to_geodetic(enu @ self._r_ecef_enu0.T + self._origin)

    def rotation_from_ned(self, lat, lon) -> np.ndarray:
        """Rotations (..., 3, 3) taking vectors in the NED frame at (lat, lon) into this local frame."""
        return self._r_ecef_enu0.T @ rotation_ecef_enu(lat, lon) @ R_ENU_NED

    def up_at(self, lat, lon) -> np.ndarray:
        """Unit ellipsoid normals (..., 3) at (lat, lon), in this local frame."""
        return (self._r_ecef_enu0.T @ rotation_ecef_enu(lat, lon))[..., :, 2]


def utm_epsg(lat: float, lon: float) -> int:
    """EPSG code of the WGS84 / UTM zone containing (lat, lon), with the Norway and Svalbard exceptions."""
    lat, lon = float(lat), float(lon)
    if not (-80.0 <= lat <= 84.0):
        raise ValueError(f"latitude {lat:.4f}° is outside the UTM range (80°S–84°N); choose a projected CRS")
    lon = (lon + 180.0) % 360.0 - 180.0
    zone = int((lon + 180.0) // 6.0) + 1
    if 56.0 <= lat < 64.0 and 3.0 <= lon < 12.0:
        zone = 32
    elif 72.0 <= lat <= 84.0 and lon >= 0.0:
        for lo, hi, z in ((0, 9, 31), (9, 21, 33), (21, 33, 35), (33, 42, 37)):
            if lo <= lon < hi:
                zone = z
    zone = min(zone, 60)
    return (32600 if lat >= 0 else 32700) + zone


class ProjectedCRS:
    """Conversions between WGS84 and a projected output CRS given as ``EPSG:nnnn`` or WKT."""

    @on_python_thread
    def __init__(self, crs: str | int):
        self.crs = f"EPSG:{crs}" if isinstance(crs, int) else str(crs)
        self._fwd = _transformer("EPSG:4326", self.crs)
        self._inv = _transformer(self.crs, "EPSG:4326")

    @classmethod
    def for_site(cls, lat, lon) -> "ProjectedCRS":
        lat, lon = np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)
        return cls(utm_epsg(float(np.nanmedian(lat)), float(np.nanmedian(lon))))

    @on_python_thread
    def from_geodetic(self, lat, lon):
        x, y = self._fwd.transform(np.asarray(lon, dtype=float), np.asarray(lat, dtype=float))
        return np.asarray(x), np.asarray(y)

    @on_python_thread
    def to_geodetic(self, x, y):
        lon, lat = self._inv.transform(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
        return np.asarray(lat), np.asarray(lon)


@on_python_thread
def meridian_convergence_deg(lat, lon, crs: str | int) -> np.ndarray:
    """Meridian convergence γ (deg) of ``crs`` at (lat, lon), as PROJ reports it.

    γ > 0 means grid north is clockwise (east) of true north, as east of a UTM central meridian in
    the northern hemisphere; grid azimuth = true azimuth − γ.
    """
    ensure_proj_data()
    import pyproj

    proj = pyproj.Proj(f"EPSG:{crs}" if isinstance(crs, int) else crs)
    factors = proj.get_factors(np.asarray(lon, dtype=float), np.asarray(lat, dtype=float))
    return np.asarray(factors.meridian_convergence)
