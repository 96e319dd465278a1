"""The in-view test stands on the ground the detections were placed on (level plane, method's plane, DEM).

One level nadir frame 10 m above the site with the scoring fixture's camera (1920 × 1200 px, fx = fy =
1000 px, principal point at the image centre, image up = north). A ground point e metres east of the
camera's foot and Δ metres below the camera's level ground is seen at depth 10 + Δ, so at

    u = 959.5 + 1000 · e / (10 + Δ)     (inside the image for −0.5 ≤ u ≤ 1919.5)

On the level plane Δ = 0; on a plane falling towards the east by α, Δ = e · tan α. That is the whole
expectation: nothing below is computed with the code under test.
"""
import math

import numpy as np
import pytest
from test_scoring import SITE, poses_over

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.geometry.dem import DemGroundFactory
from birdseye.birdseye_qgis.core.geometry.ground import MethodPlaneGround, needs_ground_height
from birdseye.birdseye_qgis.core.geometry.ground_record import (
    DEM,
    LEVEL_PLANE,
    METHOD_PLANE,
    GroundRecord,
    common_ground,
)
from birdseye.birdseye_qgis.core.scoring.evaluation import Detections, Flight, Geotags, evaluate_flights
from birdseye.birdseye_qgis.core.scoring.matching import in_view
from birdseye.birdseye_qgis.core.scoring.operating_point import OperatingPoint
from birdseye.birdseye_qgis.core.sim.terrain import synthetic_terrain

SLOPE_DEG = 20.0
TAN = math.tan(math.radians(SLOPE_DEG))


def u_px(east_m, below_m):
    return 959.5 + 1000.0 * east_m / (10.0 + below_m)


def sloped_dem(**kwargs):
    """A plane through the site's ground height, facing east (falling towards the east) by 20°."""
    return synthetic_terrain(SITE.lat0, SITE.lon0, kind="plane", slope_deg=SLOPE_DEG, aspect_deg=90.0,
                             base_height_m=SITE.h0, size_m=120.0, cell_m=0.5, **kwargs)


def on_ground(east_north):
    """Local points at the site's ground height (the ground model places them on its own ground)."""
    en = np.atleast_2d(np.asarray(east_north, dtype=float))
    return np.column_stack([en, np.zeros(len(en))])


def test_the_dem_in_view_test_sees_what_the_slope_brings_into_and_out_of_view():
    east = np.array([10.5, -9.0, 3.0])
    points = on_ground(np.column_stack([east, np.zeros(3)]))
    level_u, slope_u = u_px(east, 0.0), u_px(east, east * TAN)
    # 10.5 m east is beyond the level footprint but, 3.8 m down the slope, inside the image; 9 m west is
    # inside the level footprint but, 3.3 m up the slope and so nearer the camera, outside the image.
    np.testing.assert_array_equal(level_u <= 1919.5, [False, True, True])
    np.testing.assert_array_equal((slope_u >= -0.5) & (slope_u <= 1919.5), [True, False, True])

    frames = [poses_over([0.0, 0.0])]
    level = in_view(frames, SITE, points)
    on_dem = in_view(frames, SITE, points, ground=DemGroundFactory(sloped_dem()))
    np.testing.assert_array_equal(level.mask, [False, True, True])
    np.testing.assert_array_equal(on_dem.mask, [True, False, True])
    assert (on_dem.n_frames, on_dem.n_frames_without_ground) == (1, 0)


def test_frames_without_a_ground_height_are_kept_on_a_dem_and_left_out_on_the_planes():
    # The second frame, 30 m north (the slope runs east–west: the terrain is at the site's height there),
    # has no altimeter ground; the point under it is seen only by it.
    frames = poses_over([[0.0, 0.0], [0.0, 30.0]])
    frames.ground_height[1] = np.nan
    points = on_ground([[0.0, 30.0], [1.0, 0.0]])
    on_dem = in_view([frames], SITE, points, ground=DemGroundFactory(sloped_dem()))
    np.testing.assert_array_equal(on_dem.mask, [True, True])
    assert (on_dem.n_frames, on_dem.n_frames_without_ground) == (2, 0)
    for ground in (None, MethodPlaneGround):
        planes = in_view([frames], SITE, points, ground=ground)
        np.testing.assert_array_equal(planes.mask, [False, True])
        assert (planes.n_frames, planes.n_frames_without_ground) == (1, 1)


def test_a_point_behind_a_ridge_is_not_in_view():
    """A 5 m wall 5.5–7 m east of the camera's foot on flat ground: the ray to a point 8 m east passes
    2.5 m above the ground at 6 m east (10 m · (1 − 6/8)), through the wall."""
    flat = synthetic_terrain(SITE.lat0, SITE.lon0, kind="plane", base_height_m=SITE.h0, size_m=60.0, cell_m=0.5)
    x, _ = flat.cell_centres()
    wall = flat.heights.copy()
    wall[:, (x - x.mean() > 5.5) & (x - x.mean() < 7.0)] += 5.0
    walled = type(flat)(wall, flat.geotransform, flat.crs, flat.vertical_datum, source="walled")
    points = on_ground([[8.0, 0.0], [-8.0, 0.0]])
    frames = [poses_over([0.0, 0.0])]
    np.testing.assert_array_equal(in_view(frames, SITE, points, ground=DemGroundFactory(flat)).mask, [True, True])
    np.testing.assert_array_equal(in_view(frames, SITE, points, ground=DemGroundFactory(walled)).mask, [False, True])


def test_evaluate_flights_counts_the_recall_denominator_on_the_flights_ground():
    points = np.array([[10.5, 0.0], [-9.0, 0.0], [3.0, 0.0]])
    lat, lon, h = SITE.to_geodetic(on_ground(points))
    geotags = Geotags(np.array(["down", "up", "middle"]), lat, lon, h)
    det = Detections(lat[2:], lon[2:], h[2:], np.zeros(1), np.ones(1))
    op = OperatingPoint(min_samples=1)
    frames = [poses_over([0.0, 0.0])]
    level = evaluate_flights([Flight(det, frames)], geotags, op, local=SITE)
    on_dem = evaluate_flights([Flight(det, frames, ground=DemGroundFactory(sloped_dem()))], geotags, op, local=SITE)
    np.testing.assert_array_equal(level.flights[0].in_view.mask, [False, True, True])
    np.testing.assert_array_equal(on_dem.flights[0].in_view.mask, [True, False, True])
    assert (level.pooled.n_in_view, level.pooled.n_recovered) == (2, 1)
    assert (on_dem.pooled.n_in_view, on_dem.pooled.n_recovered) == (2, 1)


def test_the_record_gives_the_ground_it_names_and_refuses_a_missing_or_unasked_dem():
    dem = sloped_dem(vertical_datum="msl", geoid_undulation_m=41.5)
    record = GroundRecord.of(dem, "/data/site_dem.tif")
    assert (record.model, record.dem_datum, record.geoid_undulation_m) == (DEM, "msl", 41.5)
    factory = record.factory(dem, "detections")
    assert isinstance(factory, DemGroundFactory) and factory.dem is dem and not needs_ground_height(factory)
    with pytest.raises(InputError, match=r"detections, field 'DEM': .*the DEM /data/site_dem\.tif \(heights msl, "
                                         r"N = 41\.5 m\): give that DEM"):
        record.factory(None, "detections")
    assert GroundRecord.of(None).factory(None) is None and needs_ground_height(None)
    assert GroundRecord.of(None, method_plane=True).factory(None) is MethodPlaneGround
    for model in (LEVEL_PLANE, METHOD_PLANE):
        with pytest.raises(InputError, match="not on a DEM: leave DEM empty"):
            GroundRecord(model).factory(dem, "detections")
    with pytest.raises(InputError, match="ground model 'terrain' is not one of level, method_plane, dem"):
        GroundRecord("terrain")


def test_layers_placed_on_different_grounds_are_refused_together():
    dem = GroundRecord(DEM, "a.tif", "ellipsoidal")
    assert common_ground([dem, GroundRecord(DEM, "a.tif", "ellipsoidal")], ["x", "y"]) == dem
    with pytest.raises(InputError, match=r"different grounds \(x on the DEM a\.tif .*; y on the level plane"):
        common_ground([dem, GroundRecord()], ["x", "y"])
