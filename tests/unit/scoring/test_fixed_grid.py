"""A flight scores the same alone and pooled: Evaluate detections clusters every flight on the fixed
de-duplication grid, whatever other flights move the run's local frame to."""
import numpy as np

from birdseye.birdseye_qgis.core.field.geotags import Geotags
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.poses import FramePoses
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from birdseye.birdseye_qgis.core.scoring.evaluation import Detections, Flight, evaluate_flights
from birdseye.birdseye_qgis.core.scoring.operating_point import OperatingPoint

SITE = LocalFrame(-27.551234, 151.951234, 400.0)
# min_samples 5 on a 3 cm grid: cluster membership hangs on how detections fall into cells.
OP = OperatingPoint(threshold=None, dedup_cm=3, eps_m=0.10, min_samples=5, eps_pred_m=0.20)


def nadir_camera():
    mount = np.eye(4)
    mount[:3, :3] = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    return CameraModel(1920, 1200, 1000.0, 1000.0, 959.5, 599.5, (0, 0, 0, 0, 0), mount)


def simulated_flight(east, north, seed, name):
    """A 3 × 3 block of level nadir frames 10 m up over a 40 m × 30 m plot at (east, north) m from the
    site, 60 surveyed targets each detected 15–40 times with 4 cm scatter, and false alarms."""
    rng = np.random.default_rng(seed)
    centre = np.array([east, north])
    frames = centre + np.array([(x, y) for x in (-12.0, 0.0, 12.0) for y in (-8.0, 0.0, 8.0)])
    lat, lon, h = SITE.to_geodetic(np.column_stack([frames, np.full(len(frames), 10.0)]))
    zero = np.zeros(len(frames))
    poses = FramePoses(np.arange(len(frames)) + 100 * seed, lat, lon, h,
                       rotmat_to_quat(euler_zyx_to_rotmat(zero, zero, zero)), np.full(len(frames), SITE.h0),
                       nadir_camera())
    targets = centre + rng.uniform([-18, -12], [18, 12], (60, 2))
    seen = np.repeat(np.arange(60), rng.integers(15, 40, 60))
    xy = np.concatenate([targets[seen] + rng.normal(0, 0.04, (len(seen), 2)),
                         centre + rng.uniform([-18, -12], [18, 12], (300, 2))])
    dlat, dlon, dh = SITE.to_geodetic(np.column_stack([xy, np.zeros(len(xy))]))
    detections = Detections(dlat, dlon, dh, rng.integers(0, len(frames), len(xy)), rng.uniform(0.3, 1, len(xy)),
                            name=name)
    tlat, tlon, _ = SITE.to_geodetic(np.column_stack([targets, np.zeros(60)]))
    ids = [f"{name}-{i}" for i in range(60)]
    return Flight(detections, [poses], name), (ids, tlat, tlon)


def geotags_of(*parts):
    ids = sum((list(p[0]) for p in parts), [])
    lat = np.concatenate([p[1] for p in parts])
    lon = np.concatenate([p[2] for p in parts])
    return Geotags(ids, lat, lon, np.full(len(lat), np.nan))


def test_a_flight_evaluated_alone_or_pooled_with_two_others_has_the_same_clusters_and_scores():
    a, tags_a = simulated_flight(0.0, 0.0, 1, "A")
    b, tags_b = simulated_flight(700.0, 350.0, 2, "B")
    c, tags_c = simulated_flight(-2400.0, 1900.0, 3, "C")
    alone = evaluate_flights([a], geotags_of(tags_a), OP)
    pooled = evaluate_flights([b, a, c], geotags_of(tags_a, tags_b, tags_c), OP)
    # The pooled run's frame sits kilometres from flight A's: the old grid, laid out there, moved.
    assert np.hypot(*pooled.local.from_geodetic(alone.local.lat0, alone.local.lon0, alone.local.h0)[:2]) > 1000
    one, same = alone.flights[0], pooled.flights[1]
    assert one.clustering.n_clusters > 40
    np.testing.assert_array_equal(same.clustering.points.inverse, one.clustering.points.inverse)
    np.testing.assert_array_equal(same.clustering.detection_cluster, one.clustering.detection_cluster)
    np.testing.assert_array_equal(same.clustering.dbscan.core, one.clustering.dbscan.core)
    counts, expected = same.score.counts.to_dict(), one.score.counts.to_dict()
    # Extents are measured in each run's own frame: equal to a micrometre, not to the last bit.
    assert abs(counts.pop("mean_median_extent_m") - expected.pop("mean_median_extent_m")) < 1e-6
    assert counts == expected
    assert same.score.counts.recall_pre == one.score.counts.recall_pre
    assert same.score.counts.gmcf_pre == one.score.counts.gmcf_pre
