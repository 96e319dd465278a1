"""How far the level-plane ground model can be trusted on sloped terrain.

Set-up (all lengths in metres, pixels in px):

* A nadir camera (intrinsics ``fx, fy, cx, cy``) flies at height ``h`` = altitude above the *nadir
  point* N, the ground point straight below it; the altimeter gives ``h`` exactly.
* The label writer's ground model is the level plane through N (docs/design.md#ground): every target is assumed to
  lie at N's height.
* The true ground is a plane through N tilted by the slope ``α``. A target T at horizontal distance
  ``d`` from N, in the direction of steepest ascent (the worst case), lies ``d·tan α`` above N.

The model puts T at depth ``h`` and draws its label at ``f·d/h`` px from the principal point; the
camera sees it at depth ``h − d·tan α``, i.e. at ``f·d/(h − d·tan α)`` px. The label error is the
difference,

    e(α, ρ) = f·ρ²·tan α / (1 − ρ·tan α)   px,     ρ = d / h,

with ``f = max(fx, fy)`` (the image direction in which a given ground offset spans most pixels). It
depends on the altitude only through ρ: at a given pixel the error in px is the same at 10 m and at
20 m. Downhill targets err less (``1 + ρ tan α`` in the denominator) and targets at the nadir point
not at all. Where ``ρ·tan α ≥ 1`` the target would be level with or above the camera: NaN.
"""
from __future__ import annotations

import math
from typing import Optional

import numpy as np

from ..errors import InputError
from .sensor_bound import _altitude, _camera


def _focal(intr) -> float:
    fx, fy = _camera(intr)[:2]
    return max(fx, fy)


def slope_error_px(intr, altitude_m, slope_deg, distance_ratio) -> np.ndarray:
    """Label error (px) of the level-plane model, broadcast over ``slope_deg`` and ``distance_ratio``.

    ``distance_ratio`` is ρ = d/h, the target's horizontal distance from the nadir point over the
    altitude. Evaluated from the geometry (depths ``h`` and ``h − d tan α``), see the module docstring.
    """
    h = _altitude(altitude_m)
    f = _focal(intr)
    slope = np.asarray(slope_deg, dtype=float)
    rho = np.asarray(distance_ratio, dtype=float)
    if np.any(slope < 0) or np.any(slope >= 90) or np.any(rho < 0):
        raise InputError("slopes must lie in [0°, 90°) and distance ratios be non-negative")
    d = rho * h
    true_depth = h - d * np.tan(np.radians(slope))
    with np.errstate(divide="ignore", invalid="ignore"):
        err = f * d / true_depth - f * d / h
    return np.where(true_depth > 0, err, np.nan)


def slope_error_grid(intr, altitude_m, slopes_deg, distance_ratios) -> np.ndarray:
    """Label error (px), rows = ``slopes_deg`` (degrees), columns = ``distance_ratios`` (ρ = d/h)."""
    slopes = np.asarray(slopes_deg, dtype=float).reshape(-1, 1)
    ratios = np.asarray(distance_ratios, dtype=float).reshape(1, -1)
    return slope_error_px(intr, altitude_m, slopes, ratios)


def frame_distance_ratios(intr) -> dict:
    """ρ of the farthest frame edge along u, along v, and of the farthest corner (the outermost pixel centres,
    0…W − 1 and 0…H − 1)."""
    fx, fy, cx, cy, width, height = _camera(intr)
    ru = max(cx, width - 1 - cx) / fx
    rv = max(cy, height - 1 - cy) / fy
    return {"edge_u": ru, "edge_v": rv, "corner": math.hypot(ru, rv)}


def max_slope_deg(intr, tolerance_px, distance_ratio) -> float:
    """Largest slope (degrees) whose label error at ρ = ``distance_ratio`` stays within ``tolerance_px``.

    Inverts ``e = f ρ² t / (1 − ρ t)`` for ``t = tan α``: ``t = e / (ρ (f ρ + e))``; 90° at ρ = 0.
    """
    e = float(tolerance_px)
    rho = float(distance_ratio)
    if not (e > 0) or rho < 0:
        raise InputError("tolerance must be positive and the distance ratio non-negative")
    if rho == 0:
        return 90.0
    return math.degrees(math.atan(e / (rho * (_focal(intr) * rho + e))))


def plot_slope_error(intr, altitude_m, path, tolerance_px: float = 30.0, slopes_deg=None,
                     distance_ratios=None, title: Optional[str] = None):
    """Write a contour PNG of the label error (px) over slope × ρ to ``path`` and return ``path``.

    The tolerance contour is drawn in red and the frame's edge and corner ρ as vertical lines.
    Uses matplotlib's object API on an Agg canvas (the host's backend is left alone).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.colors import LogNorm
    from matplotlib.figure import Figure

    frame = frame_distance_ratios(intr)
    slopes = np.linspace(0.0, 45.0, 181) if slopes_deg is None else np.asarray(slopes_deg, dtype=float)
    ratios = (np.linspace(0.0, 1.15 * frame["corner"], 200) if distance_ratios is None
              else np.asarray(distance_ratios, dtype=float))
    err = slope_error_grid(intr, altitude_m, slopes, ratios)

    fig = Figure(figsize=(7, 4.5), dpi=120)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    levels = np.array([0.1, 0.3, 1, 3, 10, 30, 100, 300, 1000, 3000])
    filled = ax.contourf(ratios, slopes, np.clip(err, levels[0], levels[-1]), levels=levels,
                         norm=LogNorm(levels[0], levels[-1]), cmap="viridis")
    fig.colorbar(filled, ax=ax, label="label error [px]")
    lines = ax.contour(ratios, slopes, err, levels=[float(tolerance_px)], colors="tab:red", linewidths=2)
    ax.clabel(lines, fmt=f"{tolerance_px:g} px")
    for name, rho in frame.items():
        ax.axvline(rho, color="white", lw=0.8, ls="--")
        ax.text(rho, slopes[-1], f" {name.replace('_', ' ')}", color="white", fontsize=7, va="top", rotation=90)
    ax.set_xlabel("horizontal distance from nadir / altitude  (ρ = d/h)")
    ax.set_ylabel("terrain slope [deg]")
    ax.set_title(title or "Level-plane label error on sloped ground (uphill, any altitude)")
    fig.tight_layout()
    fig.savefig(path)
    return path
