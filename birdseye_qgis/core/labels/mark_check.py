"""How far labels land from where a person marked the same points: the accuracy check of a camera solution.

A solution with surveyed control points and their pinned image marks (Metashape markers) carries its own
test: project each control point into the frames as Write labels projects a geotag — the same frame
records, the same grouping by camera, :func:`.training_set.project_labels` — and measure the distance to
the mark. The figures (per mark, per point, per frame, median and 90th percentile) tell a user how good
the labels are before any training. Control points took part in the bundle adjustment that placed the
cameras; check points (flag ``check_point``) did not and are the fairer test.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..field.frame_records import local_frame_around, poses_from_records, uses_geotag_heights
from ..geometry.poses import FrameGeometry
from .training_set import project_labels

#: Fields of the check layer, one feature per image mark.
MARK_CHECK_FIELDS = [
    ("point_id", "int", "control point id (1.., as in the control-point layer)"),
    ("label", "string", "control point name in the solution"),
    ("kind", "string", "control_point (used by the adjustment) or check_point (not used)"),
    ("frame_id", "int", "frame the mark was placed in"),
    ("image", "string", "that frame's image"),
    ("u_mark", "double", "where a person marked the point (px, pixel-centre origin)"),
    ("v_mark", "double", "(px)"),
    ("u_label", "double", "where Write labels puts the point (px; empty if it does not fall in the image)"),
    ("v_label", "double", "(px)"),
    ("error_px", "double", "distance between label and mark (px)"),
    ("error_m", "double", "horizontal distance from the surveyed point to the mark's ray at the point's height (m)"),
]


@dataclass
class MarkCheck:
    """One row per image mark (``error_px`` NaN where the label does not fall inside that image).

    ``mark_lat``/``mark_lon``: where the mark's ray meets the horizontal plane at its point's surveyed
    height — the mark on the map, ``error_m`` from the point.
    """

    point_idx: np.ndarray
    frame_idx: np.ndarray
    uv_mark: np.ndarray
    uv_label: np.ndarray
    labels: list
    kinds: list
    mark_lat: np.ndarray
    mark_lon: np.ndarray
    error_m: np.ndarray

    @property
    def error_px(self) -> np.ndarray:
        return np.hypot(*(self.uv_label - self.uv_mark).T) if len(self.point_idx) else np.empty(0)

    def summary(self) -> dict:
        err = self.error_px
        found = err[np.isfinite(err)]
        out = {"marks": int(len(err)), "missing": int(np.count_nonzero(~np.isfinite(err)))}
        if len(found):
            out.update(median_px=float(np.median(found)), p90_px=float(np.percentile(found, 90)),
                       max_px=float(found.max()))
        return out

    def per_group(self, keys) -> list[tuple]:
        """(key, marks, median px, max px) for each distinct key of the marks, largest median first."""
        keys = np.asarray(keys)
        err = self.error_px
        rows = []
        for key in dict.fromkeys(keys.tolist()):
            e = err[keys == key]
            e = e[np.isfinite(e)]
            rows.append((key, int(np.count_nonzero(keys == key)), float(np.median(e)) if len(e) else np.nan,
                         float(e.max()) if len(e) else np.nan))
        return sorted(rows, key=lambda r: -np.nan_to_num(r[2], nan=np.inf))

    def records(self, frame_ids, images):
        for k in range(len(self.point_idx)):
            f, p = int(self.frame_idx[k]), int(self.point_idx[k])
            u, v = (None if not np.isfinite(x) else float(x) for x in self.uv_label[k])
            err, err_m = float(self.error_px[k]), float(self.error_m[k])
            yield {"point_id": p + 1, "label": self.labels[p], "kind": self.kinds[p],
                   "frame_id": int(frame_ids[f]), "image": images[f], "u_mark": float(self.uv_mark[k, 0]),
                   "v_mark": float(self.uv_mark[k, 1]), "u_label": u, "v_label": v,
                   "error_px": err if np.isfinite(err) else None, "error_m": err_m if np.isfinite(err_m) else None}


def check_marks(records: list, points, point_idx, frame_idx, uv_mark) -> MarkCheck:
    """Labels of ``points`` (a :class:`..field.geotags.Geotags`) in frame ``records`` against their marks.

    Mark ``k`` is point ``point_idx[k]`` marked in record ``frame_idx[k]`` at ``uv_mark[k]``.
    """
    groups = poses_from_records(records)
    local = local_frame_around(groups, points.lat, points.lon)
    frame_idx = np.asarray(frame_idx, dtype=np.int64)
    point_idx = np.asarray(point_idx, dtype=np.int64)
    uv_mark = np.asarray(uv_mark, dtype=float).reshape(-1, 2)
    surveyed = local.from_geodetic(points.lat, points.lon, np.nan_to_num(points.height))
    placed: dict[tuple[int, int], np.ndarray] = {}
    on_ground = np.full((len(frame_idx), 3), np.nan)
    for poses, idx in groups:
        for labels in project_labels(poses, points, 0.0, local, None, uses_geotag_heights(records, idx)):
            for g, uv in zip(labels.geotag_index.tolist(), labels.uv):
                placed[(int(idx[labels.frame_index]), g)] = uv
        # Each mark's ray meets the horizontal plane of its point's surveyed height: where the person's
        # mark lies on the map, beside the point itself.
        position = {int(r): k for k, r in enumerate(idx)}
        mine = np.flatnonzero(np.isin(frame_idx, idx))
        if len(mine):
            geometry = FrameGeometry(poses, local)
            local_f = np.array([position[int(f)] for f in frame_idx[mine]])
            rays = geometry.rays(local_f, uv_mark[mine])
            origin = geometry.C[local_f]
            t = (surveyed[point_idx[mine], 2] - origin[:, 2]) / rays[:, 2]
            on_ground[mine] = np.where((t > 0)[:, None], origin + t[:, None] * rays, np.nan)
    uv_label = np.array([placed.get((f, p), (np.nan, np.nan)) for f, p in zip(frame_idx.tolist(),
                                                                              point_idx.tolist())],
                        dtype=float).reshape(-1, 2)
    kinds = ["check_point" if "check_point" in f else "control_point" for f in points.flags]
    lat, lon, _ = local.to_geodetic(on_ground)
    return MarkCheck(point_idx, frame_idx, uv_mark, uv_label, list(points.labels), kinds,
                     np.asarray(lat, dtype=float), np.asarray(lon, dtype=float),
                     np.hypot(*(on_ground[:, :2] - surveyed[point_idx, :2]).T))


def describe(check: MarkCheck, frame_ids) -> tuple[list[str], list[str]]:
    """Sentences for an import report: (findings: the overall figures, the worst points and frames; notes: the
    marks that have no label, which need a look)."""
    s = check.summary()
    if not s["marks"]:
        return [], []
    lines, notes = [], []
    if "median_px" in s:
        lines.append(f"Label accuracy against {s['marks']} pinned image mark(s) of {len(check.labels)} control "
                     f"point(s): median {s['median_px']:.1f} px, 90 % within {s['p90_px']:.1f} px, max "
                     f"{s['max_px']:.1f} px")
    if s["missing"]:
        notes.append(f"{s['missing']} mark(s) have no label: the point does not project into the image it was "
                     "marked in (a wrong mark, or a frame whose pose is off)")
    worst_points = check.per_group([check.labels[p] for p in check.point_idx])[:3]
    lines.append("Per point (marks, median, max px): " + "; ".join(
        f"{name} ({n}, {med:.1f}, {mx:.1f})" for name, n, med, mx in worst_points))
    worst_frames = check.per_group(np.asarray(frame_ids)[check.frame_idx])[:3]
    lines.append("Worst frames (frame id: marks, median px): " + "; ".join(
        f"{fid}: {n}, {med:.1f}" for fid, n, med, _ in worst_frames))
    return lines, notes
