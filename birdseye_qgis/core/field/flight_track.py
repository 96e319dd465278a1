"""The flight line: the pose log's track as segments split at gaps, for the map."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geometry.geodesy import LocalFrame, ProjectedCRS

#: The flight line is split where the pose log has a gap longer than this (s).
TRACK_GAP_S = 2.0
TRACK_FIELDS = [
    ("segment", "int", "flight line segment, 1.. in time order"),
    ("label", "string", "segment summary for the map label"),
    ("start_s", "double", "first pose time (s, pose log clock)"),
    ("end_s", "double", "last pose time (s)"),
    ("duration_s", "double", "end − start (s)"),
    ("n_frames", "int", "frames exposed on this segment"),
    ("length_m", "double", "horizontal length (m)"),
]


@dataclass
class TrackSegment:
    xyz: np.ndarray
    attributes: dict


def flight_track(time_s, lat, lon, height, crs: ProjectedCRS, frame_times=(), gap_s: float = TRACK_GAP_S,
                 min_interval_s: float = 0.2) -> list[TrackSegment]:
    """The flight line as segments split at gaps > ``gap_s``, thinned to one vertex per ``min_interval_s``."""
    time_s = np.asarray(time_s, dtype=float)
    if len(time_s) < 2:
        return []
    keep = np.zeros(len(time_s), dtype=bool)
    keep[0] = keep[-1] = True
    bucket = np.floor((time_s - time_s[0]) / min_interval_s)
    keep[1:] |= bucket[1:] != bucket[:-1]
    gaps = np.flatnonzero(np.diff(time_s) > gap_s)
    keep[gaps] = keep[gaps + 1] = True
    idx = np.flatnonzero(keep)
    t, la, lo, h = time_s[idx], np.asarray(lat)[idx], np.asarray(lon)[idx], np.asarray(height)[idx]
    x, y = crs.from_geodetic(la, lo)
    local = LocalFrame.around(la, lo, h)
    enu = local.from_geodetic(la, lo, h)
    breaks = np.flatnonzero(np.diff(t) > gap_s) + 1
    frame_times = np.sort(np.asarray(frame_times, dtype=float))
    segments = []
    for number, part in enumerate(np.split(np.arange(len(t)), breaks), start=1):
        if len(part) < 2:
            continue
        start, end = float(t[part[0]]), float(t[part[-1]])
        n_frames = int(np.searchsorted(frame_times, end, "right") - np.searchsorted(frame_times, start, "left"))
        length = float(np.sum(np.linalg.norm(np.diff(enu[part, :2], axis=0), axis=1)))
        label = f"Flight line {number}: {n_frames} frames, {(end - start) / 60:.1f} min, {length:.0f} m"
        segments.append(TrackSegment(np.stack([x[part], y[part], h[part]], axis=1),
                                     {"segment": number, "label": label, "start_s": start, "end_s": end,
                                      "duration_s": end - start, "n_frames": n_frames, "length_m": length}))
    return segments
