"""`make demo-loop`, reduced: scripts/demo_loop.py --size small runs one round of the review loop (simulate →
detect with the bundled model → a simulated reviewer judges every review unit in the dock's own verdict
log → labels from the survey and the verdicts → retraining from the bundled model in its own process →
both models compared on campaigns neither training saw) in about a minute. What it leaves is checked
against the files themselves: the verdicts against the simulator's truth, the labels' provenance against
the verdicts, the pooled figures against the per-campaign comparisons, the model card against the
summary, and the project opens with valid layers.
"""
from __future__ import annotations

import csv
import json
import os
import sqlite3
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from training_python import needs_training_python

REPO_ROOT = Path(__file__).resolve().parents[2]
LOOP = REPO_ROOT / "scripts" / "demo_loop.py"
REVIEWED, TESTED = ("review1", "review2"), ("test1", "test2")

pytestmark = [pytest.mark.slow, needs_training_python]


@pytest.fixture(scope="module")
def loop(tmp_path_factory) -> dict:
    out = tmp_path_factory.mktemp("loop") / "birdseye-demo-loop"
    env = {k: v for k, v in os.environ.items() if k not in {"QGIS_CUSTOM_CONFIG_PATH", "PYTHONPATH"}}
    env["QT_QPA_PLATFORM"] = "offscreen"
    result = subprocess.run([sys.executable, str(LOOP), "--out", str(out), "--size", "small", "--minutes", "0.3"],
                            cwd=REPO_ROOT, env=env, capture_output=True, text=True, timeout=600, check=False)
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-4000:]
    return {"out": out, "stdout": result.stdout,
            "summary": json.loads((out / "loop_summary.json").read_text(encoding="utf-8"))}


def verdict_rows(path: Path) -> list[dict]:
    with sqlite3.connect(str(path)) as connection:
        connection.row_factory = sqlite3.Row
        return [dict(r) for r in connection.execute("SELECT unit_key, verdict, provenance, reviewer, lat, lon "
                                                     "FROM birdseye_verdicts ORDER BY fid")]


def metres_apart(lat1, lon1, lat2, lon2):
    """Horizontal distances (m) between WGS84 points a few metres apart (equirectangular, exact to < 1 mm
    over a field)."""
    r = 6_378_137.0
    north = np.radians(np.asarray(lat2) - np.asarray(lat1)) * r
    east = np.radians(np.asarray(lon2) - np.asarray(lon1)) * r * np.cos(np.radians(np.asarray(lat1)))
    return np.hypot(north, east)


def test_the_reviewer_judges_every_unit_by_the_simulators_truth(loop):
    out, summary = loop["out"], loop["summary"]
    for key in REVIEWED:
        rows = verdict_rows(out / "review" / f"verdicts_{key}.gpkg")
        assert len(rows) == summary["review"][key]["UNITS"] > 0
        assert {r["provenance"] for r in rows} == {"direct"} and len({r["unit_key"] for r in rows}) == len(rows)
        with open(out / "campaigns" / key / "truth" / "targets.csv", encoding="utf-8", newline="") as handle:
            truth = [(float(t["lat"]), float(t["lon"])) for t in csv.DictReader(handle)]
        for r in rows:
            nearest = min(metres_apart(r["lat"], r["lon"], lat, lon) for lat, lon in truth)
            assert r["verdict"] == ("confirmed_real" if nearest <= 0.20 else "hard_negative"), (key, r, nearest)
        confirmed = sum(r["verdict"] == "confirmed_real" for r in rows)
        assert (confirmed, len(rows) - confirmed) == (summary["review"][key]["confirmed_real"],
                                                     summary["review"][key]["hard_negative"])


def test_the_labels_carry_the_reviews_targets_and_the_model_starts_from_the_bundled_one(loop):
    out, summary = loop["out"], loop["summary"]
    review_targets = 0
    for key in REVIEWED:
        with open(out / "labels" / key / "labels.csv", encoding="utf-8", newline="") as handle:
            rows = list(csv.DictReader(handle))
        assert {r["provenance"] for r in rows} <= {"survey", "review"}
        assert any(r["provenance"] == "survey" for r in rows)
        review = json.loads((out / "labels" / key / "summary.json").read_text(encoding="utf-8"))["provenance"].get(
            "review", {"n_targets": 0, "n_labels": 0})
        assert sum(r["provenance"] == "review" for r in rows) == review["n_labels"]
        review_targets += review["n_targets"]
    assert review_targets == summary["labels"]["review_targets"]
    report = json.loads((out / "model" / "retrained.training.json").read_text(encoding="utf-8"))
    assert report["settings"]["init"].endswith("birdseye_demo_heatmap.onnx")
    assert summary["training"]["threads"] == 2 and summary["training"]["cpu_minutes"] > 0


def test_the_pooled_figures_are_the_sums_of_the_comparisons_and_reach_the_model_card(loop):
    out, summary = loop["out"], loop["summary"]
    docs = [json.loads((out / "comparison" / f"comparison_{key}.json").read_text(encoding="utf-8"))
            for key in TESTED]
    for side in ("before", "after"):
        pooled = summary["test"][side]
        for count in ("n_in_view", "n_recovered", "n_clusters", "n_hit_clusters"):
            assert pooled[count] == sum(d[side][count] for d in docs)
        assert pooled["recall_pre"] == pytest.approx(pooled["n_recovered"] / pooled["n_in_view"])
        assert pooled["gmcf_pre"] == pytest.approx(pooled["n_hit_clusters"] / pooled["n_clusters"])
    assert all(d["before"]["model"] != d["after"]["model"] or d["before"]["model_digest"] != d["after"]["model_digest"]
               for d in docs)
    card = (out / "model" / "retrained.md").read_text(encoding="utf-8")
    section = card.split("## Review loop: the test campaigns neither training saw", 1)[1]
    b, a = summary["test"]["before"], summary["test"]["after"]
    assert f"| recall_pre | {b['recall_pre']:.3f} | {a['recall_pre']:.3f} |" in section
    assert f"| gmcf_pre | {b['gmcf_pre']:.3f} | {a['gmcf_pre']:.3f} |" in section


def test_the_project_opens_with_every_layer_valid(loop, qgis_app):
    from qgis.core import QgsProject

    project = QgsProject()
    assert project.read(str(loop["out"] / "birdseye_loop.qgz"))
    layers = list(project.mapLayers().values())
    assert layers and all(layer.isValid() for layer in layers), [
        layer.name() for layer in layers if not layer.isValid()]
    groups = [g.name() for g in project.layerTreeRoot().findGroups()]
    assert {"survey", "flight", "detections", "review", "comparison", "farm map"} <= set(groups)
    names = [layer.name() for layer in layers]
    assert len(set(names)) == len(names), sorted(names)
    assert "Verdicts · review 1" in names and "Verdicts · review 2" in names
    assert sum(n.startswith("Changes · test") for n in names) == len(TESTED)
