"""The surveyed area: the ground the survey searched, where a tile without a label shows background.

A target nobody surveyed, in a tile written as negative (label all zero), teaches the network that a target is
background; the method therefore keeps the drone over surveyed ground. Write labels writes negative tiles only
where the tile's whole ground footprint lies inside the surveyed area (positives are kept anywhere), and Plan the
survey flight reports how much of each planned photo lies outside it. Both take the area from
:func:`surveyed_area`, the one definition:

* the polygons the user drew (``SURVEYED_AREA``), any number, holes allowed, by the even-odd rule (a point is
  inside when a ray from it crosses the rings an odd number of times);
* else the convex hull of the geotags grown by ``margin_m`` (default :data:`DEFAULT_SURVEY_MARGIN_M`): the
  Minkowski sum of the hull with a regular :data:`MARGIN_SIDES`-gon inscribed in the circle of radius
  ``margin_m``, so the margin is ``margin_m`` at the polygon's vertices and at least ``margin_m·cos(π/64)``
  (99.88 % of it) between them — never more than asked, as a larger area would admit unsurveyed ground.

Rings are kept as WGS84 latitude/longitude (:class:`SurveyedArea`), so each run places them in its own local
frame (:meth:`SurveyedArea.placed`) at that frame's origin height, the height of the site's ground.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..geometry.geodesy import LocalFrame

#: The hull's margin (m) when none is given: how far past its outermost geotags a partition is taken as
#: searched. A surveyor who walked to a target also looked about a metre around it; past that the survey says
#: nothing, and a larger margin would let unsurveyed ground into negative tiles. Draw the area to say more.
DEFAULT_SURVEY_MARGIN_M = 1.0
#: Sides of the polygon standing in for the margin's circle.
MARGIN_SIDES = 64
#: Points tested against the rings at once (memory: points × edges booleans).
_CHUNK = 4096


@dataclass(frozen=True)
class SurveyedArea:
    """Surveyed ground as rings of WGS84 latitude/longitude (degrees), exterior rings and holes alike.

    ``drawn``: the user drew the polygons; else the rings are the hull of the geotags grown by ``margin_m``.
    """

    rings_lat: tuple
    rings_lon: tuple
    drawn: bool
    margin_m: float | None = None
    n_geotags: int = 0

    def placed(self, local: LocalFrame) -> "PlacedArea":
        """The rings in ``local`` (east, north metres), at the frame's origin height."""
        return PlacedArea([local.from_geodetic(lat, lon, np.full(len(lat), local.h0))[:, :2]
                           for lat, lon in zip(self.rings_lat, self.rings_lon)])

    def describe(self) -> str:
        """The area's origin in words, for the log."""
        if self.drawn:
            return f"the drawn polygons ({len(self.rings_lat)} ring(s))"
        return f"the hull of the {self.n_geotags} geotag(s) grown by {self.margin_m:g} m"

    def to_dict(self) -> dict:
        """The area's origin for a summary file."""
        if self.drawn:
            return {"source": "drawn", "rings": len(self.rings_lat)}
        return {"source": "geotag_hull", "margin_m": self.margin_m, "geotags": self.n_geotags}


@dataclass
class PlacedArea:
    """A :class:`SurveyedArea` in one local frame: rings (k, 2) of east, north metres."""

    rings: list

    def contains(self, xy) -> np.ndarray:
        """Mask of the points (N, 2) inside (even-odd rule); a NaN point (a ray that missed the ground) is not."""
        return points_in_rings(self.rings, xy)

    def contains_polygons(self, polygons) -> np.ndarray:
        """Mask (T,) of the polygons (T, K, 2) (vertices in order) that lie wholly inside.

        A polygon is inside when all its vertices are, no edge of it meets an edge of the rings (touching
        counts), and no ring vertex lies inside it (a hole, or a ring, wholly within the polygon). Exact for
        polygons with straight edges; a curved footprint is as exact as its vertices sample it.
        """
        polygons = np.asarray(polygons, dtype=float)
        if not self.rings:
            return np.zeros(len(polygons), dtype=bool)
        t, k = polygons.shape[:2]
        ok = self.contains(polygons.reshape(-1, 2)).reshape(t, k).all(axis=1)
        candidates = polygons[ok]
        if len(candidates):
            a, b = _edges(self.rings)
            meets = _segments_meet(candidates, np.roll(candidates, -1, axis=1), a, b).any(axis=(1, 2))
            holds_vertex = _crossings(candidates, np.roll(candidates, -1, axis=1), a).sum(axis=2) % 2 == 1
            ok[ok] = ~(meets | holds_vertex.any(axis=1))
        return ok

    def boundary_distance(self, xy) -> np.ndarray:
        """Distance (m) from each point (N, 2) to the nearest edge of the rings (inf without rings)."""
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        if not self.rings:
            return np.full(len(xy), np.inf)
        a, b = _edges(self.rings)
        seg = b - a
        length2 = np.maximum(np.einsum("ei,ei->e", seg, seg), 1e-300)
        rel = xy[:, None, :] - a[None, :, :]
        t = np.clip(np.einsum("nei,ei->ne", rel, seg) / length2, 0.0, 1.0)
        return np.min(np.linalg.norm(rel - t[..., None] * seg[None, :, :], axis=2), axis=1)


def surveyed_area(geotag_lat, geotag_lon, margin_m: float = DEFAULT_SURVEY_MARGIN_M,
                  drawn=None, geotag_height=None) -> SurveyedArea:
    """The surveyed area: the ``drawn`` rings when given (a list of (lat, lon) arrays, WGS84 degrees, exterior
    rings and holes alike; the geotags play no part), else the convex hull of the geotags grown by ``margin_m``
    metres, measured at the median of their ellipsoidal heights ``geotag_height`` (m, NaN where unknown; none
    known: the ellipsoid — a metre there is 1 + h/R of one at height h, 0.01 % more at 600 m). A margin of 0
    around fewer than three geotags off one line encloses nothing."""
    if drawn is not None:
        rings = [(np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)) for lat, lon in drawn]
        rings = [(lat, lon) for lat, lon in rings if len(lat) >= 3]
        if not rings:
            raise InputError("the surveyed area has no polygon with three corners or more", source="SURVEYED_AREA")
        return SurveyedArea(tuple(r[0] for r in rings), tuple(r[1] for r in rings), True)
    if not margin_m >= 0:
        raise InputError(f"SURVEY_MARGIN_M = {margin_m:g} m must be zero or positive")
    lat, lon = np.asarray(geotag_lat, dtype=float), np.asarray(geotag_lon, dtype=float)
    if len(lat) == 0:
        return SurveyedArea((), (), False, float(margin_m), 0)
    heights = np.asarray([] if geotag_height is None else geotag_height, dtype=float)
    heights = heights[np.isfinite(heights)]
    local = LocalFrame.around(lat, lon, heights if len(heights) else None)
    ring = hull_with_margin(local.from_geodetic(lat, lon, np.full(len(lat), local.h0))[:, :2], margin_m)
    if ring is None:
        return SurveyedArea((), (), False, float(margin_m), len(lat))
    r_lat, r_lon, _ = local.to_geodetic(np.column_stack([ring, np.zeros(len(ring))]))
    return SurveyedArea((np.atleast_1d(r_lat),), (np.atleast_1d(r_lon),), False, float(margin_m), len(lat))


def hull_with_margin(xy, margin_m: float):
    """The convex hull of points (N, 2) grown by ``margin_m``: ring (k, 2) counter-clockwise, or None when it
    encloses nothing. Every point plus every vertex of the inscribed :data:`MARGIN_SIDES`-gon, then their hull."""
    from scipy.spatial import ConvexHull, QhullError

    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    if margin_m > 0:
        angle = 2.0 * np.pi * np.arange(MARGIN_SIDES) / MARGIN_SIDES
        disc = margin_m * np.column_stack([np.cos(angle), np.sin(angle)])
        xy = (xy[:, None, :] + disc[None, :, :]).reshape(-1, 2)
    try:
        hull = ConvexHull(xy)
    except (QhullError, ValueError):  # fewer than three points, or all on one line: no area
        return None
    return xy[hull.vertices]


def points_in_rings(rings, xy) -> np.ndarray:
    """Even-odd test of points (N, 2) against rings (each (k, 2), closing edge implied): crossings of the ray
    towards +x. A point exactly on an edge may fall either way; NaN points are outside."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    inside = np.zeros(len(xy), dtype=bool)
    if not len(rings) or not len(xy):
        return inside
    a, b = _edges(rings)
    for start in range(0, len(xy), _CHUNK):
        inside[start:start + _CHUNK] = _crossings(a[None], b[None], xy[start:start + _CHUNK])[0].sum(axis=1) % 2 == 1
    return inside


def _crossings(a, b, xy) -> np.ndarray:
    """(T, N, K): whether the ray from point n (xy (N, 2)) towards +x crosses edge a→b (T, K, 2) k of set t (a
    horizontal edge is never crossed). Summed over K, odd means inside the rings the edges close."""
    a, b = a[:, None, :, :], b[:, None, :, :]
    px, py = xy[None, :, None, 0], xy[None, :, None, 1]
    with np.errstate(invalid="ignore", divide="ignore"):
        x_cross = a[..., 0] + (py - a[..., 1]) * (b[..., 0] - a[..., 0]) / (b[..., 1] - a[..., 1])
        return ((a[..., 1] > py) != (b[..., 1] > py)) & (px < x_cross)


def _edges(rings):
    """Start and end points (E, 2) of every edge of the rings, each ring closed."""
    rings = [np.asarray(r, dtype=float).reshape(-1, 2) for r in rings]
    return np.concatenate(rings), np.concatenate([np.roll(r, -1, axis=0) for r in rings])


def _segments_meet(p, q, a, b) -> np.ndarray:
    """(..., E): whether segment p→q (..., 2) meets segment a→b (E, 2); touching and collinear overlap count."""
    def orient(o, s, t):
        return np.sign((s[..., 0] - o[..., 0]) * (t[..., 1] - o[..., 1])
                       - (s[..., 1] - o[..., 1]) * (t[..., 0] - o[..., 0]))

    p, q = p[..., None, :], q[..., None, :]
    d1, d2, d3, d4 = orient(a, b, p), orient(a, b, q), orient(p, q, a), orient(p, q, b)
    proper = (d1 * d2 <= 0) & (d3 * d4 <= 0)
    # Collinear segments (all four orientations 0) meet only where their extents overlap.
    collinear = (d1 == 0) & (d2 == 0)
    lo, hi = np.minimum(p, q), np.maximum(p, q)
    overlap = np.all((np.minimum(a, b) <= hi) & (np.maximum(a, b) >= lo), axis=-1)
    return np.where(collinear, overlap, proper)
