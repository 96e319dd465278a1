"""De-duplication, DBSCAN and cluster summaries against hand-computed fixtures and scikit-learn."""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.detect.clustering import (
    GRID_TILE_DEG,
    GroundPositions,
    cluster_detections,
    cluster_hulls,
    dbscan,
    deduplicate,
    fixed_grid_cells,
    neighbour_graph,
    summarize_clusters,
)
from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame

# A local frame at a corner of the fixed de-duplication grid: its cells are the floor of local x/y / cell.
CORNER = LocalFrame(1000 * GRID_TILE_DEG, 200 * GRID_TILE_DEG)


def on_ground(xy, local=CORNER) -> GroundPositions:
    return GroundPositions.from_local(local, np.asarray(xy, dtype=float))


def test_deduplicate_merges_detections_of_one_cell_into_their_mean():
    xy = np.array([[0.001, 0.001], [0.021, 0.011],    # cell (0, 0)
                   [0.031, 0.002],                      # cell (1, 0)
                   [-0.001, 0.005],                     # cell (-1, 0): floor, not truncation
                   [0.011, 0.029]])                     # cell (0, 0)
    d = deduplicate(on_ground(xy), 0.03)
    assert len(d) == 3
    cell00 = d.inverse[0]
    assert d.inverse[1] == cell00 and d.inverse[4] == cell00
    assert len({d.inverse[2], d.inverse[3], cell00}) == 3
    np.testing.assert_allclose(d.xy[cell00], [(0.001 + 0.021 + 0.011) / 3, (0.001 + 0.011 + 0.029) / 3])
    np.testing.assert_allclose(d.xy[d.inverse[3]], [-0.001, 0.005])
    assert d.count[cell00] == 3 and d.count.sum() == 5


def test_deduplication_and_labels_do_not_depend_on_detection_order():
    rng = np.random.default_rng(3)
    xy = np.concatenate([rng.normal([1, 1], 0.03, (60, 2)), rng.normal([3, 1], 0.03, (60, 2)),
                         rng.uniform(0, 4, (30, 2))])
    a = cluster_detections(on_ground(xy), np.arange(len(xy)), rng.uniform(0, 1, len(xy)))
    perm = rng.permutation(len(xy))
    b = cluster_detections(on_ground(xy[perm]), np.arange(len(xy))[perm], None)
    np.testing.assert_allclose(a.points.xy, b.points.xy, atol=1e-12)
    np.testing.assert_array_equal(a.dbscan.labels, b.dbscan.labels)
    np.testing.assert_array_equal(a.detection_cluster[perm], b.detection_cluster)


def test_chained_points_form_one_cluster_with_border_ends():
    """Nine points 8 cm apart on a line, eps 10 cm, min_samples 3: the interior points have three
    points (themselves and two neighbours) within eps and are core; the two ends have two and are
    border points; DBSCAN chains all nine into one 64 cm long cluster."""
    xy = np.column_stack([np.arange(9) * 0.08, np.zeros(9)])
    c = cluster_detections(on_ground(xy), np.arange(9), None, dedup_cm=3, eps_m=0.10, min_samples=3)
    assert c.n_clusters == 1
    np.testing.assert_array_equal(c.dbscan.labels, 0)
    np.testing.assert_array_equal(c.dbscan.core, [False] + [True] * 7 + [False])
    # Centroid at 0.32 m; distances 0.32, 0.24, 0.16, 0.08, 0, 0.08, ... → median 0.16 → extent 0.32 m.
    np.testing.assert_allclose(c.summary.centroid[0], [0.32, 0.0], atol=1e-12)
    np.testing.assert_allclose(c.summary.median_extent_m[0], 0.32, atol=1e-12)


def test_isolated_and_sparse_points_are_noise():
    xy = np.array([[0, 0], [0.05, 0], [5, 5], [10, 0]], dtype=float)
    c = cluster_detections(on_ground(xy), None, None, eps_m=0.10, min_samples=3)
    assert c.n_clusters == 0
    np.testing.assert_array_equal(c.dbscan.labels, -1)
    np.testing.assert_array_equal(c.detection_cluster, -1)
    assert not c.dbscan.core.any()


def test_the_methods_cells_reading_counts_each_occupied_cell_once():
    """Twenty detections in one 3 cm cell are one de-duplicated point: under the method's reading
    (core_count "cells") never a cluster at min_samples 3."""
    xy = np.full((20, 2), 0.005) + np.linspace(0, 0.02, 20)[:, None]
    c = cluster_detections(on_ground(xy), np.arange(20), None, dedup_cm=3, eps_m=0.10, min_samples=3,
                           core_count="cells")
    assert len(c.points) == 1 and c.n_clusters == 0
    c1 = cluster_detections(on_ground(xy), np.arange(20), None, dedup_cm=3, eps_m=0.10, min_samples=1,
                            core_count="cells")
    assert c1.n_clusters == 1 and c1.summary.n_detections[0] == 20 and c1.summary.n_frames[0] == 20


def test_by_default_the_core_test_counts_the_detections_of_each_cell():
    """The same twenty detections in one cell weigh 20: a cluster at min_samples 3 (and 20), noise at 21."""
    xy = np.full((20, 2), 0.005) + np.linspace(0, 0.02, 20)[:, None]
    for m, clusters in ((3, 1), (20, 1), (21, 0)):
        c = cluster_detections(on_ground(xy), np.arange(20), None, dedup_cm=3, eps_m=0.10, min_samples=m)
        assert len(c.points) == 1 and c.n_clusters == clusters and c.core_count == "detections"
    # Two cells 5 cm apart with 1 and 2 detections: 3 detections within eps of each, no cell holds 3 alone.
    xy = np.array([[0.005, 0.005], [0.055, 0.005], [0.056, 0.006]])
    c = cluster_detections(on_ground(xy), None, None, dedup_cm=3, eps_m=0.06, min_samples=3)
    np.testing.assert_array_equal(c.points.count, [1, 2])
    assert c.n_clusters == 1 and c.dbscan.core.all()
    assert cluster_detections(on_ground(xy), None, None, dedup_cm=3, eps_m=0.04, min_samples=3).n_clusters == 0


def test_weighted_graph_degree_sums_the_weights_within_eps():
    xy = np.array([[0, 0], [0.05, 0], [0.15, 0], [1, 1]], dtype=float)
    g = neighbour_graph(xy, 0.2)
    w = np.array([4, 1, 2, 7])
    np.testing.assert_array_equal(g.degree(0.2, w), [7, 7, 7, 7])
    np.testing.assert_array_equal(g.degree(0.1, w), [5, 7, 3, 7])


def tight_targets(seed=30, n_targets=30, sigma_m=0.003, cell_m=0.03):
    """Hand-made detections of refined poses: ``n_targets`` targets 1 m apart, each detected 2 to 40
    times with a 3 mm scatter. A third sit on a crossing of two grid lines, a third on one grid line, a
    third in the middle of a cell (their detections all fall in one cell). Returns detections (N, 2),
    the target of each, the targets (T, 2), in the local frame CORNER at a corner of the fixed grid."""
    rng = np.random.default_rng(seed)
    row, col = np.divmod(np.arange(n_targets), 6)
    base = np.column_stack([col, row]).astype(float) * 1.0 + 0.3
    base = np.round(base / cell_m) * cell_m                     # on a crossing of grid lines
    kind = np.arange(n_targets) % 3
    offset = np.where(kind[:, None] == 0, 0.0, np.where(kind[:, None] == 1, [0.0, 0.5 * cell_m], 0.5 * cell_m))
    targets = base + offset
    n = rng.integers(2, 41, n_targets)
    owner = np.repeat(np.arange(n_targets), n)
    return targets[owner] + rng.normal(0, sigma_m, (len(owner), 2)), owner, targets


def test_tightly_localised_detections_recover_every_target_by_default_and_straddling_decides_under_cells():
    """The reviewer's reproduction: 3 mm scatter, min_samples 2, EPS 0.20 m, EPS_PRED 0.20 m. Counting
    detections recovers every target (each has ≥ 2 detections); counting cells recovers exactly the targets
    whose detections straddle a grid line (≥ 2 occupied cells), derived here from the grid cells alone."""
    from birdseye.birdseye_qgis.core.scoring.pre_review import score_flight

    xy, owner, targets = tight_targets()
    positions = on_ground(xy)
    everywhere = np.ones(len(targets), dtype=bool)
    default = cluster_detections(positions, None, None)
    score = score_flight(default, targets, everywhere, 0.20)
    assert score.counts.recall_pre == 1.0 and default.n_clusters == len(targets)
    assert score.counts.gmcf_pre == 1.0
    np.testing.assert_array_equal(np.sort(default.summary.n_detections), np.sort(np.bincount(owner)))

    cells = fixed_grid_cells(positions.lat, positions.lon, 0.03)
    occupied = np.array([len(np.unique(cells[owner == t], axis=0)) for t in range(len(targets))])
    method = cluster_detections(positions, None, None, core_count="cells")
    recovered = score_flight(method, targets, everywhere, 0.20).recovered
    np.testing.assert_array_equal(recovered, occupied >= 2)
    assert 0 < recovered.sum() < len(targets)


@pytest.mark.parametrize("core_count", ["detections", "cells"])
def test_one_detection_per_cell_clusters_alike_under_both_readings(core_count):
    """With every cell holding one detection the two readings coincide (the chain of nine below)."""
    xy = np.column_stack([np.arange(9) * 0.08, np.zeros(9)])
    c = cluster_detections(on_ground(xy), np.arange(9), None, dedup_cm=3, eps_m=0.10, min_samples=3,
                           core_count=core_count)
    assert c.n_clusters == 1
    np.testing.assert_array_equal(c.dbscan.core, [False] + [True] * 7 + [False])


def test_cluster_summary_by_hand():
    # Cluster 0: four detections around (1, 2) from frames 7, 7, 8, 9; cluster 1: two detections; one noise.
    xy = np.array([[1.01, 2.0], [0.99, 2.0], [1.0, 2.02], [1.0, 1.98], [5.0, 5.0], [5.0, 5.1], [9.0, 9.0]])
    cluster = np.array([0, 0, 0, 0, 1, 1, -1])
    frames = np.array([7, 7, 8, 9, 1, 1, 3])
    score = np.array([0.5, 0.9, 0.6, 0.7, 0.3, 0.4, 0.99])
    s = summarize_clusters(xy, cluster, 2, frames, score)
    np.testing.assert_allclose(s.centroid, [[1.0, 2.0], [5.0, 5.05]], atol=1e-12)
    np.testing.assert_array_equal(s.n_detections, [4, 2])
    np.testing.assert_array_equal(s.n_frames, [3, 1])
    # distances 0.01, 0.01, 0.02, 0.02 → median 0.015 → extent 0.03; cluster 1: 0.05, 0.05 → 0.1
    np.testing.assert_allclose(s.median_extent_m, [0.03, 0.10], atol=1e-12)
    np.testing.assert_allclose(s.max_score, [0.9, 0.4])


@pytest.mark.parametrize("seed", range(4))
def test_dbscan_matches_scikit_learn_on_raw_points_for_every_eps_and_min_samples_of_one_graph(seed):
    """One radius graph at the largest eps answers every smaller eps and every min_samples exactly as
    scikit-learn's DBSCAN run from scratch on the coordinates (labels, core points, border rule)."""
    from sklearn.cluster import DBSCAN

    rng = np.random.default_rng(seed)
    centres = rng.uniform(0, 3, (12, 2))
    xy = np.concatenate([centres[rng.integers(0, 12, 400)] + rng.normal(0, 0.04, (400, 2)),
                         rng.uniform(0, 3, (150, 2))])
    points = deduplicate(on_ground(xy), 0.03)
    graph = neighbour_graph(points.xy, 0.16)
    for eps in (0.05, 0.08, 0.12, 0.16):
        for m in (1, 2, 3, 5, 8):
            ours = dbscan(graph, eps, m)
            ref = DBSCAN(eps=eps, min_samples=m).fit(points.xy)
            np.testing.assert_array_equal(ours.labels, ref.labels_)
            np.testing.assert_array_equal(np.flatnonzero(ours.core), np.sort(ref.core_sample_indices_))
            assert ours.n_clusters == len(set(ref.labels_) - {-1})


@pytest.mark.parametrize("seed", range(4))
def test_counting_detections_is_scikit_learns_dbscan_with_the_cell_counts_as_sample_weight(seed):
    """Core points by summed detections within eps (itself included) ≥ min_samples, on one radius graph for
    every eps and min_samples, equal scikit-learn's DBSCAN fitted with sample_weight = detections per cell."""
    from sklearn.cluster import DBSCAN

    rng = np.random.default_rng(seed)
    centres = rng.uniform(0, 3, (12, 2))
    xy = np.concatenate([centres[rng.integers(0, 12, 600)] + rng.normal(0, 0.01, (600, 2)),
                         rng.uniform(0, 3, (150, 2))])
    points = deduplicate(on_ground(xy), 0.03)
    assert points.count.max() > 5      # cells of many detections: the weights matter
    graph = neighbour_graph(points.xy, 0.16)
    for eps in (0.03, 0.05, 0.08, 0.16):
        for m in (1, 2, 3, 5, 8, 20):
            ours = dbscan(graph, eps, m, points.weights("detections"))
            ref = DBSCAN(eps=eps, min_samples=m).fit(points.xy, sample_weight=points.count)
            np.testing.assert_array_equal(ours.labels, ref.labels_)
            np.testing.assert_array_equal(np.flatnonzero(ours.core), np.sort(ref.core_sample_indices_))


def test_graph_degree_counts_self_and_neighbours_within_eps():
    xy = np.array([[0, 0], [0.05, 0], [0.15, 0], [1, 1]], dtype=float)
    g = neighbour_graph(xy, 0.2)
    np.testing.assert_array_equal(g.degree(0.2), [3, 3, 3, 1])
    np.testing.assert_array_equal(g.degree(0.1), [2, 3, 2, 1])
    with pytest.raises(ValueError):
        g.degree(0.3)


def test_single_point_hull_is_the_circumscribed_polygon_of_the_buffer():
    r, edges = 0.03, 16
    ring = cluster_hulls(np.array([[2.0, -1.0]]), np.array([0]), 1, r, edges)[0]
    np.testing.assert_allclose(np.hypot(*(ring - [2.0, -1.0]).T), r / np.cos(np.pi / edges), rtol=1e-12)
    assert polygon_area(ring) == pytest.approx(edges * r * r * np.tan(np.pi / edges), rel=1e-12)


def test_segment_hull_area_is_buffer_polygon_plus_length_times_width():
    """Minkowski sum of a segment (along x) with the circumscribed 16-gon (width 2r across x)."""
    r, length = 0.03, 0.4
    xy = np.column_stack([np.linspace(0, length, 7), np.zeros(7)])
    ring = cluster_hulls(xy, np.zeros(7, int), 1, r, 16)[0]
    assert polygon_area(ring) == pytest.approx(16 * r * r * np.tan(np.pi / 16) + 2 * r * length, rel=1e-12)


def test_hulls_contain_every_detection_with_the_buffer_and_stay_close_to_the_exact_grown_hull():
    from scipy.spatial import ConvexHull

    rng = np.random.default_rng(11)
    xy = np.concatenate([rng.normal([0, 0], 0.05, (50, 2)), rng.normal([1, 0], 0.02, (5, 2)),
                         [[3.0, 3.0]], [[4.0, 4.0], [4.3, 4.1]], rng.uniform(5, 6, (20, 2))])
    cluster = np.array([0] * 50 + [1] * 5 + [2] + [3, 3] + [-1] * 20)
    r, edges = 0.03, 32
    rings = cluster_hulls(xy, cluster, 4, r, edges)
    assert rings.shape == (4, edges, 2)
    for k in range(4):
        ring, pts = rings[k], xy[cluster == k]
        assert polygon_area(ring) > 0, "rings are counter-clockwise"
        edge = np.roll(ring, -1, axis=0) - ring
        normal = np.column_stack([edge[:, 1], -edge[:, 0]]) / np.hypot(*edge.T)[:, None]  # outward for CCW
        inside = np.einsum("ej,pej->pe", normal, ring[None] - pts[:, None])
        assert inside.min() >= r - 1e-12, "every detection lies at least the buffer inside every edge"
        hull = pts[ConvexHull(pts).vertices] if len(pts) > 2 else pts
        longest = np.hypot(*(np.roll(hull, -1, axis=0) - hull).T).max() if len(hull) > 1 else 0.0
        overshoot = (r * 2 * np.pi / edges + longest) * np.tan(np.pi / edges) / 2
        for vertex in ring:
            assert distance_to_convex(vertex, hull) - r <= overshoot + 1e-12


def test_bad_parameters_are_input_errors_naming_the_parameter():
    with pytest.raises(InputError, match="DEDUP_CM"):
        deduplicate(on_ground(np.zeros((2, 2))), 0.0)
    with pytest.raises(InputError, match="EPS_M"):
        neighbour_graph(np.zeros((2, 2)), 0.0)
    with pytest.raises(InputError, match="MIN_SAMPLES"):
        dbscan(neighbour_graph(np.zeros((2, 2)), 0.1), 0.1, 0)
    with pytest.raises(InputError, match="CORE_COUNT.*detections, cells"):
        cluster_detections(on_ground(np.zeros((2, 2))), core_count="points")
    with pytest.raises(InputError, match="no position"):
        on_ground([[0.0, np.nan]])


def test_empty_detections_give_no_clusters():
    c = cluster_detections(on_ground(np.empty((0, 2))), np.empty(0), np.empty(0))
    assert c.n_clusters == 0 and len(c.points) == 0 and len(c.summary) == 0
    assert cluster_hulls(np.empty((0, 2)), np.empty(0, int), 0).shape == (0, 32, 2)


def distance_to_convex(x, vertices):
    """Distance from a point outside a convex polygon (or segment, or point) to it."""
    a, b = vertices, np.roll(vertices, -1, axis=0)
    ab = b - a
    t = np.clip(np.einsum("ij,ij->i", x - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0, 1)
    return float(np.min(np.hypot(*(a + t[:, None] * ab - x).T)))


def polygon_area(ring):
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def test_a_border_point_between_two_clusters_joins_the_first_as_in_scikit_learn():
    from sklearn.cluster import DBSCAN

    # Two groups of four 0.3 m apart; the point between them is no core point but lies within eps of
    # a core point of each.
    x = [0.0, 0.003, 0.006, 0.02, 0.15, 0.28, 0.294, 0.297, 0.30, 5.0]
    xy = np.column_stack([x, np.zeros(len(x))])
    for order in (np.arange(len(x)), np.array([5, 6, 7, 8, 4, 0, 1, 2, 3, 9])):
        ours = dbscan(neighbour_graph(xy[order], 0.14), 0.14, 4)
        ref = DBSCAN(eps=0.14, min_samples=4).fit(xy[order])
        np.testing.assert_array_equal(ours.labels, ref.labels_)
        middle = list(order).index(4)
        assert not ours.core[middle] and ours.labels[middle] == 0 and ours.n_clusters == 2


def _simulated_flight(site, seed=11, n=4000):
    """Detections (WGS84) of a simulated flight: 150 targets of a 40 m × 40 m field, each seen a few tens
    of times with 4 cm scatter, and background false alarms."""
    rng = np.random.default_rng(seed)
    centres = rng.uniform(0, 40, (150, 2))
    xy = np.concatenate([centres[rng.integers(0, 150, n)] + rng.normal(0, 0.04, (n, 2)),
                         rng.uniform(0, 40, (n // 4, 2))])
    return site.to_geodetic(np.column_stack([xy, np.zeros(len(xy))]))


def test_a_flights_clusters_do_not_depend_on_where_the_runs_local_frame_lies():
    """The same detections, clustered in local frames whose origin moved by 1.5 cm, or by kilometres (what
    other flights in a run do to the frame's mid-range origin), give the same cells and the same clusters.
    A grid laid out in the run's own frame would not: the check below shows it regroups the cells."""
    site = LocalFrame(52.123456, 5.432101, 12.0)
    lat, lon, h = _simulated_flight(site)
    reference = cluster_detections(GroundPositions.from_geodetic(site, lat, lon, h), None, None, 3, 0.20, 5)
    assert reference.n_clusters > 100
    for shift_east_north in ((0.015, 0.0), (0.0, 0.015), (2500.0, -1800.0)):
        moved_lat, moved_lon, _ = site.to_geodetic(np.array([*shift_east_north, 0.0]))
        moved = LocalFrame(float(moved_lat), float(moved_lon), site.h0)
        positions = GroundPositions.from_geodetic(moved, lat, lon, h)
        again = cluster_detections(positions, None, None, 3, 0.20, 5)
        np.testing.assert_array_equal(again.points.inverse, reference.points.inverse)
        np.testing.assert_array_equal(again.points.count, reference.points.count)
        np.testing.assert_array_equal(again.detection_cluster, reference.detection_cluster)
        np.testing.assert_array_equal(again.summary.n_detections, reference.summary.n_detections)
        local_grid = np.floor(positions.xy / 0.03).astype(np.int64)
        _, local_cells = np.unique(local_grid, axis=0, return_inverse=True)
        _, fixed_cells = np.unique(np.floor(site.from_geodetic(lat, lon, h)[:, :2] / 0.03), axis=0,
                                   return_inverse=True)
        assert not np.array_equal(local_cells.reshape(-1), fixed_cells.reshape(-1))


def test_fixed_grid_cells_are_cell_sized_squares_on_the_ground():
    """Positions 1 cm apart along a line 2 m long fall into consecutive cells, 3 or 4 to a 3 cm cell; each
    tile's grid starts at its south-west corner."""
    corner = LocalFrame(1000 * GRID_TILE_DEG, 200 * GRID_TILE_DEG)
    east = np.arange(200) * 0.01 + 0.005
    lat, lon, _ = corner.to_geodetic(np.column_stack([east, np.full(200, 0.015), np.zeros(200)]))
    cells = fixed_grid_cells(lat, lon, 0.03)
    np.testing.assert_array_equal(cells[:, :2], [[1000, 200]] * 200)
    np.testing.assert_array_equal(cells[:, 2], np.floor(east / 0.03))
    np.testing.assert_array_equal(cells[:, 3], 0)
    west = fixed_grid_cells(*corner.to_geodetic(np.array([[-0.005, 0.015, 0.0]]))[:2], 0.03)
    assert tuple(west[0, :2]) == (1000, 199)
