"""Two detectors on one flight: each scored as ``evaluatedetections`` scores it, and what changed.

Both detection layers are scored by :func:`.evaluation.evaluate_flights` in one local frame (the
flight's), so every figure is the one Evaluate detections gives for that layer alone. What changed:

* **Targets** — each in-view geotag, by whether each detector recovered it (a core point within
  ``eps_pred_m``, as recall counts it): ``found_by_both``, ``found_only_by_new``, ``lost_by_new``,
  ``missed_by_both``.
* **False clusters** — clusters no in-view geotag matches (those GMCF counts against a detector). Two
  clusters of the two detectors are *the same spot* when a core point of one lies within
  ``eps_pred_m`` of a core point of the other (the match radius of the scores). An old false cluster
  with no new false cluster at its spot is ``false_removed``, else ``false_kept``; a new false cluster
  with no old false cluster at its spot is ``false_added``.

"Before" is the old detector, "after" the new one.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Sequence

import numpy as np

from ..errors import InputError
from ..field.geotags import Geotags
from ..geometry.ground_record import RASTER, common_ground
from ..geometry.poses import FramePoses
from .evaluation import Detections, Evaluation, Flight, evaluate_flights, local_frame_for, mosaic_flight
from .matching import in_view, match_to_clusters
from .operating_point import OperatingPoint
from .pre_review import ratio
from .verdicts import VerdictLog

FOUND_BY_BOTH, FOUND_ONLY_BY_NEW, LOST_BY_NEW, MISSED_BY_BOTH = (
    "found_by_both", "found_only_by_new", "lost_by_new", "missed_by_both")
FALSE_REMOVED, FALSE_ADDED, FALSE_KEPT = "false_removed", "false_added", "false_kept"
TARGET_CHANGES = (FOUND_BY_BOTH, FOUND_ONLY_BY_NEW, LOST_BY_NEW, MISSED_BY_BOTH)
CLUSTER_CHANGES = (FALSE_REMOVED, FALSE_ADDED, FALSE_KEPT)
CHANGES = TARGET_CHANGES + CLUSTER_CHANGES

#: (name, type, description) of the change layer.
CHANGE_FIELDS = [
    ("change", "string", "found_by_both, found_only_by_new, lost_by_new, missed_by_both (in-view geotags); "
                         "false_removed, false_added, false_kept (clusters no geotag matches)"),
    ("kind", "string", "target (an in-view geotag) or false_cluster"),
    ("geotag_id", "string", "the geotag (targets)"),
    ("cluster_old", "int", "the old detector's cluster at this spot (cluster_id of its Cluster detections "
                           "output), NULL when none"),
    ("cluster_new", "int", "the new detector's cluster at this spot, NULL when none"),
    ("n_detections_old", "int", "detections in the old cluster"),
    ("n_detections_new", "int", "detections in the new cluster"),
]


@dataclass(frozen=True)
class Change:
    """One spot that changed (or not): a geotag, or a false cluster's centroid (local metres)."""

    change: str
    x: float
    y: float
    geotag: int | None = None
    cluster_old: int | None = None
    cluster_new: int | None = None

    @property
    def kind(self) -> str:
        return "target" if self.change in TARGET_CHANGES else "false_cluster"


def _same_spot(clustering_a, clusters_a, clustering_b, clusters_b, radius_m: float) -> list[list[int]]:
    """For each cluster of ``clusters_a``, the clusters of ``clusters_b`` with a core point within
    ``radius_m`` of one of its core points."""
    keep_b = np.isin(clustering_b.core_cluster, clusters_b)
    keep_a = np.isin(clustering_a.core_cluster, clusters_a)
    m = match_to_clusters(clustering_b.core_xy[keep_b], clustering_b.core_cluster[keep_b],
                          clustering_a.core_xy[keep_a], radius_m)
    owner = clustering_a.core_cluster[keep_a][m.point]
    return [sorted(set(m.cluster[owner == k].tolist())) for k in clusters_a]


def classify_changes(old, new, in_view_mask, geotag_xy, eps_pred_m: float) -> list[Change]:
    """What changed from ``old`` to ``new`` (:class:`.evaluation.FlightEvaluation` of the same flight in
    one local frame): targets first (in geotag order), then false clusters (old, then added new)."""
    geotag_xy = np.asarray(geotag_xy, dtype=float).reshape(-1, 2)
    out = []
    names = {(True, True): FOUND_BY_BOTH, (False, True): FOUND_ONLY_BY_NEW, (True, False): LOST_BY_NEW,
             (False, False): MISSED_BY_BOTH}
    for g in np.flatnonzero(np.asarray(in_view_mask, dtype=bool)):
        change = names[(bool(old.score.recovered[g]), bool(new.score.recovered[g]))]
        out.append(Change(change, float(geotag_xy[g, 0]), float(geotag_xy[g, 1]), geotag=int(g)))
    false_old = np.flatnonzero(~np.asarray(old.score.cluster_hit, dtype=bool))
    false_new = np.flatnonzero(~np.asarray(new.score.cluster_hit, dtype=bool))
    old_to_new = _same_spot(old.clustering, false_old, new.clustering, false_new, eps_pred_m)
    new_to_old = _same_spot(new.clustering, false_new, old.clustering, false_old, eps_pred_m)
    centroid_old, centroid_new = old.clustering.summary.centroid, new.clustering.summary.centroid
    for k, near in zip(false_old.tolist(), old_to_new):
        x, y = centroid_old[k]
        out.append(Change(FALSE_KEPT if near else FALSE_REMOVED, float(x), float(y), cluster_old=k,
                          cluster_new=near[0] if near else None))
    for k, near in zip(false_new.tolist(), new_to_old):
        if not near:
            x, y = centroid_new[k]
            out.append(Change(FALSE_ADDED, float(x), float(y), cluster_new=k))
    return out


def _figures(evaluation: Evaluation) -> dict:
    """The figures compared side by side, of a one-flight evaluation."""
    flight, pooled = evaluation.flights[0], evaluation.pooled
    figures = {"recall_pre": pooled.recall_pre, "gmcf_pre": pooled.gmcf_pre, "f1_geo": pooled.f1_geo,
               "n_in_view": pooled.n_in_view, "n_recovered": pooled.n_recovered, "n_clusters": pooled.n_clusters,
               "n_hit_clusters": pooled.n_hit_clusters, "n_false_clusters": pooled.n_clusters - pooled.n_hit_clusters,
               "n_detections": flight.n_detections, "n_frames": flight.in_view.n_frames,
               "detections_per_frame": ratio(flight.n_detections, flight.in_view.n_frames)}
    for convention, post in (evaluation.post or {}).items():
        figures[f"gmcf_post_{convention}"] = post.pooled.gmcf_post
        figures[f"recall_post_{convention}"] = post.pooled.recall_post
    return figures


@dataclass
class Comparison:
    """Both evaluations (as Evaluate detections makes them) and the changes, in the flight's local frame."""

    before: Evaluation
    after: Evaluation
    changes: list
    detections: tuple

    def counts(self) -> dict:
        return {name: sum(1 for c in self.changes if c.change == name) for name in CHANGES}

    def side_by_side(self) -> list[dict]:
        """One row per figure: before, after and after − before (None where either is undefined)."""
        before, after = _figures(self.before), _figures(self.after)
        return [{"figure": name, "before": before[name], "after": after.get(name),
                 "difference": None if before[name] is None or after.get(name) is None
                 else after[name] - before[name]} for name in before]

    def to_dict(self) -> dict:
        def about(evaluation, det: Detections):
            return {"name": det.name, "model": det.model, "model_digest": det.model_digest,
                    "threshold": det.threshold,
                    **{k: v for k, v in evaluation.to_dict().items() if k != "parameters"}}

        old, new = self.detections
        return {"parameters": self.before.op.to_dict(), "before": about(self.before, old),
                "after": about(self.after, new),
                "side_by_side": self.side_by_side(), "changes": self.counts(),
                "definitions": {"false cluster": "a cluster no in-view geotag matches (within eps_pred_m of its "
                                                 "core points), as GMCF counts it",
                                "same spot": "a core point of one cluster within eps_pred_m of a core point of "
                                             "the other"}}


def _seen_by_frames(mosaic: Detections, pose_groups, local, op: OperatingPoint, ground) -> Detections:
    """The mosaic's detections on ground the frames see: beyond it the frames could find nothing, and a
    cluster there would count against the mosaic as a false one (no geotag in view matches it)."""
    xy = mosaic.ground_positions(local).xy  # a mosaic has no heights: its points at the frames' ground level
    points = np.column_stack([xy, np.zeros(len(xy))])
    seen = in_view(pose_groups, local, points, op.edge_buffer_px, ground).mask
    return replace(mosaic, lat=mosaic.lat[seen], lon=mosaic.lon[seen], height=mosaic.height[seen],
                   frame_id=mosaic.frame_id[seen], score=mosaic.score[seen])


def compare_detectors(old: Detections, new: Detections, pose_groups: Sequence[FramePoses], geotags: Geotags,
                      op: OperatingPoint = OperatingPoint(), log: VerdictLog | None = None, ground=None,
                      progress=None, is_canceled=None, inside_raster=None) -> Comparison:
    """Score two detection layers of one flight as Evaluate detections does and classify what changed.

    Both must have been placed on one ground (a change of ground is not a change of detector), whose
    factory ``ground`` (``old.ground.factory(dem)``; None = the level plane) the in-view test stands on —
    except frames against mosaic: one layer found on a raster (an orthomosaic of the flight, ground RASTER)
    and one on the frames' ground (``ground``'s). Both are then scored over the same geotags, those in view of
    the frames *and* on the raster's valid pixels (``inside_raster`` (G,)); the mosaic's detections cluster
    with a core test of one (:attr:`.evaluation.Flight.seen_once`)."""
    local = local_frame_for(pose_groups, geotags)
    on_raster = [d.ground.model == RASTER for d in (old, new)]
    if not any(on_raster):
        common_ground([old.ground, new.ground], [old.name, new.name])
        flights = [Flight(d, pose_groups, d.name, ground) for d in (old, new)]
    else:
        if inside_raster is None:
            raise InputError("a layer of detections found on a raster is scored over the geotags the raster "
                             "covers: give that raster", source=(old, new)[on_raster.index(True)].name)
        # The frames' layer's ground is the in-view test's; two raster layers must come from one raster.
        one_ground = [d for d, r in zip((old, new), on_raster) if not r] or [old, new]
        common_ground([d.ground for d in one_ground], [d.name for d in one_ground])
        frames_view = in_view(pose_groups, local, geotags.in_local(local), op.edge_buffer_px, ground).mask
        flights = [mosaic_flight(_seen_by_frames(d, pose_groups, local, op, ground), pose_groups, inside_raster,
                                 frames_view) if r
                   else Flight(d, pose_groups, d.name, ground, np.asarray(inside_raster, dtype=bool))
                   for d, r in zip((old, new), on_raster)]

    def half(fraction_start):
        if progress is None:
            return None
        return lambda f: progress(fraction_start + 0.5 * f)

    before = evaluate_flights([flights[0]], geotags, op, log, local, half(0.0), is_canceled)
    after = evaluate_flights([flights[1]], geotags, op, log, local, half(0.5), is_canceled)
    geotag_xy = geotags.in_local(local)[:, :2]
    changes = classify_changes(before.flights[0], after.flights[0], before.flights[0].in_view.mask, geotag_xy,
                               op.eps_pred_m)
    return Comparison(before, after, changes, (old, new))
