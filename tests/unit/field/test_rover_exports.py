"""Rover exports as they really are: Emlid Flow (42 columns) and ReachView 3 (27 columns) with no mapping,
heights by meaning and unit, fixes in the rover's words, per-point accuracy, capture time, bad rows.

Oracles that are not the reader: the fixture's own numbers times the US survey foot (1200/3937 m, by
definition), the file's Longitude/Latitude, its Easting/Northing against the positions read projected with
pyproj, and NGA's published EGM96 test value.
"""
from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.geotags import (
    ColumnMapping,
    geotags_from_columns,
    prepare_geotags,
    read_geotags,
    utc_text,
)
from birdseye.birdseye_qgis.core.geometry import heights
from birdseye.birdseye_qgis.core.geometry.geodesy import ensure_proj_data

EMLID = Path(__file__).resolve().parents[2] / "data" / "rover" / "emlid_flow_reach_rs4_ftus.csv"
US_FT = 1200.0 / 3937.0
#: ReachView 3's 27 columns, as its export writes them (written out here, not taken from the reader).
REACHVIEW = ("Name,Easting,Northing,Elevation,Description,Longitude,Latitude,Ellipsoidal height,Easting RMS,"
             "Northing RMS,Elevation RMS,Lateral RMS,Antenna height,Antenna height units,Solution status,"
             "Averaging start,Averaging end,Samples,PDOP,Base easting,Base northing,Base elevation,Base longitude,"
             "Base latitude,Base ellipsoidal height,Baseline,CS name").split(",")


def emlid_rows() -> list[dict]:
    """The fixture's rows as a plain CSV reader gives them (the test's own reading of the file)."""
    with EMLID.open(newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def write_rows(path: Path, columns, rows) -> Path:
    """A CSV of ``rows`` (dicts) with the header ``columns``."""
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=list(columns), extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    path.write_text(text.getvalue(), encoding="utf-8")
    return path


def check_emlid_values(tags, rows):
    """What the reader must give for the fixture's rows, each number from the file times the foot."""
    assert tags.labels.tolist() == [r["Name"] for r in rows]
    assert tags.lat.tolist() == [float(r["Latitude"]) for r in rows]          # positions exactly as written
    assert tags.lon.tolist() == [float(r["Longitude"]) for r in rows]
    np.testing.assert_allclose(tags.height, [float(r["Ellipsoidal height"]) * US_FT for r in rows], atol=1e-9)
    np.testing.assert_allclose(tags.h_msl, [float(r["Elevation"]) * US_FT for r in rows], atol=1e-9)
    np.testing.assert_allclose(tags.h_acc, [float(r["Lateral RMS"]) * US_FT for r in rows], atol=1e-12)
    np.testing.assert_allclose(tags.v_acc, [float(r["Elevation RMS"]) * US_FT for r in rows], atol=1e-12)
    assert tags.fix_quality.tolist() == [1, 4, 4]                              # SINGLE, FIX, FIX
    assert tags.problems == []


# ------------------------------------------------------------------------------------ Emlid Flow, 42 columns
def test_emlid_flow_export_in_us_survey_feet_reads_with_no_mapping():
    tags = read_geotags(EMLID)
    rows = emlid_rows()
    check_emlid_values(tags, rows)
    tcu1 = tags.labels.tolist().index("TCU1")
    # The acceptance figure: 461.923 ftUS is 140.7946 m; the orthometric 570.143 is never taken as it.
    assert tags.height[tcu1] == pytest.approx(140.7946, abs=0.01)
    assert tags.h_msl[tcu1] == pytest.approx(173.7799, abs=0.01)
    assert tags.time_utc.tolist() == ["2026-05-20T15:09:54.400Z", "2026-05-20T15:27:09.400Z",
                                      "2026-05-20T15:27:30.000Z"]
    assert tags.source_row.tolist() == [2, 3, 4]
    assert tags.worker.tolist() == [r["Author"] for r in rows] and tags.worker[0] != ""  # who collected each point
    assert tags.ground_heights  # Emlid removed the 6.812 ft antenna height already
    notes = "\n".join(tags.notes)
    assert "Emlid Flow export (42 columns)" in notes
    assert "height: 'Ellipsoidal height', ellipsoidal by its name" in notes
    assert "h_msl: 'Elevation', orthometric" in notes and "NAVD88(GEOID18) height (ftUS)" in notes
    assert "lengths in US survey feet, from the coordinate system" in notes
    assert "NAD83(2011)" in notes  # positions are in the coordinate system's datum, and the log says so


def test_emlid_positions_are_the_file_grid_coordinates():
    """An independent check that latitude and longitude came from the right columns: projected by PROJ into
    the file's own State Plane system they give its Easting and Northing to a few hundredths of a foot."""
    pyproj = pytest.importorskip("pyproj")
    ensure_proj_data()
    from pyproj.database import query_crs_info

    code, = [c.code for c in query_crs_info(auth_name="EPSG") if c.name == "NAD83(2011) / Illinois West (ftUS)"]
    to_grid = pyproj.Transformer.from_crs("EPSG:6318", f"EPSG:{code}", always_xy=True)  # NAD83(2011) geographic
    tags = read_geotags(EMLID)
    easting, northing = to_grid.transform(tags.lon, tags.lat)
    rows = emlid_rows()
    np.testing.assert_allclose(easting, [float(r["Easting"]) for r in rows], atol=0.02)
    np.testing.assert_allclose(northing, [float(r["Northing"]) for r in rows], atol=0.02)


def test_emlid_heights_are_ground_heights_so_a_pole_height_is_refused():
    tags = read_geotags(EMLID)
    with pytest.raises(InputError, match="ground point already") as err:
        prepare_geotags(tags, pole_height_m=2.076)
    assert err.value.field == "POLE_HEIGHT_M" and str(EMLID) in str(err.value)
    prepared = prepare_geotags(tags)
    np.testing.assert_allclose(prepared.geotags.height, tags.height)  # nothing removed
    assert prepared.geotags.flags == [["no_rtk"], [], []]


# ------------------------------------------------------------------------------------ ReachView 3, 27 columns
def test_reachview_27_column_export_reads_like_emlid_flow(tmp_path):
    rows = emlid_rows()
    path = write_rows(tmp_path / "reachview.csv", REACHVIEW, rows)
    assert len(path.read_text().splitlines()[0].split(",")) == 27
    tags = read_geotags(path)
    check_emlid_values(tags, rows)
    assert "ReachView 3 export (27 columns)" in tags.notes[0]


# ------------------------------------------------------------------------------------ coordinate systems
def test_a_coordinate_system_without_a_vertical_part_makes_elevation_ellipsoidal(tmp_path):
    """Emlid writes the ellipsoidal height as Elevation when the coordinate system has no vertical part:
    with the Ellipsoidal height column present it wins, and without it Elevation is read, in the CS's feet."""
    rows = [{**r, "CS name": "NAD83(2011) / Illinois West (ftUS)", "Elevation": r["Ellipsoidal height"]}
            for r in emlid_rows()]
    columns = list(rows[0])
    tags = read_geotags(write_rows(tmp_path / "both.csv", columns, rows))
    np.testing.assert_allclose(tags.height, [float(r["Ellipsoidal height"]) * US_FT for r in rows], atol=1e-9)
    assert np.isnan(tags.h_msl).all()
    without = [c for c in columns if c != "Ellipsoidal height"]
    tags = read_geotags(write_rows(tmp_path / "elevation_only.csv", without, rows))
    np.testing.assert_allclose(tags.height, [float(r["Ellipsoidal height"]) * US_FT for r in rows], atol=1e-9)
    assert np.isnan(tags.h_msl).all()
    assert any("'Elevation', ellipsoidal: the coordinate system" in n for n in tags.notes)


def test_a_metric_utm_export_is_read_in_metres(tmp_path):
    path = tmp_path / "utm.csv"
    path.write_text("Name,Longitude,Latitude,Elevation,Easting RMS,Northing RMS,Elevation RMS,Solution status,"
                    "CS name\n"
                    "P1,-93.1000001,44.9500002,262.481,0.006,0.008,0.012,FIX,WGS 84 / UTM zone 15N\n"
                    "P2,-93.1000101,44.9500102,262.530,0.030,0.040,0.050,FLOAT,WGS 84 / UTM zone 15N\n",
                    encoding="utf-8")
    tags = read_geotags(path)
    np.testing.assert_allclose(tags.height, [262.481, 262.530])
    np.testing.assert_allclose(tags.h_acc, [0.01, 0.05])  # √(E² + N²): 3-4-5 triangles
    np.testing.assert_allclose(tags.v_acc, [0.012, 0.05])
    assert tags.fix_quality.tolist() == [4, 5] and np.isnan(tags.h_msl).all()
    assert not any("datum" in n for n in tags.notes)  # WGS 84 needs no warning


# ------------------------------------------------------------------------------------ orthometric only
def test_orthometric_only_file_is_converted_with_egm96_as_nga_publishes_it(tmp_path):
    """NGA's EGM96 test value: N = −31.628 m at 38.6281550 N, 269.7791550 E. A file with only heights above
    the geoid gets h = H + N there, from PROJ's EGM96 grid, and says so."""
    assert heights.geoid_grid_installed("EGM96"), "PROJ's EGM96 grid is missing (make setup installs proj-data)"
    path = tmp_path / "ortho.csv"
    path.write_text("Name,Latitude,Longitude,Elevation,CS name\n"
                    "A,38.6281550,-90.2208450,100.000,WGS 84 + EGM96 height\n", encoding="utf-8")
    tags = read_geotags(path)
    assert tags.h_msl.tolist() == [100.0]
    assert tags.height[0] == pytest.approx(100.0 - 31.628, abs=0.1)
    assert any("converted, h = H + N" in n and "EGM96 grid" in n for n in tags.notes)


def test_orthometric_only_file_with_a_given_undulation(tmp_path):
    path = tmp_path / "msl.csv"
    path.write_text("point,lat,long,altMSL (ft)\nA,40.0,-89.0,570.0\nB,40.001,-89.0,\n", encoding="utf-8")
    tags = read_geotags(path, geoid_undulation_m=-32.98)
    np.testing.assert_allclose(tags.h_msl[:1], [570.0 * 0.3048])
    np.testing.assert_allclose(tags.height[:1], [570.0 * 0.3048 - 32.98])
    assert np.isnan(tags.height[1]) and np.isnan(tags.h_msl[1])
    assert any("N = -32.98 m as given" in n for n in tags.notes)
    assert any("in international feet as its name says" in n for n in tags.notes)


def test_orthometric_only_without_a_geoid_keeps_the_height_unknown_and_says_why(tmp_path, monkeypatch):
    def missing(*args, **kwargs):
        raise heights.GeoidGridMissing("converting needs PROJ's EGM96 geoid grid (us_nga_egm96_15.tif)")

    monkeypatch.setattr(heights, "height_shift", missing)
    path = tmp_path / "msl.csv"
    path.write_text("name,latitude,longitude,msl\nA,40.0,-89.0,173.78\n", encoding="utf-8")
    tags = read_geotags(path)
    assert np.isnan(tags.height[0]) and tags.h_msl[0] == pytest.approx(173.78)
    assert any(n.startswith("height unknown") and "us_nga_egm96_15.tif" in n for n in tags.notes)
    assert prepare_geotags(tags).geotags.flags == [["fix_unknown", "no_height"]]


def test_an_orthometric_elevation_is_never_taken_as_ellipsoidal_even_when_empty(tmp_path):
    """With an Ellipsoidal height column present, a row whose ellipsoidal cell is empty keeps an unknown height:
    its orthometric Elevation is not converted in its place, nor taken as it."""
    rows = emlid_rows()
    rows[1]["Ellipsoidal height"] = ""
    tags = read_geotags(write_rows(tmp_path / "gap.csv", list(rows[0]), rows))
    assert np.isnan(tags.height[1]) and tags.h_msl[1] == pytest.approx(570.143 * US_FT)


# ------------------------------------------------------------------------------------ bad rows
def test_a_bad_row_names_file_row_and_field_and_the_good_rows_are_kept(tmp_path):
    rows = emlid_rows()
    rows[1]["Ellipsoidal height"] = "46l.923"   # TCU1, line 3 of the file
    rows[2]["Solution status"] = "FIXX"          # TCU2, line 4
    path = write_rows(tmp_path / "bad.csv", list(rows[0]), rows)
    tags = read_geotags(path)
    assert tags.labels.tolist() == ["base point"] and tags.source_row.tolist() == [2]
    first, second = tags.problems
    assert (first.row, first.field, second.row, second.field) == (3, "Ellipsoidal height", 4, "Solution status")
    assert str(first) == (f"{path}, row 3, field 'Ellipsoidal height': '46l.923' is not a number; expected "
                          "ellipsoidal height in US survey feet")
    assert "FIX/FLOAT/SINGLE" in str(second)


def test_a_height_out_of_range_in_feet_is_refused_with_its_unit(tmp_path):
    rows = emlid_rows()
    rows[0]["Ellipsoidal height"] = "40000"  # 12.2 km: a wrong column or a wrong unit
    tags = read_geotags(write_rows(tmp_path / "high.csv", list(rows[0]), rows))
    assert [(p.row, p.field) for p in tags.problems] == [(2, "Ellipsoidal height")]
    assert "out of range; expected ellipsoidal height in US survey feet" in str(tags.problems[0])


# ------------------------------------------------------------------------------------ units
@pytest.mark.parametrize("units, factor", [("m", 1.0), ("ft", 0.3048), ("ftUS", US_FT)])
def test_the_units_asked_for_override_the_file(units, factor):
    tags = read_geotags(EMLID, units=units)
    rows = emlid_rows()
    np.testing.assert_allclose(tags.height, [float(r["Ellipsoidal height"]) * factor for r in rows], atol=1e-9)
    np.testing.assert_allclose(tags.h_acc, [float(r["Lateral RMS"]) * factor for r in rows], atol=1e-12)
    assert any("as asked (UNITS)" in n for n in tags.notes)


def test_a_units_column_applies_where_no_coordinate_system_names_one(tmp_path):
    path = tmp_path / "units.csv"
    path.write_text("name,lat,lon,ellipsoidal_height,units\nA,40.0,-89.0,100.0,ftUS\nB,40.0,-89.0,30.0,m\n"
                    "C,40.0,-89.0,30.0,yards\n", encoding="utf-8")
    tags = read_geotags(path)
    np.testing.assert_allclose(tags.height, [100.0 * US_FT, 30.0])
    assert [(p.row, p.field) for p in tags.problems] == [(4, "units")]
    assert "'yards' is not a length unit" in str(tags.problems[0])


def test_the_antenna_height_unit_of_an_emlid_export_is_not_the_unit_of_its_coordinates():
    """The fixture's antenna height is in international feet ('ft'); its heights are in US survey feet."""
    tags = read_geotags(EMLID)
    assert tags.height[1] == pytest.approx(461.923 * US_FT, abs=1e-9)
    assert abs(tags.height[1] - 461.923 * 0.3048) > 1e-4


# ------------------------------------------------------------------------------------ other rovers
def test_other_rovers_columns_and_fix_words(tmp_path):
    path = tmp_path / "trimble_like.csv"
    path.write_text("Point,Lat,Long,Ellipsoid height,HRMS,VRMS,Solution\n"
                    "1,52.1,5.2,48.012,0.010,0.015,RTK Fixed\n"
                    "2,52.2,5.3,48.5,0.080,0.120,RTK Float\n"
                    "3,52.3,5.4,49.0,1.5,2.5,Autonomous\n"
                    "4,52.4,5.5,49.0,0.6,0.9,DGPS\n"
                    "5,52.5,5.6,49.0,0.02,0.03,PPP\n", encoding="utf-8")
    tags = read_geotags(path)
    assert tags.labels.tolist() == ["1", "2", "3", "4", "5"]
    assert tags.fix_quality.tolist() == [4, 5, 1, 2, 2]
    np.testing.assert_allclose(tags.height, [48.012, 48.5, 49.0, 49.0, 49.0])
    np.testing.assert_allclose(tags.h_acc, [0.01, 0.08, 1.5, 0.6, 0.02])
    np.testing.assert_allclose(tags.v_acc, [0.015, 0.12, 2.5, 0.9, 0.03])


def test_a_height_whose_name_says_nothing_is_taken_as_ellipsoidal_and_the_notes_say_so(tmp_path):
    path = tmp_path / "logger.csv"
    path.write_text("time,lat,lon,elevation,accuracy\n"
                    "2019-09-14T11:32:34.999Z,43.80223697,11.20030008,90.568,4.0\n"
                    "2019-09-14 11:33:04,43.80223697,11.20030008,93.448,4.0\n", encoding="utf-8")
    tags = read_geotags(path)
    np.testing.assert_allclose(tags.height, [90.568, 93.448])
    np.testing.assert_allclose(tags.h_acc, [4.0, 4.0])
    assert tags.time_utc.tolist() == ["2019-09-14T11:32:34.999Z", ""]  # the second has no time zone
    assert any("'elevation' taken as ellipsoidal" in n for n in tags.notes)
    assert any("capture time" in n and "(1 of 2 rows)" in n for n in tags.notes)


def test_a_sw_maps_export_reads_with_no_mapping(tmp_path):
    """SW Maps' columns, with the values of one real point a user published (New Hampshire, RTK fixed):
    its Elevation is the ellipsoidal height, Ortho Height the orthometric one."""
    path = tmp_path / "swmaps.csv"
    path.write_text("ID,Remarks,Time,Geometry,Latitude,Longitude,Elevation,Ortho Height,Instrument Ht,Fix ID,Speed,"
                    "Bearing,Horizontal Accuracy,Vertical Accuracy\n"
                    "233,road,08/29/2023 13:31:48.000 EDT,POINT Z (-71.15969189 44.14395690 480.087),44.1439569,"
                    "-71.15969189,480.087,513.999,2.038,4,0.005,0,0.024,0.039\n", encoding="utf-8")
    tags = read_geotags(path)
    assert (tags.lat[0], tags.lon[0]) == (44.1439569, -71.15969189)
    assert (tags.height[0], tags.h_msl[0]) == (480.087, 513.999)
    assert (tags.fix_quality[0], tags.h_acc[0], tags.v_acc[0]) == (4, 0.024, 0.039)
    assert tags.labels.tolist() == ["road"] and tags.time_utc.tolist() == [""]  # a US date with a zone name
    assert not tags.ground_heights
    notes = "\n".join(tags.notes)
    assert "'Elevation' taken as ellipsoidal" in notes and "h_msl: 'Ortho Height'" in notes
    assert "antenna height ('Instrument Ht') but does not say whether" in notes


def test_a_bad_elf_style_export_with_units_in_its_column_names(tmp_path):
    """Bad Elf's published column names: a unit as the last word, QUALITY as an NMEA code, a UTC time
    column without a zone."""
    path = tmp_path / "badelf.csv"
    path.write_text("LINE,DATE_TIME_UTC,LATITUDE,LONGITUDE,ELEVATION_MSL,ELLIPSOIDAL_M,QUALITY,H_RMS,V_RMS,"
                    "ANTENNA_HEIGHT_M,POINT_NAME\n"
                    "1,2023-11-13 14:22:33,35.1,-106.6,1500.25,1478.5,4,0.012,0.02,2.0,P1\n", encoding="utf-8")
    tags = read_geotags(path)
    assert (tags.height[0], tags.h_msl[0], tags.fix_quality[0]) == (1478.5, 1500.25, 4)
    assert (tags.h_acc[0], tags.v_acc[0], tags.labels[0]) == (0.012, 0.02, "P1")
    assert tags.time_utc.tolist() == ["2023-11-13T14:22:33.000Z"]
    assert any("'ELLIPSOIDAL_M', ellipsoidal by its name, in metres as its name says" in n for n in tags.notes)


def test_a_trimble_penmap_export_with_its_format_line_as_header(tmp_path):
    """Trimble's published Penmap example: the format string as the header line and its example point."""
    path = tmp_path / "penmap.csv"
    path.write_text("[PointId],[FeatureCode],[Northing:Meter:3],[Easting:Meter:3],[Elevation:Meter:3],"
                    "[Latitude:Degree:9],[Longitude:Degree:9],[EllipsoidHeight:Meter:3],[Pdop],[Rms3D:Meter:3],"
                    "[Rms2D:Meter:3],[SatEpochs],[SatCount],[SatQuality],[CorrectionMode],[AntHeight:Meter:3],"
                    "[AntOffset:Meter:3],[UtcDateTime],[PointType]\n"
                    "7,3,5807299.068,32529273.978,54.337,52.415131,9.430413,97.218,2,1.148,0.68,5,11,Float,Ntrip,"
                    "2.065,0.065,2020-11-18 13:08:04Z,GPSPoint\n", encoding="utf-8")
    tags = read_geotags(path)
    assert (tags.lat[0], tags.lon[0], tags.height[0]) == (52.415131, 9.430413, 97.218)
    assert np.isnan(tags.h_msl[0])  # its Elevation says nothing of its reference; the ellipsoidal height wins
    assert (tags.fix_quality[0], tags.h_acc[0], tags.labels[0]) == (5, 0.68, "7")
    assert tags.time_utc.tolist() == ["2020-11-18T13:08:04.000Z"]


@pytest.mark.parametrize("text, expected", [
    ("2026-05-20 10:27:09.4 UTC-05:00", "2026-05-20T15:27:09.400Z"),
    ("2026-05-20T23:30:00+02:00", "2026-05-20T21:30:00.000Z"),
    ("2026-12-31 23:59:59.9995 UTC-01:00", "2027-01-01T00:59:59.999Z"),
    ("2026-05-20 10:27:09Z", "2026-05-20T10:27:09.000Z"),
    ("2026-05-20 10:27:09", None),           # no zone: not guessed
    ("10:27:09 UTC", None),                  # no date
    ("2026-02-30 10:00:00 UTC", None),       # no such day
])
def test_capture_times_become_utc(text, expected):
    assert utc_text(text) == expected


# ------------------------------------------------------------------------------------ accuracy filter
def test_accuracy_filter_drops_coarse_geotags_keeps_ids_and_counts():
    tags = read_geotags(EMLID)  # lateral RMS 0.599, 0.054, 0.055 ftUS = 0.183, 0.016, 0.017 m
    prepared = prepare_geotags(tags, max_h_accuracy_m=0.05)
    assert prepared.dropped_accuracy == 1 and prepared.dropped_not_fixed == 0 and prepared.unknown_accuracy == 0
    assert [r["id"] for r in prepared.geotags.records()] == [2, 3]
    assert prepare_geotags(tags, max_h_accuracy_m=0.0167).dropped_accuracy == 2   # TCU2's 0.01676 m is over
    both = prepare_geotags(tags, fixed_only=True, max_h_accuracy_m=0.05)
    assert both.dropped_not_fixed == 1 and both.dropped_accuracy == 0   # a geotag is counted by one filter
    with pytest.raises(InputError, match="MAX_H_ACCURACY_M|positive number"):
        prepare_geotags(tags, max_h_accuracy_m=0.0)


def test_accuracy_filter_keeps_geotags_without_an_accuracy_and_counts_them():
    tags = geotags_from_columns([10.0, 10.001, 10.002], [20.0, 20.0, 20.0], h_acc=[0.02, None, "0.5"])
    prepared = prepare_geotags(tags, max_h_accuracy_m=0.1)
    assert prepared.geotags.source_row.tolist() == [1, 2]
    assert prepared.dropped_accuracy == 1 and prepared.unknown_accuracy == 1


def test_records_carry_the_new_fields():
    record = list(read_geotags(EMLID).records())[1]
    assert record["h_acc_m"] == pytest.approx(0.054 * US_FT) and record["v_acc_m"] == pytest.approx(0.038 * US_FT)
    assert record["time_utc"] == "2026-05-20T15:27:09.400Z"
    empty = list(geotags_from_columns([1.0], [2.0]).records())[0]
    assert empty["h_acc_m"] is None and empty["v_acc_m"] is None and empty["time_utc"] is None


# ------------------------------------------------------------------------------------ point-layer columns
def test_layer_columns_with_accuracies_in_a_unit():
    tags = geotags_from_columns([10.0, 10.1], [20.0, 20.1], h_ellipsoid=[100.0, "200"], h_acc=[0.05, "x"],
                                v_acc=[0.1, 0.2], unit_m=US_FT, field_names={"h_acc": "hrms"})
    assert tags.height.tolist() == [pytest.approx(100.0 * US_FT)]
    assert tags.h_acc.tolist() == [pytest.approx(0.05 * US_FT)] and tags.v_acc.tolist() == [pytest.approx(0.1 * US_FT)]
    assert [(p.row, p.field) for p in tags.problems] == [(2, "hrms")]


def test_a_mapped_column_is_the_ellipsoidal_height_whatever_its_name(tmp_path):
    path = tmp_path / "mapped.csv"
    path.write_text("N,E,Elevation,Q\n-1.5,36.8,1700.2,4\n", encoding="utf-8")
    tags = read_geotags(path, "header", ColumnMapping(lat="N", lon="E", height="Elevation", fix="Q"))
    assert tags.height.tolist() == [1700.2] and math.isnan(tags.h_msl[0])
    assert any("as the column mapping says" in n for n in tags.notes)
