"""The transfer report against hand computations: survey density (in-view geotags per frame), the validation →
held-out changes of recall and GMCF, and Spearman's ρ across checkpoints (ties, too few checkpoints, no ranking)."""
import numpy as np
import pytest
from test_scoring import OP, SITE, all_geotags, flights, geodetic, poses_over

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.scoring.evaluation import evaluate_flights
from birdseye.birdseye_qgis.core.scoring.matching import in_view
from birdseye.birdseye_qgis.core.scoring.pre_review import PreCounts
from birdseye.birdseye_qgis.core.scoring.reports import evaluation_report_html, screening_report_html
from birdseye.birdseye_qgis.core.scoring.screening import CheckpointScreen
from birdseye.birdseye_qgis.core.scoring.transfer import (
    SurveyDensity,
    rank_correlation,
    transfer_report,
)


# -------------------------------------------------------------------- survey density
def test_each_processed_frame_counts_the_points_in_its_own_view():
    """Frames at 0 and 15 m east see ±9.6 m east of themselves; the third has no ground height (not processed)."""
    p = poses_over([[0.0, 0.0], [15.0, 0.0], [40.0, 0.0]])
    p.ground_height[2] = np.nan
    east = [-5.0, 0.0, 7.0, 20.0, 30.0, 40.0]   # frame 0: -5, 0, 7; frame 1: 7, 20; none: 30; 40 (unprocessed)
    pts = SITE.from_geodetic(*geodetic(np.column_stack([east, np.zeros(6)])))
    v = in_view([p], SITE, pts)
    np.testing.assert_array_equal(v.per_frame, [3, 2])
    assert v.n_frames == len(v.per_frame) == 2
    assert in_view([p], SITE, np.empty((0, 3))).per_frame.tolist() == [0, 0]


def test_survey_density_summary_by_hand():
    d = SurveyDensity.of([[0, 1, 3, 4], [2]])     # pooled: 0, 1, 2, 3, 4
    assert (d.n_frames, d.mean, d.median, d.min, d.max) == (5, 2.0, 2.0, 0, 4)
    # linear interpolation: the 10th percentile lies 0.1 · 4 = 0.4 of the way up the sorted counts
    assert d.p10 == pytest.approx(0.4) and d.p90 == pytest.approx(3.6)
    assert d.frames_without_geotag == pytest.approx(1 / 5)
    empty = SurveyDensity.of([])
    assert empty.n_frames == 0 and empty.mean is None and empty.to_dict()["frames_without_geotag"] is None


def test_evaluate_detections_reports_the_survey_density_per_flight_and_pooled():
    """Flight 1's one frame sees g1, g_border, g2, g4 and g5 (5); flight 2's sees h1 and h2 (2)."""
    d = evaluate_flights(flights(), all_geotags(), OP).to_dict()
    assert [f["survey_density"]["mean"] for f in d["flights"]] == [5.0, 2.0]
    assert d["survey_density"]["n_frames"] == 2 and d["survey_density"]["mean"] == 3.5
    assert d["survey_density"]["frames_without_geotag"] == 0.0


# -------------------------------------------------------------------- Spearman's ρ
def test_spearman_rho_by_hand():
    # ranks 4 3 2 1 against 3 4 2 1: Σd² = 2, ρ = 1 − 6·2 / (4·(4² − 1)) = 0.8
    r = rank_correlation([0.9, 0.8, 0.7, 0.6], [0.5, 0.7, 0.4, 0.3])
    assert r.rho == pytest.approx(0.8) and r.n == 4 and r.note == ""


def test_spearman_rho_gives_tied_figures_their_average_rank():
    # validation ranks 4, 2.5, 2.5, 1 (0.8 twice); held-out ranks 2, 3, 1, 4: Pearson's r of the ranks,
    # deviations (1.5, 0, 0, −1.5) and (−0.5, 0.5, −1.5, 1.5): −3 / √(4.5 · 5)
    r = rank_correlation([0.9, 0.8, 0.8, 0.6], [0.2, 0.3, 0.1, 0.4])
    assert r.rho == pytest.approx(-3 / np.sqrt(4.5 * 5))


def test_too_few_checkpoints_or_no_ranking_give_a_reason_not_nan():
    two = rank_correlation([0.9, 0.8, None], [0.5, 0.7, 0.6])
    assert two.rho is None and two.n == 2 and two.note.startswith("not enough checkpoints: 2")
    flat = rank_correlation([0.5, 0.5, 0.5], [0.1, 0.2, 0.3])
    assert flat.rho is None and flat.n == 3 and "no ranking" in flat.note and "validation" in flat.note
    assert "held-out" in rank_correlation([0.1, 0.2, 0.3], [1.0, 1.0, 1.0]).note


# -------------------------------------------------------------------- validation → held-out
def screen(name, in_view_, recovered, clusters, hit, healthy=True):
    return CheckpointScreen(name, PreCounts(in_view_, recovered, clusters, hit), 30, 10, 0.9, 3.0, "b", 0, 0, 0, 10.0,
                            collapsed=not healthy, too_sparse=False)


def test_deltas_and_rank_correlations_across_the_healthy_checkpoints():
    validation = [screen("a", 10, 9, 20, 10), screen("b", 10, 8, 10, 8), screen("c", 10, 6, 8, 4),
                  screen("d", 10, 5, 5, 5, healthy=False)]
    heldout = [screen("b", 20, 14, 10, 3), screen("a", 20, 16, 10, 2), screen("c", 20, 10, 4, 1),
               screen("d", 20, 20, 10, 9)]
    report = transfer_report(validation, heldout)
    rows = {t.checkpoint: t for t in report.checkpoints}
    assert [t.checkpoint for t in report.checkpoints] == ["a", "b", "c", "d"]
    # a: recall 0.9 → 0.8, GMCF 0.5 → 0.2
    assert rows["a"].delta_recall == pytest.approx(0.8 - 0.9) and rows["a"].delta_gmcf == pytest.approx(0.2 - 0.5)
    assert rows["c"].delta_recall == pytest.approx(0.5 - 0.6) and rows["c"].delta_gmcf == pytest.approx(0.25 - 0.5)
    # over a, b, c (d is unhealthy): recall 0.9, 0.8, 0.6 → 0.8, 0.7, 0.5: same order, ρ = 1;
    # GMCF 0.5, 0.8, 0.5 (ranks 1.5, 3, 1.5) → 0.2, 0.3, 0.25 (ranks 1, 3, 2): rank deviations
    # (−0.5, 1, −0.5) and (−1, 1, 0), r = 1.5 / √(1.5 · 2)
    assert report.recall.rho == pytest.approx(1.0) and report.recall.n == 3
    assert report.gmcf.rho == pytest.approx(1.5 / np.sqrt(3.0))
    d = report.to_dict()
    assert d["checkpoints"][0]["recall_validation"] == 0.9 and d["checkpoints"][0]["recall_heldout"] == 0.8
    assert d["checkpoints"][3]["healthy_on_validation"] is False
    assert d["spearman"]["gmcf"]["spearman_rho"] == pytest.approx(1.5 / np.sqrt(3.0))
    # an undefined figure (no cluster on the held-out flights) has no change, and leaves the ranking
    empty = transfer_report(validation[:2], [screen("a", 20, 16, 10, 2), screen("b", 20, 0, 0, 0)])
    assert {t.checkpoint: t.delta_gmcf for t in empty.checkpoints}["b"] is None
    assert empty.gmcf.rho is None and empty.gmcf.n == 1


def test_held_out_flights_must_be_screened_with_the_same_checkpoints():
    with pytest.raises(InputError, match="HELDOUT_FRAMES.*not on held-out flights: b"):
        transfer_report([screen("a", 1, 1, 1, 1), screen("b", 1, 1, 1, 1)], [screen("a", 1, 1, 1, 1)])


def test_the_reports_show_the_density_and_the_transfer():
    from birdseye.birdseye_qgis.core.scoring.operating_point import OperatingPoint

    html = evaluation_report_html(evaluate_flights(flights(), all_geotags(), OP))
    assert "Survey density" in html and "geotags per frame (mean)" in html and "3.500" in html
    validation = [screen("a", 10, 9, 20, 10), screen("b", 10, 8, 10, 8)]
    heldout = [screen("a", 20, 16, 10, 2), screen("b", 20, 14, 10, 3)]
    report = transfer_report(validation, heldout)
    density = {"f": SurveyDensity.of([[1, 2]]), "pooled": SurveyDensity.of([[1, 2]])}
    html = screening_report_html(OperatingPoint(0.03), validation, density, heldout, density, report)
    assert "Validation → held-out" in html and "-0.100" in html        # a's ΔRecall 0.8 − 0.9
    assert "not enough checkpoints: 2" in html and "core_count = detections" in html
