"""Training validation that predicts a flight: held-out frames that share no targets with training, scored on the
ground as the product scores a flight.

**The split** (:func:`plan_split`, chosen by ``TrainJob.validation``):

* ``blocks`` (default) — every target of every Write-labels folder (``targets.csv``) falls into a square ground
  block of side :data:`BLOCK_FOOTPRINTS` × the frames' footprint diagonal (median, from the frame records; without
  them the 90th percentile of the largest distance between two targets one frame sees). Blocks are taken in a
  seeded random order, each held out while its targets still fit under the held-out share of all targets (the
  smallest block alone when none fits; never every block). A frame that sees (``labels.csv``) only held-out
  targets goes to validation, one that sees only training targets to training, one that sees both is dropped
  from both tile sets and counted, but scored on the ground (:meth:`SplitPlan.ground_frames`: every view of a
  held-out target counts there, as in a flight); a frame that sees none follows the block of its footprint centre
  (without frame records: the side of the nearest frame, in frame order, that sees a target). A held-out block
  is held out in every folder, so two flights over one site never put a target on both sides. A folder written
  on a raster (:mod:`..labels.raster_labels`) has one frame per tile, whose footprint is the tile's ground
  diagonal; its tiles without a target follow their neighbour in tile order (the row they lie in).
* ``flights`` — whole folders (one flight, or one frame layer, each) held out, taken the same way by their
  targets; needs two folders or more. Held-out targets a training folder holds too (within
  :data:`SAME_TARGET_M`; by id without positions) are counted, with a warning.
* ``none`` — nothing held out.

A folder without ``targets.csv`` (written before it existed) cannot be split by blocks: the frames are then held
out at random (:func:`.recipe.split_tiles`) and the result says those figures are not independent.

**Ground figures** (:func:`ground_figures`): the exported model runs with the plugin's detector over the held-out
frames' full images (:func:`detect_frames_at_thresholds`, one heatmap per frame, peaks at each threshold),
detections are back-projected, clustered and scored by :func:`..scoring.evaluation.evaluate_flights` at each
threshold, against the held-out *geotags* as the product scores a flight against its survey: ``recall`` counts
the held-out geotags in view of the scored frames recovered by a cluster; ``gmcf`` the clusters on a held-out
geotag among the clusters that are not on a training target (a training target seen at a frame's edge is neither
a false cluster nor a validated one: the model learnt it). A cluster on a held-out target a review confirmed
(``provenance`` review) is no geotag match, as on a flight whose survey missed that target — scored against them
too, the figures flattered what the test flights then showed — and is counted apart
(``clusters_on_review_targets``). The default threshold is
chosen from them (:func:`.recipe.best_threshold`). Fewer than :data:`FEW_HELD_OUT_TARGETS` held-out targets
in view make a warning: one target then moves recall by more than a tenth.

No torch here: numpy and the plugin's core; the detector needs onnxruntime.
"""
from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError, check_cancel
from ..field.geotags import SURVEY, Geotags
from ..geometry.geodesy import LocalFrame
from ..labels.raster_labels import raster_record
from ..labels.training_set import read_targets
from .choices import SPLITS
from .recipe import THRESHOLDS

# The validation splits a run offers are :data:`.choices.SPLITS` (``TrainJob.validation``); "frames" is the
# fallback for folders without targets.csv, never chosen.

#: Side of a spatial block, in frame footprint diagonals: the smallest block a frame's footprint fits in whole.
#: Smaller blocks drop more frames (those that see two blocks), larger ones leave a small field a single block.
BLOCK_FOOTPRINTS = 1.0
#: Thresholds the ground figures are given at (the detector's peaks, one heatmap per frame): the tile figures'.
GROUND_THRESHOLDS = THRESHOLDS
TRAIN, VAL, DROPPED = "train", "val", "dropped"
#: Below this many held-out targets in view, the ground figures and the threshold chosen from them get a warning.
FEW_HELD_OUT_TARGETS = 10


# ====================================================================================== what a folder holds
@dataclass
class FolderView:
    """What the split needs of one Write-labels folder.

    ``frames``: frame ids (text) with tiles or labels; ``frame_targets``: frame id → ids (text) of the targets
    it sees (labels.csv); ``target_xy``: target id → (x, y) in the run's local frame (None: no targets.csv);
    ``centre_xy``: frame id → footprint centre (x, y) (frames with a pose and ground height); ``footprint_m``:
    the median footprint diagonal (m), None without frame records.
    """

    name: str
    frames: list
    frame_targets: dict
    target_xy: dict | None
    centre_xy: dict = field(default_factory=dict)
    footprint_m: float | None = None


def read_frame_targets(folder) -> dict:
    """frame id → set of the target ids it sees, from ``labels.csv`` (empty without the file)."""
    path = Path(folder) / "labels.csv"
    out: dict = {}
    if path.is_file():
        with open(path, newline="", encoding="utf-8") as f:
            for row in csv.DictReader(f):
                out.setdefault(str(row["frame_id"]), set()).add(str(row["geotag_id"]))
    return out


def footprints(records, local: LocalFrame) -> tuple[dict, float | None]:
    """(frame id → footprint centre (x, y) in ``local``, median footprint diagonal in m) of frame records, on the
    level plane of each frame's ground height (frames without one have no centre)."""
    from ..field.frame_records import poses_from_records
    from ..geometry.ground import LevelPlaneGround
    from ..geometry.poses import FrameGeometry
    from ..geometry.projection import pixel_to_ground

    centres, diagonals = {}, []
    for poses, _ in poses_from_records(records, "frame records"):
        has_ground = np.flatnonzero(np.isfinite(poses.ground_height))
        if not len(has_ground):
            continue
        poses = poses.subset(has_ground)
        geom = FrameGeometry(poses, local)
        ground = LevelPlaneGround(geom)
        cam = poses.camera
        idx = np.arange(len(poses))
        points = {}
        for name, uv in (("centre", ((cam.width - 1) / 2, (cam.height - 1) / 2)), ("first", (0.0, 0.0)),
                         ("last", (cam.width - 1.0, cam.height - 1.0))):
            hit, valid = pixel_to_ground(geom, ground, idx, np.tile([uv], (len(idx), 1)))
            points[name] = np.where(valid[:, None], hit, np.nan)
        for k, fid in enumerate(poses.frame_id):
            if np.all(np.isfinite(points["centre"][k])):
                centres[str(fid)] = tuple(points["centre"][k, :2].tolist())
        diag = np.linalg.norm(points["last"][:, :2] - points["first"][:, :2], axis=1)
        diagonals.extend(diag[np.isfinite(diag)].tolist())
    return centres, (float(np.median(diagonals)) if diagonals else None)


def folder_views(folders, records_of, frames_with_tiles) -> tuple[list[FolderView], LocalFrame | None, list]:
    """The :class:`FolderView` of each folder, their common local frame (None without targets and records) and
    each folder's targets (:func:`..labels.training_set.read_targets`, None where absent).

    ``records_of[k]``: frame records of folder k (None: none given); ``frames_with_tiles[k]``: its frame ids
    (text) that have tiles."""
    targets = [read_targets(f) for f in folders]
    frame_targets = [read_frame_targets(f) for f in folders]
    lat = np.concatenate([t.lat for t in targets if t is not None and len(t)] + [np.zeros(0)])
    lon = np.concatenate([t.lon for t in targets if t is not None and len(t)] + [np.zeros(0)])
    if not len(lat):
        recs = [r for rs in records_of if rs for r in rs]
        lat = np.array([r["lat"] for r in recs], float)
        lon = np.array([r["lon"] for r in recs], float)
    local = LocalFrame.around(lat, lon) if len(lat) else None
    views = []
    for k, folder in enumerate(folders):
        mine = set(frames_with_tiles[k]) | set(frame_targets[k])
        xy = None
        if targets[k] is not None and local is not None:
            pts = local.from_geodetic(targets[k].lat, targets[k].lon, np.zeros(len(targets[k])))
            xy = {str(i): (float(p[0]), float(p[1])) for i, p in zip(targets[k].ids, pts)}
        centres, diagonal = {}, None
        records = [r for r in (records_of[k] or []) if str(r.get("frame_id")) in mine]
        raster = raster_record(folder)
        if raster is not None:  # each tile is a frame (labels.raster_labels): its footprint is the tile's ground
            diagonal = float(raster["tile_diagonal_m"])
        elif records and local is not None:
            centres, diagonal = footprints(records, local)
        views.append(FolderView(Path(folder).name, sorted(mine, key=_frame_order), frame_targets[k], xy, centres,
                                diagonal))
    return views, local, targets


def _frame_order(fid: str):
    try:
        return (0, float(fid), fid)
    except ValueError:
        return (1, 0.0, fid)


# ====================================================================================== the split
@dataclass
class SplitPlan:
    """Where every frame goes: ``side[(folder index, frame id)]`` is :data:`TRAIN`, :data:`VAL` or
    :data:`DROPPED`; ``info`` the JSON-able record of the split (method, counts each side, frames dropped, why
    nothing was held out); ``warnings`` sentences for the log and the model card."""

    method: str
    side: dict
    info: dict
    warnings: list = field(default_factory=list)
    #: folder index → ids (text) of its held-out targets
    held_targets: dict = field(default_factory=dict)

    @property
    def held_out(self) -> bool:
        return any(s == VAL for s in self.side.values())

    def frames(self, k: int, which: str = VAL) -> list:
        return [fid for (j, fid), s in self.side.items() if j == k and s == which]

    def ground_frames(self, k: int) -> list:
        """The frames of folder ``k`` scored on the ground: the held-out ones and those dropped for seeing
        held-out and training targets both (no tile of theirs is trained or validated on)."""
        return [fid for (j, fid), s in self.side.items() if j == k and s in (VAL, DROPPED)]


def plan_split(views: list[FolderView], method: str = "blocks", fraction: float = 0.15, seed: int = 0) -> SplitPlan:
    """Assign every frame of ``views`` to training, validation or dropped (module docstring); no tiles read."""
    if method not in SPLITS:
        raise InputError(f"unknown validation split '{method}'; one of {', '.join(SPLITS)}", field="VALIDATION")
    everything = {(k, fid): TRAIN for k, v in enumerate(views) for fid in v.frames}
    if method == "none" or fraction <= 0:
        return nothing_held(everything, "none", "no validation was asked for")
    if method == "flights":
        return _split_flights(views, everything, fraction, seed)
    if any(v.target_xy is None for v in views):
        missing = ", ".join(v.name for v in views if v.target_xy is None)
        return SplitPlan("frames", {}, {"method": "frames", "reason": f"no targets.csv in {missing}"},
                         [f"{missing}: no targets.csv (written by an older Write training labels), so targets cannot "
                          "be grouped on the ground; frames were held out at random instead, and neighbouring "
                          "frames show the same targets: the validation figures are optimistic. Write the labels "
                          "again for a validation that predicts a flight."])
    return _split_blocks(views, everything, fraction, seed)


def nothing_held(side: dict, method: str, reason: str) -> SplitPlan:
    """The plan that holds nothing out (every frame of ``side`` in training), with the warning saying why."""
    return SplitPlan(method, side, {"method": method, "held_out": False, "reason": reason},
                     [f"Nothing was held out for validation ({reason}): the default threshold was not validated."])


def block_side_m(views: list[FolderView]) -> float | None:
    """The block side (m): :data:`BLOCK_FOOTPRINTS` footprint diagonals; the footprint from the frame records,
    else the 90th percentile of the largest distance between two targets one frame sees, else the median
    nearest-neighbour spacing of the targets. None with fewer than two targets."""
    diagonals = [v.footprint_m for v in views if v.footprint_m]
    if diagonals:
        return BLOCK_FOOTPRINTS * float(np.median(diagonals))
    spans = []
    for v in views:
        for ids in v.frame_targets.values():
            pts = np.array([v.target_xy[i] for i in ids if i in v.target_xy])
            if len(pts) >= 2:
                spans.append(float(np.max(np.linalg.norm(pts[:, None] - pts[None], axis=2))))
    if spans:
        return BLOCK_FOOTPRINTS * float(np.percentile(spans, 90))
    pts = np.array([p for v in views for p in v.target_xy.values()])
    if len(pts) < 2:
        return None
    d = np.linalg.norm(pts[:, None] - pts[None], axis=2)
    d[d == 0] = np.inf
    nearest = d.min(axis=1)
    return BLOCK_FOOTPRINTS * float(np.median(nearest[np.isfinite(nearest)])) if np.isfinite(nearest).any() else None


def _split_blocks(views, side, fraction, seed) -> SplitPlan:
    side_m = block_side_m(views)
    all_xy = np.array([p for v in views for p in v.target_xy.values()]).reshape(-1, 2)
    if side_m is None or not side_m > 0:
        return nothing_held(side, "blocks", "fewer than two targets to group into blocks")
    origin = all_xy.min(axis=0)

    def block(xy):
        return tuple(np.floor((np.asarray(xy) - origin) / side_m).astype(int).tolist())

    target_block = [{i: block(p) for i, p in v.target_xy.items()} for v in views]
    weight: dict = {}
    for blocks in target_block:
        for b in blocks.values():
            weight[b] = weight.get(b, 0) + 1
    order = sorted(weight)
    if len(order) < 2:
        return nothing_held(side, "blocks", f"all targets lie in one block of {side_m:.2f} m")
    held = _draw(order, weight, fraction, seed)
    for k, v in enumerate(views):
        for fid in v.frames:
            seen = [target_block[k][i] for i in v.frame_targets.get(fid, ()) if i in target_block[k]]
            if seen:
                in_held = [b in held for b in seen]
                side[(k, fid)] = VAL if all(in_held) else TRAIN if not any(in_held) else DROPPED
            elif fid in v.centre_xy:
                side[(k, fid)] = VAL if block(v.centre_xy[fid]) in held else TRAIN
            else:
                side[(k, fid)] = None
        _follow_neighbours(side, k, v.frames)
    held_targets = sum(weight[b] for b in held)
    info = {"method": "blocks", "block_m": round(side_m, 3), "blocks": len(order), "held_out_blocks": len(held),
            "targets": {"train": sum(weight.values()) - held_targets, "val": held_targets}}
    plan = _finish(views, side, "blocks", info)
    if plan.held_out:
        plan.held_targets = {k: {i for i, b in blocks.items() if b in held} for k, blocks in enumerate(target_block)}
    return plan


def _draw(units, weight, fraction, seed) -> set:
    """The held-out units: in a seeded random order, each unit whose targets still fit under ``fraction`` of all
    (the smallest unit alone when none fits); never every unit."""
    rng = np.random.default_rng(seed)
    total = sum(weight[u] for u in units)
    held, n = set(), 0
    for i in rng.permutation(len(units)):
        if n + weight[units[i]] <= fraction * total and len(held) < len(units) - 1:
            held.add(units[i])
            n += weight[units[i]]
    if not held:
        held.add(min(units, key=lambda u: (weight[u], units.index(u))))
    return held


def _follow_neighbours(side, k, frames) -> None:
    """Frames without a side (no target seen, no footprint) take the side of the nearest frame in frame order
    that sees a target (training when none does)."""
    known = [j for j, fid in enumerate(frames) if side[(k, fid)] in (TRAIN, VAL)]
    for j, fid in enumerate(frames):
        if side[(k, fid)] is None:
            near = min(known, key=lambda i: (abs(i - j), i), default=None)
            side[(k, fid)] = TRAIN if near is None else side[(k, frames[near])]


def _split_flights(views, side, fraction, seed) -> SplitPlan:
    weight = {k: len({i for ids in v.frame_targets.values() for i in ids}) for k, v in enumerate(views)}
    units = [k for k in weight if weight[k] > 0]
    if len(units) < 2:
        return nothing_held(side, "flights", f"{len(views)} labels folder(s), {len(units)} with targets: holding "
                                              "out whole flights needs two or more")
    held = _draw(units, weight, fraction, seed)
    for (k, fid) in side:
        side[(k, fid)] = VAL if k in held else TRAIN
    ids = [{i for ids in v.frame_targets.values() for i in ids} for v in views]
    info = {"method": "flights", "held_out_folders": [views[k].name for k in sorted(held)],
            "targets": {"train": sum(weight[k] for k in weight if k not in held),
                        "val": sum(weight[k] for k in held)},
            "targets_on_both_sides": _shared_targets(views, ids, held)}
    plan = _finish(views, side, "flights", info)
    if plan.held_out:
        plan.held_targets = {k: set(v.target_xy or ()) | ids[k] for k, v in enumerate(views) if k in held}
    if plan.held_out and info["targets_on_both_sides"]:
        plan.warnings.append(f"{info['targets_on_both_sides']} held-out target(s) are also in a training folder (the "
                             "same site flown twice?): the held-out flight is not independent of training for them; "
                             "hold out spatial blocks instead.")
    return plan


#: Targets of two folders closer than this (m; the scoring's match radius) are one target seen twice.
SAME_TARGET_M = 0.20


def _shared_targets(views, ids, held) -> int:
    """Held-out targets that a training folder holds too: within :data:`SAME_TARGET_M` of one of its targets when
    every folder has positions (ids of independent surveys may repeat), else by id."""
    train = [k for k in range(len(views)) if k not in held]
    if all(v.target_xy is not None for v in views):
        train_xy = np.array([views[k].target_xy[i] for k in train for i in ids[k] if i in views[k].target_xy])
        val_xy = np.array([views[k].target_xy[i] for k in held for i in ids[k] if i in views[k].target_xy])
        if not len(train_xy) or not len(val_xy):
            return 0
        from scipy.spatial import cKDTree

        d, _ = cKDTree(train_xy.reshape(-1, 2)).query(val_xy.reshape(-1, 2), distance_upper_bound=SAME_TARGET_M)
        return int(np.sum(d <= SAME_TARGET_M))
    return len(set().union(*(ids[k] for k in train)) & set().union(*(ids[k] for k in held)))


def _finish(views, side, method, info) -> SplitPlan:
    counts = {s: sum(1 for v in side.values() if v == s) for s in (TRAIN, VAL, DROPPED)}
    info.update({"held_out": counts[VAL] > 0, "frames": {"train": counts[TRAIN], "val": counts[VAL]},
                 "frames_dropped": counts[DROPPED]})
    if not counts[VAL] or not counts[TRAIN]:
        empty = "validation" if not counts[VAL] else "training"
        return nothing_held({key: TRAIN for key in side}, method,
                             f"the {method} split left no frame for {empty}")
    return SplitPlan(method, side, info)


# ====================================================================================== ground figures
@dataclass
class GroundFlight:
    """The held-out frames of one folder and what to score them against: frame ``records`` (frame-layer
    records, :func:`..field.frame_records.poses_from_records`), the folder's ``targets`` and ``held`` (True for
    the held-out ones: recall counts those)."""

    name: str
    records: list
    targets: Geotags
    held: np.ndarray


def detections_of(found) -> "Detections":  # noqa: F821 — imported lazily
    """One :class:`..scoring.evaluation.Detections` of the :class:`..detect.detector.FrameDetections` of a run."""
    from ..scoring.evaluation import Detections

    if not found:
        return Detections(np.zeros(0), np.zeros(0), np.zeros(0), np.zeros(0, dtype=np.int64), np.zeros(0))
    return Detections(*(np.concatenate([getattr(f, key) for f in found]) for key in ("lat", "lon", "height")),
                      np.concatenate([np.full(len(f), f.frame_id) for f in found]),
                      np.concatenate([f.score for f in found]))


def detect_at_thresholds(model, poses, images, thresholds, local, is_canceled=None) -> tuple[list, list]:
    """(per frame processed: one FrameDetections per threshold, the frame indices processed) of the detector's
    run over ``poses``/``images`` (:func:`..detect.detector.detect_frames_at_thresholds`); frames it skipped
    (unreadable image, no ground height) are left out."""
    from ..detect.detector import detect_frames_at_thresholds

    runs, processed = [], []
    for per_threshold in detect_frames_at_thresholds(model, poses, images, thresholds, local=local,
                                                     is_canceled=is_canceled):
        if per_threshold[0].skipped is None:
            runs.append(per_threshold)
            processed.append(per_threshold[0].frame_index)
    return runs, processed


def ground_figures(model_path, flights: list[GroundFlight], thresholds=GROUND_THRESHOLDS, op=None,
                   is_canceled=None, progress=None) -> dict:
    """Recall of the held-out targets and GMCF per threshold, pooled over ``flights`` (sums of counts, one
    division), the model run as Detect runs it (module docstring).

    Returns ``{"frames", "frames_skipped", "targets" (held-out geotags in view), "by_threshold": {t: {"recall",
    "gmcf", "f1", "clusters" (those GMCF counts), "clusters_on_review_targets", "clusters_on_training_targets",
    "detections", ...}},
    "operating_point"}``; ``f1`` is the harmonic mean of recall and GMCF (:func:`..scoring.pre_review.f1_geo`)."""
    from dataclasses import replace

    from ..detect.detector import HeatmapModel
    from ..field.frame_records import poses_from_records
    from ..scoring.evaluation import Flight, evaluate_flights, local_frame_for
    from ..scoring.operating_point import OperatingPoint
    from ..scoring.pre_review import f1_geo

    op = op or OperatingPoint()
    model = HeatmapModel(model_path)
    thresholds = [float(t) for t in thresholds]
    tot = {t: dict(in_view=0, recovered=0, clusters=0, hit_clusters=0, review_clusters=0, training_clusters=0,
                   detections=0) for t in thresholds}
    n_frames = n_skipped = 0
    for n, flight in enumerate(flights):
        groups = poses_from_records(flight.records, flight.name)
        local = local_frame_for([p for p, _ in groups], flight.targets)
        held_geotags = flight.held & (np.asarray(flight.targets.provenance) == SURVEY)
        found, processed_groups = {t: [] for t in thresholds}, []
        for poses, index in groups:
            images = [flight.records[i]["image"] for i in index]
            runs, processed = detect_at_thresholds(model, poses, images, thresholds, local, is_canceled)
            n_frames += len(processed)
            n_skipped += len(poses) - len(processed)
            if processed:
                processed_groups.append(poses.subset(np.asarray(processed)))
            for per_threshold in runs:
                for t, frame in zip(thresholds, per_threshold):
                    found[t].append(frame)
        if not processed_groups:
            continue
        for t in thresholds:
            check_cancel(is_canceled)
            ev = evaluate_flights([Flight(detections_of(found[t]), processed_groups, flight.name)], flight.targets,
                                  replace(op, threshold=t), local=local).flights[0]
            counted = ev.in_view.mask & held_geotags
            tot[t]["in_view"] += int(counted.sum())
            tot[t]["recovered"] += int((ev.score.recovered & counted).sum())
            on_held = np.array([bool(flight.held[g].any()) for g in ev.score.cluster_geotags], dtype=bool)
            on_geotag = np.array([bool(held_geotags[g].any()) for g in ev.score.cluster_geotags], dtype=bool)
            on_training_only = ev.score.cluster_hit & ~on_held
            tot[t]["clusters"] += int(ev.score.counts.n_clusters - on_training_only.sum())
            tot[t]["hit_clusters"] += int(on_geotag.sum())
            tot[t]["review_clusters"] += int((on_held & ~on_geotag).sum())
            tot[t]["training_clusters"] += int(on_training_only.sum())
            tot[t]["detections"] += int(ev.n_detections)
        if progress is not None:
            progress((n + 1) / len(flights))
    by = {}
    for t, c in tot.items():
        recall = c["recovered"] / c["in_view"] if c["in_view"] else None
        gmcf = c["hit_clusters"] / c["clusters"] if c["clusters"] else None
        f1 = float(f1_geo(recall, gmcf)) if recall is not None and gmcf is not None else 0.0
        by[f"{t:g}"] = {"recall": _round(recall), "gmcf": _round(gmcf), "f1": round(f1 if np.isfinite(f1) else 0.0, 4),
                        "targets_recovered": c["recovered"], "clusters": c["clusters"],
                        "clusters_on_target": c["hit_clusters"], "clusters_on_review_targets": c["review_clusters"],
                        "clusters_on_training_targets": c["training_clusters"], "detections": c["detections"]}
    return {"frames": n_frames, "frames_skipped": n_skipped, "targets": tot[thresholds[0]]["in_view"],
            "by_threshold": by, "operating_point": {k: v for k, v in op.to_dict().items() if k != "threshold"}}


def _round(x):
    return None if x is None else round(float(x), 4)


def require_positive_tiles(positive, folders) -> None:
    """Refuse a training set without a tile that holds a target: nothing to learn a target from."""
    if not np.any(positive):
        raise InputError("no training tile holds a target (a label value of 255 at a target's centre) in "
                         + ", ".join(str(f) for f in folders) + ": a detector needs positive tiles. Write the "
                         "labels from geotags the frames see (Write training labels reports the targets in view "
                         "and the tiles written) and train again", field="LABELS")
