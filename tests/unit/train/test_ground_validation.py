"""Validation that predicts a flight (core.train.ground_validation): the spatial-block and whole-flight splits
against a derivation by hand, the refusal of a labels set without a positive tile, the warning when nothing is
held out, and the threshold chosen from the ground figures."""
from __future__ import annotations

import csv
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.train import ground_validation as gv
from birdseye.birdseye_qgis.core.train import recipe
from birdseye.birdseye_qgis.core.train.job import (
    GROUND_RULE,
    TILE_RULE,
    Source,
    TrainJob,
    choose_threshold,
    not_validated_warning,
    run_job,
    threshold_warning,
)

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fake_labels import make_label_folder  # noqa: E402


def line_of_frames(n_targets=10, footprint_m=2.0):
    """Targets every metre along x (ids "0".."9"); frame i (ids "0".."8") sees targets i and i + 1; frames "20" and
    "21" see none, their footprint centres at x = 0.5 and x = 8.5; frame "22" sees none and has no footprint."""
    targets = {str(i): (float(i), 0.0) for i in range(n_targets)}
    seen = {str(i): {str(i), str(i + 1)} for i in range(n_targets - 1)}
    frames = list(seen) + ["20", "21", "22"]
    return gv.FolderView("line", frames, seen, targets, {"20": (0.5, 0.0), "21": (8.5, 0.0)}, footprint_m)


def sides_by_hand(view, held_targets, block_of_point):
    """Each frame's side from the held-out targets alone: the split's rule, derived again."""
    out = {}
    for fid in view.frames:
        seen = view.frame_targets.get(fid, set())
        if seen:
            held = [t in held_targets for t in seen]
            out[fid] = "val" if all(held) else "train" if not any(held) else "dropped"
        elif fid in view.centre_xy:
            held_blocks = {block_of_point(view.target_xy[t]) for t in held_targets}
            out[fid] = "val" if block_of_point(view.centre_xy[fid]) in held_blocks else "train"
    return out


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_blocks_put_no_target_on_both_sides_and_count_the_frames_dropped(seed):
    view = line_of_frames()
    plan = gv.plan_split([view], "blocks", 0.3, seed)
    side_m = plan.info["block_m"]
    assert side_m == 2.0 * gv.BLOCK_FOOTPRINTS  # footprint diagonals of 2 m
    held = plan.held_targets[0]

    def block(p):
        return math.floor(p[0] / side_m)

    # Held-out targets are whole blocks, at most 30 % of the targets.
    held_blocks = {block(view.target_xy[t]) for t in held}
    assert held == {t for t, p in view.target_xy.items() if block(p) in held_blocks}
    assert 0 < len(held) <= 3 and plan.info["targets"] == {"train": 10 - len(held), "val": len(held)}
    expected = sides_by_hand(view, held, block)
    got = {fid: plan.side[(0, fid)] for fid in view.frames}
    assert {f: got[f] for f in expected} == expected
    # No target is seen from both sides.
    train_seen = set().union(*(view.frame_targets.get(f, set()) for f in view.frames if got[f] == "train"))
    val_seen = set().union(*(view.frame_targets.get(f, set()) for f in view.frames if got[f] == "val"))
    assert val_seen and train_seen and not train_seen & val_seen and val_seen <= held
    # Frames i see i and i + 1: one straddles each boundary between a held-out and a training block.
    boundaries = sum((block((i, 0)) in held_blocks) != (block((i + 1, 0)) in held_blocks) for i in range(9))
    assert plan.info["frames_dropped"] == boundaries == sum(s == "dropped" for s in got.values())
    # Frame 22 (no target, no footprint) takes the side of its neighbour in frame order, frame 21.
    assert got["22"] == got["21"]
    assert plan.info["frames"]["val"] == sum(s == "val" for s in got.values())
    # Scored on the ground: every frame that sees a held-out target, those that see training targets too.
    assert set(plan.ground_frames(0)) == {f for f, s in got.items() if s in ("val", "dropped")}
    assert {t for f in plan.ground_frames(0) for t in view.frame_targets.get(f, ())} >= held


def test_a_block_is_held_out_in_every_folder():
    a, b = line_of_frames(), line_of_frames()
    b.name = "second flight"
    plan = gv.plan_split([a, b], "blocks", 0.3, 0)
    assert plan.held_targets[0] == plan.held_targets[1]
    assert [plan.side[(0, f)] for f in a.frames] == [plan.side[(1, f)] for f in b.frames]


def test_whole_flights_hold_out_folders_and_count_shared_targets():
    a, b, c = line_of_frames(), line_of_frames(), line_of_frames()
    plan = gv.plan_split([a, b, c], "flights", 0.3, 0)
    held = {k for (k, _), side in plan.side.items() if side == "val"}
    assert len(held) == 1 and all(plan.side[(k, f)] == ("val" if k in held else "train")
                                  for k, v in enumerate((a, b, c)) for f in v.frames)
    assert plan.info["frames_dropped"] == 0 and plan.info["targets_on_both_sides"] == 10
    assert any("not independent" in w for w in plan.warnings)
    # Independent surveys may number their targets alike: the same ids 10 m away are other targets (b and c are
    # one site, a another).
    for v in (b, c):
        v.target_xy = {i: (x + 10.0, y) for i, (x, y) in v.target_xy.items()}
    plan = gv.plan_split([a, b, c], "flights", 0.3, 0)
    held = next(iter(plan.held_targets))
    assert plan.info["targets_on_both_sides"] == (10 if held in (1, 2) else 0) and plan.info["held_out"]


@pytest.mark.parametrize("method, view, reason", [
    ("none", line_of_frames(), "no validation was asked for"),
    ("blocks", gv.FolderView("one block", ["1"], {"1": {"a", "b"}}, {"a": (0.0, 0.0), "b": (0.1, 0.0)}, {}, 1.0),
     "one block"),
    ("flights", line_of_frames(), "two or more"),
])
def test_nothing_held_out_says_so(method, view, reason):
    plan = gv.plan_split([view], method, 0.2, 0)
    assert not plan.held_out and reason in plan.info["reason"]
    assert all(side == "train" for side in plan.side.values())
    assert "the default threshold was not validated" in plan.warnings[0]


def test_folders_without_targets_csv_fall_back_to_a_frame_split_with_a_warning():
    view = line_of_frames()
    view.target_xy = None
    plan = gv.plan_split([view], "blocks", 0.2, 0)
    assert plan.method == "frames" and "targets.csv" in plan.warnings[0] and "optimistic" in plan.warnings[0]


def test_the_default_threshold_comes_from_the_ground_figures():
    """Ground F1 (of recall and GMCF) 0.70 at 0.3, 0.74 at 0.4, 0.70 at 0.5, 0.60 at 0.6 over 20 held-out targets:
    within 1/20 of the best are 0.3, 0.4 and 0.5; the highest, 0.5, is the default. The tiles would say 0.2."""
    ground = {"targets": 20, "by_threshold": {"0.3": {"f1": 0.70}, "0.4": {"f1": 0.74}, "0.5": {"f1": 0.70},
                                              "0.6": {"f1": 0.60}}}
    tiles = {"targets": 20, "by_threshold": {"0.2": {"f1": 0.9}, "0.5": {"f1": 0.5}}}
    plan = gv.plan_split([line_of_frames()], "blocks", 0.3, 0)
    job = TrainJob(sources=[], out="m.onnx")
    threshold, rule, on = choose_threshold(job, plan, tiles, ground)
    assert (threshold, on) == (0.5, "ground") and rule.startswith(GROUND_RULE.split("(")[0])
    assert "spatial blocks" in rule
    assert choose_threshold(job, plan, tiles, None) == (0.2, TILE_RULE, "tiles")
    assert choose_threshold(job, plan, tiles, {"targets": 0, "by_threshold": {}})[2] == "tiles"
    # A model that recovers no held-out target at any threshold cannot choose one on the ground.
    nothing = {"targets": 20, "by_threshold": {"0.3": {"f1": 0.0}, "0.9": {"f1": 0.0}}}
    assert choose_threshold(job, plan, tiles, nothing)[2] == "tiles"
    assert choose_threshold(job, plan, None, nothing) == (0.5, choose_threshold(job, plan, None, None)[1], None)
    assert "recovered no held-out target" in not_validated_warning(plan, None, nothing, ["a flight"])
    assert choose_threshold(job, plan, None, None)[2] is None
    job.threshold = 0.35
    assert choose_threshold(job, plan, tiles, ground) == (0.35, "given", None)


@pytest.mark.parametrize("targets, warned", [(gv.FEW_HELD_OUT_TARGETS - 1, True), (gv.FEW_HELD_OUT_TARGETS, False)])
def test_a_threshold_chosen_on_few_held_out_targets_says_how_rough_it_is(targets, warned):
    ground = {"targets": targets, "by_threshold": {"0.3": {"f1": 0.7}, "0.5": {"f1": 0.6}}}
    plan = gv.plan_split([line_of_frames()], "blocks", 0.3, 0)
    job = TrainJob(sources=[], out="m.onnx")
    assert choose_threshold(job, plan, None, ground)[2] == "ground"
    text = threshold_warning(job, plan, None, ground, ["a flight"], "ground")
    if warned:
        assert f"rests on {targets} held-out target(s)" in text and f"by {1 / targets:.2f}" in text
        assert "VALIDATION flights" in text
    else:
        assert text is None


def test_a_job_written_before_the_split_existed_reads_as_blocks_without_poses():
    old = '{"sources": [{"folder": "f", "gsd_default": 1.0}], "out": "m.onnx", "val_fraction": 0.2}'
    job = TrainJob.from_json(old)
    assert job.validation == "blocks" and job.sources[0].frames is None
    assert TrainJob.from_json(job.to_json()) == job


# ====================================================================================== runs of the job
def write_targets(folder, spacing_m=3.0):
    """targets.csv for a fake labels folder: frame f's targets about f·spacing_m east of a point."""
    with open(folder / "labels.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    with open(folder / "targets.csv", "w", newline="", encoding="utf-8") as f:
        out = csv.writer(f)
        out.writerow(["geotag_id", "label", "provenance", "lat", "lon", "height_m", "height_ref"])
        for r in rows:
            x = int(r["frame_id"]) * spacing_m + 0.1 * int(r["geotag_id"]) % 0.5
            out.writerow([r["geotag_id"], "burrow", r["provenance"], f"{47.0:.9f}",
                          f"{8.0 + x / (111320 * math.cos(math.radians(47))):.9f}", "500.000", "ellipsoidal"])
    return folder


def test_a_job_split_by_blocks_without_poses_warns_the_threshold_is_not_validated_on_the_ground(tmp_path):
    labels = write_targets(make_label_folder(tmp_path / "labels", n_frames=8))
    events = []
    job = TrainJob(sources=[Source(str(labels), gsd_default=1.0)], out=str(tmp_path / "m.onnx"), steps=2,
                   val_fraction=0.25, threads=2)
    result = run_job(job, events.append)
    split = result["split"]
    assert split["method"] == "blocks" and split["held_out"] and split["tiles"]["val"] > 0
    assert split["tiles"]["train"] + split["tiles"]["val"] + split["tiles"]["dropped"] == 16
    # Two steps seldom find a target: the tiles choose the threshold when they can, else it is 0.5.
    assert result["ground_validation"] is None and result["validated_on"] in ("tiles", None)
    assert result["threshold_rule"] == TILE_RULE or result["threshold"] == 0.5
    warnings = [e["text"] for e in events if e.get("level") == "warning"]
    assert any("not validated on the ground" in w and "no frame layer" in w for w in warnings)
    card = Path(result["card"]).read_text(encoding="utf-8")
    assert "## Validation split" in card and "Spatial blocks" in card and "**Warning:**" in card
    assert "Not measured: the default threshold was" in card


def test_a_job_with_nothing_held_out_warns_in_log_and_card(tmp_path):
    labels = make_label_folder(tmp_path / "labels", n_frames=4)
    events = []
    job = TrainJob(sources=[Source(str(labels), gsd_default=1.0)], out=str(tmp_path / "n.onnx"), steps=2,
                   validation="none", threads=2)
    result = run_job(job, events.append)
    assert result["threshold"] == 0.5 and result["validated_on"] is None and not result["split"]["held_out"]
    assert any(e.get("level") == "warning" and "not validated" in e["text"] for e in events)
    card = Path(result["card"]).read_text(encoding="utf-8")
    assert "Nothing held out" in card and "the default threshold was not validated" in card


def test_labels_without_a_positive_tile_are_refused_and_no_model_is_written(tmp_path):
    import cv2

    labels = make_label_folder(tmp_path / "labels", n_frames=3)
    for path in (labels / "tiles" / "labels").glob("*.png"):
        cv2.imwrite(str(path), np.zeros((96, 96), np.uint8))
    labels_csv = labels / "labels.csv"  # labels.csv decides which tiles hold a target: none does
    labels_csv.write_text(labels_csv.read_text(encoding="utf-8").splitlines()[0] + "\n", encoding="utf-8")
    job = TrainJob(sources=[Source(str(labels), gsd_default=1.0)], out=str(tmp_path / "none.onnx"), steps=2)
    with pytest.raises(InputError, match=r"no training tile holds a target .*labels.*needs positive tiles"):
        run_job(job)
    assert not list(tmp_path.glob("*.onnx")) and not list(tmp_path.glob("*.pt"))


def test_tile_figures_match_one_peak_to_one_target():
    """Two peaks 2 px either side of one target (radius 3 px): one true positive, one false; recall 1,
    precision 1/2 (counting every peak near a target would say precision 1)."""
    import dataclasses

    from test_recipe import FixedHeatmap, blob

    label = blob((32, 32), (16, 16), 0.95).astype(np.float32)
    heat = np.maximum.reduce([blob((32, 32), (14, 16), 0.8, 0.8), blob((32, 32), (18, 16), 0.8, 0.8),
                              np.full((32, 32), 1e-4)])
    tiles = recipe.TileSet([np.zeros((32, 32, 3), np.uint8)], [label], np.array([True]), np.array([1.0]))
    meta = dataclasses.replace(recipe.make_metadata(tiles, 1.0, 0.5, 1.0, "test"), peak_blur_sigma_px=0.0)
    row = recipe.validation_figures(FixedHeatmap(heat), tiles, meta, thresholds=(0.5,),
                                    match_radius_px=3.0)["by_threshold"]["0.5"]
    assert (row["detections"], row["recall"], row["precision"], row["false_per_tile"]) == (2, 1.0, 0.5, 1.0)


def four_targets_figures(monkeypatch, provenance):
    """Two nadir frames 10 m up see four targets 0.5 m apart (``provenance`` each): a, b, c held out, d a training
    target. The detector (stood in for) finds, in both frames, a, b, d and a spot 0.5 m from every target at 0.3,
    and a alone at 0.6. Clustering and scoring are Evaluate detections' own."""
    from birdseye.birdseye_qgis.core.detect import detector
    from birdseye.birdseye_qgis.core.detect.detector import FrameDetections
    from birdseye.birdseye_qgis.core.field.geotags import Geotags
    from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
    from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame

    nadir = np.eye(4)
    nadir[:3, :3] = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    camera = CameraModel(1920, 1200, 4264.0, 4264.0, 959.5, 599.5, (0.0, 0.0, 0.0, 0.0, 0.0), nadir)
    site = LocalFrame(-27.55, 151.95, 400.0)
    records = []
    for k, east in enumerate((0.0, 0.3)):
        lat, lon, h = site.to_geodetic(np.array([east, 0.0, 10.0]))
        records.append({"frame_id": k + 1, "image": f"frame_{k + 1}.jpg", "lat": float(lat), "lon": float(lon),
                        "height_m": float(h), "qw": 1.0, "qx": 0.0, "qy": 0.0, "qz": 0.0, "ground_h_m": 400.0,
                        "height_ref": "ellipsoidal", "camera": camera.to_json()})
    spots = {"a": (-0.5, 0.0), "b": (0.0, 0.5), "c": (0.5, 0.0), "d": (0.0, -0.5), "false": (1.0, 0.5)}
    targets_xy = np.array([spots[t] for t in "abcd"])
    lat, lon, h = site.to_geodetic(np.column_stack([targets_xy, np.zeros(4)]))
    targets = Geotags(list("abcd"), lat, lon, h, ["burrow"] * 4, provenance)

    def found(frame_index, names, offset):
        xy = np.array([spots[n] for n in names]).reshape(-1, 2) + offset
        la, lo, he = site.to_geodetic(np.column_stack([xy, np.zeros(len(xy))]))
        n = len(xy)
        return FrameDetections(frame_index, frame_index + 1, "", np.zeros((n, 2)), np.full(n, 0.9),
                               np.zeros((n, 3)), la, lo, he)

    def fake_detect(model, poses, images, thresholds, local, is_canceled=None):
        runs = [[found(k, ["a", "b", "d", "false"], 0.01 * k), found(k, ["a"], 0.01 * k)] for k in range(2)]
        return runs, [0, 1]

    monkeypatch.setattr(detector, "HeatmapModel", lambda path: None)
    monkeypatch.setattr(gv, "detect_at_thresholds", fake_detect)
    return gv.ground_figures("model.onnx", [gv.GroundFlight("f", records, targets, np.array([1, 1, 1, 0], bool))],
                             thresholds=(0.3, 0.6))


def test_ground_figures_count_held_out_targets_and_leave_training_targets_out(monkeypatch):
    """Every target surveyed. At 0.3: recall 2/3 (of the held-out targets), 4 clusters: one on d (learnt in
    training: neither false nor validated, left out), 2 of the other 3 on a held-out target: GMCF 2/3. At 0.6:
    recall 1/3, GMCF 1/1."""
    figures = four_targets_figures(monkeypatch, ["survey"] * 4)
    assert figures["frames"] == 2 and figures["targets"] == 3
    low, high = figures["by_threshold"]["0.3"], figures["by_threshold"]["0.6"]
    assert (low["recall"], low["gmcf"], low["clusters"], low["detections"]) == (0.6667, 0.6667, 3, 8)
    assert (low["clusters_on_target"], low["clusters_on_training_targets"]) == (2, 1)
    assert (high["recall"], high["gmcf"], high["clusters"], high["clusters_on_training_targets"]) == (0.3333, 1.0, 1, 0)
    assert low["f1"] == round(2 * (2 / 3) * (2 / 3) / (2 / 3 + 2 / 3), 4)
    # F1 0.67 at 0.3 and 0.5 at 0.6 are within one target's worth (1/3), but 0.6 finds one held-out target
    # where 0.3 finds two: a tie never gives up a target.
    assert recipe.best_threshold(figures) == 0.3


def test_a_target_only_a_review_confirmed_is_no_geotag_match_on_the_ground(monkeypatch):
    """b was found in a review, not surveyed: the held-out figures score against the geotags, as a flight's are,
    so b is in no recall and its cluster is no match — counted apart. At 0.3: recall 1/2 (a of a, c), 3
    clusters (d's left out), 1 on a geotag: GMCF 1/3, 1 on b. At 0.6: recall 1/2, GMCF 1/1."""
    figures = four_targets_figures(monkeypatch, ["survey", "review", "survey", "survey"])
    assert figures["targets"] == 2
    low, high = figures["by_threshold"]["0.3"], figures["by_threshold"]["0.6"]
    assert (low["recall"], low["gmcf"], low["clusters"]) == (0.5, 0.3333, 3)
    assert (low["clusters_on_target"], low["clusters_on_review_targets"], low["clusters_on_training_targets"]) == \
        (1, 1, 1)
    assert (high["recall"], high["gmcf"], high["clusters_on_review_targets"]) == (0.5, 1.0, 0)


def test_a_training_python_without_onnxruntime_is_told_what_to_install(monkeypatch):
    import importlib.util

    from birdseye.birdseye_qgis.core.train.job import score_on_ground

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None if name == "onnxruntime" else real(name))
    with pytest.raises(InputError, match="no onnxruntime.*install onnxruntime into it"):
        score_on_ground(None, None, "test", [], lambda: False, lambda event: None)
