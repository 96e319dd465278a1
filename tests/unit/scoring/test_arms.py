"""The method's three arms from a sweep table: rules, ties, the front only, and the files in and out."""
import json

import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.scoring.arms import SCHEMA, arms_document, read_arms, read_sweep, select_arms
from birdseye.birdseye_qgis.core.scoring.sweep import f1_geo


def row(recall, gmcf, dpf, credible=True, pareto=True, checkpoint="a.onnx", **op):
    point = {"threshold": 0.05, "dedup_cm": 3.0, "eps_m": 0.2, "min_samples": 2, "eps_pred_m": 0.2,
             "edge_buffer_px": 0.0, "core_count": "detections", **op}
    return {"checkpoint": checkpoint, "model_digest": "d" * 64, **point, "recall_pre": recall, "gmcf_pre": gmcf,
            "f1_geo": float(f1_geo(recall, gmcf)), "detections_per_frame": dpf, "n_clusters": 10,
            "credible": credible, "pareto": pareto}


def test_each_rule_picks_its_row_of_the_credible_front():
    rows = [
        row(0.9, 0.5, 5.0, threshold=0.03),                  # F1 0.643: the highest recall
        row(0.8, 0.7, 3.0, checkpoint="b.onnx"),             # F1 2·0.56/1.5 = 0.747: the highest F1
        row(0.5, 0.9, 2.0, threshold=0.12, eps_m=0.1),       # F1 0.643, 2 per frame: the lightest
        row(0.95, 0.1, 0.5, pareto=False),                   # off the front: never an arm
        row(0.99, 0.99, 0.1, credible=False, pareto=False),  # not credible: never an arm
        row(0.5, 0.9, 2.0, threshold=0.12, eps_m=0.15),      # same burden, F1 and recall: the earlier row wins
    ]
    arms = {a["name"]: a for a in select_arms(rows, "sweep.json")}
    assert list(arms) == ["max_f1", "max_recall", "lowest_review_burden"]
    assert arms["max_f1"]["sweep_row"] == 2 and arms["max_f1"]["checkpoint"] == "b.onnx"
    assert arms["max_recall"]["sweep_row"] == 1 and arms["max_recall"]["operating_point"]["threshold"] == 0.03
    burden = arms["lowest_review_burden"]
    assert burden["sweep_row"] == 3
    assert burden["operating_point"] == {"threshold": 0.12, "dedup_cm": 3.0, "eps_m": 0.1, "min_samples": 2,
                                         "eps_pred_m": 0.2, "edge_buffer_px": 0.0, "core_count": "detections"}
    assert burden["scores"]["detections_per_frame"] == 2.0 and burden["scores"]["n_clusters"] == 10


def test_a_sweep_made_before_core_count_was_recorded_gives_arms_that_count_cells():
    """Such a sweep's DBSCAN counted cells: its arms must say so, not take today's default."""
    old = row(0.8, 0.7, 3.0)
    del old["core_count"]
    cells = row(0.8, 0.7, 3.0, core_count="cells")
    assert select_arms([old])[0]["operating_point"] == select_arms([cells])[0]["operating_point"]
    assert select_arms([old])[0]["operating_point"]["core_count"] == "cells"
    with pytest.raises(InputError, match="core_count is 'clusters'"):
        select_arms([row(0.8, 0.7, 3.0, core_count="clusters")])


def test_ties_go_to_the_higher_recall_then_gmcf_then_f1():
    # F1 of (0.6, 0.9) and (0.9, 0.6) are both 2·0.54/1.5 = 0.72: max F1 takes the higher recall
    assert select_arms([row(0.6, 0.9, 1.0), row(0.9, 0.6, 1.0)])[0]["sweep_row"] == 2
    # equal recall: max recall takes the higher GMCF (rows 1 and 2 cannot both be on a true front, but
    # the rule must still be defined)
    assert select_arms([row(0.9, 0.5, 1.0), row(0.9, 0.6, 1.0)])[1]["sweep_row"] == 2
    # equal detections per frame: the lightest arm takes the higher F1
    assert select_arms([row(0.5, 0.5, 1.0), row(0.6, 0.6, 1.0)])[2]["sweep_row"] == 2
    # no detections per frame known (no frame): the heaviest possible burden
    assert select_arms([row(0.5, 0.5, None), row(0.4, 0.4, 3.0)])[2]["sweep_row"] == 2


def test_a_table_without_a_credible_front_or_with_bad_rows_is_refused():
    with pytest.raises(InputError, match="no credible configuration on its Pareto front"):
        select_arms([row(0.9, 0.5, 1.0, credible=False, pareto=False)], "s.json")
    bad = row(0.9, 0.5, 1.0)
    bad["recall_pre"] = None
    with pytest.raises(InputError, match="s.json, row 2, field 'recall_pre'"):
        select_arms([row(0.5, 0.5, 1.0), bad], "s.json")
    no_flag = row(0.9, 0.5, 1.0)
    del no_flag["pareto"]
    with pytest.raises(InputError, match="row 1, field 'pareto'"):
        select_arms([no_flag], "s.json")


def test_sweep_and_arms_files(tmp_path):
    sweep_path = tmp_path / "sweep.json"
    sweep_path.write_text(json.dumps({"flights": ["f1"], "grid": {"eps_m": [0.2]}, "credibility": {},
                                      "configurations": [row(0.8, 0.7, 3.0)]}), encoding="utf-8")
    document = read_sweep(sweep_path)
    arms = select_arms(document["configurations"], str(sweep_path))
    out = tmp_path / "arms.json"
    out.write_text(json.dumps(arms_document(document, arms, str(sweep_path))), encoding="utf-8")
    back = read_arms(out)
    assert [a["name"] for a in back] == ["max_f1", "max_recall", "lowest_review_burden"]
    assert json.loads(out.read_text())["sweep"]["flights"] == ["f1"]
    (tmp_path / "table.json").write_text("[]", encoding="utf-8")
    with pytest.raises(InputError, match="no 'configurations' list"):
        read_sweep(tmp_path / "table.json")
    with pytest.raises(InputError, match=f"not an arms file \\(schema '{SCHEMA}'\\)"):
        read_arms(sweep_path)
    broken = json.loads(out.read_text())
    broken["arms"][1]["operating_point"]["eps_m"] = 0
    out.write_text(json.dumps(broken), encoding="utf-8")
    with pytest.raises(InputError, match="EPS_M"):
        read_arms(out)
    del broken["arms"][0]["model_digest"]
    out.write_text(json.dumps(broken), encoding="utf-8")
    with pytest.raises(InputError, match="arm 1, field 'model_digest'"):
        read_arms(out)
