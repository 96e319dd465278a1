"""Flight planning: merge guarantee, TSP quality, metric distances, splitting, estimates, bad input."""
import itertools

import numpy as np
import pytest
from hypothesis import given
from hypothesis import settings as hsettings
from hypothesis import strategies as st

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.surveyed_area import PlacedArea, surveyed_area
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import project_pairs
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from birdseye.birdseye_qgis.core.plan.flight_plan import (
    ACCELERATION_MS2,
    CLIMB_RATE_MS,
    DESCENT_RATE_MS,
    OUTSIDE_SAMPLES_LONG_SIDE,
    PHOTO_ACTION_S,
    WAYPOINT_FIELDS,
    FlightSettings,
    along_track_footprint_m,
    distance_matrix,
    footprint_radius_m,
    leg_time_s,
    merge_geotags,
    min_enclosing_circle,
    mission_metrics,
    nearest_neighbour_tour,
    order_route,
    photo_outside_share,
    plan_flight,
    solve_tour,
    split_route,
    suggested_capture_interval_s,
    tour_length,
    waypoint_records,
)

LAT0, LON0 = 52.2, 5.6
# A nadir camera (docs/design.md#camera): camera x = body right, y = −body forward, z = body down.
NADIR_MOUNT = np.array([[0, 1, 0, 0], [-1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], dtype=float)


def to_latlon(xy, lat0=LAT0, lon0=LON0):
    """Local east/north metres → WGS84 through the exact local frame."""
    frame = LocalFrame(lat0, lon0, 0.0)
    lat, lon, _ = frame.to_geodetic(np.column_stack([xy, np.zeros(len(xy))]))
    return np.atleast_1d(lat), np.atleast_1d(lon)


def geod_distance(lat1, lon1, lat2, lon2):
    from birdseye.birdseye_qgis.core.geometry import geodesy

    geodesy.ensure_proj_data()
    import pyproj

    return pyproj.Geod(ellps="WGS84").inv(lon1, lat1, lon2, lat2)[2]


def wide_camera(dist=(0.0, 0.0, 0.0, 0.0, 0.0)):
    return CameraModel(1200, 800, 900.0, 900.0, 599.5, 399.5, dist=dist)


# ---------------------------------------------------------------------- merging
@hsettings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(0, 60), st.floats(0, 60)), min_size=1, max_size=60),
       st.floats(0.05, 12.0))
def test_merge_every_geotag_within_radius_and_counted_once(points, radius):
    xy = np.array(points, dtype=float)
    centres, labels = merge_geotags(xy, radius)
    assert labels.shape == (len(xy),) and labels.min() == 0 and labels.max() == len(centres) - 1
    assert len(np.unique(labels)) == len(centres)  # no empty waypoint
    offsets = np.linalg.norm(xy - centres[labels], axis=1)
    assert np.all(offsets <= radius * (1 + 1e-9) + 1e-9)
    # Lower bound: points pairwise more than 2r apart can never share a waypoint.
    packing = []
    for p in xy:
        if all(np.linalg.norm(p - q) > 2 * radius for q in packing):
            packing.append(p)
    assert len(packing) <= len(centres) <= len(xy)


def test_merge_tight_cluster_is_one_waypoint_at_its_enclosing_centre():
    rng = np.random.default_rng(3)
    angles = rng.uniform(0, 2 * np.pi, 25)
    xy = np.column_stack([np.cos(angles), np.sin(angles)]) * rng.uniform(0, 1.5, (25, 1)) + [10, 20]
    centres, labels = merge_geotags(xy, 2.0)
    assert len(centres) == 1
    centre, r = min_enclosing_circle(xy)
    assert np.allclose(centres[0], centre)
    assert r <= 1.5 + 1e-12 and np.isclose(np.max(np.linalg.norm(xy - centre, axis=1)), r)


def test_merge_two_far_groups_stay_apart():
    xy = np.array([[0, 0], [1, 0], [0, 1], [50, 50], [51, 50]], dtype=float)
    centres, labels = merge_geotags(xy, 2.0)
    assert len(centres) == 2
    assert labels[0] == labels[1] == labels[2] != labels[3] == labels[4]


@hsettings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(-50, 50), st.floats(-50, 50)), min_size=1, max_size=30))
def test_min_enclosing_circle_is_minimal_on_vertices(points):
    xy = np.array(points, dtype=float)
    centre, r = min_enclosing_circle(xy)
    d = np.linalg.norm(xy - centre, axis=1)
    assert np.all(d <= r + 1e-7)
    # Independent bound: the circle is at least half the diameter and at most the Jung bound D/√3.
    diameter = np.max(np.linalg.norm(xy[:, None] - xy[None], axis=2))
    assert diameter / 2 - 1e-7 <= r <= diameter / np.sqrt(3) + 1e-7


def test_footprint_radius_matches_pinhole_closed_form():
    cam = wide_camera()
    altitude, margin = 15.0, 40.0
    # Pinhole, principal point centred: the inset image is a rectangle on the ground; the largest
    # circle inside it at any heading has the half-width of its shorter side.
    half_short = (min(cam.width, cam.height) / 2 - margin) / cam.fx * altitude
    assert footprint_radius_m(cam, altitude, margin) == pytest.approx(half_short, rel=1e-9)
    assert along_track_footprint_m(cam, altitude) == pytest.approx(cam.height / cam.fy * altitude,
                                                                   rel=1e-9)
    interval = suggested_capture_interval_s(cam, altitude, 4.0, 0.8)
    assert interval == pytest.approx(0.2 * cam.height / cam.fy * altitude / 4.0, rel=1e-9)


def _nadir_projection_in_view(frame, camera, wp_xy, geotag_xy, altitude, yaw, margin):
    """Independent check: a level aircraft at the waypoint, camera on the documented nadir mount."""
    lat, lon, _ = frame.to_geodetic(np.column_stack([wp_xy, np.zeros(len(wp_xy))]))
    quat = rotmat_to_quat(euler_zyx_to_rotmat(np.zeros(len(yaw)), np.zeros(len(yaw)), yaw))
    cam = CameraModel(camera.width, camera.height, camera.fx, camera.fy, camera.cx, camera.cy,
                      dist=camera.dist, T_cam_imu=NADIR_MOUNT)
    poses = FramePoses(np.arange(len(yaw)), np.atleast_1d(lat), np.atleast_1d(lon),
                       np.full(len(yaw), altitude), quat, np.zeros(len(yaw)), cam)
    geometry = FrameGeometry(poses, frame)
    glat, glon = frame.to_geodetic(np.column_stack([geotag_xy, np.zeros(len(geotag_xy))]))[:2]
    pts = frame.from_geodetic(glat, glon, np.zeros(len(geotag_xy)))
    return project_pairs(geometry, np.arange(len(yaw)), pts, edge_buffer_px=margin).in_view


@pytest.mark.parametrize("dist", [(0.0, 0.0, 0.0, 0.0, 0.0), (-0.28, 0.09, 0.001, -0.002, -0.01)])
def test_every_geotag_inside_its_waypoint_footprint_at_any_heading(dist):
    rng = np.random.default_rng(11)
    cam = wide_camera(dist)
    xy = rng.uniform(0, 120, (150, 2))
    lat, lon = to_latlon(xy)
    settings = FlightSettings(altitude_m=8.0, merge_radius_m=6.0, footprint_margin_px=60.0)
    plan = plan_flight(lat, lon, settings=settings, camera=cam)
    assert plan.footprint_radius_m < 6.0  # the camera, not the merge radius, is limiting here
    labels = np.empty(len(xy), dtype=int)
    for w, members in enumerate(plan.members):
        labels[members] = w
    assert np.all(np.linalg.norm(plan.geotag_xy - plan.waypoint_xy[labels], axis=1)
                  <= settings.merge_radius_m + 1e-9)
    # Random headings, not the planner's 5° grid.
    yaw = rng.uniform(0, 2 * np.pi, len(xy))
    ok = _nadir_projection_in_view(plan.local, cam, plan.waypoint_xy[labels], plan.geotag_xy,
                                   settings.altitude_m, yaw, settings.footprint_margin_px)
    assert ok.all()
    assert plan.waypoint_count < len(xy)  # merging still happened


# ---------------------------------------------------------------------- ordering
def brute_force_tour(dist):
    n = len(dist)
    best = min(itertools.permutations(range(1, n)), key=lambda p: tour_length(dist, (0,) + p))
    return tour_length(dist, (0,) + best)


@pytest.mark.parametrize("n,seed", [(4, 0), (5, 1), (6, 2), (7, 3), (8, 4), (9, 5)])
def test_tour_equals_brute_force_on_small_instances(n, seed):
    xy = np.random.default_rng(seed).uniform(0, 500, (n, 2))
    dist = distance_matrix(xy)
    tour = solve_tour(dist)
    assert sorted(tour) == list(range(n))
    # fast-tsp sees distances rounded to 1/65535 of the longest: that is the only allowed slack.
    slack = n * dist.max() / 65535
    assert tour_length(dist, tour) == pytest.approx(brute_force_tour(dist), abs=slack)


@pytest.mark.parametrize("n,seed", [(12, 0), (40, 1), (120, 2), (300, 3)])
def test_tour_never_worse_than_nearest_neighbour(n, seed):
    rng = np.random.default_rng(seed)
    # Clustered points are where nearest-neighbour is typically bad.
    xy = np.concatenate([rng.normal(c, 15, (n // 4, 2)) for c in rng.uniform(0, 800, (4, 2))])
    dist = distance_matrix(xy)
    tour = solve_tour(dist, seconds=0.2)
    assert sorted(tour) == list(range(len(xy)))
    for start in range(0, len(xy), max(1, len(xy) // 5)):
        assert tour_length(dist, tour) <= tour_length(dist, nearest_neighbour_tour(dist, start)) + 1e-9


def test_open_path_without_home_equals_brute_force():
    xy = np.random.default_rng(7).uniform(0, 300, (7, 2))
    dist = distance_matrix(xy)
    order = order_route(xy, None)
    best = min(tour_length(dist, p, closed=False) for p in itertools.permutations(range(7)))
    assert sorted(order) == list(range(7))
    assert tour_length(dist, order, closed=False) == pytest.approx(best, abs=7 * dist.max() / 65535)


def test_route_distances_are_metres_even_at_high_latitude():
    """At 78°N a degree of longitude is 4.7× shorter than one of latitude: a planner working in
    degrees would pick a different, longer route. Ours must be the metric optimum."""
    lat0, lon0 = 78.22, 15.65  # Svalbard
    rng = np.random.default_rng(5)
    lat = lat0 + rng.uniform(0, 0.004, 8)  # up to ~450 m north
    lon = lon0 + rng.uniform(0, 0.02, 8)   # up to ~450 m east
    home = (lat0, lon0)
    plan = plan_flight(lat, lon, home=home, settings=FlightSettings(merge_radius_m=0.0))
    (mission,) = plan.missions
    route_lat, route_lon = plan.route_latlon(mission)
    geodesic = sum(geod_distance(route_lat[k], route_lon[k], route_lat[k + 1], route_lon[k + 1])
                   for k in range(len(route_lat) - 1))
    assert mission.length_m == pytest.approx(geodesic, rel=1e-5)

    # Pairwise geodesic and naive degree distances over home (node 0) and the geotags.
    la, lo = np.concatenate([[home[0]], lat]), np.concatenate([[home[1]], lon])
    n = len(la)
    metres = np.array([[geod_distance(la[i], lo[i], la[j], lo[j]) if i != j else 0.0
                        for j in range(n)] for i in range(n)])
    degrees = np.hypot(la[:, None] - la[None], lo[:, None] - lo[None])
    perms = np.array([(0,) + p for p in itertools.permutations(range(1, n))])
    closed = np.column_stack([perms, np.zeros(len(perms), int)])
    metric_lengths = metres[closed[:, :-1], closed[:, 1:]].sum(axis=1)
    degree_lengths = degrees[closed[:, :-1], closed[:, 1:]].sum(axis=1)
    best_metric = metric_lengths.min()
    metric_of_degree_optimum = metric_lengths[np.argmin(degree_lengths)]
    assert metric_of_degree_optimum > best_metric * 1.02  # planning in degrees would be wrong
    assert mission.length_m == pytest.approx(best_metric, rel=1e-4)


# ---------------------------------------------------------------------- time and splitting
def test_leg_time_closed_forms():
    v, a = 5.0, ACCELERATION_MS2
    ramp = v * v / a
    assert leg_time_s(100.0, v) == pytest.approx(100.0 / v + v / a)
    assert leg_time_s(ramp / 4, v) == pytest.approx(2 * np.sqrt(ramp / 4 / a))
    # Continuous where the profile changes from triangle to trapezoid.
    assert leg_time_s(ramp * (1 - 1e-9), v) == pytest.approx(leg_time_s(ramp, v), rel=1e-6)
    assert leg_time_s(0.0, v) == 0.0


def test_mission_time_of_a_square():
    s = FlightSettings(altitude_m=20.0, speed_ms=4.0, hover_s=3.0)
    side = 100.0
    xy = np.array([[side, 0], [side, side], [0, side]])
    length, time_s = mission_metrics(xy, np.zeros(2), s)
    assert length == pytest.approx(4 * side)
    expected = (20 / CLIMB_RATE_MS + 20 / DESCENT_RATE_MS + 4 * (side / 4.0 + 4.0 / ACCELERATION_MS2)
                + 3 * (3.0 + PHOTO_ACTION_S))
    assert time_s == pytest.approx(expected)


def brute_force_split(seq, home, s, min_size):
    n = len(seq)
    best = None
    for cuts in itertools.product([0, 1], repeat=n - 1):
        bounds, start = [], 0
        for k, c in enumerate(cuts, start=1):
            if c:
                bounds.append((start, k))
                start = k
        bounds.append((start, n))
        if any(b - a > s.max_waypoints or b - a < min_size for a, b in bounds):
            continue
        metrics = [mission_metrics(seq[a:b], home, s) for a, b in bounds]
        if any(t > 60 * s.max_flight_min for _, t in metrics):
            continue
        key = (len(bounds), sum(m[0] for m in metrics))
        if best is None or key < best[0]:
            best = (key, bounds)
    return best


@pytest.mark.parametrize("seed,max_wp,max_min", [(0, 3, 30.0), (1, 10, 3.0), (2, 4, 2.5), (3, 2, 60.0)])
def test_split_is_the_exact_optimum(seed, max_wp, max_min):
    rng = np.random.default_rng(seed)
    seq = rng.uniform(-300, 300, (9, 2))
    home = np.array([0.0, 0.0])
    s = FlightSettings(max_waypoints=max_wp, max_flight_min=max_min, speed_ms=5.0)
    for min_size in (1, 2):
        bounds = split_route(seq, home, s, min_size=min_size)
        expected = brute_force_split(seq, home, s, min_size)
        if expected is None:
            assert bounds == []
            continue
        assert len(bounds) == expected[0][0]
        assert sum(mission_metrics(seq[a:b], home, s)[0] for a, b in bounds) == pytest.approx(
            expected[0][1])


def test_plan_splits_into_missions_from_home_to_home_within_limits():
    rng = np.random.default_rng(21)
    xy = rng.uniform(0, 600, (140, 2))
    lat, lon = to_latlon(xy)
    home = to_latlon(np.array([[-40.0, -30.0]]))
    home = (home[0][0], home[1][0])
    s = FlightSettings(max_waypoints=25, max_flight_min=9.0, merge_radius_m=1.0, speed_ms=6.0)
    plan = plan_flight(lat, lon, home=home, settings=s)
    assert len(plan.missions) >= int(np.ceil(plan.waypoint_count / 25))
    flown = np.concatenate([m.waypoints for m in plan.missions])
    assert sorted(flown) == list(range(plan.waypoint_count))
    for m in plan.missions:
        assert 2 <= len(m.waypoints) <= 25
        assert m.time_s <= 9.0 * 60 + 1e-9
        rlat, rlon = plan.route_latlon(m)
        assert (rlat[0], rlon[0]) == home and (rlat[-1], rlon[-1]) == home
        length, time_s = mission_metrics(plan.waypoint_xy[m.waypoints], plan.home_xy, s)
        assert (m.length_m, m.time_s) == (pytest.approx(length), pytest.approx(time_s))
    numbers = plan.mission_of_waypoint()
    assert np.all(numbers[:, 0] >= 1) and np.all(numbers[:, 1] >= 1)


def test_single_geotag_is_a_one_waypoint_mission():
    lat, lon = to_latlon(np.array([[5.0, 5.0]]))
    plan = plan_flight(lat, lon, ids=["g7"], home=(LAT0, LON0))
    assert plan.waypoint_count == 1 and len(plan.missions) == 1
    assert plan.members[0].tolist() == [0] and plan.geotag_ids == ["g7"]
    assert plan.waypoint_lat[0] == pytest.approx(lat[0], abs=1e-12)
    assert plan.missions[0].length_m == pytest.approx(2 * np.hypot(5, 5), rel=1e-6)


def test_waypoint_records_list_every_geotag_once_in_flight_order():
    rng = np.random.default_rng(2)
    lat, lon = to_latlon(rng.uniform(0, 200, (50, 2)))
    plan = plan_flight(lat, lon, ids=[f"t{i}" for i in range(50)],
                       settings=FlightSettings(merge_radius_m=8.0, max_waypoints=6))
    records = waypoint_records(plan)
    assert len(records) == plan.waypoint_count
    assert all(set(r) == {name for name, _, _ in WAYPOINT_FIELDS} for r in records)
    assert [(r["mission"], r["order"]) for r in records] == sorted((r["mission"], r["order"]) for r in records)
    ids = [g for r in records for g in r["geotag_ids"].split(";")]
    assert sorted(ids) == sorted(f"t{i}" for i in range(50))
    assert sum(r["geotag_count"] for r in records) == 50
    assert max(r["max_offset_m"] for r in records) <= 8.0 + 1e-4


def test_waypoints_say_where_their_targets_came_from():
    """A geotag and an unresolved cluster 1 m apart share a waypoint that names both origins; a lone
    cluster's waypoint is review only, with the review's outcome."""
    lat, lon = to_latlon(np.array([[0.0, 0.0], [1.0, 0.0], [40.0, 0.0], [80.0, 0.0]]))
    plan = plan_flight(lat, lon, ids=["g1", "det#0", "det#1", "g2"], settings=FlightSettings(merge_radius_m=2.0),
                       origins=["survey", "review:uncertain", "review:conflicting", "survey"])
    by_ids = {r["geotag_ids"]: (r["provenance"], r["review_outcomes"]) for r in waypoint_records(plan)}
    assert by_ids == {"g1;det#0": ("review;survey", "uncertain"), "det#1": ("review", "conflicting"),
                      "g2": ("survey", "")}
    plain = waypoint_records(plan_flight(lat[:1], lon[:1]))
    assert (plain[0]["provenance"], plain[0]["review_outcomes"]) == ("survey", "")


def test_share_of_a_photo_outside_a_round_area_counts_the_pixels_seeing_beyond_it():
    """Around the nadir a round area looks the same at every heading, so the share is the fraction of sampled
    pixels whose ground lies farther than R: for an undistorted nadir camera at 10 m a pixel (u, v) sees the
    ground at |(u − cx, v − cy)|·10/f. The area is a 720-gon inscribed in the circle of radius R; no sample lies
    between it and the circle, so the polygon and the circle agree on every sample."""
    cam = CameraModel(800, 500, 1000.0, 1000.0, 399.5, 249.5, T_cam_imu=NADIR_MOUNT)
    n_u, n_v = OUTSIDE_SAMPLES_LONG_SIDE, round(OUTSIDE_SAMPLES_LONG_SIDE * 500 / 800)
    u = (np.arange(n_u) + 0.5) * 800 / n_u - 0.5
    v = (np.arange(n_v) + 0.5) * 500 / n_v - 0.5
    radius = np.hypot(*np.meshgrid(u - cam.cx, v - cam.cy)).ravel() * 10.0 / 1000.0
    big_r, angle = 3.0, np.linspace(0.0, 2 * np.pi, 720, endpoint=False)
    centre = np.array([12.0, -7.0])
    area = PlacedArea([centre + big_r * np.column_stack([np.cos(angle), np.sin(angle)])])
    assert not np.any((radius > big_r * np.cos(np.pi / 720)) & (radius <= big_r))
    expected = float(np.mean(radius > big_r))
    assert 0.2 < expected < 0.8
    local = LocalFrame(LAT0, LON0, 0.0)
    share = photo_outside_share(local, cam, 10.0, np.array([centre, centre + [100.0, 0.0], centre + [0.5, 0.0]]),
                                area)
    assert share[0] == pytest.approx(expected, abs=1e-12)
    assert share[1] == 1.0  # far outside: the whole photo
    assert expected < share[2] < 1.0  # off-centre: more of the photo sees past the rim at the worst heading


def test_waypoints_report_how_much_of_their_photo_lies_outside_the_surveyed_area():
    """Geotags on a 40 m square and at its centre, the area their hull grown by 1 m. The photo covers 10 × 6.25 m
    at 10 m (800 × 500 px, f = 800 px): the centre's lies inside. A corner's, at heading 0, keeps inside at most
    the part east and north of the margin's edges 1 m out: (5 + 1)/10 × (3.125 + 1)/6.25 = 39.6 % (the rounded
    corner takes more), so at least 60.4 % lies outside at the worst heading; by symmetry every corner alike.
    Without a camera there is no photo to measure."""
    xy = np.array([[0.0, 0.0], [40.0, 0.0], [40.0, 40.0], [0.0, 40.0], [20.0, 20.0]])
    lat, lon = to_latlon(xy)
    cam = CameraModel(800, 500, 800.0, 800.0, 399.5, 249.5, T_cam_imu=NADIR_MOUNT)
    area = surveyed_area(lat, lon, 1.0)
    plan = plan_flight(lat, lon, ids=list("abcde"), settings=FlightSettings(merge_radius_m=0.5), camera=cam,
                       surveyed=area)
    pct = {r["geotag_ids"]: r["outside_pct"] for r in waypoint_records(plan)}
    assert pct["e"] == 0.0
    corners = np.array([pct[k] for k in "abcd"])
    assert np.all((corners > 60.4) & (corners < 100.0)) and np.ptp(corners) <= 0.5
    assert plan.surveyed is area
    blind = plan_flight(lat, lon, ids=list("abcde"), settings=FlightSettings(merge_radius_m=0.5), surveyed=area)
    assert blind.outside_share is None and {r["outside_pct"] for r in waypoint_records(blind)} == {None}


def test_uneven_ground_is_flagged():
    lat, lon = to_latlon(np.array([[0.0, 0.0], [30.0, 0.0]]))
    plan = plan_flight(lat, lon, settings=FlightSettings(altitude_m=10.0), ground_heights=[40.0, 42.5])
    assert any("vary by 2.5 m" in w for w in plan.warnings)
    level = plan_flight(lat, lon, settings=FlightSettings(altitude_m=10.0), ground_heights=[40.0, np.nan])
    assert not any("vary by" in w for w in level.warnings)


def test_timed_capture_interval_from_camera_when_zero():
    cam = wide_camera()
    lat, lon = to_latlon(np.random.default_rng(1).uniform(0, 50, (10, 2)))
    s = FlightSettings(capture="timed", capture_interval_s=0.0, speed_ms=2.0, forward_overlap=0.75)
    plan = plan_flight(lat, lon, settings=s, camera=cam)
    expected = 0.25 * cam.height / cam.fy * s.altitude_m / 2.0
    assert plan.suggested_interval_s == pytest.approx(expected)
    assert plan.capture_interval_s == pytest.approx(round(expected, 1))
    spec = plan.mission_specs("f")[0]
    assert spec.capture == "timed" and spec.capture_interval_s == plan.capture_interval_s


# ---------------------------------------------------------------------- bad input
@pytest.mark.parametrize("altitude", [1.0, 150.0, -3.0])
def test_altitude_outside_limits_is_refused(altitude):
    with pytest.raises(InputError, match=r"ALTITUDE_M = .* outside 2–120 m"):
        plan_flight([LAT0], [LON0], settings=FlightSettings(altitude_m=altitude))


def test_empty_input_is_refused():
    with pytest.raises(InputError, match="no geotags"):
        plan_flight([], [])


def test_spread_over_tens_of_km_is_refused_unless_forced():
    xy = np.array([[0, 0], [100, 50], [50, 80], [30_000, 5_000]], dtype=float)
    lat, lon = to_latlon(xy)
    with pytest.raises(InputError, match=r"span 30\.\d km.*farthest.* c .*FORCE"):
        plan_flight(lat, lon, ids=["a", "b", "x", "c"])
    plan = plan_flight(lat, lon, ids=["a", "b", "x", "c"],
                       settings=FlightSettings(force=True, max_flight_min=1000.0))
    assert plan.waypoint_count == 4


def test_implausible_coordinates_are_refused():
    with pytest.raises(InputError, match="feature 2 .*not degrees.*CRS"):
        plan_flight([LAT0, 5_803_214.0], [LON0, 402_117.0])
    with pytest.raises(InputError, match="feature 3 has no position"):
        plan_flight([LAT0, LAT0 + 1e-4, np.nan], [LON0, LON0, LON0])
    with pytest.raises(InputError, match="feature b lies at 0°, 0°"):
        plan_flight([LAT0, 0.0], [LON0, 0.0], ids=["a", "b"])


def test_flight_time_too_short_for_one_waypoint_is_explained():
    lat, lon = to_latlon(np.array([[3000.0, 0.0], [3005.0, 0.0]]))
    with pytest.raises(InputError, match=r"geotag\(s\) .* takes .* min .*300[05] m from HOME.*MAX_FLIGHT_MIN"):
        plan_flight(lat, lon, home=(LAT0, LON0), settings=FlightSettings(max_flight_min=5.0))


def test_interval_from_camera_needs_a_camera():
    with pytest.raises(InputError, match="CAPTURE_INTERVAL_S = 0 .*no CAMERA"):
        plan_flight([LAT0], [LON0], settings=FlightSettings(capture="timed", capture_interval_s=0.0))


def test_margin_larger_than_the_image_is_refused():
    with pytest.raises(InputError, match="FOOTPRINT_MARGIN_PX = 500 px leaves nothing"):
        plan_flight([LAT0], [LON0], camera=wide_camera(),
                    settings=FlightSettings(footprint_margin_px=500.0))
