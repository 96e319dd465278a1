"""A cluster's review outcome over all its judgements: agreed, conflicting, abstained or never judged."""
import pytest

from birdseye.birdseye_qgis.core.scoring.reviewed_clusters import ReviewedCluster, cluster_outcome
from birdseye.birdseye_qgis.core.scoring.verdicts import VerdictLog


def log(*rows):
    return VerdictLog.from_records([{"unit_key": u, "verdict": v, "provenance": p} for u, v, p in rows])


@pytest.mark.parametrize("rows, units, outcome", [
    ([("u1", "confirmed_real", "direct"), ("u2", "uncertain", "direct")], ("u1", "u2"), "confirmed_real"),
    ([("u1", "hard_negative", "direct"), ("u1", "hard_negative", "propagated:dbscan_0.20m")], ("u1",),
     "hard_negative"),
    # two to one is a majority, yet the conventions disagree: no training label, a spot to revisit
    ([("u1", "confirmed_real", "direct"), ("u2", "confirmed_real", "direct"),
      ("u2", "hard_negative", "propagated:dbscan_0.20m")], ("u1", "u2"), "conflicting"),
    ([("u1", "uncertain", "direct")], ("u1",), "uncertain"),
    ([("u1", "confirmed_real", "direct"), ("u1", "unreviewed", "direct")], ("u1",), "unreviewed"),  # withdrawn
    ([("u1", "confirmed_real", "direct")], (), "unreviewed"),                # no unit attached to the cluster
])
def test_cluster_outcome_by_hand(rows, units, outcome):
    assert cluster_outcome(log(*rows), units) == outcome


def test_a_geotag_settles_a_cluster_whatever_the_review_says():
    def cluster(hit, outcome):
        return ReviewedCluster("det", 0, 0.0, 0.0, hit, outcome, 9)

    assert cluster(False, "confirmed_real").is_target and not cluster(True, "confirmed_real").is_target
    assert cluster(False, "hard_negative").is_hard_negative and not cluster(True, "hard_negative").is_hard_negative
    assert [cluster(False, o).is_unresolved for o in ("conflicting", "uncertain", "unreviewed", "confirmed_real")] == [
        True, True, True, False]
    assert not cluster(True, "unreviewed").is_unresolved
    assert cluster(False, "uncertain").key == "det#0"
