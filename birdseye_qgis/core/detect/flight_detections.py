"""One checkpoint over a whole flight, kept in memory at one or several thresholds — what checkpoint
screening and operating-point sweeps score (Detect writes a layer instead)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..geometry.geodesy import LocalFrame
from ..geometry.poses import FramePoses
from .clustering import GroundPositions
from .detector import DetectRequest, HeatmapModel, detect_frames_at_thresholds


@dataclass
class ThresholdDetections:
    """The flight's detections from a peak extraction at ``threshold``: ``frame_id`` (N,), pixels
    ``uv`` (N, 2) in the original images, and their ``positions`` on the ground."""

    threshold: float
    frame_id: np.ndarray
    uv: np.ndarray
    positions: GroundPositions

    def __len__(self) -> int:
        return len(self.frame_id)


@dataclass
class FlightDetections:
    """``processed``: ids of the frames that were processed, in flight order; ``skipped``: (frame id,
    reason) of the others; ``by_threshold``: one :class:`ThresholdDetections` per threshold asked for."""

    processed: np.ndarray
    skipped: list
    by_threshold: list


def detect_flight(model: HeatmapModel, pose_groups: Sequence[FramePoses], images: Sequence[Sequence[str]],
                  thresholds: Sequence[float], edge_buffer_px: float, local: LocalFrame,
                  progress=None, is_canceled=None, ground=None) -> FlightDetections:
    """Every frame of every pose group (``images[g][k]`` is frame k of group g) through ``model``, one
    heatmap per frame and its peaks at every threshold (:func:`~.detector.detect_frames_at_thresholds`),
    placed on ``ground`` (a ground-model factory as Detect takes it; None = the level plane)."""
    request = DetectRequest(edge_buffer_px=edge_buffer_px)
    parts = [([], [], [], []) for _ in thresholds]
    processed, skipped = [], []
    total = max(1, sum(len(p) for p in pose_groups))
    done = 0
    for poses, paths in zip(pose_groups, images):
        def group_progress(fraction, offset=done, size=len(poses)):
            if progress is not None:
                progress((offset + fraction * size) / total)

        for found in detect_frames_at_thresholds(model, poses, paths, thresholds, request, local,
                                                 progress=group_progress, is_canceled=is_canceled, ground=ground):
            if found[0].skipped:
                skipped.append((found[0].frame_id, found[0].skipped))
                continue
            processed.append(found[0].frame_id)
            for (frame_ids, uvs, xys, lat_lons), at in zip(parts, found):
                frame_ids.append(np.full(len(at), at.frame_id, dtype=object))
                uvs.append(at.uv)
                xys.append(at.ground_local[:, :2])
                lat_lons.append(np.column_stack([at.lat, at.lon]))
        done += len(poses)
    by_threshold = []
    for t, (f, u, x, ll) in zip(thresholds, parts):
        lat_lon = _concat(ll, np.empty((0, 2)))
        by_threshold.append(ThresholdDetections(float(t), _concat(f, np.empty(0, dtype=object)),
                                                _concat(u, np.empty((0, 2))),
                                                GroundPositions(_concat(x, np.empty((0, 2))), lat_lon[:, 0],
                                                                lat_lon[:, 1])))
    return FlightDetections(np.array(processed, dtype=object), skipped, by_threshold)


def _concat(parts, empty):
    return np.concatenate(parts) if parts else empty
