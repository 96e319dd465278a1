"""What a review decided, acted on through the registry: verdicts become labels (Write labels) and the
clusters it left open become targets of the next flight (Plan the survey flight).

The scene of ``test_cluster_algorithms``: one nadir frame 10 m above level ground at the site (1920 ×
1200 px, fx = fy = 1000 px, so 1 m east = +100 px in u, 1 m north = −100 px in v from the centre
959.5, 599.5). Six clusters of nine detections each; geotag 1 matches A, the review judged the rest.
"""
from __future__ import annotations

import csv
import json

import numpy as np
import pytest
from qgis.core import QgsProcessingException
from test_cluster_algorithms import detection_layer, frame_layer, geotag_layer, grid9, run, verdict_layer

SPOTS = {"A": (-3.0, 0.0),   # matches geotag 1: settled by the survey whatever the review says
         "B": (3.0, 1.0),    # confirmed real, no geotag: a review target
         "C": (6.0, 3.0),    # hard negative
         "D": (-6.0, 3.0),   # uncertain
         "E": (0.0, -4.0),   # conflicting: confirmed directly, rejected by propagation
         "F": (-6.0, -3.0)}  # never judged
UNRESOLVED = {"D": "uncertain", "E": "conflicting", "F": "unreviewed"}


def scene():
    det = detection_layer(np.concatenate([grid9(*xy) for xy in SPOTS.values()]))
    verdicts = verdict_layer([("uA", "hard_negative", "direct", SPOTS["A"]),
                              ("uB", "confirmed_real", "direct", SPOTS["B"]),
                              ("uC", "hard_negative", "direct", SPOTS["C"]),
                              ("uD", "uncertain", "direct", SPOTS["D"]),
                              ("uE", "confirmed_real", "direct", SPOTS["E"]),
                              ("uE", "hard_negative", "propagated:dbscan_0.20m", SPOTS["E"])])
    return det, verdicts


def pixel(east, north):
    return 959.5 + 100.0 * east, 599.5 - 100.0 * north


@pytest.fixture
def frame_image(tmp_path):
    import cv2
    path = tmp_path / "frame0.png"
    cv2.imwrite(str(path), np.full((1200, 1920, 3), 80, np.uint8))
    return str(path)


def test_writelabels_labels_confirmed_clusters_and_draws_hard_negative_tiles_first(birdseye_provider, tmp_path,
                                                                                  frame_image):
    import cv2
    det, verdicts = scene()
    out = tmp_path / "labels"
    result = run("writelabels", {"GEOTAGS": geotag_layer(), "FRAMES": frame_layer(images=[frame_image]),
                                 "SIGMA_PX": 5.0, "WRITE_RASTERS": False, "WRITE_TILES": True, "TILE_SIZE": 224,
                                 # The whole frame is surveyed ground here: the geotags' hull grown by 20 m.
                                 "SURVEY_MARGIN_M": 20.0,
                                 "NEGATIVE_RATIO": 1.0, "REVIEW": verdicts, "REVIEW_DETECTIONS": [det],
                                 "OUTPUT_FOLDER": str(out), "OUTPUT_FRAMES": None,
                                 "OUTPUT_GEOTAGS": "TEMPORARY_OUTPUT"})
    assert (result["REVIEW_TARGETS"], result["HARD_NEGATIVES"]) == (1, 1)
    rows = list(csv.DictReader(open(out / "labels.csv", encoding="utf-8")))
    # Geotags 1 and 2 in view (3 is 15 m east, outside ±9.6 m); B from the review; A (hit), C (hard
    # negative) and the unresolved D, E, F are no targets.
    assert sorted((r["geotag_id"].split("#")[0], r["provenance"]) for r in rows) == [
        ("1", "survey"), ("2", "survey"), ("detections", "review")]
    review = next(r for r in rows if r["provenance"] == "review")
    assert (float(review["u"]), float(review["v"])) == pytest.approx(pixel(*SPOTS["B"]), abs=0.05)
    assert review["label"] == "burrow"                  # the survey's one class
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["provenance"] == {"survey": {"n_targets": 3, "n_in_view": 2, "n_labels": 2},
                                     "review": {"n_targets": 1, "n_in_view": 1, "n_labels": 1}}
    assert summary["hard_negatives"] == {"n_clusters": 1, "n_in_view": 1, "n_frames": 1}
    # C projects to (1559.5, 299.5): tile column 1344, row 224, holding no target. Three positive tiles or
    # more keep as many negatives, the hard one first.
    assert summary["tiles"]["hard_negative"] == 1 and summary["tiles"]["negative"] == summary["tiles"]["positive"]
    hard_tile = cv2.imread(str(out / "tiles" / "labels" / "0_224_1344.png"), cv2.IMREAD_UNCHANGED)
    assert hard_tile is not None and hard_tile.max() == 0
    # The unresolved clusters may be targets: no tile within 3σ = 15 px of one is written. D (359.5, 299.5) lies
    # in tile (224, 224) alone; E (959.5, 999.5) in column 896 of both rows 896 and 976 (the last row is flush
    # with the border); F (359.5, 899.5) in row 896 and 4 px from row 672, column 224: 1 + 2 + 2 tiles.
    assert summary["n_unresolved_in_view"] == 3 and summary["tiles"]["skipped"]["unlabelled_target"] == 5
    # The geotag copy still counts the survey's geotags only.
    assert {f["id"]: f["frames_seen"] for f in result["OUTPUT_GEOTAGS"].getFeatures()} == {1: 1, 2: 1, 3: 0}


def test_writelabels_without_review_is_unchanged_and_refuses_detections_without_verdicts(birdseye_provider, tmp_path):
    det, _ = scene()
    base = {"GEOTAGS": geotag_layer(), "FRAMES": frame_layer(), "WRITE_RASTERS": False, "OUTPUT_FRAMES": None,
            "OUTPUT_GEOTAGS": None}
    result = run("writelabels", {**base, "OUTPUT_FOLDER": str(tmp_path / "plain")})
    assert (result["LABEL_COUNT"], result["REVIEW_TARGETS"], result["HARD_NEGATIVES"]) == (2, 0, 0)
    rows = list(csv.DictReader(open(tmp_path / "plain" / "labels.csv", encoding="utf-8")))
    assert {r["provenance"] for r in rows} == {"survey"}
    with pytest.raises(QgsProcessingException, match="REVIEW_DETECTIONS is given without REVIEW"):
        run("writelabels", {**base, "REVIEW_DETECTIONS": [det], "OUTPUT_FOLDER": str(tmp_path / "x")})


def test_planflight_flies_back_to_the_unresolved_clusters(birdseye_provider):
    det, verdicts = scene()
    review = {"REVIEW": verdicts, "REVIEW_DETECTIONS": [det], "REVIEW_FRAMES": [frame_layer()],
              "MERGE_RADIUS_M": 0.5, "OUTPUT_WAYPOINTS": "TEMPORARY_OUTPUT", "OUTPUT_ROUTE": "TEMPORARY_OUTPUT"}
    result = run("planflight", {"GEOTAGS": geotag_layer(), **review})
    assert (result["GEOTAG_COUNT"], result["UNRESOLVED_COUNT"], result["WAYPOINT_COUNT"]) == (3, 3, 6)
    waypoints = list(result["OUTPUT_WAYPOINTS"].getFeatures())
    assert sorted(f["provenance"] for f in waypoints) == ["review"] * 3 + ["survey"] * 3
    assert sorted(f["review_outcomes"] for f in waypoints if f["provenance"] == "review") == sorted(
        UNRESOLVED.values())
    assert all(f["geotag_ids"].startswith("detections#") for f in waypoints if f["provenance"] == "review")

    only = run("planflight", {"GEOTAGS": geotag_layer(), "UNRESOLVED_ONLY": True, **review})
    assert (only["GEOTAG_COUNT"], only["UNRESOLVED_COUNT"], only["WAYPOINT_COUNT"]) == (0, 3, 3)
    # Each waypoint sits on its cluster: the unresolved spots, and nothing else, are visited.
    from test_cluster_algorithms import SITE

    visited = []
    for f in only["OUTPUT_WAYPOINTS"].getFeatures():
        east, north, _ = SITE.from_geodetic(f["lat"], f["lon"], SITE.h0).reshape(3)
        visited.append((round(east, 2), round(north, 2), f["review_outcomes"]))
    assert sorted(visited) == sorted((*SPOTS[k], outcome) for k, outcome in UNRESOLVED.items())

    with pytest.raises(QgsProcessingException, match="UNRESOLVED_ONLY needs a review"):
        run("planflight", {"GEOTAGS": geotag_layer(), "UNRESOLVED_ONLY": True,
                           "OUTPUT_WAYPOINTS": "TEMPORARY_OUTPUT", "OUTPUT_ROUTE": "TEMPORARY_OUTPUT"})
    with pytest.raises(QgsProcessingException, match="REVIEW_DETECTIONS"):
        run("planflight", {"GEOTAGS": geotag_layer(), "REVIEW": verdicts, "OUTPUT_WAYPOINTS": "TEMPORARY_OUTPUT",
                           "OUTPUT_ROUTE": "TEMPORARY_OUTPUT"})
