"""How far labels land from where a person marked the same points: the accuracy check of a camera solution.

A solution with surveyed control points and their pinned image marks (Metashape markers) carries its own
test: project each control point into the frames as Write labels projects a geotag — the same frame
records, the same grouping by camera, :func:`.training_set.project_labels` — and measure the distance to
the mark. The figures (per mark, per point, per frame, median and 90th percentile) tell a user how good
the labels are before any training. Control points took part in the bundle adjustment that placed the
cameras; check points (flag ``check_point``) did not and are the fairer test.

**σ of the labels from the check** (:func:`measured_sigma`, Write labels' ``SIGMA_SOURCE``). The sensor bound
sizes a label of radius r px for a label error of variance (r/3)² in each image direction (docs/design.md
§3.6), so σ_label is the per-axis standard deviation of the label error. Measured, that is the per-axis RMS of
the residuals label − mark, σ = √(mean(Δu² + Δv²) / 2) px — an RMS, not a standard deviation about the mean, so
that a systematic offset counts as error too. A label of radius 3σ then holds 98.9 % of an isotropic Gaussian
error (2.45σ holds 95 %). The check points are used when the check has any with a label (they did not shape the
solution), else the control points, which flatter it. Marks without a label (the point fell outside the
image) are left out and counted: they need a look, not an average.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
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


#: Below this many marks the measured σ is uncertain by more than ±16 % (:attr:`MeasuredSigma.relative_uncertainty`).
FEW_MARKS = 10
#: The fields :func:`measured_sigma` reads from each record of a check.
SIGMA_FIELDS = ("kind", "u_mark", "v_mark", "u_label", "v_label")
CHECK_POINT, CONTROL_POINT = "check_point", "control_point"


def sigma_from_residuals(du, dv) -> float:
    """σ_label (px) of label − mark residuals ``du``, ``dv`` (px): their per-axis RMS, √(mean(Δu² + Δv²) / 2)."""
    du, dv = np.asarray(du, dtype=float), np.asarray(dv, dtype=float)
    return float(np.sqrt(np.mean(du ** 2 + dv ** 2) / 2.0))


@dataclass
class MeasuredSigma:
    """σ_label measured on a check: from ``n_marks`` marks of ``kind``; ``n_without_label`` marks had no label."""

    sigma_px: float
    n_marks: int
    kind: str
    n_without_label: int
    rms_u_px: float
    rms_v_px: float
    max_px: float
    source: str

    @property
    def few(self) -> bool:
        return self.n_marks < FEW_MARKS

    @property
    def relative_uncertainty(self) -> float:
        """Relative standard uncertainty of σ from n marks (2n residual components, each adding one degree of
        freedom to the variance): 1/√(2·2n) = 1/√(4n)."""
        return 1.0 / np.sqrt(4.0 * self.n_marks)

    def to_dict(self) -> dict:
        return {"source": "mark_check", "file": self.source, "marks": self.kind, "n_marks": self.n_marks,
                "n_without_label": self.n_without_label, "rms_u_px": round(self.rms_u_px, 3),
                "rms_v_px": round(self.rms_v_px, 3), "max_error_px": round(self.max_px, 3),
                "rule": "per-axis RMS of label - mark: sqrt(mean(du^2 + dv^2) / 2)"}


def measured_sigma(records, source: str = "label check") -> MeasuredSigma:
    """σ_label from the records of a check (dicts with :data:`SIGMA_FIELDS`; u_label and v_label None where the
    point had no label), as the label check of Import camera solution writes them (:data:`MARK_CHECK_FIELDS`).

    Bad records are refused naming ``source``, the row (1..) and the field; so is a check with no mark that has
    a label.
    """
    kinds, du, dv, missing = [], [], [], []
    for row, rec in enumerate(records, start=1):
        kind = rec.get("kind")
        if kind not in (CHECK_POINT, CONTROL_POINT):
            raise InputError(f"{kind!r} is not {CHECK_POINT} or {CONTROL_POINT}", source=source, row=row,
                             field="kind")
        mark = [_number(rec, name, source, row) for name in ("u_mark", "v_mark")]
        label = [_number(rec, name, source, row, optional=True) for name in ("u_label", "v_label")]
        if (label[0] is None) != (label[1] is None):
            raise InputError("u_label and v_label must both be given or both be empty (no label in that image)",
                             source=source, row=row, field="u_label" if label[0] is None else "v_label")
        kinds.append(kind)
        missing.append(label[0] is None)
        du.append(np.nan if label[0] is None else label[0] - mark[0])
        dv.append(np.nan if label[1] is None else label[1] - mark[1])
    kinds, du, dv, missing = np.array(kinds, dtype=object), np.array(du), np.array(dv), np.array(missing, bool)
    kind = CHECK_POINT if np.any((kinds == CHECK_POINT) & ~missing) else CONTROL_POINT
    used = (kinds == kind) & ~missing
    if not used.any():
        raise InputError("has no mark with a label (u_label, v_label): nothing to measure the labels' error on",
                         source=source)
    du, dv = du[used], dv[used]
    return MeasuredSigma(sigma_from_residuals(du, dv), int(used.sum()), kind, int(((kinds == kind) & missing).sum()),
                         float(np.sqrt(np.mean(du ** 2))), float(np.sqrt(np.mean(dv ** 2))),
                         float(np.max(np.hypot(du, dv))), source)


def _number(rec, name, source, row, optional=False):
    value = rec.get(name)
    if value is None or value == "":
        if optional:
            return None
        raise InputError("is empty; a mark needs its pixel position", source=source, row=row, field=name)
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{value!r} is not a number (px)", source=source, row=row, field=name) from None
    if not np.isfinite(number):
        raise InputError(f"{value!r} is not a finite number (px)", source=source, row=row, field=name)
    return number
