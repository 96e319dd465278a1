"""Which geotags are in view of a flight, and which clusters their positions match."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..errors import check_cancel
from ..geometry.geodesy import LocalFrame
from ..geometry.ground import LevelPlaneGround, placeable_frames
from ..geometry.poses import FrameGeometry, FramePoses
from ..geometry.projection import project_in_view


@dataclass
class InView:
    """``mask`` (G,) True for points in view of at least one processed frame; frame counts
    (``n_frames_without_ground``: frames left out for want of the ground height their ground model needs);
    ``per_frame`` (n_frames,) how many of the points each processed frame sees (pose-group order): with
    the geotags as points, the survey density (:mod:`.transfer`)."""

    mask: np.ndarray
    n_frames: int
    n_frames_without_ground: int
    per_frame: np.ndarray


def in_view(pose_groups: Sequence[FramePoses], local: LocalFrame, points, edge_buffer_px: float = 0.0,
            ground=None, progress=None, is_canceled=None) -> InView:
    """Which local points (G, 3) pass the in-frame test in at least one frame of ``pose_groups``.

    Each point is placed on the ground its frame sees, built by ``ground`` (a factory ``FrameGeometry ->
    GroundModel`` as Detect takes it, e.g. :class:`~.dem.DemGroundFactory`; None = the level plane), so
    the test stands on the ground the detections were placed on. Points the ground hides from a frame (a
    DEM's ridge) are not in view of it. Frames without a ground height are left out and counted when the
    ground model needs one (the level plane, the method's plane: Detect skips them, so they were not
    processed); a DEM places them.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    mask = np.zeros(len(points), dtype=bool)
    n_frames = n_skipped = 0
    per_frame = []
    for g, poses in enumerate(pose_groups):
        check_cancel(is_canceled)
        placeable = placeable_frames(poses, ground)
        n_skipped += int((~placeable).sum())
        if not placeable.all():
            poses = poses.subset(np.flatnonzero(placeable))
        n_frames += len(poses)
        seen = np.zeros(len(poses), dtype=np.int64)
        if len(poses) and len(points):
            geom = FrameGeometry(poses, local)
            model = (ground or LevelPlaneGround)(geom)
            proj = project_in_view(geom, points, model, edge_buffer_px)
            hidden = model.occluded(proj.frame_idx, model.place(proj.frame_idx, points[proj.point_idx]))
            mask[proj.point_idx[~hidden]] = True
            pairs = np.unique(proj.frame_idx[~hidden] * len(points) + proj.point_idx[~hidden])
            seen = np.bincount(pairs // len(points), minlength=len(poses))
        per_frame.append(seen)
        if progress is not None:
            progress((g + 1) / len(pose_groups))
    return InView(mask, n_frames, n_skipped,
                  np.concatenate(per_frame) if per_frame else np.empty(0, dtype=np.int64))

@dataclass
class Matches:
    """(point, cluster) pairs with the smallest distance (m) from the point to the cluster's core points."""

    point: np.ndarray
    cluster: np.ndarray
    distance: np.ndarray

    def within(self, radius_m: float) -> "Matches":
        keep = self.distance <= radius_m
        return Matches(self.point[keep], self.cluster[keep], self.distance[keep])


def match_to_clusters(core_xy, core_cluster, points_xy, radius_m: float) -> Matches:
    """Every (point, cluster) pair with a core point of the cluster within ``radius_m`` of the point."""
    from scipy.spatial import cKDTree

    core_xy = np.asarray(core_xy, dtype=float).reshape(-1, 2)
    points_xy = np.asarray(points_xy, dtype=float).reshape(-1, 2)
    empty = Matches(np.empty(0, np.int64), np.empty(0, np.int64), np.empty(0))
    if len(core_xy) == 0 or len(points_xy) == 0:
        return empty
    hits = cKDTree(core_xy).query_ball_point(points_xy, radius_m * (1 + 1e-9), return_sorted=False)
    counts = np.fromiter((len(h) for h in hits), dtype=np.int64, count=len(hits))
    if counts.sum() == 0:
        return empty
    point = np.repeat(np.arange(len(points_xy)), counts)
    core = np.fromiter((i for h in hits for i in h), dtype=np.int64, count=int(counts.sum()))
    d = np.hypot(points_xy[point, 0] - core_xy[core, 0], points_xy[point, 1] - core_xy[core, 1])
    cluster = np.asarray(core_cluster, dtype=np.int64)[core]
    keep = d <= radius_m
    point, cluster, d = point[keep], cluster[keep], d[keep]
    order = np.lexsort((d, cluster, point))
    point, cluster, d = point[order], cluster[order], d[order]
    first = np.ones(len(point), dtype=bool)
    first[1:] = (point[1:] != point[:-1]) | (cluster[1:] != cluster[:-1])
    return Matches(point[first], cluster[first], d[first])
