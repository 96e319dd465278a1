"""The relief check: does a target standing above the ground its label was placed on stay inside its label?

A point raised by h above the ground at horizontal distance r from the camera's nadir, seen from height d above
that ground, lies on the ray that meets the ground at r·d/(d − h) from the nadir: its image moves outwards. To first
order in h/d the move, measured on the ground at the target's height, is

    δ = h · r / d            (metres; e.g. h = 0.52 m, r = 2.5 m, d = 10 m: δ = 0.13 m)

and in the image, with f = √(fx·fy) the focal length in pixels and d/f the ground sample distance at the target,
δ_px = δ · f / d = f·h·r/d². The exact image move f·h·r/(d·(d − h)) is larger by d/(d − h): 5.5 % at h = 0.52 m
from 10 m, so the check is a screen, not a correction. r and d come from each label's own geometry
(:attr:`.training_set.FrameLabels.nadir_distance_m`, ``height_m``): for a nadir camera r is the label's distance
from the principal point in the image, taken to the ground.

A frame fails the check when one of its labels moves by more than the label radius (3σ,
:data:`.training_set.LABEL_RADIUS_SIGMAS`): the raised target then lies outside the label drawn for it.

The relief h of each target is given (``RELIEF_M``: the targets' height above the ground, e.g. a mound), or read
from a DEM: the range of the DEM's heights (highest − lowest) within :data:`RELIEF_WINDOW_M` of the target, the
relief the target may stand on. Kept simple on purpose: the range is an upper bound of the target's height above
its surroundings, and where the labels were placed on that same DEM they already follow the relief the DEM
resolves.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

#: Radius (m) of the DEM window around each target whose height range is its relief.
RELIEF_WINDOW_M = 1.0
#: Frames listed in the log; summary.json lists them all.
LOGGED_FRAMES = 5


def relief_displacement_m(relief_m, nadir_distance_m, height_m):
    """δ = h·r/d (m): the ground move of a point raised by ``relief_m`` at ``nadir_distance_m`` from the nadir,
    seen from ``height_m`` above the ground (first order in h/d; module docstring)."""
    return np.asarray(relief_m, dtype=float) * np.asarray(nadir_distance_m, dtype=float) / np.asarray(
        height_m, dtype=float)


def dem_relief_m(dem, lat, lon, radius_m: float = RELIEF_WINDOW_M) -> np.ndarray:
    """Relief (m) at each target (WGS84 degrees): highest − lowest DEM height (bilinear, the DEM's own
    reference — a range needs none) over a grid of spacing min(cell, radius/4) within ``radius_m``; NaN where
    the DEM has no height there."""
    from ..geometry.geodesy import ProjectedCRS

    x, y = ProjectedCRS(dem.crs).from_geodetic(np.asarray(lat, dtype=float), np.asarray(lon, dtype=float))
    step = min(dem.cell_size_m, radius_m / 4.0)
    n = int(np.ceil(radius_m / step))
    grid = np.arange(-n, n + 1) * step
    dx, dy = np.meshgrid(grid, grid)
    disc = dx ** 2 + dy ** 2 <= radius_m ** 2 + 1e-12
    dx, dy = dx[disc], dy[disc]
    heights = dem.sample(np.atleast_1d(x)[:, None] + dx[None, :], np.atleast_1d(y)[:, None] + dy[None, :])
    known = np.isfinite(heights).any(axis=1)
    out = np.full(len(known), np.nan)
    out[known] = np.nanmax(heights[known], axis=1) - np.nanmin(heights[known], axis=1)
    return out


@dataclass
class TargetRelief:
    """The relief h (m) of each target (NaN: unknown, not checked) and where it came from, for the report."""

    relief_m: np.ndarray
    source: str


@dataclass
class ReliefCheck:
    """Collects, frame by frame, the worst relief displacement against the label radius."""

    relief: TargetRelief
    radius_px: float
    frames_over: list = field(default_factory=list)
    n_labels: int = 0
    max_px: float = 0.0
    max_cm: float = 0.0

    def add(self, frame_id, geotag_ids, targets, nadir_distance_m, height_m, focal_px: float) -> None:
        """The labels of one frame: target indices ``targets``, their r and d (m); ``focal_px`` = √(fx·fy)."""
        h = self.relief.relief_m[targets]
        known = np.isfinite(h)
        if not known.any():
            return
        h, r, d, ids = h[known], nadir_distance_m[known], height_m[known], np.asarray(geotag_ids)[known]
        move_m = relief_displacement_m(h, r, d)
        move_px = move_m * focal_px / d
        self.n_labels += len(h)
        k = int(np.argmax(move_px))
        self.max_px = max(self.max_px, float(move_px[k]))
        self.max_cm = max(self.max_cm, float(100.0 * move_m.max()))
        if move_px[k] > self.radius_px:
            self.frames_over.append({
                "frame_id": _plain(frame_id), "geotag_id": _plain(ids[k]), "relief_m": round(float(h[k]), 3),
                "nadir_distance_m": round(float(r[k]), 3), "height_m": round(float(d[k]), 3),
                "displacement_px": round(float(move_px[k]), 2), "displacement_cm": round(100.0 * float(move_m[k]), 2),
                "label_radius_px": round(self.radius_px, 2),
                "label_radius_cm": round(100.0 * self.radius_px * float(d[k]) / focal_px, 2)})

    def summary(self) -> dict:
        h = self.relief.relief_m[np.isfinite(self.relief.relief_m)]
        return {"source": self.relief.source, "relief_m": _range(h), "label_radius_px": round(self.radius_px, 3),
                "n_labels_checked": self.n_labels, "max_displacement_px": round(self.max_px, 2),
                "max_displacement_cm": round(self.max_cm, 2), "n_frames_over": len(self.frames_over),
                "frames_over": self.frames_over,
                "rule": "displacement h·r/d (m), ·f/d (px); a frame is over when a label moves past 3σ"}


def _range(values) -> dict | None:
    if not len(values):
        return None
    return {"min": round(float(values.min()), 3), "max": round(float(values.max()), 3)}


def _plain(value):
    return value.item() if hasattr(value, "item") else value
