"""birdseye:comparedetectors through the registry, on synthetic detections of one frame.

The scene of test_cluster_algorithms (one nadir frame 10 m over the site, footprint ±9.6 m east, ±6 m
north; geotags 1 at (−2.9, 0) and 2 at (5, −5) in view, 3 at (15, 0) out). Clusters are 3 × 3 grids of
4 cm step, so with the default EPS 0.20 m each grid is one cluster.
"""
from __future__ import annotations

import json

import numpy as np
import pytest
from qgis.core import QgsProcessingException
from test_cluster_algorithms import (
    SITE,
    UTM,
    detection_layer,
    frame_layer,
    geotag_layer,
    grid9,
    run,
    verdict_layer,
)

OLD = {"g1": (-3.0, 0.0), "kept": (3.0, 1.0), "removed": (-6.0, 3.0)}
NEW = {"g1": (-3.0, 0.0), "g2": (5.0, -5.0), "kept": (3.05, 1.0), "added": (0.0, -4.0)}


def layer(spots, name, digest):
    return detection_layer(np.concatenate([grid9(*xy) for xy in spots.values()]), digest=digest, name=name)


def site_en(feature):
    lat, lon = UTM.to_geodetic(feature.geometry().asPoint().x(), feature.geometry().asPoint().y())
    east, north, _ = SITE.from_geodetic(lat, lon, SITE.h0).reshape(3)
    return round(float(east), 2), round(float(north), 2)


def test_comparedetectors_scores_both_and_maps_what_changed(birdseye_provider, tmp_path):
    old, new = layer(OLD, "old model", "a" * 64), layer(NEW, "new model", "b" * 64)
    common = {"FRAMES": frame_layer(), "GEOTAGS": geotag_layer()}
    out_json, out_html = tmp_path / "compare.json", tmp_path / "compare.html"
    verdicts = verdict_layer([("u_kept", "confirmed_real", "direct", NEW["kept"])])
    result = run("comparedetectors", {"DETECTIONS_OLD": old, "DETECTIONS_NEW": new, **common, "REVIEW": verdicts,
                                      "OUTPUT": "TEMPORARY_OUTPUT", "OUTPUT_JSON": str(out_json),
                                      "OUTPUT_REPORT": str(out_html)})
    # Old: g1 of 2 in-view geotags, 1 hit of 3 clusters; new: both, 2 hits of 4 clusters.
    assert (result["RECALL_PRE_OLD"], result["RECALL_PRE_NEW"]) == (0.5, 1.0)
    assert result["GMCF_PRE_OLD"] == pytest.approx(1 / 3) and result["GMCF_PRE_NEW"] == 0.5
    assert (result["FOUND_ONLY_BY_NEW"], result["LOST_BY_NEW"], result["FALSE_REMOVED"], result["FALSE_ADDED"]) == (
        1, 0, 1, 1)
    changes = {f["change"]: f for f in result["OUTPUT"].getFeatures()}
    assert sorted(changes) == ["false_added", "false_kept", "false_removed", "found_by_both", "found_only_by_new"]
    assert result["OUTPUT"].crs().authid() == "EPSG:32756"
    assert (changes["found_by_both"]["geotag_id"], changes["found_only_by_new"]["geotag_id"]) == ("1", "2")
    assert site_en(changes["found_only_by_new"]) == (5.0, -5.0)
    assert site_en(changes["false_removed"]) == OLD["removed"] and site_en(changes["false_added"]) == NEW["added"]
    assert site_en(changes["false_kept"]) == OLD["kept"]          # the old cluster's centroid
    assert changes["false_kept"]["n_detections_old"] == changes["false_kept"]["n_detections_new"] == 9
    assert changes["false_kept"]["kind"] == "false_cluster" and changes["found_by_both"]["kind"] == "target"

    doc = json.loads(out_json.read_text(encoding="utf-8"))
    rows = {r["figure"]: r for r in doc["side_by_side"]}
    assert (rows["detections_per_frame"]["before"], rows["detections_per_frame"]["after"]) == (27.0, 36.0)
    assert (rows["n_false_clusters"]["before"], rows["n_false_clusters"]["after"]) == (2, 2)
    # The review confirms the cluster at "kept": c = 1 for both detectors (POST of each, as Evaluate gives).
    assert rows["gmcf_post_majority_wins"]["before"] == pytest.approx(2 / 3)
    assert rows["gmcf_post_majority_wins"]["after"] == pytest.approx(3 / 4)
    assert (doc["before"]["name"], doc["after"]["model_digest"]) == ("old model", "b" * 64)
    # The same figures Evaluate detections writes for each layer alone.
    for key, det in (("before", old), ("after", new)):
        alone = tmp_path / f"{key}.json"
        run("evaluatedetections", {"DETECTIONS": [det], "FRAMES": [common["FRAMES"]], "GEOTAGS": common["GEOTAGS"],
                                   "REVIEW": verdicts, "OUTPUT_JSON": str(alone), "OUTPUT_REPORT": None})
        expected = json.loads(alone.read_text(encoding="utf-8"))
        assert {k: doc[key][k] for k in expected if k != "parameters"} == {
            k: v for k, v in expected.items() if k != "parameters"}
    report = out_html.read_text(encoding="utf-8")
    assert "old model" in report and "false_removed" in report


def test_comparedetectors_refuses_a_layer_that_is_not_detections(birdseye_provider, tmp_path):
    with pytest.raises(QgsProcessingException, match="not a BirdsEye detection layer"):
        run("comparedetectors", {"DETECTIONS_OLD": geotag_layer(), "DETECTIONS_NEW": layer(NEW, "new", "b" * 64),
                                 "FRAMES": frame_layer(), "GEOTAGS": geotag_layer(), "OUTPUT": "TEMPORARY_OUTPUT",
                                 "OUTPUT_JSON": str(tmp_path / "x.json"), "OUTPUT_REPORT": None})
