"""Measure where a simulated burrow hole really is in a rendered frame, from the image alone."""
import numpy as np


def dark_core_centroid(gray: np.ndarray, guess, radius_px: float, outer_px: float):
    """Centroid of the darkest half of a hole, measured in the image alone (re-centred twice).

    Darkness is relative to the median of a ring outside the mound; only pixels darker than half
    the darkest one, within 1.1 hole radii, count (weighted by how much darker).
    """
    yy, xx = np.mgrid[0:gray.shape[0], 0:gray.shape[1]]
    centre = np.asarray(guess, float)
    for _ in range(3):
        d = np.hypot(xx - centre[0], yy - centre[1])
        background = np.median(gray[(d > 1.3 * outer_px) & (d < 1.7 * outer_px)])
        darkness = background - gray
        window = d < 1.1 * radius_px
        weight = np.clip(darkness - 0.5 * darkness[window].max(), 0.0, None) * window
        centre = np.array([(weight * xx).sum(), (weight * yy).sum()]) / weight.sum()
    return centre
