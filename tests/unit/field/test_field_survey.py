"""Reading what QField leaves in a field survey package: its quality descriptions as fixes, its geotag table as a
point layer (heights by field name, capture time, worker), and the decisions at the points it visited as
verdicts of the review they came from."""
from __future__ import annotations

import json

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.field_survey import (
    GNSS_FIELDS,
    HEIGHT_FIELDS,
    fix_from_description,
)
from birdseye.birdseye_qgis.core.field.geotags import (
    GEOTAG_FIELD_NAMES,
    ColumnMapping,
    Geotags,
    _fix_code,
    geotags_from_layer,
    layer_fields,
)
from birdseye.birdseye_qgis.core.review.actions import PlannedRow
from birdseye.birdseye_qgis.core.review.field_decisions import (
    FIELD_REVIEWER,
    Visit,
    field_reviewer,
    plan_field_decisions,
    read_visits,
)
from birdseye.birdseye_qgis.core.scoring.verdicts import CONFIRMED, DIRECT, HARD_NEGATIVE, UNCERTAIN

#: The package's geotag table (field_survey): label, the height field, radius, note, worker, then the GNSS fields.
PACKAGE_GEOTAG_FIELDS = ["label", "h_msl", "radius_m", "note", "worker"] + [f.name for f in GNSS_FIELDS]


# ------------------------------------------------------------------------------------ fixes
@pytest.mark.parametrize("text, code", [
    ("Fixed RTK", 4), ("Float RTK", 5), ("DGPS", 2), ("Autonomous", 1), ("PPS", 3), ("Estimated", 6),
    ("Unknown (4)", 4), ("Unknown (5)", 5), ("Fixed RTK - IMU active", 4), ("float  rtk -  IMU active", 5),
    ("", 0), (None, 0), ("Festes RTK", None), ("Unknown", None),
])
def test_fix_from_description_reads_qfields_words(text, code):
    assert fix_from_description(text) == code


@pytest.mark.parametrize("text, code", [
    ("Fixed RTK", 4), ("Float RTK", 5), ("Unknown (4)", 4), ("Float RTK - IMU active", 5),
    ("Autonomous", 1), ("FIX", 4), ("4", 4), ("", 0),
])
def test_fix_code_takes_qfields_descriptions_with_the_rovers_words(text, code):
    assert _fix_code(text, "survey.gpkg|geotags", 3, "fix") == code


def test_a_description_no_table_knows_names_file_row_and_field():
    with pytest.raises(InputError) as info:
        _fix_code("RTK fixe", "survey.gpkg|geotags", 7, "fix")
    error = info.value
    assert (error.source, error.row, error.field) == ("survey.gpkg|geotags", 7, "fix")
    assert "'RTK fixe' is not a fix quality" in str(error) and "QField's 'Fixed RTK'" in str(error)


# ------------------------------------------------------------------------------------ the geotag table
def test_layer_fields_of_a_field_package_and_of_a_geotag_layer():
    assert layer_fields(PACKAGE_GEOTAG_FIELDS) == {
        "msl": "h_msl", "fix": "fix", "label": "label", "time": "time_utc", "worker": "worker",
        "h_acc": "h_acc_m", "v_acc": "v_acc_m"}
    ellipsoidal = [HEIGHT_FIELDS["ellipsoidal"] if n == "h_msl" else n for n in PACKAGE_GEOTAG_FIELDS]
    assert layer_fields(ellipsoidal)["height"] == "h_ellipsoid" and "msl" not in layer_fields(ellipsoidal)
    # Import geotags' own layer read back: its fix quality (not a word), both heights, the worker.
    again = layer_fields(GEOTAG_FIELD_NAMES)
    assert (again["height"], again["msl"], again["fix"], again["time"], again["worker"]) == (
        "h_ellipsoid", "h_msl", "fix_quality", "time_utc", "worker")
    # The mapping wins, and a field is taken once: "status" or "name" are not guessed for a layer.
    mapped = layer_fields(["alt", "h_msl", "status", "name", "fix"], ColumnMapping(height="alt", fix="status"))
    assert mapped == {"height": "alt", "msl": "h_msl", "fix": "status"}


def columns(attributes, lat=(52.0, 52.0001, 52.0002), z=(40.0, 40.0, 40.0)):
    n = len(lat)
    return {"lat": np.asarray(lat), "lon": np.full(n, 5.0), "z": np.asarray(z), "row": np.arange(1, n + 1),
            "attributes": attributes}


def test_a_package_geotag_table_read_as_qfield_filled_it():
    attributes = {
        "label": ["burrow", "nest", None], "h_msl": [12.5, 12.75, None], "worker": ["Ann", "Bob", None],
        "fix": ["Fixed RTK", "Float RTK", "Unknown (4)"], "h_acc_m": [0.012, 0.08, None],
        "v_acc_m": [0.02, 0.15, None],
        "time_utc": ["2026-05-20T15:27:09.400Z", "2026-05-20 15:30:00", "2026-05-20T17:31:02.000+02:00"]}
    fields = layer_fields(PACKAGE_GEOTAG_FIELDS)
    tags = geotags_from_layer(columns(attributes), fields, "birdseye_survey.gpkg|geotags", geoid_undulation_m=47.25)
    assert tags.problems == []
    assert tags.fix_quality.tolist() == [4, 5, 4]
    # h = H + N by the CSV's rule; the geometry's Z (QField's altitude, of the same reference) is not used.
    np.testing.assert_allclose(tags.height[:2], [59.75, 60.0])
    assert np.isnan(tags.height[2]) and np.isnan(tags.h_msl[2])
    np.testing.assert_allclose(tags.h_msl[:2], [12.5, 12.75])
    np.testing.assert_allclose(tags.h_acc[:2], [0.012, 0.08])
    # A time without a zone in a field named time_utc is UTC; an offset is applied.
    assert tags.time_utc.tolist() == ["2026-05-20T15:27:09.400Z", "2026-05-20T15:30:00.000Z",
                                      "2026-05-20T15:31:02.000Z"]
    assert tags.worker.tolist() == ["Ann", "Bob", ""] and tags.labels.tolist() == ["burrow", "nest", ""]
    assert tags.notes[0] == "height: from 'h_msl' (above mean sea level); the geometry's Z is not used"
    assert any("h = H + N" in note for note in tags.notes)
    records = list(tags.records())
    assert [r["worker"] for r in records] == ["Ann", "Bob", None]
    assert list(records[0]) == GEOTAG_FIELD_NAMES


def test_heights_by_name_else_z_and_a_time_without_zone_elsewhere_is_not_kept():
    attributes = {"h_ellipsoid": [60.0, 61.0], "time": ["2026-05-20 15:30:00", None]}
    fields = {"height": "h_ellipsoid", "time": "time"}
    tags = geotags_from_layer(columns(attributes, lat=(52.0, 52.0001), z=(1.0, 2.0)), fields)
    assert tags.height.tolist() == [60.0, 61.0] and tags.time_utc.tolist() == ["", ""]
    assert tags.notes[0] == "height: 'h_ellipsoid', ellipsoidal"
    assert any("capture time: 'time' not kept" in note for note in tags.notes)
    z_only = geotags_from_layer(columns({}, lat=(52.0,), z=(7.5,)), {})
    assert z_only.height.tolist() == [7.5] and z_only.notes == ["height: the geometry's Z, taken as ellipsoidal"]


def test_the_worker_travels_with_subsets_and_sums():
    tags = Geotags([1, 2], [52.0, 52.1], [5.0, 5.1], [1.0, 2.0], worker=["Ann", None])
    assert tags.worker.tolist() == ["Ann", ""]
    assert tags.subset([1]).worker.tolist() == [""]
    assert (tags + tags.subset([0])).worker.tolist() == ["Ann", "", "Ann"]
    assert Geotags([3], [52.0], [5.0], [1.0]).worker.tolist() == [""]


# ------------------------------------------------------------------------------------ decisions
def visit_record(row, decision, keys, worker="Ann", lat=52.0, lon=5.0):
    return {"row": row, "visit_id": f"v{row}", "unit_keys": json.dumps(keys), "decision": decision,
            "worker": worker, "lat": lat, "lon": lon}


def test_read_visits_keeps_good_rows_and_names_bad_ones():
    visits, problems = read_visits([
        visit_record(1, CONFIRMED, ["u1"]), visit_record(2, "maybe", ["u2"]),
        {**visit_record(3, None, []), "unit_keys": "u3"}, visit_record(4, None, [], lat=float("nan")),
        visit_record(5, HARD_NEGATIVE, ["u5"], lat=float("nan")), {**visit_record(6, " uncertain ", []),
                                                                     "unit_keys": None}], "visits")
    assert [(v.row, v.decision, v.unit_keys) for v in visits] == [
        (1, CONFIRMED, ("u1",)), (4, None, ()), (6, UNCERTAIN, ())]
    assert [(e.row, e.field) for e in problems] == [(2, "decision"), (3, "unit_keys"), (5, "geometry")]
    assert "'maybe' is not a field decision" in str(problems[0])


def log_row(fid, key, verdict, reviewer="office", provenance=DIRECT, digests='{"det": "abc"}'):
    return {"fid": fid, "unit_key": key, "verdict": verdict, "provenance": provenance, "reviewer": reviewer,
            "layers_fired": '["yolo"]', "input_digests": digests, "matching_parameters": '{"eps_pred_m": 0.2}',
            "postprocessing": '{"dedup_cm": 3}'}


def test_plan_one_direct_verdict_per_unit_with_the_units_metadata():
    visits = [Visit(1, "v1", ("u1", "u2"), CONFIRMED, "Ann", 52.0, 5.0),
              Visit(2, "v2", ("u3",), HARD_NEGATIVE, "", 52.1, 5.1),
              Visit(3, "v3", (), CONFIRMED, "Ann", 52.2, 5.2),
              Visit(4, "v4", ("u4",), None, "Ann", 52.3, 5.3)]
    log = [log_row(1, "u1", UNCERTAIN), log_row(2, "u1", UNCERTAIN, provenance="propagated:dbscan_0.20m/u2")]
    plan = plan_field_decisions(visits, log)
    assert [v.row for v in plan.verdicts] == [
        PlannedRow("u1", CONFIRMED, DIRECT, 52.0, 5.0, ("yolo",)), PlannedRow("u2", CONFIRMED, DIRECT, 52.0, 5.0),
        PlannedRow("u3", HARD_NEGATIVE, DIRECT, 52.1, 5.1)]
    assert [v.reviewer for v in plan.verdicts] == ["field:Ann", "field:Ann", FIELD_REVIEWER]
    assert plan.verdicts[0].input_digests == '{"det": "abc"}' and plan.verdicts[0].postprocessing == '{"dedup_cm": 3}'
    assert (plan.verdicts[1].input_digests, plan.verdicts[1].matching_parameters) == ("{}", "{}")
    assert [v.visit_id for v in plan.plain] == ["v3"] and plan.undecided == 1 and plan.notes == []
    assert field_reviewer("  Bob ") == "field:Bob"


def test_importing_again_appends_nothing_and_a_later_visit_decides_a_unit():
    visits = [Visit(1, "v1", ("u1",), CONFIRMED, "Ann", 52.0, 5.0)]
    again = [log_row(1, "u1", UNCERTAIN), log_row(2, "u1", CONFIRMED, reviewer="field:Ann")]
    plan = plan_field_decisions(visits, again)
    assert plan.verdicts == [] and plan.already == ["u1"]
    # The same verdict from someone else, or a later other verdict, is no reason to skip.
    assert len(plan_field_decisions(visits, [log_row(1, "u1", CONFIRMED)]).verdicts) == 1
    assert len(plan_field_decisions(visits, again + [log_row(3, "u1", HARD_NEGATIVE)]).verdicts) == 1
    twice = plan_field_decisions(visits + [Visit(2, "v2", ("u1",), HARD_NEGATIVE, "Bob", 52.0, 5.0)], [])
    assert [(v.row.verdict, v.reviewer) for v in twice.verdicts] == [(HARD_NEGATIVE, "field:Bob")]
    assert twice.notes == ["unit u1: visit v1 decided confirmed_real, the later visit v2 hard_negative; the later "
                           "one is recorded"]


def test_a_layers_fix_in_words_no_table_knows_keeps_the_point_with_the_fix_unknown():
    """QField translates its descriptions into the phone's language: a German worker's "Festes RTK" is no reason
    to lose the point. It is kept with fix 0 (flag fix_unknown) and the notes name the words; a number that is
    no GGA code is still a bad row."""
    from birdseye.birdseye_qgis.core.field.geotags import geotags_from_columns, prepare_geotags

    tags = geotags_from_columns([10.0, 10.0001, 10.0002, 10.0003], [20.0] * 4, h_ellipsoid=[500.0] * 4,
                                fix_quality=["Fixed RTK", "Festes RTK", "Festes RTK", "12"], source="survey.gpkg",
                                field_names={"fix": "fix"})
    assert tags.fix_quality.tolist() == [4, 0, 0] and [(e.row, e.field) for e in tags.problems] == [(4, "fix")]
    assert any("'Festes RTK' ×2" in note and "fix unknown" in note for note in tags.notes)
    prepared = prepare_geotags(tags)
    assert ["fix_unknown" in f for f in prepared.geotags.flags] == [False, True, True]
    assert len(prepare_geotags(tags, fixed_only=True).geotags) == 1
