"""Two detectors compared on one flight: the change classification by hand, and the figures are those
Evaluate detections gives each layer alone.

One level nadir frame 10 m over the site (footprint ±9.6 m east, ±6 m north; the scene of
test_scoring.py). Clusters are 3 × 3 grids of 4 cm step; EPS 0.10 m, MIN_SAMPLES 3, EPS_PRED 0.20 m.
"""
import numpy as np
import pytest
from test_scoring import SITE, detections, geodetic, grid9, poses_over

from birdseye.birdseye_qgis.core.field.geotags import Geotags
from birdseye.birdseye_qgis.core.scoring.compare import compare_detectors
from birdseye.birdseye_qgis.core.scoring.evaluation import Detections, Flight, evaluate_flights
from birdseye.birdseye_qgis.core.scoring.operating_point import OperatingPoint

OP = OperatingPoint(threshold=None, dedup_cm=3, eps_m=0.10, min_samples=3, eps_pred_m=0.20)
GEOTAGS = {"g0": (-8.0, 0.0),   # found by both
           "g1": (-4.0, 0.0),   # only the old detector
           "g2": (0.0, 0.0),    # only the new one
           "g3": (4.0, 0.0),    # neither
           "g4": (20.0, 0.0)}   # out of view: in no change
OLD = {"c_g0": (-8.0, 0.0), "c_g1": (-4.0, 0.0),
       "f1": (6.0, 3.0),       # false in both: the new F1 is 0.10 m east (core points 2 cm apart)
       "f2": (6.0, -3.0),      # false, gone in the new
       "f4": (-6.0, -4.0)}     # false, gone in the new
NEW = {"c_g0": (-8.0, 0.0), "c_g2": (0.0, 0.0), "f1": (6.1, 3.0),
       "f3": (-6.0, 4.0)}      # false, new


def layer(spots, name):
    return detections(np.concatenate([grid9(*xy) for xy in spots.values()]), name)


def geotags():
    lat, lon, _ = geodetic(list(GEOTAGS.values()))
    return Geotags(list(GEOTAGS), lat, lon, np.full(len(lat), np.nan))


def test_changes_by_hand():
    frames = [poses_over([0.0, 0.0])]
    comparison = compare_detectors(layer(OLD, "old"), layer(NEW, "new"), frames, geotags(), OP)
    got = [(c.change, c.kind, None if c.geotag is None else list(GEOTAGS)[c.geotag]) for c in comparison.changes]
    assert got[:4] == [("found_by_both", "target", "g0"), ("lost_by_new", "target", "g1"),
                       ("found_only_by_new", "target", "g2"), ("missed_by_both", "target", "g3")]
    local = comparison.before.local        # the flight's frame, not the site's: back to site metres

    def site(x, y):
        lat, lon, h = local.to_geodetic(np.array([x, y, 0.0]))
        east, north, _ = SITE.from_geodetic(lat, lon, h).reshape(3)
        return round(float(east), 3), round(float(north), 3)

    clusters = sorted((c.change, *site(c.x, c.y)) for c in comparison.changes[4:])
    assert clusters == [("false_added", -6.0, 4.0), ("false_kept", 6.0, 3.0), ("false_removed", -6.0, -4.0),
                        ("false_removed", 6.0, -3.0)]
    kept = next(c for c in comparison.changes if c.change == "false_kept")
    assert site(*comparison.after.flights[0].clustering.summary.centroid[kept.cluster_new]) == (6.1, 3.0)
    assert comparison.counts() == {"found_by_both": 1, "found_only_by_new": 1, "lost_by_new": 1, "missed_by_both": 1,
                                   "false_removed": 2, "false_added": 1, "false_kept": 1}


def test_figures_side_by_side_are_evaluate_detections_figures():
    frames = [poses_over([0.0, 0.0])]
    old, new = layer(OLD, "old"), layer(NEW, "new")
    comparison = compare_detectors(old, new, frames, geotags(), OP)
    rows = {r["figure"]: r for r in comparison.side_by_side()}
    # Old: 5 clusters, 2 hit, 2 of 4 in-view geotags; new: 4 clusters, 2 hit, 2 of 4; one frame.
    assert (rows["recall_pre"]["before"], rows["recall_pre"]["after"]) == (0.5, 0.5)
    assert (rows["gmcf_pre"]["before"], rows["gmcf_pre"]["after"]) == (0.4, 0.5)
    assert rows["gmcf_pre"]["difference"] == pytest.approx(0.1)
    assert (rows["n_false_clusters"]["before"], rows["n_false_clusters"]["after"]) == (3, 2)
    assert (rows["detections_per_frame"]["before"], rows["detections_per_frame"]["after"]) == (45.0, 36.0)
    for det, evaluation in ((old, comparison.before), (new, comparison.after)):
        alone = evaluate_flights([Flight(det, frames, det.name)], geotags(), OP).to_dict()
        assert {k: v for k, v in evaluation.to_dict().items()} == alone
    d = comparison.to_dict()
    assert (d["before"]["name"], d["after"]["name"]) == ("old", "new") and d["changes"]["false_added"] == 1


def test_frames_against_a_mosaic_count_one_set_of_targets_and_a_mosaic_detection_is_a_cluster():
    """The frames' layer is OLD; the mosaic shows each target once: one detection on g0, g2 and g4 (g4 is out
    of the frame's view) and one false spot. The raster covers every geotag but g3. Both are scored over g0, g1
    and g2 (in view of the frame *and* on the raster): the frames found g0, g1 (2 of 3), the mosaic g0, g2
    (2 of 3). Its detection on g4 lies beyond the frame's view, where the frames could find nothing: left out.
    Its 3 other single detections are 3 clusters (a core test of one), 2 on a geotag."""
    from dataclasses import replace

    from birdseye.birdseye_qgis.core.errors import InputError
    from birdseye.birdseye_qgis.core.geometry.ground_record import RASTER, GroundRecord

    frames = [poses_over([0.0, 0.0])]
    lat, lon, h = geodetic([GEOTAGS["g0"], GEOTAGS["g2"], GEOTAGS["g4"], (2.0, -2.0)])
    mosaic = Detections(lat, lon, np.full(4, np.nan), np.zeros(4, int), np.full(4, 0.8), name="mosaic",
                        ground=GroundRecord(RASTER, "ortho.tif"))
    inside_raster = np.array([True, True, True, False, True])
    old = layer(OLD, "frames")
    comparison = compare_detectors(old, mosaic, frames, geotags(), OP, inside_raster=inside_raster)
    before, after = comparison.before.pooled, comparison.after.pooled
    assert (before.n_in_view, before.n_recovered) == (after.n_in_view, after.n_recovered) == (3, 2)
    assert (after.n_clusters, after.n_hit_clusters) == (3, 2)
    assert comparison.counts()["found_by_both"] == 1 and comparison.counts()["lost_by_new"] == 1
    assert comparison.counts()["found_only_by_new"] == 1 and comparison.counts()["missed_by_both"] == 0
    # The frames' layer alone is scored over g0–g3 (g3 in view): the raster took g3 out of both.
    assert evaluate_flights([Flight(old, frames, "frames")], geotags(), OP).pooled.n_in_view == 4
    with pytest.raises(InputError, match="give that raster"):
        compare_detectors(old, mosaic, frames, geotags(), OP)
    with pytest.raises(InputError, match="one ground|placed on"):
        compare_detectors(old, replace(old, ground=GroundRecord("dem", "d.tif", "ellipsoidal")), frames,
                          geotags(), OP)
