"""The ground a nominal camera's focal length is fixed by (refinement.choose_grounds): geotags' ellipsoidal heights
converted into the frames' reference, the drone's own ground or the surveyed one by RTK status, per camera group,
with the reason and the warning the report gives. Synthetic frames; no structure from motion."""
from __future__ import annotations

import math

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.frames import Frames
from birdseye.birdseye_qgis.core.field.refinement import (
    OWN_GROUND,
    SURVEYED_GROUND,
    TERRAIN_GROUND,
    choose_grounds,
    ground_text,
    terrain_grounds,
)
from birdseye.birdseye_qgis.core.geometry import heights
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel

#: Two drones over Brighton Beach (Lake Superior, ≈ 183 m above sea level; EGM96 N ≈ −28.5 m there).
LAT, LON = 46.8426, -91.9941
DRONE_A = CameraModel(960, 540, 560.0, 560.0, 479.5, 269.5)
DRONE_B = CameraModel(1280, 960, 900.0, 900.0, 639.5, 479.5)


def frames(ground_h, rtk_status, reference=heights.EGM96_REFERENCE, sources=None, cameras=None) -> Frames:
    """Frames 40 m above ``ground_h`` (m; NaN: none) with the given RTK status, reference and ground sources."""
    ground_h = np.asarray(ground_h, dtype=float)
    n = len(ground_h)
    sources = sources or [heights.TAKEOFF if math.isfinite(g) else heights.NO_GROUND for g in ground_h]
    return Frames(np.arange(n), [f"/flight/IMG_{i:04d}.JPG" for i in range(n)], np.arange(n, dtype=float),
                  np.full(n, LAT) + 1e-4 * np.arange(n), np.full(n, LON), np.nan_to_num(ground_h, nan=183.0) + 40.0,
                  np.tile([1.0, 0.0, 0.0, 0.0], (n, 1)), ground_h, np.asarray(rtk_status), np.zeros(n),
                  cameras or [DRONE_A] * n, [[] for _ in range(n)], reference=reference, ground_source=sources)


def test_without_rtk_the_drones_own_ground_is_used_and_the_surveyed_one_compared():
    """A barometric AbsoluteAltitude 24.5 m low puts the take-off ground at 158.5 m where the beach is at 183 m:
    camera height minus that ground is still right (the offset cancels), camera height minus the surveyed ground
    is not. The surveyed ground (ellipsoidal, N = −28.5 m given) is converted and its difference reported."""
    flight = frames([158.5] * 4, [1] * 4)
    ground, (choice,) = choose_grounds(flight, np.full(3, 183.0 - 28.5), geoid_undulation_m=-28.5)
    assert choice.used == OWN_GROUND and not choice.rtk
    np.testing.assert_allclose(ground, 158.5)
    assert choice.surveyed_m == pytest.approx(183.0) and choice.difference_m == pytest.approx(24.5)
    assert "no RTK fix" in choice.reason and "N = -28.50 m as given" in choice.conversion
    assert "take-off point" in choice.warning
    text = ground_text(choice, flight)
    assert "own ground 158.50 m (takeoff)" in text and "surveyed ground 183.00 m" in text
    assert "lies 24.50 m above the own ground" in text


def test_with_an_rtk_fix_the_surveyed_ground_is_used_per_camera():
    """Two drones in one layer: the RTK one takes the geotags' ground (converted into its EGM96 heights), the other
    keeps its take-off ground; no warning for the surveyed one."""
    flight = frames([180.0] * 3 + [150.0] * 3, [3] * 3 + [1] * 3, cameras=[DRONE_A] * 3 + [DRONE_B] * 3)
    ground, choices = choose_grounds(flight, [154.0, 154.5, 155.0], geoid_undulation_m=-28.5)
    rtk, other = sorted(choices, key=lambda c: c.frames)
    assert (rtk.used, other.used) == (SURVEYED_GROUND, OWN_GROUND) and rtk.rtk and not other.rtk
    np.testing.assert_allclose(ground, [183.0] * 3 + [150.0] * 3)
    assert rtk.warning == "" and "RTK fix" in rtk.reason and other.warning


def test_frames_without_a_ground_take_the_geotags():
    """EXIF-only images imported without a flight height have no ground: the geotags give it."""
    flight = frames([math.nan] * 4, [1] * 4)
    ground, (choice,) = choose_grounds(flight, [160.0], geoid_undulation_m=-30.0)
    assert choice.used == SURVEYED_GROUND and math.isnan(choice.own_m) and choice.own_source == ""
    np.testing.assert_allclose(ground, 190.0)
    assert choice.warning == "" and "no ground of their own" in choice.reason


def test_no_ground_and_no_geotags_leaves_none():
    ground, (choice,) = choose_grounds(frames([math.nan] * 3, [1] * 3))
    assert choice.used == "" and np.isnan(ground).all()
    assert "no ground to measure" in ground_text(choice, frames([math.nan] * 3, [1] * 3))


def test_frames_in_an_unknown_reference_keep_their_own_ground_and_say_why():
    flight = frames([150.0] * 3, [3] * 3, reference=heights.UNKNOWN_REFERENCE)
    ground, (choice,) = choose_grounds(flight, [120.0], geoid_undulation_m=-28.5)
    assert choice.used == OWN_GROUND and math.isnan(choice.surveyed_m)
    np.testing.assert_allclose(ground, 150.0)
    assert "unstated vertical reference" in choice.reason


def test_ellipsoidal_frames_compare_without_a_geoid():
    """Pose-log frames are ellipsoidal like the geotags: nothing to convert."""
    flight = frames([130.0] * 3, [3] * 3, reference=heights.ELLIPSOIDAL_REFERENCE,
                    sources=[heights.ALTIMETER] * 3)
    ground, (choice,) = choose_grounds(flight, [129.0, 131.0])
    assert choice.used == SURVEYED_GROUND and choice.conversion == "" and choice.warning == ""
    np.testing.assert_allclose(ground, 130.0)


def test_an_unnamed_mean_sea_level_without_n_is_refused_naming_the_parameter():
    with pytest.raises(InputError, match="GEOID_UNDULATION_M"):
        choose_grounds(frames([150.0] * 3, [3] * 3, reference=heights.MSL_REFERENCE), [120.0])


def test_egm96_frames_convert_through_projs_grid_when_no_n_is_given():
    assert heights.geoid_grid_installed("EGM96"), "PROJ's EGM96 grid is missing (make setup installs proj-data)"
    n = float(heights.geoid_undulation(LAT, LON))
    _, (choice,) = choose_grounds(frames([158.5] * 3, [1] * 3), [183.0 + n])
    assert choice.surveyed_m == pytest.approx(183.0, abs=0.01) and "EGM96 grid" in choice.conversion


def test_a_dems_terrain_under_the_frames_comes_first_where_it_covers_them():
    """The terrain a DEM holds in each frame's view (terrain_grounds: converted into the frames' heights, checked
    against their ground) replaces a take-off point that lies 4 m below the field, frame by frame; a camera the
    DEM covers for fewer than half its frames keeps the rule without it."""
    flight = frames([158.5] * 4 + [150.0] * 3, [1] * 7, cameras=[DRONE_A] * 4 + [DRONE_B] * 3)
    terrain = np.array([162.1, 162.6, np.nan, 162.3, np.nan, 151.0, np.nan])
    ground, choices = choose_grounds(flight, terrain=terrain)
    covered, other = sorted(choices, key=lambda c: c.frames)
    assert covered.used == TERRAIN_GROUND and covered.terrain_m == pytest.approx(162.3) and covered.warning == ""
    assert other.used == OWN_GROUND and other.warning  # one of three frames covered: not most of them
    np.testing.assert_array_equal(ground[:4], terrain[:4])
    np.testing.assert_allclose(ground[4:], 150.0)
    assert "the DEM's terrain in view 162.30 m (median), +3.80 m from the own ground" in ground_text(covered, flight)


def test_the_terrain_in_view_is_the_dems_median_where_the_frames_look():
    """Over a DEM tilted along the flight, each frame's terrain is the DEM's height under its image centre (a
    plane: the median of a symmetric grid of rays is its centre's), in the frames' EGM96 heights (DEM given above
    sea level: no conversion); the take-off ground 13 m above the DEM under the frames is relief the DEM has
    within reach of them, so the check passes."""
    from birdseye.birdseye_qgis.core.sim.terrain import synthetic_terrain

    flight = frames([170.0] * 3, [1] * 3)  # the camera's axis along body down: straight down
    dem = synthetic_terrain(LAT, LON, "plane", base_height_m=157.0, size_m=400.0, cell_m=1.0, vertical_datum="msl",
                            slope_deg=5.0, aspect_deg=180.0)
    terrain, check = terrain_grounds(flight, dem)
    np.testing.assert_allclose(terrain, dem.sample_geodetic(flight.lat, flight.lon), atol=0.05)
    assert check.offset_m == 0.0 and check.takeoff_miss_m == pytest.approx(0.0, abs=1.2)
