"""Heights: references, units and the one conversion, against NGA's published EGM96 values and PROJ's own
command line (GDAL's gdaltransform), not against this module."""
import subprocess

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.geometry import heights
from birdseye.birdseye_qgis.core.geometry.heights import (
    EGM96_REFERENCE,
    ELLIPSOIDAL_REFERENCE,
    MSL_REFERENCE,
    UNKNOWN_REFERENCE,
    GeoidGridMissing,
    VerticalReference,
    convert_heights,
    crs_name_units,
    crs_vertical_reference,
    geoid_undulation,
    height_shift,
    metres_per_unit,
)

#: NGA's test points for EGM96 (latitude, longitude east, N in m), computed from the spherical harmonics; the
#: 15' grid PROJ interpolates agrees within a few centimetres.
NGA_EGM96 = [(38.6281550, 269.7791550, -31.628), (-14.6212170, 305.0211140, -2.969),
             (46.8743190, 102.4487290, -43.575), (-23.6174460, 133.8747120, 15.871),
             (38.6254730, 359.9995000, 50.066), (-0.4667440, 0.0023000, 17.329)]


def test_egm96_undulation_matches_ngas_published_values():
    lat, lon, n = (np.array(c) for c in zip(*NGA_EGM96))
    np.testing.assert_allclose(geoid_undulation(lat, (lon + 180.0) % 360.0 - 180.0), n, atol=0.07)


def test_egm96_undulation_matches_proj_through_gdals_command_line():
    points = [(46.8, -92.1), (-27.55, 151.95), (40.7167, -89.6702)]
    text = "\n".join(f"{lon} {lat} 0" for lat, lon in points) + "\n"
    out = subprocess.run(["gdaltransform", "-s_srs", "EPSG:4979", "-t_srs", "EPSG:4326+5773"], input=text,
                         capture_output=True, text=True, check=True).stdout.split()
    geoid_height = np.array(out, dtype=float).reshape(-1, 3)[:, 2]
    lat, lon = np.array(points).T
    np.testing.assert_allclose(geoid_undulation(lat, lon), -geoid_height, atol=1e-6)


def test_units_are_exact_and_named_as_files_name_them():
    assert metres_per_unit("ftUS") == 1200.0 / 3937.0 == metres_per_unit("US survey foot")
    assert metres_per_unit("ft") == 0.3048 == metres_per_unit("Foot") and metres_per_unit("metre") == 1.0
    with pytest.raises(InputError, match="'chains' is not a length unit"):
        metres_per_unit("chains")
    assert crs_name_units("NAD83(2011) / Illinois West (ftUS) + NAVD88(GEOID18) height (ftUS)") == (
        1200.0 / 3937.0, 1200.0 / 3937.0)
    assert crs_name_units("WGS 84 / UTM zone 15N") == (None, None)
    assert crs_name_units("NAD83 / Texas Central (ft) + NAVD88 height (m)") == (0.3048, 1.0)
    # 461.923 US survey feet (a real Emlid export's ellipsoidal height) is 140.7944 m, 0.3 mm from the international
    # foot's reading: 2 ppm.
    assert 461.923 * metres_per_unit("ftUS") == pytest.approx(140.7944, abs=1e-4)


def test_references_read_back_as_written():
    for ref in (ELLIPSOIDAL_REFERENCE, MSL_REFERENCE, UNKNOWN_REFERENCE, EGM96_REFERENCE,
                VerticalReference("geoid", "EGM2008")):
        assert VerticalReference.parse(ref.text) == ref
    assert VerticalReference.parse("egm96") == EGM96_REFERENCE and VerticalReference.parse(None) == UNKNOWN_REFERENCE
    with pytest.raises(InputError, match="row 3, field 'height_ref': 'NAVD88' is not a vertical reference"):
        VerticalReference.parse("NAVD88", "frames", 3, "height_ref")
    assert crs_vertical_reference("EPSG:32615+5773") == EGM96_REFERENCE
    assert crs_vertical_reference("EPSG:4979") == ELLIPSOIDAL_REFERENCE
    assert crs_vertical_reference("EPSG:6455+6360") == MSL_REFERENCE  # NAVD88 height (ftUS): a named system
    assert crs_vertical_reference("EPSG:32615") is None


def test_conversions_go_through_the_ellipsoid_and_never_mix_silently():
    lat, lon = 46.8, -92.1
    n = float(geoid_undulation(lat, lon))
    # Same reference: nothing asked, nothing said.
    same = height_shift(EGM96_REFERENCE, EGM96_REFERENCE, lat, lon)
    assert same.median_m == 0.0 and same.note == ""
    # A geoid model through PROJ's grid, both ways; the user's N wins where given.
    assert convert_heights(158.5, lat, lon, EGM96_REFERENCE, ELLIPSOIDAL_REFERENCE) == pytest.approx(158.5 + n)
    assert convert_heights(158.5 + n, lat, lon, ELLIPSOIDAL_REFERENCE, EGM96_REFERENCE) == pytest.approx(158.5)
    given = height_shift(EGM96_REFERENCE, ELLIPSOIDAL_REFERENCE, lat, lon, given_undulation_m=-30.0)
    assert given.median_m == -30.0 and "N = -30.00 m as given" in given.note
    # Mean sea level without a model: only with N; the message says what EGM96 would give.
    with pytest.raises(InputError, match=rf"GEOID_UNDULATION_M.*EGM96 puts it at {n:+.2f} m here"):
        height_shift(MSL_REFERENCE, ELLIPSOIDAL_REFERENCE, lat, lon)
    # Two mean sea levels without N: the same assumed, and said.
    assert "same mean sea level assumed" in height_shift(MSL_REFERENCE, EGM96_REFERENCE, lat, lon).note
    with pytest.raises(InputError, match="unstated vertical reference cannot be converted"):
        height_shift(UNKNOWN_REFERENCE, ELLIPSOIDAL_REFERENCE, lat, lon)


def test_a_missing_geoid_grid_stops_the_run_naming_the_grid(monkeypatch):
    """Where PROJ lacks the grid it would fall back to a 'ballpark' operation that returns N = 0: refused, naming
    the grid file and how to install it, or the N to give."""
    monkeypatch.setitem(heights.GEOID_MODELS, "EGM96", (5773, ("no_such_grid.tif",)))

    class NoGrid:
        best_available = False
        transformers = []

    monkeypatch.setattr("pyproj.transformer.TransformerGroup", lambda *a, **k: NoGrid())
    heights._geoid_transformer.__wrapped__.cache_clear()
    try:
        with pytest.raises(GeoidGridMissing, match=r"no_such_grid\.tif.*proj-data.*GEOID_UNDULATION_M") as err:
            height_shift(EGM96_REFERENCE, ELLIPSOIDAL_REFERENCE, 46.8, -92.1)
        assert err.value.field == "GEOID_UNDULATION_M"
        # The user's N still converts.
        assert height_shift(EGM96_REFERENCE, ELLIPSOIDAL_REFERENCE, 46.8, -92.1, -28.6).median_m == -28.6
        assert not heights.geoid_grid_installed("EGM96")
    finally:
        heights._geoid_transformer.__wrapped__.cache_clear()  # the real grid again once monkeypatch undoes
