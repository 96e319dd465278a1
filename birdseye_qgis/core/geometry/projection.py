"""World → pixel for frames × points, and pixel → ground.

The forward chain for a point X (local frame) seen by frame f:

    X_cam = R_local_cam[f]ᵀ (X − C[f]),   in front if z_cam > 0,
    (u, v) = K · distort(x_cam / z_cam, y_cam / z_cam),
    in frame if the pixel lies inside the image by at least ``edge_buffer_px``.

With a ground model the point is first placed on the ground the frame sees (:mod:`.ground`).
Large campaigns are pre-filtered spatially: each frame's footprint on the ground gives a disc, and a
k-d tree over the points yields the candidate (frame, point) pairs, so the cost grows with the number
of pairs in view, not frames × points.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .ground import GroundModel
from .poses import FrameGeometry


@dataclass
class Projection:
    """One entry per (frame, point) pair considered; ``in_view`` = in front and inside the buffer."""

    frame_idx: np.ndarray
    point_idx: np.ndarray
    uv: np.ndarray
    depth: np.ndarray
    margin_px: np.ndarray
    in_front: np.ndarray
    in_frame: np.ndarray

    FIELDS = ("frame_idx", "point_idx", "uv", "depth", "margin_px", "in_front", "in_frame")

    @property
    def in_view(self) -> np.ndarray:
        return self.in_front & self.in_frame

    def select(self, mask) -> "Projection":
        return Projection(*(getattr(self, f)[mask] for f in self.FIELDS))


def project_pairs(geometry: FrameGeometry, frame_idx, points, ground: GroundModel | None = None,
                  edge_buffer_px: float = 0.0, point_idx=None) -> Projection:
    """Project one point per frame index: ``points[k]`` into frame ``frame_idx[k]``."""
    frame_idx = np.asarray(frame_idx, dtype=np.int64)
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    if ground is not None:
        points = ground.place(frame_idx, points)
    cam = geometry.to_camera(frame_idx, points)
    in_front = cam[:, 2] > 1e-6
    uv = geometry.camera.project(cam)
    margin = geometry.camera.edge_margin(uv)
    in_frame = in_front & geometry.camera.in_frame(uv, edge_buffer_px)
    return Projection(frame_idx, np.arange(len(points)) if point_idx is None else np.asarray(point_idx),
                      uv, cam[:, 2], margin, in_front, in_frame)


def project_all(geometry: FrameGeometry, points, ground: GroundModel | None = None,
                edge_buffer_px: float = 0.0) -> Projection:
    """Dense F × M projection (every frame against every point), pairs in frame-major order."""
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    f, m = len(geometry), len(points)
    fi = np.repeat(np.arange(f), m)
    pi = np.tile(np.arange(m), f)
    return project_pairs(geometry, fi, points[pi], ground, edge_buffer_px, point_idx=pi)


def footprints(geometry: FrameGeometry, ground: GroundModel, per_edge: int = 8):
    """Ground points (F, 4·per_edge, 3) of each image border, and a mask (F,) of complete footprints."""
    border = geometry.camera.boundary_pixels(per_edge)
    f, k = len(geometry), len(border)
    fi = np.repeat(np.arange(f), k)
    uv = np.tile(border, (f, 1))
    pts, valid = ground.intersect(fi, geometry.C[fi], geometry.rays(fi, uv))
    return pts.reshape(f, k, 3), valid.reshape(f, k).all(axis=1)


def candidate_pairs(geometry: FrameGeometry, points, ground: GroundModel, margin_m: float = 0.5):
    """(frame_idx, point_idx) pairs whose point lies near the frame's ground footprint.

    A frame whose border rays do not all reach the ground (a view above the horizon) is tested
    against every point, so the filter never drops a pair the full projection would keep.
    """
    from scipy.spatial import cKDTree

    points = np.asarray(points, dtype=float).reshape(-1, 3)
    if len(points) == 0 or len(geometry) == 0:
        return np.empty(0, np.int64), np.empty(0, np.int64)
    fp, complete = footprints(geometry, ground, per_edge=4)
    centre = np.nanmean(fp, axis=1)
    radius = np.sqrt(np.nanmax(np.sum((fp - centre[:, None]) ** 2, axis=2), axis=1)) + margin_m
    # Horizontal search in the local frame; the vertical spread of a field is far below a footprint.
    tree = cKDTree(points[:, :2])
    fi_parts, pi_parts = [], []
    ok = np.flatnonzero(complete)
    if len(ok):
        hits = tree.query_ball_point(centre[ok, :2], radius[ok], return_sorted=False)
        counts = np.fromiter((len(h) for h in hits), dtype=np.int64, count=len(hits))
        fi_parts.append(np.repeat(ok, counts))
        pi_parts.append(np.fromiter((i for h in hits for i in h), dtype=np.int64, count=int(counts.sum())))
    for f in np.flatnonzero(~complete):
        fi_parts.append(np.full(len(points), f, dtype=np.int64))
        pi_parts.append(np.arange(len(points), dtype=np.int64))
    return np.concatenate(fi_parts), np.concatenate(pi_parts)


def project_in_view(geometry: FrameGeometry, points, ground: GroundModel | None = None,
                    edge_buffer_px: float = 0.0, prefilter_ground: GroundModel | None = None,
                    keep_edge: bool = False) -> Projection:
    """Every (frame, point) pair in view, found through the spatial pre-filter.

    ``ground`` places points on the frame's ground (None: use the points' own heights);
    ``prefilter_ground`` gives footprints for the filter (defaults to ``ground``). With
    ``keep_edge`` the pairs in front and inside the image but within the edge buffer are kept too
    (``in_frame`` False), so callers can report them as "edge".
    """
    prefilter_ground = prefilter_ground or ground
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    if prefilter_ground is None:
        proj = project_all(geometry, points, None, edge_buffer_px)
    else:
        fi, pi = candidate_pairs(geometry, points, prefilter_ground)
        proj = project_pairs(geometry, fi, points[pi], ground, edge_buffer_px, point_idx=pi)
    if keep_edge:
        return proj.select(proj.in_front & geometry.camera.in_frame(proj.uv, 0.0))
    return proj.select(proj.in_view)


def pixel_to_ground(geometry: FrameGeometry, ground: GroundModel, frame_idx, uv):
    """Back-project pixels (N, 2) of frames ``frame_idx`` (N,) to ground points (N, 3), and validity."""
    frame_idx = np.asarray(frame_idx, dtype=np.int64)
    uv = np.asarray(uv, dtype=float).reshape(-1, 2)
    return ground.intersect(frame_idx, geometry.C[frame_idx], geometry.rays(frame_idx, uv))


def centre_gsd_m(geom: FrameGeometry, ground: GroundModel) -> np.ndarray:
    """Ground sample distance (m/px) at each image centre: the altimeter's level depth over the focal
    length (:meth:`FrameGeometry.gsd_m`), the measured range, where the frame has a ground height;
    elsewhere the camera's vertical distance to where the principal ray meets ``ground`` (a DEM), NaN
    where it misses."""
    gsd = geom.gsd_m()
    missing = np.flatnonzero(~np.isfinite(gsd))
    if len(missing):
        cam = geom.camera
        centre = np.tile([[cam.cx, cam.cy]], (len(missing), 1))
        hit, valid = ground.intersect(missing, geom.C[missing], geom.rays(missing, centre))
        depth = np.einsum("fi,fi->f", geom.C[missing] - hit, geom.up[missing])
        gsd[missing] = np.where(valid, depth / np.sqrt(cam.fx * cam.fy), np.nan)
    return gsd
