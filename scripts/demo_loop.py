"""`make demo-loop`: one round of the review loop on simulated campaigns, ending in a QGIS project.

The bundled model was trained on fields with few look-alikes; these fields hold LOOK_ALIKES times as
many (dark moist patches, shaded depressions, loose-soil mounds, stones), so it fires on some of them.
Runs in a standalone QGIS application, every step through the Processing registry (see scripts/demo.py):

1. simulate two *review* campaigns and two *test* campaigns, each over its own paddock
   (``simulatecampaign``), and import their geotags and flight logs;
2. detect on the review campaigns with the bundled model and cluster the detections (``detect``,
   ``clusterdetections``);
3. review them as a person would in the review dock, through the same session and verdict log, but with
   the simulator's truth as the reviewer's eyes: a review unit within EPS_PRED_M of a true target
   (surveyed or not) is confirmed real, every other one a hard negative;
4. write labels from the survey *and* the verdicts: confirmed targets nobody surveyed become targets,
   hard negatives become hard-negative tiles (``writelabels`` with REVIEW);
5. retrain from the bundled model on those labels, in its own PyTorch process (``traindetector``), for
   7.25 minutes on 2 CPU threads (within 15 CPU-minutes);
6. detect on the test campaigns, which neither training saw, with both models, and compare them
   (``detect``, ``comparedetectors``): recall_pre and gmcf_pre before and after, pooled over the test
   campaigns (sums of counts, one division), and what changed; the figures are added to the retrained
   model's card.

    .venv/bin/python scripts/demo_loop.py [--out birdseye-demo-loop] [--size full|small] [--minutes M]
        [--seeds R1,R2[,R3…],T1,T2] [--model round1/model/retrained.onnx [--init round1/model/retrained.pt]]
        [--validation-fraction F] [--validation blocks|flights|none]

``--seeds`` simulates other campaigns than the demo's 401, 402, 501, 502: a round on campaigns the project has not
used. The last two seeds are the test campaigns, the ones before them (two or more) the review campaigns: with
three, ``--validation flights`` holds one whole review campaign out, a paddock of its own as the test campaigns are.
``--model`` starts the round from another model than the bundled one (it detects on the review campaigns, is the
"before" on the test campaigns and is retrained); ``--init`` gives the weights retraining starts from
(default: the ``.pt`` beside ``--model`` when there is one, else ``--model``), so a second round goes on from the first
round's ``.pt``.
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import os
import runpy
import sys
import time
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import demo  # noqa: E402  (scripts/demo.py: the Processing runner, terminal feedback and project helpers)

REPO_ROOT = demo.REPO_ROOT
PROJECT_NAME = "birdseye_loop.qgz"
SUMMARY_NAME = "loop_summary.json"
LOOK_ALIKES = 4.0          # times the simulator's default look-alike density
EPS_PRED_M = 0.20          # the reviewer's "same spot": the matching radius of the scores
REVIEWER = "simulated reviewer (the simulator's truth)"
#: Train detector's VALIDATION choices, from the plugin's one list (standard library only: readable before QGIS starts).
SPLITS = runpy.run_path(str(REPO_ROOT / "birdseye_qgis" / "core" / "train" / "choices.py"))["SPLITS"]
GROUPS = ["survey", "flight", "detections", "review", "labels", "model", "comparison", "farm map"]


@dataclass(frozen=True)
class Campaign:
    key: str
    title: str
    tag: str               # names its layers: "Frames · review 1"
    seed: int
    review: bool           # reviewed and relabelled (True) or kept for the test (False)
    offset: int            # paddocks side by side, this many spacings east of the first


#: Test campaigns in every round; the seeds before them are review campaigns.
TEST_CAMPAIGNS = 2


def campaigns_of(seeds) -> list:
    """Campaigns for ``seeds``: every seed but the last :data:`TEST_CAMPAIGNS` a review campaign, those last
    ones the test campaigns, the paddocks side by side in that order."""
    n_review = len(seeds) - TEST_CAMPAIGNS
    out = []
    for offset, seed in enumerate(seeds):
        review = offset < n_review
        n = offset + 1 if review else offset - n_review + 1
        kind = "review" if review else "test"
        out.append(Campaign(f"{kind}{n}", f"{kind} campaign {n}", f"{kind} {n}", seed, review, offset))
    return out


#: The demo's round: two review campaigns, two test campaigns.
CAMPAIGNS = campaigns_of((401, 402, 501, 502))


@dataclass(frozen=True)
class LoopRound:
    """One round of the loop: its campaigns, the model it starts from (ONNX: detects before retraining) and the
    weights retraining starts from (a .pt or that ONNX model)."""

    campaigns: tuple
    model: Path
    init: Path
    validation_fraction: float | None = None  # Train detector's share of held-out targets (None: its default)
    validation: str | None = None  # Train detector's VALIDATION split (None: its default, blocks)

    @classmethod
    def of(cls, seeds=None, model: Path | None = None, init: Path | None = None,
           validation_fraction: float | None = None, validation: str | None = None) -> "LoopRound":
        campaigns = CAMPAIGNS if seeds is None else campaigns_of(seeds)
        model = Path(model or demo.BUNDLED_MODEL)
        beside = model.with_suffix(".pt")
        return cls(tuple(campaigns), model, Path(init) if init else beside if beside.is_file() else model,
                   validation_fraction, validation)

    @property
    def reviewed(self) -> list:
        return [c for c in self.campaigns if c.review]

    @property
    def tested(self) -> list:
        return [c for c in self.campaigns if not c.review]


@dataclass(frozen=True)
class LoopSize:
    demo_size: str         # the simulated campaign size of scripts/demo.py
    minutes: float         # training budget (wall-clock minutes on TRAINING_THREADS threads)


# 7.25 minutes on 2 threads: within a CPU time budget of 15 minutes (the last step ends past the budget).
TRAINING_THREADS = 2
SIZES = {"full": LoopSize("full", 7.25), "small": LoopSize("small", 0.5)}


def campaign_steps(size: demo.DemoSize, loop: LoopRound) -> list[demo.Step]:
    steps = []
    for c in loop.campaigns:
        steps.append(demo.Step(f"campaign_{c.key}", "simulatecampaign", f"Simulate the {c.title}", {
            "SEED": c.seed, "N_TARGETS": size.n_targets, "FIELD_WIDTH_M": size.field_width_m,
            "FIELD_LENGTH_M": size.field_length_m, "ALTITUDE_M": demo.ALTITUDE_M, "SPEED_MS": 2.5,
            "FPS": size.training_fps if c.review else size.held_out_fps,
            "IMAGE_WIDTH": size.image_width, "IMAGE_HEIGHT": size.image_height, "SIGMAS": demo.SIGMAS,
            "LOOK_ALIKE_DENSITY": LOOK_ALIKES, "SITE_LAT": demo.SITE_LAT,
            "SITE_LON": demo.field_longitude(c.offset * size.field_spacing_m),
            "OUTPUT_FOLDER": f"{{out}}/campaigns/{c.key}"},
            tag=c.tag, maps=(("ORTHOMOSAIC", "Mosaic"),), map_group="farm map"))
        steps.append(demo.Step(f"geotags_{c.key}", "importgeotags", f"Import the geotags of the {c.title}", {
            "INPUT": f"{{campaign_{c.key}[GEOTAGS]}}", "OUTPUT": f"{{out}}/survey/geotags_{c.key}.gpkg"},
            group="survey", tag=c.tag))
        steps.append(demo.Step(f"flight_{c.key}", "importflightlog", f"Import the {c.title}'s log", {
            "POSE_LOG": f"{{campaign_{c.key}[POSES]}}", "IMAGES": f"{{campaign_{c.key}[OUTPUT_FOLDER]}}",
            "CALIBRATION": f"{{campaign_{c.key}[CALIBRATION]}}",
            "FPS": size.training_fps if c.review else size.held_out_fps,
            "OUTPUT": f"{{out}}/flight/frames_{c.key}.gpkg", "OUTPUT_TRACK": f"{{out}}/flight/track_{c.key}.gpkg"},
            group="flight", tag=c.tag, hidden=("OUTPUT",), expected=demo.FLIGHT_LOG_EXPECTED))
        steps.append(demo.Step(f"detect_{c.key}", "detect", f"Detect on the {c.title} with the round's model", {
            "FRAMES": f"{{flight_{c.key}[OUTPUT]}}", "MODEL": str(loop.model),
            "OUTPUT": f"{{out}}/detections/before_{c.key}.gpkg"},
            group="detections", tag=c.tag, kinds={"OUTPUT": "Starting model"}, hidden=("OUTPUT",)))
    return steps


def review_steps(loop: LoopRound) -> list[demo.Step]:
    steps = []
    for c in loop.reviewed:
        steps.append(demo.Step(f"clusters_{c.key}", "clusterdetections", f"Cluster the {c.title}'s detections", {
            "DETECTIONS": f"{{detect_{c.key}[OUTPUT]}}", "GEOTAGS": f"{{geotags_{c.key}[OUTPUT]}}",
            "FRAMES": f"{{flight_{c.key}[OUTPUT]}}", "OUTPUT": f"{{out}}/review/clusters_{c.key}.gpkg",
            "OUTPUT_POINTS": None}, group="review", tag=c.tag))
    return steps


def relabel_and_train_steps(size: demo.DemoSize, minutes: float, loop: LoopRound) -> list[demo.Step]:
    steps = []
    for c in loop.reviewed:
        steps.append(demo.Step(f"labels_{c.key}", "writelabels", f"Write labels from the survey and the review "
                               f"of the {c.title}", {
            "GEOTAGS": f"{{geotags_{c.key}[OUTPUT]}}", "FRAMES": f"{{flight_{c.key}[OUTPUT]}}",
            "REVIEW": f"{{review_{c.key}[VERDICTS]}}", "REVIEW_DETECTIONS": [f"{{detect_{c.key}[OUTPUT]}}"],
            "SIGMA_PX": 10.0, "EDGE_BUFFER_PX": 20.0, "WRITE_RASTERS": False, "WRITE_TILES": True,
            "TILE_SIZE": size.tile_size, "NEGATIVE_RATIO": 1.5, "OUTPUT_FOLDER": f"{{out}}/labels/{c.key}",
            "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None}))
    steps.append(demo.Step("train", "traindetector", "Retrain the round's model on the review's labels", {
        "LABELS": [f"{{labels_{c.key}[OUTPUT_FOLDER]}}" for c in loop.reviewed],
        "FRAMES": [f"{{flight_{c.key}[OUTPUT]}}" for c in loop.reviewed],
        "INIT": str(loop.init), "MINUTES": minutes, "THREADS": TRAINING_THREADS, "SEED": 1,
        **({} if loop.validation_fraction is None else {"VALIDATION_FRACTION": loop.validation_fraction}),
        **({} if loop.validation is None else {"VALIDATION": SPLITS.index(loop.validation)}),
        # The demo runs in the repository's venv, which has the training extra (requirements-train.txt).
        "PYTHON": sys.executable,
        "OUTPUT_MODEL": "{out}/model/retrained.onnx"}))
    for c in loop.tested:
        steps.append(demo.Step(f"retrained_{c.key}", "detect", f"Detect on the {c.title} with the retrained model", {
            "FRAMES": f"{{flight_{c.key}[OUTPUT]}}", "MODEL": "{train[OUTPUT_MODEL]}",
            "OUTPUT": f"{{out}}/detections/retrained_{c.key}.gpkg"},
            group="detections", tag=c.tag, kinds={"OUTPUT": "Retrained model"}, hidden=("OUTPUT",)))
        steps.append(demo.Step(f"compare_{c.key}", "comparedetectors", f"Compare both models on the {c.title}", {
            "DETECTIONS_OLD": f"{{detect_{c.key}[OUTPUT]}}", "DETECTIONS_NEW": f"{{retrained_{c.key}[OUTPUT]}}",
            "FRAMES": f"{{flight_{c.key}[OUTPUT]}}", "GEOTAGS": f"{{geotags_{c.key}[OUTPUT]}}",
            "OUTPUT": f"{{out}}/comparison/changes_{c.key}.gpkg",
            "OUTPUT_JSON": f"{{out}}/comparison/comparison_{c.key}.json",
            "OUTPUT_REPORT": f"{{out}}/comparison/comparison_{c.key}.html"},
            group="comparison", tag=c.tag))
    return steps


# ------------------------------------------------------------------------------------------ the reviewer
def true_targets(campaign_folder: Path) -> tuple[list, list]:
    """Latitudes and longitudes of every simulated target, surveyed or not (truth/targets.csv)."""
    with open(campaign_folder / "truth" / "targets.csv", encoding="utf-8", newline="") as handle:
        rows = list(csv.DictReader(handle))
    return [float(r["lat"]) for r in rows], [float(r["lon"]) for r in rows]


def simulated_review(campaign: Campaign, values: dict, out: Path) -> dict:
    """Judge every review unit of the campaign's detections with the review dock's own session and verdict
    log; the simulator's truth decides. Returns the step's results: the verdict table and the counts."""
    import numpy as np
    from qgis.core import QgsVectorLayer

    from birdseye.birdseye_qgis.core.review.units import ReviewParameters, build_units
    from birdseye.birdseye_qgis.qgis_io.review_store import ReviewSession, VerdictStore, read_review_inputs

    def layer(path, name):
        loaded = QgsVectorLayer(str(path), name, "ogr")
        if not loaded.isValid():
            raise demo.DemoError(f"the simulated review cannot open {path}")
        return loaded

    detections = layer(values[f"detect_{campaign.key}"]["OUTPUT"], f"the round's model, {campaign.title}")
    frames = layer(values[f"flight_{campaign.key}"]["OUTPUT"], f"frames, {campaign.title}")
    geotags = layer(values[f"geotags_{campaign.key}"]["OUTPUT"], f"geotags, {campaign.title}")
    inputs = read_review_inputs([detections], frames, geotags)
    params = ReviewParameters()
    units = build_units(inputs.layers, inputs.local, inputs.geotags, inputs.pose_groups, params, inputs.ground)
    lat, lon = true_targets(Path(values[f"campaign_{campaign.key}"]["OUTPUT_FOLDER"]))
    truth = inputs.local.from_geodetic(np.asarray(lat), np.asarray(lon), np.full(len(lat), inputs.local.h0))[:, :2]
    unit_xy = inputs.local.from_geodetic(np.asarray(units.lat), np.asarray(units.lon),
                                         np.full(len(units.lat), inputs.local.h0))[:, :2]
    path = out / "review" / f"verdicts_{campaign.key}.gpkg"
    path.parent.mkdir(parents=True, exist_ok=True)
    store = VerdictStore(path)
    session = ReviewSession(store, units, REVIEWER, inputs.digests, params)
    counts = {"confirmed_real": 0, "hard_negative": 0}
    try:
        for key, xy in zip(units.keys, unit_xy):
            real = len(truth) and float(np.min(np.hypot(*(truth - xy).T))) <= EPS_PRED_M
            verdict = "confirmed_real" if real else "hard_negative"
            session.set_verdict(key, verdict)
            counts[verdict] += 1
    finally:
        store.close()
    print(f"    {len(units.keys)} review units: {counts['confirmed_real']} confirmed real, "
          f"{counts['hard_negative']} hard negatives → {path.relative_to(out)}", flush=True)
    return {"VERDICTS": f"{path}|layername=birdseye_verdicts", "UNITS": len(units.keys), **counts}


# ------------------------------------------------------------------------------------------ figures
POOLED = ("n_in_view", "n_recovered", "n_clusters", "n_hit_clusters")


def f1_of(recall, gmcf) -> float | None:
    """The method's F1 of a recall and a GMCF (:func:`core.scoring.pre_review.f1_geo`); None where either is."""
    from birdseye.birdseye_qgis.core.scoring.pre_review import f1_geo

    return None if recall is None or gmcf is None else float(f1_geo(recall, gmcf))


def pooled_comparison(values: dict, loop: LoopRound) -> dict:
    """Before and after, pooled over the test campaigns (sums of counts, one division), and the changes."""
    sums = {side: dict.fromkeys(POOLED, 0) for side in ("before", "after")}
    changes = {}
    for c in loop.tested:
        doc = json.loads(Path(values[f"compare_{c.key}"]["OUTPUT_JSON"]).read_text(encoding="utf-8"))
        for side in sums:
            for key in POOLED:
                sums[side][key] += int(doc[side][key])
        for name, n in doc["changes"].items():
            changes[name] = changes.get(name, 0) + int(n)

    def ratio(a, b):
        return None if b == 0 else a / b

    out = {}
    for side, s in sums.items():
        recall, gmcf = ratio(s["n_recovered"], s["n_in_view"]), ratio(s["n_hit_clusters"], s["n_clusters"])
        out[side] = dict(s, recall_pre=recall, gmcf_pre=gmcf, f1_geo=f1_of(recall, gmcf))
    out["changes"] = changes
    return out


def append_to_model_card(card: Path, numbers: dict) -> None:
    """The comparison on the test campaigns, after the card's own (tile) figures: what a user needs to
    decide whether the retrained model replaces the bundled one."""
    b, a, t = numbers["test"]["before"], numbers["test"]["after"], numbers["training"]
    rows = [("recall_pre", demo.fmt(b["recall_pre"]), demo.fmt(a["recall_pre"])),
            ("gmcf_pre", demo.fmt(b["gmcf_pre"]), demo.fmt(a["gmcf_pre"])),
            ("geotags recovered / in view", f"{b['n_recovered']} / {b['n_in_view']}",
             f"{a['n_recovered']} / {a['n_in_view']}"),
            ("clusters on a geotag / clusters", f"{b['n_hit_clusters']} / {b['n_clusters']}",
             f"{a['n_hit_clusters']} / {a['n_clusters']}")]
    text = ["", "## Review loop: the test campaigns neither training saw", "",
            f"{numbers['round']['model_name']} before, this model after, pooled over {numbers['test_campaigns']} "
            "simulated campaigns "
            f"with {numbers['look_alike_density']:g}× the look-alikes (sums of counts, one division; scored as "
            "Evaluate detections scores, each model at its own default threshold). Training: "
            f"{t['seconds'] / 60:.1f} min on {TRAINING_THREADS} CPU threads ({t['cpu_minutes']:.1f} CPU-minutes).",
            "", "| figure | before | after |", "| --- | ---: | ---: |",
            *[f"| {name} | {before} | {after} |" for name, before, after in rows],
            "", "Changes: " + ", ".join(f"{k.replace('_', ' ')} {v}" for k, v in numbers["test"]["changes"].items())
            + ".", ""]
    with open(card, "a", encoding="utf-8") as handle:
        handle.write("\n".join(text))


def summary_lines(numbers: dict, shown_out: str) -> str:
    b, a = numbers["test"]["before"], numbers["test"]["after"]
    lines = ["", "=" * 78,
             f" BirdsEye review loop finished in {numbers['seconds'] / 60:.1f} min; everything is in {shown_out}/",
             "-" * 78]
    for key, review in numbers["review"].items():
        lines.append(f" Review      {key}: {review['UNITS']} units → {review['confirmed_real']} confirmed real, "
                     f"{review['hard_negative']} hard negatives")
    labels = numbers["labels"]
    lines += [f" Labels      {labels['review_targets']} review targets, {labels['hard_negatives']} hard-negative "
              "clusters in the training labels",
              f" Training    {numbers['training']['tiles']} tiles, {numbers['training']['seconds']:.0f} s, "
              f"threshold {demo.fmt(numbers['training']['threshold'], 2)} → model/retrained.onnx",
              f" Validation held-out frames at that threshold: recall "
              f"{demo.fmt(numbers['training']['validation_recall'])}, GMCF "
              f"{demo.fmt(numbers['training']['validation_gmcf'])}, F1 {demo.fmt(numbers['training']['validation_f1'])}"
              f" (test campaigns after: F1 {demo.fmt(a['f1_geo'])})",
              f" Test        recall_pre {demo.fmt(b['recall_pre'])} → {demo.fmt(a['recall_pre'])}, "
              f"gmcf_pre {demo.fmt(b['gmcf_pre'])} → {demo.fmt(a['gmcf_pre'])} "
              f"({b['n_clusters']} → {a['n_clusters']} clusters)",
              f" Changes     {', '.join(f'{k}: {v}' for k, v in numbers['test']['changes'].items())}",
              "-" * 78, f" Open it     qgis {shown_out}/{PROJECT_NAME}", "=" * 78]
    return "\n".join(lines)


# ------------------------------------------------------------------------------------------ the run
def run(out: Path, size_name: str, minutes: float | None, loop: LoopRound | None = None) -> int:
    started = time.monotonic()
    size = SIZES[size_name]
    demo_size = demo.SIZES[size.demo_size]
    minutes = size.minutes if minutes is None else minutes
    loop = loop or LoopRound.of()
    _app, _provider = demo.start_qgis()
    from qgis.core import QgsProject

    first, review = campaign_steps(demo_size, loop), review_steps(loop)
    second = relabel_and_train_steps(demo_size, minutes, loop)
    try:
        demo.preflight(first + review + second, None)
        demo.prepare_folder(out, PROJECT_NAME, SUMMARY_NAME, "review-loop demo")
        project = QgsProject.instance()
        project.clear()
        project.setTitle("BirdsEye review loop")
        values = {"out": str(out)}
        farm_layers = []
        numbered = [*first, *review, None, *second]
        for number, step in enumerate(numbered, 1):
            if step is None:
                for c in loop.reviewed:
                    print(f"[{number}/{len(numbered)}] Review the {c.title} (simulated reviewer)", flush=True)
                    values[f"review_{c.key}"] = simulated_review(c, values, out)
                continue
            print(f"[{number}/{len(numbered)}] {step.title} (birdseye:{step.alg_id})", flush=True)
            step_start = time.monotonic()
            results, layers = demo.run_step(step, values, project)
            maps = demo.load_maps(step, results)
            values[step.name] = results
            demo.add_to_group(project, step.group, layers, GROUPS)
            demo.add_to_group(project, step.map_group, maps, GROUPS)
            if (layers or maps) and not project.crs().isValid():
                project.setCrs((layers or maps)[0][0].crs())
            farm_layers += [layer for layer, *_ in maps]
            print(f"    done in {time.monotonic() - step_start:.1f} s", flush=True)
        add_verdict_layers(project, values, loop)
        demo.add_to_group(project, "farm map", [demo.osm_basemap()], GROUPS)
        demo.finish_project(project, farm_layers, GROUPS, on_top=("survey",))
        project_path = out / PROJECT_NAME
        if not project.write(str(project_path)):
            raise demo.DemoError(f"could not write {project_path}: {project.error()}")
        invalid = demo.check_saved_project(project_path)
        if invalid:
            raise demo.DemoError(f"{project_path} opens with invalid layers: {', '.join(invalid)}")
        reviewed = loop.reviewed
        train = values["train"]
        numbers = {
            "look_alike_density": LOOK_ALIKES,
            "review": {c.key: {k: v for k, v in values[f"review_{c.key}"].items() if k != "VERDICTS"}
                       for c in reviewed},
            "labels": {"review_targets": sum(int(values[f"labels_{c.key}"]["REVIEW_TARGETS"]) for c in reviewed),
                       "hard_negatives": sum(int(values[f"labels_{c.key}"]["HARD_NEGATIVES"]) for c in reviewed)},
            "training": {"tiles": int(train["TILES"]), "seconds": float(train["TRAIN_SECONDS"]),
                         "minutes_budget": minutes, "threads": TRAINING_THREADS,
                         "cpu_minutes": round(float(train["TRAIN_SECONDS"]) * TRAINING_THREADS / 60.0, 2),
                         "threshold": train["THRESHOLD_USED"],
                         # the held-out frames' ground figures at that threshold (Train detector's validation)
                         "validation_recall": train["VALIDATION_RECALL"], "validation_gmcf": train["VALIDATION_GMCF"],
                         "validation_f1": f1_of(train["VALIDATION_RECALL"], train["VALIDATION_GMCF"]),
                         "tiles_per_second": train["TILES_PER_SECOND"], "model_card": Path(train["MODEL_CARD"]).name},
            "round": {"seeds": {c.key: c.seed for c in loop.campaigns}, "model": str(loop.model),
                      "validation_fraction": loop.validation_fraction, "validation": loop.validation,
                      "model_name": "The bundled model" if loop.model == demo.BUNDLED_MODEL else loop.model.name,
                      "init": str(loop.init)},
            "test": pooled_comparison(values, loop),
            "test_campaigns": len(loop.tested),
            "seconds": round(time.monotonic() - started, 1),
        }
        (out / SUMMARY_NAME).write_text(json.dumps(numbers, indent=2) + "\n", encoding="utf-8")
        append_to_model_card(Path(train["MODEL_CARD"]), numbers)
        shown = os.path.relpath(out) if not os.path.relpath(out).startswith("..") else str(out)
        print(summary_lines(numbers, shown))
        return 0
    except demo.DemoError as exc:
        print(f"\nThe review-loop demo stopped: {exc}", file=sys.stderr)
        return 1


def add_verdict_layers(project, values: dict, loop: LoopRound) -> None:
    from qgis.core import QgsVectorLayer

    layers = []
    for c in loop.reviewed:
        layer = QgsVectorLayer(values[f"review_{c.key}"]["VERDICTS"], f"Verdicts · {c.tag}", "ogr")
        if not layer.isValid():
            raise demo.DemoError(f"the verdict log of the {c.title} cannot be opened as a layer")
        layers.append((layer, False, False))
    demo.add_to_group(project, "review", layers, GROUPS)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=REPO_ROOT / "birdseye-demo-loop")
    parser.add_argument("--size", choices=sorted(SIZES), default="full")
    parser.add_argument("--minutes", type=float, default=None,
                        help="training budget in minutes on 2 threads (default: 7.25 at full size, 0.5 small)")
    parser.add_argument("--seeds", default=None,
                        help="seeds of the review campaigns (two or more) and then of the two test campaigns, "
                             "comma-separated (default: " + ",".join(str(c.seed) for c in CAMPAIGNS) + ")")
    parser.add_argument("--model", type=Path, default=None,
                        help="the ONNX model the round starts from (default: the bundled model)")
    parser.add_argument("--init", type=Path, default=None,
                        help="the weights retraining starts from (default: the .pt beside --model, else --model)")
    parser.add_argument("--validation-fraction", type=float, default=None,
                        help="share of the review campaigns' targets Train detector holds out (default: its own)")
    parser.add_argument("--validation", choices=SPLITS, default=None,
                        help="how Train detector holds targets out: blocks of ground, whole review campaigns "
                             "(flights) or none (default: its own, blocks)")
    args = parser.parse_args(argv)
    if args.validation_fraction is not None and not 0 < args.validation_fraction <= 0.5:
        parser.error("--validation-fraction must lie in (0, 0.5]")
    if args.minutes is not None and not (0 < args.minutes and math.isfinite(args.minutes)):
        parser.error("--minutes must be a positive number")
    seeds = None
    if args.seeds is not None:
        try:
            seeds = [int(s) for s in args.seeds.split(",")]
        except ValueError:
            parser.error(f"--seeds: {args.seeds!r} is not whole numbers separated by commas")
        if len(seeds) < TEST_CAMPAIGNS + 2 or len(set(seeds)) != len(seeds):
            parser.error(f"--seeds takes {TEST_CAMPAIGNS + 2} or more different seeds: two or more review campaigns, "
                         f"then {TEST_CAMPAIGNS} test campaigns")
    for given in (args.model, args.init):
        if given is not None and not given.is_file():
            parser.error(f"{given}: no such file")
    loop = LoopRound.of(seeds, args.model and args.model.resolve(), args.init and args.init.resolve(),
                        args.validation_fraction, args.validation)
    return run(args.out.resolve(), args.size, args.minutes, loop)


if __name__ == "__main__":
    sys.exit(main())
