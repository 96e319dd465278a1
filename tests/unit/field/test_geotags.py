"""Geotag readers: rover CSV, header CSV, NMEA GGA, point-layer columns, fix filter, pole, duplicates."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.geotags import (
    ColumnMapping,
    Geotags,
    detect_format,
    geotag_ids,
    geotags_from_columns,
    prepare_geotags,
    read_geotags,
)
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


# ------------------------------------------------------------------------------------ rover CSV
def test_rover_csv_values_order_and_rows(tmp_path):
    path = write(tmp_path, "rover.csv",
                 "-33.8688001,151.2093002,45.120,22.050,4,burrow\n"
                 "\n"
                 "-33.8688101,151.2093102,45.300,22.230,5,burrow, entrance\n"
                 "# a comment line\n"
                 "-33.8688201,151.2093202,45.400,22.330,1\n")
    tags = read_geotags(path)
    assert len(tags) == 3
    np.testing.assert_allclose(tags.lat, [-33.8688001, -33.8688101, -33.8688201])
    np.testing.assert_allclose(tags.lon, [151.2093002, 151.2093102, 151.2093202])
    np.testing.assert_allclose(tags.height, [45.12, 45.3, 45.4])
    np.testing.assert_allclose(tags.h_msl, [22.05, 22.23, 22.33])
    assert tags.fix_quality.tolist() == [4, 5, 1]
    assert tags.labels.tolist() == ["burrow", "burrow,entrance", ""]
    assert tags.source_row.tolist() == [1, 3, 5]  # line numbers as an editor shows them
    assert tags.problems == []


def test_rover_csv_bad_rows_are_reported_and_good_rows_kept(tmp_path):
    path = write(tmp_path, "rover.csv",
                 "10.0,20.0,5.0,1.0,4,a\n"
                 "10.0,abc,5.0,1.0,4,b\n"
                 "95.0,20.0,5.0,1.0,4,c\n"
                 "10.0,20.0\n"
                 "10.0,20.0,5.0,1.0,fixed-ish?,d\n"
                 "10.1,20.1,5.0,1.0,4,e\n")
    tags = read_geotags(path, "rover")
    assert tags.labels.tolist() == ["a", "e"]
    assert tags.source_row.tolist() == [1, 6]
    by_row = {e.row: e for e in tags.problems}
    assert sorted(by_row) == [2, 3, 4, 5]
    assert by_row[2].field == "lon" and "'abc' is not a number" in str(by_row[2])
    assert by_row[3].field == "lat" and "out of range" in str(by_row[3])
    assert "2 column(s)" in str(by_row[4]) and "expected 6" in str(by_row[4])
    assert by_row[5].field == "gpsStatus"
    assert str(by_row[2]).startswith(f"{path}, row 2, field 'lon':")


def test_all_bad_or_empty_file_is_an_input_error(tmp_path):
    with pytest.raises(InputError, match="no usable geotag: all 2 row"):
        read_geotags(write(tmp_path, "bad.csv", "x,y,z,w,4,a\n1,2\n"), "rover")
    with pytest.raises(InputError, match="empty"):
        read_geotags(write(tmp_path, "empty.csv", "\n\n"))
    with pytest.raises(InputError, match="not found"):
        read_geotags(tmp_path / "missing.csv")


# ------------------------------------------------------------------------------------ header CSV
def test_header_csv_finds_columns_by_common_names(tmp_path):
    path = write(tmp_path, "survey.csv",
                 "Name,Latitude,Longitude,Ellipsoidal_Height,h_msl,Solution\n"
                 "T1,52.1,5.2,48.0,5.5,FIXED\n"
                 "T2,52.2,5.3,48.5,6.0,Float\n"
                 "T3,52.3,5.4,,,single\n")
    tags = read_geotags(path)  # auto → header
    assert tags.labels.tolist() == ["T1", "T2", "T3"]
    np.testing.assert_allclose(tags.lat, [52.1, 52.2, 52.3])
    np.testing.assert_allclose(tags.height[:2], [48.0, 48.5])
    assert math.isnan(tags.height[2]) and math.isnan(tags.h_msl[2])
    np.testing.assert_allclose(tags.h_msl[:2], [5.5, 6.0])
    assert tags.fix_quality.tolist() == [4, 5, 1]
    assert tags.source_row.tolist() == [2, 3, 4]


def test_header_csv_explicit_mapping_and_unknown_column(tmp_path):
    path = write(tmp_path, "survey.csv", "N,E,H,Q,what\n-1.5,36.8,1700.2,4,gap\n")
    tags = read_geotags(path, "header", ColumnMapping(lat="N", lon="E", height="H", fix="Q", label="what"))
    assert tags.lat.tolist() == [-1.5] and tags.lon.tolist() == [36.8]
    assert tags.height.tolist() == [1700.2] and tags.fix_quality.tolist() == [4] and tags.labels.tolist() == ["gap"]
    with pytest.raises(InputError) as err:
        read_geotags(path, "header", ColumnMapping(lat="Lat"))
    assert "no column 'Lat'" in str(err.value) and "N, E, H, Q, what" in str(err.value)
    with pytest.raises(InputError, match="no latitude column"):
        read_geotags(write(tmp_path, "nolat.csv", "a,b\nx,y\n"), "header")


# ------------------------------------------------------------------------------------ NMEA
def gga(lat, lon, quality, msl, sep, checksum=True, talker="GN"):
    """An NMEA GGA sentence built independently of the reader (ddmm.mmmm, hemispheres, checksum)."""
    la, lo = abs(lat), abs(lon)
    lat_txt = f"{int(la):02d}{(la - int(la)) * 60:010.7f}"
    lon_txt = f"{int(lo):03d}{(lo - int(lo)) * 60:010.7f}"
    body = (f"{talker}GGA,123519.00,{lat_txt},{'N' if lat >= 0 else 'S'},{lon_txt},{'E' if lon >= 0 else 'W'},"
            f"{quality},12,0.8,{msl:.3f},M,{sep:.3f},M,1.0,0000")
    cs = 0
    for ch in body:
        cs ^= ord(ch)
    return f"${body}*{cs:02X}" if checksum else f"${body}"


def test_nmea_gga_positions_heights_and_hemispheres(tmp_path):
    lines = [gga(52.123456789, 5.987654321, 4, 3.210, 43.5),
             "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A",
             gga(-33.5, -70.25, 5, 520.0, 25.25, checksum=False, talker="GP"),
             gga(10.0, 10.0, 0, 1.0, 1.0)]
    tags = read_geotags(write(tmp_path, "log.nmea", "\n".join(lines) + "\n"))
    assert len(tags) == 2
    np.testing.assert_allclose(tags.lat, [52.123456789, -33.5], atol=1e-9)
    np.testing.assert_allclose(tags.lon, [5.987654321, -70.25], atol=1e-9)
    np.testing.assert_allclose(tags.h_msl, [3.21, 520.0])
    np.testing.assert_allclose(tags.height, [3.21 + 43.5, 520.0 + 25.25])
    assert tags.fix_quality.tolist() == [4, 5]
    assert tags.source_row.tolist() == [1, 3]
    assert len(tags.problems) == 1 and tags.problems[0].row == 4 and "no position" in str(tags.problems[0])


def test_nmea_bad_checksum_and_bad_angle_are_reported(tmp_path):
    good = gga(1.0, 2.0, 4, 1.0, 2.0)
    corrupt = good.replace(",0100.0000000,", ",0100.0000001,", 1)  # old checksum, altered latitude
    assert corrupt != good
    bad_angle = gga(1.0, 2.0, 4, 1.0, 2.0, checksum=False).replace(",N,", ",Q,")
    tags = read_geotags(write(tmp_path, "log.nmea", "\n".join([corrupt, bad_angle, good])), "nmea")
    assert tags.source_row.tolist() == [3]
    assert tags.problems[0].field == "checksum" and tags.problems[0].row == 1
    assert tags.problems[1].field == "latitude hemisphere"


def test_detect_format():
    assert detect_format(["$GPGGA,1,2"]) == "nmea"
    assert detect_format(["lat,lon", "1,2"]) == "header"
    assert detect_format(["1.0,2.0,3,4,4,a"]) == "rover"


# ------------------------------------------------------------------------------------ layer columns
def test_geotags_from_columns_parses_raw_values_and_reports_bad_ones():
    tags = geotags_from_columns([10.0, float("nan"), 10.2, 10.3], [20.0, 20.1, 20.2, 20.3],
                                h_ellipsoid=[5.0, 5.0, "7.5", "high"], fix_quality=["4", 4, "float", 5],
                                label=["a", "b", None, "d"], source_row=[1, 2, 3, 4], source="survey layer",
                                field_names={"height": "alt"})
    assert tags.source_row.tolist() == [1, 3]
    assert tags.height.tolist() == [5.0, 7.5]
    assert tags.fix_quality.tolist() == [4, 5]
    assert tags.labels.tolist() == ["a", ""]
    assert [(e.row, e.field) for e in tags.problems] == [(2, "geometry"), (4, "alt")]


# ------------------------------------------------------------------------------------ checks
def offsets_to_geodetic(local, east_north):
    e, n = np.asarray(east_north, dtype=float).T
    return local.to_geodetic(np.stack([e, n, np.zeros_like(e)], axis=1))


def test_prepare_pole_height_fix_filter_flags_and_duplicates():
    local = LocalFrame(48.0, 11.0, 500.0)
    # Points 1 cm and 3 cm from the first; one far away with float fix; one without height.
    lat, lon, _ = offsets_to_geodetic(local, [[0, 0], [0.01, 0], [0.0, 0.03], [5, 5], [9, 9]])
    tags = geotags_from_columns(lat, lon, h_ellipsoid=[501.8, 501.8, 501.8, 502.0, None],
                                h_msl=[450.0, 450.0, 450.0, 450.2, None], fix_quality=[4, 4, 4, 5, 2])
    prepared = prepare_geotags(tags, fixed_only=False, pole_height_m=1.8)
    out = prepared.geotags
    np.testing.assert_allclose(out.height[:4], [500.0, 500.0, 500.0, 500.2])
    np.testing.assert_allclose(out.h_msl[:4], [448.2, 448.2, 448.2, 448.4])
    assert out.flags == [[], ["duplicate_2cm"], [], ["rtk_float"], ["no_rtk", "no_height"]]
    assert prepared.duplicates == 1 and prepared.dropped_not_fixed == 0
    assert prepared.counts_by_fix == {"DGPS": 1, "RTK fixed": 3, "RTK float": 1}
    fixed = prepare_geotags(tags, fixed_only=True)
    assert fixed.dropped_not_fixed == 2 and len(fixed.geotags) == 3
    assert fixed.geotags.source_row.tolist() == [1, 2, 3]  # file order kept
    records = list(fixed.geotags.records())
    assert [r["id"] for r in records] == [1, 2, 3] and records[1]["flags"] == "duplicate_2cm"
    with pytest.raises(InputError, match="pole height"):
        prepare_geotags(tags, pole_height_m=-1.0)


def test_a_target_keeps_its_id_when_the_fix_filter_drops_an_earlier_geotag():
    """Ids number the geotags as read: dropping the float fix in row 2 must not renumber rows 3 and 4,
    or labels and evaluations made with and without the filter would name different targets."""
    local = LocalFrame(48.0, 11.0, 500.0)
    lat, lon, _ = offsets_to_geodetic(local, [[0, 0], [5, 0], [10, 0], [15, 0]])
    tags = geotags_from_columns(lat, lon, h_ellipsoid=[500.0] * 4, h_msl=[450.0] * 4, fix_quality=[4, 5, 4, 4])
    every = [r["id"] for r in prepare_geotags(tags).geotags.records()]
    fixed = list(prepare_geotags(tags, fixed_only=True).geotags.records())
    assert every == [1, 2, 3, 4]
    assert [r["id"] for r in fixed] == [1, 3, 4] and fixed[1]["lat"] == pytest.approx(lat[2])


# ------------------------------------------------------------------------------------ fuzz
def valid_row(draw_lat, draw_lon, fix, label):
    return f"{draw_lat:.8f},{draw_lon:.8f},12.345,-3.21,{fix},{label}"


garbage = st.text(alphabet=st.characters(blacklist_categories=("Cs",)), max_size=40).map(
    lambda s: s.replace("\n", " ").replace("\r", " "))
good_rows = st.tuples(st.floats(-89.9, 89.9), st.floats(-179.9, 179.9), st.sampled_from([1, 2, 4, 5]),
                      st.text(alphabet="abcxyz_ ", max_size=8))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(rows=st.lists(st.one_of(good_rows, garbage), min_size=1, max_size=25),
       fmt=st.sampled_from(["auto", "rover", "header", "nmea"]))
def test_fuzz_readers_only_raise_input_errors_and_keep_good_rows(tmp_path, rows, fmt):
    lines, expected = [], []
    for item in rows:
        if isinstance(item, tuple):
            lat, lon, fix, label = item
            lines.append(valid_row(lat, lon, fix, label))
            expected.append((len(lines), lat, lon))
        else:
            lines.append(item)
    path = tmp_path / "fuzz.csv"
    path.write_text("\n".join(lines), encoding="utf-8")
    try:
        tags = read_geotags(path, fmt)
    except InputError:
        return
    if fmt == "rover" or (fmt == "auto" and detect_format(lines) == "rover"):
        kept = dict(zip(tags.source_row.tolist(), zip(tags.lat.tolist(), tags.lon.tolist())))
        for row, lat, lon in expected:
            assert row in kept
            assert kept[row] == pytest.approx((lat, lon), abs=1e-8)
    assert len(tags) + len(tags.problems) <= len(lines)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.binary(max_size=300))
def test_fuzz_binary_content_never_crashes(tmp_path, data):
    path = tmp_path / "junk.bin"
    path.write_bytes(data)
    for fmt in ("auto", "rover", "header", "nmea"):
        try:
            read_geotags(path, fmt)
        except InputError:
            pass


@pytest.mark.parametrize("content, kind", [
    (b"\x89PNG\r\n\x1a\n" + bytes(range(256)) * 4, "a PNG image"),
    (b"\xff\xd8\xff\xe0\x00\x10JFIF" + bytes(200), "a JPEG image"),
    (b"PK\x03\x04" + bytes(100), "a ZIP archive"),
    (b"SQLite format 3\x00" + bytes(100), "an SQLite database or GeoPackage"),
    (bytes(range(1, 32)) * 20, "binary data"),
])
def test_a_file_that_is_not_text_is_refused_by_name_not_parsed(tmp_path, content, kind):
    path = tmp_path / "survey.csv"
    path.write_bytes(content)
    with pytest.raises(InputError) as err:
        read_geotags(path)
    message = str(err.value)
    assert "survey.csv" in message and f"is not a text CSV ({kind})" in message
    assert "PNG\r" not in message and "\x00" not in message   # no bytes printed as a header


def test_text_with_a_bom_and_a_stray_byte_is_still_text(tmp_path):
    path = tmp_path / "survey.csv"
    path.write_bytes(b"\xef\xbb\xbf-27.5,151.9,410.0,368.5,4,burrow\n-27.50001,151.9,410.0,368.5,4,bu\xffrrow\n")
    tags = read_geotags(path)
    assert len(tags) == 2


# ------------------------------------------------------------------------------------ the id rule
def test_ids_are_the_id_field_else_the_row():
    assert geotag_ids(None, [1, 2, 4]).tolist() == [1, 2, 4]
    # Shapefile and GeoPackage give an int field as int, a DBF may give a whole number as a float.
    assert geotag_ids([17, 3.0, " A7 ", np.int64(8)], [1, 2, 3, 4]).tolist() == [17, 3, "A7", 8]


@given(st.lists(st.integers(1, 30), min_size=1, max_size=30))
def test_ids_are_unique_or_refused_naming_the_first_shared_id_and_its_rows(values):
    rows = list(range(1, len(values) + 1))
    if len(set(values)) == len(values):
        assert geotag_ids(values, rows).tolist() == values
        return
    with pytest.raises(InputError) as info:
        geotag_ids(values, rows, "survey")
    first = next(v for v in values if values.count(v) > 1)
    where = [r for r, v in zip(rows, values) if v == first]
    assert info.value.source == "survey" and info.value.field == "id" and info.value.row == where[0]
    assert f"gives id {first} to {len(where)} geotags (rows {', '.join(map(str, where[:10]))}" in str(info.value)


def test_empty_ids_are_refused_naming_their_rows():
    with pytest.raises(InputError, match=r"survey, row 3, field 'code': has 2 geotag\(s\) without an id "
                                         r"\(row\(s\) 3, 7\)"):
        geotag_ids([1, 2, None, "  "], [1, 2, 3, 7], "survey", "code")


def test_subset_and_concatenation_keep_ids_rows_and_provenance():
    tags = Geotags(["a", "b", "c"], [1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, np.nan, 9.0], source_row=[2, 5, 6])
    part = tags.subset(np.array([False, True, True]))
    assert part.ids.tolist() == ["b", "c"] and part.source_row.tolist() == [5, 6]
    assert np.isnan(part.height[0]) and part.labels.tolist() == ["target", "target"]
    both = part + Geotags(["det#1"], [0.0], [0.0], [np.nan], ["burrow"], ["review"])
    assert both.ids.tolist() == ["b", "c", "det#1"] and both.provenance.tolist() == ["survey", "survey", "review"]
    assert both.labels.tolist() == ["target", "target", "burrow"] and len(both.flags) == 3
