"""DEM ground model: ray casting against closed forms, round trips, misses, holes, ridges, datum checks."""
import math
from dataclasses import replace

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.design import terrain_slope as ts
from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.geometry import geodesy
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.dem import (
    TAKEOFF_REACH_M,
    DemGround,
    DemRaster,
    Heightfield,
    check_vertical_datum,
    dem_tolerance_m,
    exceeds_flat_envelope,
    flat_envelope_warning,
    frame_terrain_slope,
    heightfield_from_dem,
    intersect_heightfield,
)
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
from birdseye.birdseye_qgis.core.geometry.heights import (
    EGM96_REFERENCE,
    ELLIPSOIDAL_REFERENCE,
    MSL_REFERENCE,
    UNKNOWN_REFERENCE,
    geoid_undulation,
)
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import footprints, pixel_to_ground, project_pairs
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from birdseye.birdseye_qgis.core.sim.terrain import synthetic_terrain

NADIR = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
SITE = (-27.55, 151.95, 400.0)


def make_camera(dist=(-0.08, 0.12, 4e-4, -3e-4, 0.01), lever=(0.05, -0.02, 0.03), f=(4264.4945, 4262.8927)):
    t = np.eye(4)
    t[:3, :3] = NADIR
    t[:3, 3] = -NADIR @ np.asarray(lever)
    return CameraModel(1920, 1200, f[0], f[1], 958.4594, 592.5033, dist, t)


def make_geometry(camera, east, north, up, roll=0.0, pitch=0.0, yaw=0.0, ground_h=np.nan, site=SITE):
    """Frames whose IMU sits at (east, north, up) of the local frame at ``site``; attitudes in degrees."""
    east, north, up, roll, pitch, yaw, ground_h = np.broadcast_arrays(
        *(np.atleast_1d(np.asarray(a, float)) for a in (east, north, up, roll, pitch, yaw, ground_h)))
    local = geodesy.LocalFrame(*site)
    lat, lon, h = local.to_geodetic(np.column_stack([east, north, up]))
    q = rotmat_to_quat(euler_zyx_to_rotmat(*np.radians([roll, pitch, yaw])))
    poses = FramePoses(np.arange(len(east)), lat, lon, h, q, ground_h, camera)
    return FrameGeometry(poses, local)


def frames_above(dem, camera, agl, site, **kw):
    """Frames ``agl`` metres above the DEM's terrain under their planned local east/north."""
    east, north = np.asarray(kw.pop("east"), float), np.asarray(kw.pop("north"), float)
    local = geodesy.LocalFrame(*site)
    lat, lon, _ = local.to_geodetic(np.column_stack([east, north, np.zeros_like(east)]))
    terrain_u = local.from_geodetic(lat, lon, dem.sample_geodetic(lat, lon))[:, 2]
    return make_geometry(camera, east, north, terrain_u + np.asarray(agl, float), site=site, **kw)


def plane_heightfield(a=0.0, b=0.0, c=0.0, half=150.0, step=1.0, **kw):
    """U = a + b·E + c·N on a square grid of side 2·half (local metres)."""
    e = np.arange(-half, half + step / 2, step)
    ee, nn = np.meshgrid(e, e)
    return Heightfield(-half, -half, step, a + b * ee + c * nn, **kw)


def pixel_grid(cam, nu=21, nv=15):
    u, v = np.meshgrid(np.linspace(-0.5, cam.width - 0.5, nu), np.linspace(-0.5, cam.height - 0.5, nv))
    return np.column_stack([u.ravel(), v.ravel()])


FRAMES = dict(east=[0.0, 30.0, -40.0, 10.0], north=[0.0, -20.0, 35.0, 50.0], roll=[0.0, 4.0, -6.0, 2.0],
              pitch=[0.0, -3.0, 5.0, 8.0], yaw=[0.0, 130.0, 250.0, 45.0])


def frames_over(cam, up=(10.0, 20.0, 15.0, 12.0), **kw):
    return make_geometry(cam, up=list(up), **{**FRAMES, **kw})


def cast(geom, ground, uv):
    fi = np.repeat(np.arange(len(geom)), len(uv))
    pts, ok = pixel_to_ground(geom, ground, fi, np.tile(uv, (len(geom), 1)))
    return fi, np.tile(uv, (len(geom), 1)), pts, ok


# --------------------------------------------------------------------------- closed forms
def test_tilted_plane_intersection_equals_the_analytic_ray_plane_point():
    cam = make_camera()
    a, b, c = 1.5, math.tan(math.radians(20.0)), -0.15  # ~21° of slope, rising east
    hf = plane_heightfield(a, b, c)
    geom = frames_over(cam, up=(40.0, 50.0, 30.0, 45.0))
    fi, uv, pts, ok = cast(geom, DemGround(geom, hf), pixel_grid(cam))
    assert ok.all()
    o, d = geom.C[fi], geom.rays(fi, uv)
    # Plane U − bE − cN = a:  t = (a − (o_U − b o_E − c o_N)) / (d_U − b d_E − c d_N).
    t = (a - (o[:, 2] - b * o[:, 0] - c * o[:, 1])) / (d[:, 2] - b * d[:, 0] - c * d[:, 1])
    expected = o + t[:, None] * d
    assert np.max(np.linalg.norm(pts - expected, axis=1)) < 1e-3
    assert np.max(np.linalg.norm(pts - expected, axis=1)) < 1e-6  # in fact to the solver's tolerance
    # The same answer down the robust path alone.
    marched = intersect_heightfield(hf, o, d, fast=False)
    assert marched.valid.all() and marched.marched.all()
    assert np.max(np.linalg.norm(marched.points - expected, axis=1)) < 1e-6


def test_bilinear_heights_are_exact_on_a_plane_and_the_raster_convention_is_cell_centres():
    a, b, c = 3.0, 0.31, -0.17
    hf = plane_heightfield(a, b, c, half=20.0, step=0.7)
    rng = np.random.default_rng(1)
    e, n = rng.uniform(-20, hf.east_max, 500), rng.uniform(-20, hf.north_max, 500)
    h, ge, gn = hf.height_and_gradient(e, n)
    np.testing.assert_allclose(h, a + b * e + c * n, atol=1e-12)
    np.testing.assert_allclose(ge, b, atol=1e-12)
    np.testing.assert_allclose(gn, c, atol=1e-12)
    assert np.isnan(hf.height_at(np.array([-20.01, 0.0]), np.array([0.0, hf.north_max + 0.01]))).all()

    # A raster: x0 = 1000, 2 m cells, y0 = 5000, rows running south. Cell (r, c) has its centre at
    # (1000 + 2c + 1, 5000 − 2r − 1) and its value there.
    heights = np.arange(12.0).reshape(3, 4) ** 1.5
    dem = DemRaster(heights, (1000.0, 2.0, 5000.0, -2.0), "EPSG:32756", "ellipsoidal")
    r, col = np.meshgrid(np.arange(3), np.arange(4), indexing="ij")
    np.testing.assert_allclose(dem.sample(1000 + 2 * col + 1, 5000 - 2 * r - 1), heights, atol=1e-12)
    # Between centres: bilinear; outside the outermost centres: NaN.
    assert dem.sample(1002.0, 4998.0) == pytest.approx(heights[:2, :2].mean())
    assert np.isnan(dem.sample(1000.5, 4999.0))
    with pytest.raises(InputError, match="geographic CRS.*reproject"):
        DemRaster(heights, (150.0, 1e-5, -27.0, -1e-5), "EPSG:4326", "ellipsoidal")
    with pytest.raises(InputError, match="not a north-up grid"):
        DemRaster(heights, (1000.0, -2.0, 5000.0, -2.0), "EPSG:32756")
    plane = DemRaster(2.0 + 0.1 * np.arange(4)[None, :] - 0.3 * np.arange(3)[:, None], (0.0, 1.0, 0.0, -1.0), 32756)
    x, y = np.random.default_rng(2).uniform(0.5, 3.5, 50), np.random.default_rng(3).uniform(-2.5, -0.5, 50)
    np.testing.assert_allclose(plane.sample(x, y), 2.0 + 0.1 * (x - 0.5) - 0.3 * (-y - 0.5), atol=1e-12)


def test_dem_in_utm_to_local_heightfield_keeps_hits_on_the_dem_surface():
    """Through the geodesy: hit points, taken back to WGS84 and the DEM's UTM grid, lie on the DEM."""
    lat0, lon0 = 45.0, 11.95  # 2.95° from the central meridian: convergence ≈ 2.1°, scale ≠ 1
    dem = synthetic_terrain(lat0, lon0, "plane", slope_deg=20.0, aspect_deg=210.0, base_height_m=250.0,
                            size_m=300.0, cell_m=1.0)
    cam = make_camera()
    geom = frames_above(dem, cam, [12.0, 18.0, 25.0, 15.0], (lat0, lon0, 250.0), **FRAMES)
    ground = DemGround.from_dem(geom, dem)
    fi, uv, pts, ok = cast(geom, ground, pixel_grid(cam, 9, 7))
    assert ok.all()
    lat, lon, h = geom.local.to_geodetic(pts)
    # Nodes are exact (iterated through ECEF, curvature included) and a plane stays a plane: far below
    # the 1 mm goal (one round of the node iteration alone would leave ~0.5 mm here).
    assert np.max(np.abs(h - dem.sample_geodetic(lat, lon))) < 1e-5
    # The resampled heightfield covers what the frames see, and no more than the DEM.
    _, complete = footprints(geom, ground)
    assert complete.all()
    assert ground.heightfield.shape[0] * ground.heightfield.shape[1] < dem.heights.size


def test_no_data_of_the_raster_carries_into_the_local_heightfield():
    base = synthetic_terrain(SITE[0], SITE[1], "plane", slope_deg=10.0, base_height_m=SITE[2], size_m=100.0,
                             cell_m=2.0)
    heights = base.heights.copy()
    heights[20:24, 30:33] = -9999.0  # a 3 × 4-cell hole, flagged with a no-data value
    dem = DemRaster(heights, base.geotransform, base.crs, "ellipsoidal", nodata=-9999.0)
    assert np.isnan(dem.heights).sum() == 12
    local = geodesy.LocalFrame(*SITE)
    hf = heightfield_from_dem(dem, local, extent=(-40.0, 40.0, -40.0, 40.0), step_m=1.0)
    e, n = hf.node_coordinates()
    ee, nn = np.meshgrid(e, n)
    lat, lon, _ = local.to_geodetic(np.column_stack([ee.ravel(), nn.ravel(), np.zeros(ee.size)]))
    x, y = geodesy.ProjectedCRS(dem.crs).from_geodetic(lat, lon)
    x0, dx, y0, dy = dem.geotransform
    col, row = (x - x0) / dx - 0.5, (y - y0) / dy - 0.5  # fractional cell-centre indices
    # Bilinear needs the four centres around a node: a node is unknown iff one of them is in the hole.
    touches = (np.floor(row) <= 23) & (np.ceil(row) >= 20) & (np.floor(col) <= 32) & (np.ceil(col) >= 30)
    assert touches.sum() > 50
    assert np.array_equal(np.isnan(hf.z.ravel()), touches)
    with pytest.raises(InputError, match="needs 6,561 nodes.*clip the DEM"):
        heightfield_from_dem(dem, local, extent=(-40.0, 40.0, -40.0, 40.0), step_m=1.0, max_nodes=5000)


def test_round_trip_pixel_to_hilly_ground_to_pixel():
    cam = make_camera()
    dem = synthetic_terrain(SITE[0], SITE[1], "hills", slope_deg=8.0, aspect_deg=60.0, relief_m=12.0,
                            base_height_m=SITE[2], size_m=400.0, cell_m=1.0, wavelength_m=40.0, seed=3)
    geom = frames_above(dem, cam, [10.0, 15.0, 20.0, 12.0], SITE, **FRAMES)
    ground = DemGround.from_dem(geom, dem)
    uv_grid = pixel_grid(cam, 33, 21)
    fi, uv, pts, ok = cast(geom, ground, uv_grid)
    assert ok.all()
    back = project_pairs(geom, fi, pts, ground=ground)
    assert back.in_front.all()
    assert np.max(np.abs(back.uv - uv)) < 1e-3


def test_level_plane_error_on_a_20_degree_slope_matches_the_closed_form():
    """Nadir camera h above the nadir point N, terrain rising at α towards image right (east).

    The level plane through N puts a target d east of N at depth h (u = cx + f·d/h); the camera sees
    it at depth h − d·tan α (u = cx + f·d/(h − d·tan α)). The DEM ground must give the latter; the
    difference is e = f·ρ²·tan α / (1 − ρ·tan α), ρ = d/h (as in the terrain-slope study).
    """
    f = 4000.0
    cam = make_camera(dist=(0, 0, 0, 0, 0), lever=(0, 0, 0), f=(f, f))
    h, alpha = 10.0, math.radians(20.0)
    geom = make_geometry(cam, 0.0, 0.0, h, ground_h=SITE[2])  # yaw 0: image right = east
    dem_ground = DemGround(geom, plane_heightfield(0.0, math.tan(alpha), 0.0, half=60.0, step=1.0))
    level = LevelPlaneGround(geom)
    d = np.array([0.0, 0.5, 1.0, 1.5, 2.0, 2.4])
    rho = d / h
    targets = np.column_stack([d, np.zeros_like(d), d * math.tan(alpha)])  # surveyed on the slope
    fi = np.zeros(len(d), dtype=int)
    uv_dem = project_pairs(geom, fi, targets, ground=dem_ground).uv
    uv_level = project_pairs(geom, fi, targets, ground=level).uv
    np.testing.assert_allclose(uv_dem[:, 0], cam.cx + f * d / (h - d * math.tan(alpha)), atol=1e-6)
    np.testing.assert_allclose(uv_level[:, 0], cam.cx + f * d / h, atol=1e-6)
    np.testing.assert_allclose(uv_dem[:, 1], cam.cy, atol=1e-6)
    error = uv_dem[:, 0] - uv_level[:, 0]
    np.testing.assert_allclose(error, f * rho ** 2 * math.tan(alpha) / (1 - rho * math.tan(alpha)), atol=1e-6)
    np.testing.assert_allclose(error, ts.slope_error_px(cam, h, 20.0, rho), atol=1e-6)
    assert error[-1] > 30.0  # far beyond a label's tolerance at the frame edge


# --------------------------------------------------------------------------- misses, holes, ridges
def test_rays_that_miss_the_dem_are_invalid():
    hf = plane_heightfield(0.0, 0.1, 0.0, half=50.0)
    o = np.array([[0.0, 0.0, 20.0],    # straight down: hits
                  [0.0, 0.0, 20.0],    # upwards: never meets the terrain
                  [0.0, 0.0, 20.0],    # horizontal above the highest terrain
                  [0.0, 0.0, 20.0],    # oblique, leaves the DEM's side before coming down
                  [-80.0, 0.0, 2.0],   # outside the DEM and inside the terrain's height range
                  [10.0, 0.0, 0.5]])   # under the terrain (U = 1 there)
    d = np.array([[0.0, 0.0, -1.0], [0.1, 0.0, 1.0], [1.0, 0.0, 0.0], [-1.0, 0.3, -0.3],
                  [1.0, 0.0, -0.01], [0.0, 0.0, -1.0]])
    for fast in (True, False):
        hits = intersect_heightfield(hf, o, d, fast=fast)
        assert hits.valid.tolist() == [True, False, False, False, False, False]
        assert np.isnan(hits.points[1:]).all()
    # The oblique ray does hit once the DEM is large enough: it was the extent that it left.
    assert intersect_heightfield(plane_heightfield(0.0, 0.1, 0.0, half=150.0), o[3:4], d[3:4]).valid.all()


def test_no_data_holes_invalidate_rays_and_placements_only_where_the_terrain_is_unknown():
    cam = make_camera()
    b = math.tan(math.radians(15.0))
    hf_full = plane_heightfield(0.0, b, 0.0, half=60.0)
    z = hf_full.z.copy()
    e, n = hf_full.node_coordinates()
    z[(np.abs(e)[None, :] <= 1.0) & (np.abs(n)[:, None] <= 0.5)] = np.nan  # nodes E −1…1, N 0
    hf = Heightfield(hf_full.east0, hf_full.north0, hf_full.step, z)
    geom = make_geometry(cam, 0.0, 0.0, 25.0)
    uv = pixel_grid(cam, 61, 41)
    fi, uv, pts, ok = cast(geom, DemGround(geom, hf), uv)
    _, _, truth, _ = cast(geom, DemGround(geom, hf_full), uv)
    # Cells with a no-data corner span E −2…2, N −1…1: rays landing there are invalid.
    in_hole_cells = (np.abs(truth[:, 0]) < 2.0) & (np.abs(truth[:, 1]) < 1.0)
    assert in_hole_cells.sum() > 40 and not ok[in_hole_cells].any()
    # Every ray that lands is where the full plane puts it; away from the hole all of them land.
    assert np.max(np.linalg.norm(pts[ok] - truth[ok], axis=1)) < 1e-6
    far = (np.abs(truth[:, 0]) > 3.5) | (np.abs(truth[:, 1]) > 2.5)
    assert ok[far].all() and far.sum() > 0.5 * len(uv)
    # Rays crossing the hole high above its rim pass on: from 25 m up, a ray landing 1 m beyond the
    # hole cells crossed them ~20 m up, far above the ~6 m of valid terrain around the hole.
    assert ok[(truth[:, 0] > 3.0) & (truth[:, 0] < 3.5) & (np.abs(truth[:, 1]) < 0.5)].all()
    # A camera low over the hole cannot see past it; one high above it can.
    low = intersect_heightfield(hf, [[0.0, 0.0, 0.5]], [[1.0, 0.0, -0.01]])
    assert not low.valid.any()
    # A geotag over the hole has no terrain height: it is not projected into the frame.
    targets = np.array([[0.0, 0.0, 0.0], [2.5, 1.5, 0.0]])
    proj = project_pairs(geom, [0, 0], targets, ground=DemGround(geom, hf))
    assert proj.in_view.tolist() == [False, True]


def ridge_heightfield():
    """Two north–south ridges over flat ground, then a plane rising at 0.5 from E = 70: a thin one
    (crest 8 m at E = 30, faces of slope 8, 2 m wide) and a broad one (crest 10 m at E = 50, faces of
    slope 2). 0.5 m nodes, so the piecewise-linear profile is represented exactly."""
    e = np.arange(-10.0, 150.25, 0.5)
    n = np.arange(-20.0, 20.25, 0.5)
    profile = (np.maximum(0.0, 8.0 - 8.0 * np.abs(e - 30.0)) + np.maximum(0.0, 10.0 - 2.0 * np.abs(e - 50.0))
               + np.maximum(0.0, 0.5 * (e - 70.0)))
    return Heightfield(-10.0, -20.0, 0.5, np.tile(profile, (len(n), 1)))


def test_grazing_rays_over_ridges_stop_at_the_first_hit():
    hf = ridge_heightfield()
    o = np.array([[0.0, 0.0, 12.0]] * 4)
    # 1: clears the thin crest by 25 cm, hits the broad ridge's near face at E = 48 (U = 6); it would
    #    leave that ridge at E ≈ 52.27 and hit the far slope at E ≈ 75.2 — the first hit is the face.
    # 2: clears the broad crest by 1 cm and lands on the far slope: 12 − s·E = 0.5·(E − 70).
    # 3: clears the broad crest by 1 cm but is cut off by the DEM's north edge before it comes down.
    # 4: passes 1.6 m below the thin crest, inside it for only 0.4 m (1.6 half-cells), enters at
    #    12 − s·E = 8E − 232; a march with steps of a cell or more would miss it and hit the broad ridge.
    s2, s4 = (12.0 - 10.01) / 50.0, (12.0 - 6.4) / 30.0
    d = np.array([[48.0, 0.0, -6.0], [1.0, 0.0, -s2], [1.0, 0.25, -s2], [1.0, 0.0, -s4]])
    e2, e4 = (12.0 + 35.0) / (0.5 + s2), 244.0 / (8.0 + s4)
    expected = np.array([[48.0, 0.0, 6.0], [e2, 0.0, 12.0 - s2 * e2], [np.nan] * 3, [e4, 0.0, 12.0 - s4 * e4]])
    for fast in (True, False):
        hits = intersect_heightfield(hf, o, d, fast=fast)
        assert hits.valid.tolist() == [True, True, False, True]
        np.testing.assert_allclose(hits.points, expected, atol=1e-6)
        assert hits.marched[hits.valid].all()  # these rays are not certifiable: they must be marched


def test_grazing_ray_along_a_slope_and_a_ray_parallel_to_it():
    alpha, beta = math.radians(10.0), math.radians(9.5)  # terrain rises at 10°, the ray at 9.5°
    hf = plane_heightfield(0.0, math.tan(alpha), 0.0, half=150.0, step=1.0)
    o = np.array([[-20.0, 3.0, 1.0 - 20.0 * math.tan(alpha)], [-20.0, 3.0, 1.0 - 20.0 * math.tan(alpha)]])
    d = np.array([[math.cos(beta), 0.0, math.sin(beta)], [math.cos(alpha), 0.0, math.sin(alpha)]])
    hits = intersect_heightfield(hf, o, d)
    e_hit = -20.0 + 1.0 / (math.tan(alpha) - math.tan(beta))  # 1 m above the slope, closing at 0.5°
    assert hits.valid.tolist() == [True, False]
    np.testing.assert_allclose(hits.points[0], [e_hit, 3.0, math.tan(alpha) * e_hit], atol=1e-6)


def test_fast_path_agrees_with_marching_on_rough_terrain():
    """The certified Newton path must return the first hit, exactly where marching finds it."""
    cam = make_camera()
    dem = synthetic_terrain(SITE[0], SITE[1], "hills", slope_deg=12.0, relief_m=25.0, base_height_m=SITE[2],
                            size_m=300.0, cell_m=1.0, wavelength_m=30.0, seed=5)
    geom = frames_over(cam, up=(30.0, 28.0, 35.0, 32.0), roll=[0, 15, -20, 10], pitch=[0, -10, 25, 30])
    ground = DemGround.from_dem(geom, dem)
    fi = np.repeat(np.arange(len(geom)), 315)
    uv = np.tile(pixel_grid(cam, 21, 15), (len(geom), 1))
    o, d = geom.C[fi], geom.rays(fi, uv)
    fast = intersect_heightfield(ground.heightfield, o, d, start_height=ground.heightfield.z_max)
    slow = intersect_heightfield(ground.heightfield, o, d, fast=False)
    assert 0.3 < fast.marched.mean() < 1.0  # both paths are exercised
    assert (fast.valid == slow.valid).all() and fast.valid.mean() > 0.95
    np.testing.assert_allclose(fast.points[fast.valid], slow.points[slow.valid], atol=1e-5)


def test_fast_path_is_not_fooled_by_a_wall_beyond_the_certified_neighbourhood():
    """A 45° ray over flat ground with a 28 m wall early on its way: the ray's slab segment (set by a
    30 m spike elsewhere) is far longer than the 4 m tiles around its flat middle, so it must be
    marched — Newton from the level plane would converge on the flat ground behind the wall."""
    e = np.arange(-60.0, 60.5, 1.0)
    z = np.zeros((len(e), len(e)))
    z[:, e == -30.0] = 28.0       # wall along N, faces of slope 28
    z[-1, -1] = 30.0              # spike in the far corner: the slab is 0…30 m
    hf = Heightfield(-60.0, -60.0, 1.0, z, tile_cells=4)
    hits = intersect_heightfield(hf, [[-40.0, 0.0, 35.0]], [[1.0, 0.0, -1.0]], start_height=[0.0])
    e_hit = -873.0 / 29.0  # U = −5 − E meets the near face U = 28·(E + 31)
    assert hits.valid.all() and hits.marched.all()
    np.testing.assert_allclose(hits.points[0], [e_hit, 0.0, -5.0 - e_hit], atol=1e-6)


# --------------------------------------------------------------------------- place
def test_place_moves_points_along_the_frame_up_onto_the_terrain():
    cam = make_camera()
    b, c = math.tan(math.radians(20.0)), 0.1
    hf = plane_heightfield(2.0, b, c, half=200.0)
    geom = make_geometry(cam, [0.0, 150.0], [0.0, -120.0], [12.0, 12.0])  # the second frame's up is tilted
    ground = DemGround(geom, hf)
    p = np.array([[1.0, 2.0, 9.0], [140.0, -118.0, -30.0]])
    placed = ground.place(np.array([0, 1]), p)
    np.testing.assert_allclose(placed[:, 2], hf.height_at(placed[:, 0], placed[:, 1]), atol=1e-9)
    moved = placed - p
    np.testing.assert_allclose(np.cross(moved, geom.up), 0.0, atol=1e-9)
    assert np.linalg.norm(moved[1, :2]) > 1e-4  # not simply straight down the local frame's U axis
    # On level terrain at the altimeter's ground the DEM and the level plane place points alike.
    geom_level = make_geometry(cam, 0.0, 0.0, 12.0, ground_h=SITE[2])
    flat = Heightfield(-200.0, -200.0, 1.0, np.full((401, 401), geom_level.ground_point[0, 2]))
    pts = np.random.default_rng(4).uniform([-5, -5, -2], [5, 5, 2], (50, 3))
    np.testing.assert_allclose(DemGround(geom_level, flat).place(np.zeros(50, int), pts),
                               LevelPlaneGround(geom_level).place(np.zeros(50, int), pts), atol=1e-6)


def test_points_behind_a_ridge_are_occluded():
    hf = ridge_heightfield()
    cam = make_camera(dist=(0, 0, 0, 0, 0), lever=(0, 0, 0))
    geom = make_geometry(cam, 0.0, 0.0, 12.0)
    ground = DemGround(geom, hf)
    targets = ground.place(np.zeros(4, int), np.array([[20.0, 0.0, 0.0],     # flat ground before the ridges
                                                      [49.0, 0.0, 0.0],     # the broad ridge's near face
                                                      [60.0, 0.0, 0.0],     # behind the broad ridge
                                                      [32.0, 0.0, 0.0]]))   # right behind the thin ridge
    assert ground.occluded(np.zeros(4, int), targets).tolist() == [False, False, True, True]


# --------------------------------------------------------------------------- vertical datum
def flat_dem(datum="ellipsoidal", height=400.0, undulation=None, lat=SITE[0], lon=SITE[1]):
    return synthetic_terrain(lat, lon, "plane", base_height_m=height, size_m=200.0, cell_m=2.0,
                             vertical_datum=datum, geoid_undulation_m=undulation)


def poses_over(ground_h, lat=SITE[0], lon=SITE[1], reference=ELLIPSOIDAL_REFERENCE, source="altimeter", up=15.0):
    """Three frames ``up`` m above the site's height (400 m + ``up``), their ground at ``ground_h`` in
    ``reference``, measured as ``source`` says."""
    geom = make_geometry(make_camera(), [0.0, 20.0, -30.0], [0.0, 10.0, 25.0], up, ground_h=ground_h,
                         site=(lat, lon, 400.0))
    return replace(geom.poses, reference=reference, ground_source=[source] * 3)


def test_vertical_datum_configuration_errors_name_the_references():
    with pytest.raises(InputError, match=r"mean sea level with no geoid named.*GEOID_UNDULATION_M.*EGM96 puts it"):
        check_vertical_datum(flat_dem("msl", 370.0), poses_over(400.0))
    with pytest.raises(InputError, match=r"DEM's vertical reference is not stated.*no ground heights"):
        check_vertical_datum(flat_dem("unknown"), poses_over(np.nan))
    with pytest.raises(InputError, match=r"flight's vertical reference is not stated"):
        check_vertical_datum(flat_dem(), poses_over(np.nan, reference=UNKNOWN_REFERENCE))
    with pytest.raises(InputError, match="vertical datum 'egm96'"):
        DemRaster(np.zeros((3, 3)), (0, 1, 0, -1), 32756, "egm96")
    # Converting references with the undulation given, both ways (ellipsoidal = MSL + N).
    assert check_vertical_datum(flat_dem("msl", 370.0, undulation=30.0), poses_over(400.0)).offset_m == 30.0
    assert check_vertical_datum(flat_dem("ellipsoidal", 400.0, undulation=30.0),
                                poses_over(370.0, reference=MSL_REFERENCE)).offset_m == -30.0
    # Unknown on one side: taken as the other's, confirmed by the ground (within ±0.45 m at 15 m).
    assert check_vertical_datum(flat_dem("unknown"), poses_over(400.3)).offset_m == 0.0


def test_like_is_compared_with_like_whatever_the_frames_heights_are_measured_from():
    """DJI frames (EGM96 above sea level over a take-off point) against a DEM at their take-off ground,
    given above sea level or as ellipsoidal heights: accepted either way, the DEM shifted into the frames'
    heights by N — as given, else PROJ's EGM96 grid at the site."""
    n_site = float(geoid_undulation(SITE[0], SITE[1]))
    dji = poses_over(370.0, reference=EGM96_REFERENCE, source="takeoff")
    as_msl = check_vertical_datum(flat_dem("msl", 370.0), dji)
    assert as_msl.offset_m == 0.0 and "same mean sea level" in as_msl.conversion and as_msl.takeoff_miss_m == 0.0
    assert check_vertical_datum(flat_dem("msl", 370.0, undulation=-28.7), dji).offset_m == 0.0
    given = check_vertical_datum(flat_dem("ellipsoidal", 370.0 - 28.7, undulation=-28.7), dji)
    assert given.offset_m == pytest.approx(28.7) and "N = -28.70 m as given" in given.conversion
    from_grid = check_vertical_datum(flat_dem("ellipsoidal", 370.0 + n_site), dji)
    # N at the frames' median position, 25 m from the site: within a millimetre of N there.
    assert from_grid.offset_m == pytest.approx(-n_site, abs=1e-3) and "EGM96 grid" in from_grid.conversion
    assert "take-off height is one the terrain around has" in from_grid.describe()
    # Pose-log frames (ellipsoidal, altimeter) against the same DEM above sea level with N.
    rtk = poses_over(370.0 + n_site)
    assert check_vertical_datum(flat_dem("msl", 370.0, undulation=n_site), rtk).measured_m == pytest.approx(0.0)


def test_the_tolerance_follows_the_height_above_ground_and_the_offset_is_reported():
    """A few per cent of the flight's height above its ground, at least 0.2 m: a DEM 1 m off at 10 m above
    ground is refused, at 40 m it is used and the offset said; what is within is measured either way."""
    assert dem_tolerance_m(10.0) == pytest.approx(0.3) and dem_tolerance_m(40.0) == pytest.approx(1.2)
    assert dem_tolerance_m(3.0) == 0.2 and dem_tolerance_m(float("nan")) == 0.2
    low = poses_over(400.0, up=10.0)
    with pytest.raises(InputError, match=r"\+1\.00 m off the ground measured.*±0\.30 m tolerance at 10\.0 m"):
        check_vertical_datum(flat_dem("ellipsoidal", 401.0), low)
    near = check_vertical_datum(flat_dem("ellipsoidal", 400.25), low)
    assert near.measured_m == pytest.approx(0.25) and "+0.25 m from their measured ground" in near.describe()
    high = check_vertical_datum(flat_dem("ellipsoidal", 401.0), poses_over(400.0, up=40.0))
    assert high.measured_m == pytest.approx(1.0) and high.tolerance_m == pytest.approx(1.2)
    assert "tolerance ±1.20 m at 40.0 m above ground" in high.describe()


def test_a_dem_in_another_vertical_reference_is_caught_against_the_altimeter():
    # Declared ellipsoidal but really MSL: 38 m below the altimeter's ground under every frame.
    with pytest.raises(InputError) as err:
        check_vertical_datum(flat_dem("ellipsoidal", 362.0), poses_over([400.0, 400.5, 399.6]))
    msg = str(err.value)
    assert "median" in msg and "-38.00 m" in msg and "-38.50" in msg and "-37.60" in msg
    assert "±0.45 m tolerance at 15.0 m above ground" in msg and "geoid undulation" in msg
    # A wrong undulation is caught the same way, with the configured tolerance.
    with pytest.raises(InputError, match=r"\+8\.00 m.*±2\.00 m tolerance"):
        check_vertical_datum(flat_dem("msl", 370.0, undulation=38.0), poses_over(400.0), 2.0)
    # Hundreds of metres: not a datum, a unit or no-data problem.
    with pytest.raises(InputError, match="not a geoid undulation"):
        check_vertical_datum(flat_dem("ellipsoidal", 1312.0), poses_over(400.0))
    # A DEM somewhere else (or in the wrong CRS) covers none of the frames.
    with pytest.raises(InputError, match="none of the 3 frames.*CRS"):
        check_vertical_datum(flat_dem(lat=-27.0), poses_over(400.0))
    # Through the ground model's constructor too.
    geom = make_geometry(make_camera(), 0.0, 0.0, 15.0, ground_h=400.0)
    with pytest.raises(InputError, match="another vertical reference"):
        DemGround.from_dem(geom, flat_dem("ellipsoidal", 362.0))


def field_below_a_knoll(knoll_east_m, field=387.0, knoll=400.0, size_m=200.0, cell_m=2.0, **kw):
    """A level field with a 10 m × 10 m knoll ``knoll − field`` metres higher, ``knoll_east_m`` east of
    the site: a drone that takes off from the knoll flies over the field below it."""
    dem = synthetic_terrain(SITE[0], SITE[1], "plane", base_height_m=field, size_m=size_m, cell_m=cell_m, **kw)
    x, y = dem.cell_centres()
    xc, yc = geodesy.ProjectedCRS(dem.crs).from_geodetic(SITE[0], SITE[1])
    on_knoll = (np.abs(y - yc)[:, None] <= 5.0) & (np.abs(x - xc - knoll_east_m)[None, :] <= 5.0)
    dem.heights = np.where(on_knoll, knoll, dem.heights)
    return dem


def test_take_off_height_passes_with_honest_relief_and_fails_with_a_datum_mix_up():
    # Frames over a field 13 m below the knoll the drone took off from: their ground is the take-off
    # height (400 m). Taken as a ground measured under the frames it would be refused; as a take-off it passes.
    dem = field_below_a_knoll(80.0)
    with pytest.raises(InputError, match="another vertical reference"):
        check_vertical_datum(dem, poses_over(400.0))
    assert check_vertical_datum(dem, poses_over(400.0, source="takeoff")).takeoff_miss_m == 0.0
    # The same terrain in MSL heights declared ellipsoidal (N = 38 m): the take-off height lies 38 m above
    # the highest terrain anywhere near the flight.
    wrong = field_below_a_knoll(80.0, field=349.0, knoll=362.0, vertical_datum="ellipsoidal")
    with pytest.raises(InputError) as err:
        check_vertical_datum(wrong, poses_over(400.0, source="takeoff"))
    msg = str(err.value)
    assert "take-off height (400.00 m" in msg and "38.00 m above the highest" in msg
    assert "(349.00 … 362.00 m" in msg and "±0.45 m tolerance" in msg and "geoid undulation" in msg
    assert "barometrically" in msg
    # Declared correctly, with its undulation, it passes and gives the offset.
    msl = field_below_a_knoll(80.0, field=349.0, knoll=362.0, vertical_datum="msl", geoid_undulation_m=38.0)
    assert check_vertical_datum(msl, poses_over(400.0, source="takeoff")).offset_m == 38.0
    # Below the lowest terrain: a take-off 20 m under the field.
    with pytest.raises(InputError, match="20.00 m below the lowest"):
        check_vertical_datum(dem, poses_over(367.0, source="takeoff"))
    with pytest.raises(InputError, match="none of the 3 frames"):
        check_vertical_datum(dem, poses_over(400.0, lat=-27.0, source="takeoff"))
    # A flight height the user gave stands for a take-off ground too, and says so.
    with pytest.raises(InputError, match=r"camera height − flight height\) \(367\.00 m"):
        check_vertical_datum(dem, poses_over(367.0, source="flight_height"))


def test_take_off_check_judges_the_flights_median_within_its_reach():
    dem = field_below_a_knoll(80.0)
    # One frame with a wild height does not sink the flight; the flight's median (0.2 m above the knoll, within
    # the tolerance) decides, and how far it lies above the terrain is reported.
    check = check_vertical_datum(dem, poses_over([400.0, 400.2, 470.0], source="takeoff"))
    assert check.takeoff_miss_m == pytest.approx(0.2) and "lies 0.20 m above the terrain around" in check.describe()
    with pytest.raises(InputError, match=r"take-off height \(470\.00 m, the median over 3 frames"):
        check_vertical_datum(dem, poses_over([470.0, 470.0, 400.0], source="takeoff"))
    # The take-off point counts within TAKEOFF_REACH_M of the frames (the easternmost frame is at 20 m),
    # not beyond.
    near = field_below_a_knoll(20.0 + TAKEOFF_REACH_M - 20.0, size_m=1400.0, cell_m=5.0)
    far = field_below_a_knoll(20.0 + TAKEOFF_REACH_M + 20.0, size_m=1400.0, cell_m=5.0)
    assert check_vertical_datum(near, poses_over(400.0, source="takeoff")).takeoff_miss_m == 0.0
    with pytest.raises(InputError, match="13.00 m above the highest"):
        check_vertical_datum(far, poses_over(400.0, source="takeoff"))


def test_frames_without_a_ground_are_not_checked_and_a_flight_mixes_sources_frame_by_frame():
    """Each frame is checked by its own ground source: refined frames (tie points, under the frame) beside
    unregistered ones (their take-off ground); frames with no ground take no part."""
    dem = field_below_a_knoll(80.0)
    mixed = replace(poses_over([387.1, 400.0, np.nan]), ground_source=["tie_points", "takeoff", ""])
    check = check_vertical_datum(dem, mixed)
    assert (check.n_under, check.n_site) == (1, 1) and check.measured_m == pytest.approx(-0.1)
    assert check.takeoff_miss_m == 0.0


def test_a_flight_level_offset_is_not_checked_again_per_geometry():
    """``vertical_offset_m`` (from one check over the whole flight) is applied as given; without it the
    geometry's own frames are checked (and this one, 13 m above the field, is refused)."""
    dem = field_below_a_knoll(80.0)
    geom = make_geometry(make_camera(), 0.0, 0.0, 15.0, ground_h=400.0)
    with pytest.raises(InputError, match="another vertical reference"):
        DemGround.from_dem(geom, dem)
    for offset in (0.0, 2.5):
        ground = DemGround.from_dem(geom, dem, vertical_offset_m=offset)
        # The field's height in the local frame (up from h0 = 400 m at the site), raised by the offset.
        assert ground.heightfield.height_at(np.array([0.0]), np.array([0.0]))[0] == pytest.approx(
            387.0 + offset - 400.0, abs=1e-3)


# --------------------------------------------------------------------------- slope
def test_terrain_slope_and_aspect_under_each_frame():
    lat0, lon0 = 45.0, 11.95  # convergence ≈ 2.1°: aspect must still come out about true north
    cam = make_camera()
    for slope_deg, aspect_deg in ((20.0, 135.0), (5.0, 310.0)):
        dem = synthetic_terrain(lat0, lon0, "plane", slope_deg=slope_deg, aspect_deg=aspect_deg,
                                base_height_m=250.0, size_m=300.0, cell_m=1.0)
        geom = frames_above(dem, cam, [15.0, 20.0, 12.0, 18.0], (lat0, lon0, 250.0), **FRAMES)
        ground = DemGround.from_dem(geom, dem)
        progress = []
        slope = frame_terrain_slope(geom, ground, progress=progress.append)
        np.testing.assert_allclose(slope.slope_deg, slope_deg, atol=0.1)
        np.testing.assert_allclose(slope.aspect_deg, aspect_deg, atol=0.1)
        assert np.all(slope.rms_m < 1e-3) and np.all(slope.n_samples == 63) and progress[-1] == 1.0
        steep = exceeds_flat_envelope(slope)
        assert steep.tolist() == [slope_deg > 10.0] * 4
        warning = flat_envelope_warning(geom.poses.frame_id, slope)
        if slope_deg > 10.0:
            assert "4 of 4 frames" in warning and "steeper than 10°" in warning and "20.0°" in warning
        else:
            assert warning is None


def test_hilly_terrain_has_the_requested_relief_and_a_fitted_slope_with_roughness():
    dem = synthetic_terrain(SITE[0], SITE[1], "hills", relief_m=20.0, base_height_m=100.0, size_m=200.0,
                            cell_m=2.0, wavelength_m=50.0, seed=7)
    assert dem.heights.shape == (100, 100)
    assert np.nanmax(dem.heights) - np.nanmin(dem.heights) == pytest.approx(20.0)
    assert np.array_equal(dem.heights, synthetic_terrain(SITE[0], SITE[1], "hills", relief_m=20.0,
                                                         base_height_m=100.0, size_m=200.0, cell_m=2.0,
                                                         wavelength_m=50.0, seed=7).heights)
    # About one hill and valley every 50 m: level crossings of the mean along rows every ~25 m.
    rows = dem.heights - dem.heights.mean()
    crossings = np.count_nonzero(np.diff(np.sign(rows), axis=1)) / rows.shape[0]
    assert 200.0 / crossings == pytest.approx(25.0, rel=0.4)
    with pytest.raises(InputError, match="not 'plane' or 'hills'"):
        synthetic_terrain(SITE[0], SITE[1], "mountains")
