"""The surveyed area (core/field/surveyed_area.py) that Write labels and Plan flight share: the geotags' hull
grown by a margin, drawn polygons with holes, and which tile footprints lie wholly inside."""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.surveyed_area import (
    MARGIN_SIDES,
    PlacedArea,
    points_in_rings,
    surveyed_area,
)
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame

SITE = LocalFrame(-27.55, 151.95, 400.0)


def geodetic(xy):
    """WGS84 of local east, north (m) on the site's ground (up 0: the site's height)."""
    lat, lon, _ = SITE.to_geodetic(np.column_stack([xy, np.zeros(len(xy))]))
    return np.atleast_1d(lat), np.atleast_1d(lon)


def shoelace(ring) -> float:
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def polygon_area_of_margin(m: float) -> float:
    """Area of the regular 64-gon inscribed in the circle of radius m: (n/2)·m²·sin(2π/n)."""
    return MARGIN_SIDES / 2 * m ** 2 * np.sin(2 * np.pi / MARGIN_SIDES)


def test_hull_of_a_square_of_geotags_grown_by_two_metres():
    """Four geotags on a 10 m square (and one inside), margin 2 m. The Minkowski sum of the square with the
    64-gon has area 100 + perimeter·2 (the 64-gon has vertices at 0°, 90°, 180°, 270°, so its support along the
    square's normals is the full 2 m) + the 64-gon's own area; its boundary lies 2 m out beside the sides, and
    in the corners at 2 m at a vertex (225°) but only 2·cos(π/64) half-way between two vertices."""
    corners = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0], [4.0, 6.0]])
    area = surveyed_area(*geodetic(corners), margin_m=2.0, geotag_height=[SITE.h0] * 4 + [np.nan])
    assert not area.drawn and area.to_dict() == {"source": "geotag_hull", "margin_m": 2.0, "geotags": 5}
    placed = area.placed(SITE)
    assert len(placed.rings) == 1
    assert shoelace(placed.rings[0]) == pytest.approx(100 + 40 * 2 + polygon_area_of_margin(2.0), abs=1e-6)
    beside = np.array([[-1.99, 5.0], [-2.01, 5.0], [5.0, 11.99], [5.0, 12.01]])
    assert placed.contains(beside).tolist() == [True, False, True, False]
    at_vertex, between = np.radians(225.0), np.radians(225.0) + np.pi / MARGIN_SIDES
    reach = 2.0 * np.cos(np.pi / MARGIN_SIDES)  # 1.99759 m
    corner = np.array([[r * np.cos(a), r * np.sin(a)] for a, r in
                       ((at_vertex, 1.99), (at_vertex, 2.01), (between, reach - 1e-3), (between, reach + 1e-3))])
    assert placed.contains(corner).tolist() == [True, False, True, False]


def test_one_geotag_gives_the_margin_disc_and_no_margin_gives_nothing():
    one = surveyed_area(*geodetic(np.array([[3.0, 4.0]])), margin_m=1.5, geotag_height=[SITE.h0])
    ring = one.placed(SITE).rings[0]
    assert shoelace(ring) == pytest.approx(polygon_area_of_margin(1.5), abs=1e-3)
    assert one.placed(SITE).contains(np.array([[3.0, 5.49], [3.0, 5.51]])).tolist() == [True, False]
    nothing = surveyed_area(*geodetic(np.array([[3.0, 4.0], [5.0, 4.0]])), margin_m=0.0)
    assert nothing.placed(SITE).contains(np.array([[4.0, 4.0]])).tolist() == [False]
    assert surveyed_area([], [], 1.0).placed(SITE).contains(np.zeros((1, 2))).tolist() == [False]
    with pytest.raises(InputError, match="SURVEY_MARGIN_M"):
        surveyed_area(*geodetic(np.array([[3.0, 4.0]])), margin_m=-1.0)


def test_drawn_polygons_with_a_hole_by_the_even_odd_rule():
    outer = np.array([[0.0, 0.0], [20.0, 0.0], [20.0, 20.0], [0.0, 20.0]])
    hole = np.array([[5.0, 5.0], [10.0, 5.0], [10.0, 10.0], [5.0, 10.0]])
    other = np.array([[30.0, 0.0], [40.0, 0.0], [35.0, 8.0]])
    area = surveyed_area([], [], drawn=[geodetic(r) for r in (outer, hole, other)])
    assert area.drawn and area.to_dict() == {"source": "drawn", "rings": 3}
    points = np.array([[1.0, 1.0], [7.0, 7.0], [15.0, 15.0], [35.0, 2.0], [35.0, 9.0], [25.0, 5.0], [np.nan, 1.0]])
    assert area.placed(SITE).contains(points).tolist() == [True, False, True, True, False, False, False]
    with pytest.raises(InputError, match="three corners"):
        surveyed_area([], [], drawn=[geodetic(outer[:2])])


def square(x0, y0, side):
    return np.array([[x0, y0], [x0 + side, y0], [x0 + side, y0 + side], [x0, y0 + side]])


def test_a_footprint_is_inside_only_when_nothing_of_the_outside_reaches_into_it():
    """All corners inside is not enough: a hole wholly within the footprint, or a thin strip of outside that
    crosses it between its corners, leaves ground outside the area."""
    field = square(0.0, 0.0, 100.0)
    plain = PlacedArea([field])
    holed = PlacedArea([field, square(12.0, 12.0, 2.0)])
    # A notch 0.2 m wide cut from the top edge down to y = 0.5, across the footprint [10, 18] × [1, 9]: no corner
    # of either lies inside the other. A footprint touching the boundary is not inside.
    notched = PlacedArea([np.array([[0.0, 0.0], [100.0, 0.0], [100.0, 100.0], [15.1, 100.0], [15.1, 0.5],
                                    [14.9, 0.5], [14.9, 100.0], [0.0, 100.0]])])
    tiles = np.stack([square(10.0, 10.0, 10.0), square(95.0, 10.0, 10.0), square(10.0, 1.0, 8.0),
                      square(40.0, 40.0, 10.0), square(40.0, 0.0, 10.0)])
    assert plain.contains_polygons(tiles).tolist() == [True, False, True, True, False]
    assert holed.contains_polygons(tiles).tolist() == [False, False, True, True, False]
    assert notched.contains_polygons(tiles).tolist() == [False, False, False, True, False]
    assert notched.contains(tiles[2]).all()  # every corner of the crossed footprint is inside
    assert PlacedArea([]).contains_polygons(tiles).tolist() == [False] * 5


def test_boundary_distance_and_rings_given_closed_or_open():
    plain = PlacedArea([square(0.0, 0.0, 10.0)])
    assert plain.boundary_distance(np.array([[5.0, 5.0], [1.0, 3.0], [13.0, 14.0]])) == pytest.approx([5.0, 1.0, 5.0])
    closed = np.vstack([square(0.0, 0.0, 10.0), [[0.0, 0.0]]])
    points = np.array([[5.0, 5.0], [10.5, 5.0], [-0.5, 0.0]])
    assert points_in_rings([closed], points).tolist() == points_in_rings([square(0.0, 0.0, 10.0)], points).tolist()
