"""Survey report and field partitions (core/field/survey_report.py): sessions, working time, rates, the method's
throughput arithmetic, and equal-area partitions of a concave field."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.survey_report import (
    area_below,
    capture_seconds,
    label_counts,
    long_axis,
    partition_field,
    partition_records,
    report_geotags_per_hour,
    sessions,
    survey_report,
    survey_report_html,
    working_seconds,
)


def clock(hhmm: str, day: str = "2026-05-20") -> str:
    return f"{day}T{hhmm}:00Z"


def every(start: str, step_min: int, count: int) -> list[str]:
    """``count`` capture times from ``start`` (HH:MM), ``step_min`` minutes apart."""
    h, m = map(int, start.split(":"))
    return [clock(f"{(h * 60 + m + k * step_min) // 60:02d}:{(h * 60 + m + k * step_min) % 60:02d}")
            for k in range(count)]


def morning():
    """The worked example: two workers over a morning with a break, partitions 1–4 and one flight.

    Worker A: one capture every 2 min, 08:00…08:58 (30), a break, 09:30…09:58 (15); partition 1, then 2.
    Worker B: one capture every 3 min, 08:10…09:07 (20), a break, 09:40…10:07 (10), all in partition 3; and one
    geotag without a time, outside every partition."""
    a1, a2 = every("08:00", 2, 30), every("09:30", 2, 15)
    b1, b2 = every("08:10", 3, 20), every("09:40", 3, 10)
    times = a1 + a2 + b1 + b2 + [""]
    workers = ["A"] * 45 + ["B"] * 31
    partition_of = [1] * 30 + [2] * 15 + [3] * 30 + [None]
    flight = np.array([p in (1, 3) for p in partition_of])  # the flight's footprints cover partitions 1 and 3
    return times, workers, partition_of, {"flight 1": flight}


def test_the_worked_example_by_hand():
    times, workers, partition_of, flights = morning()
    report = survey_report(times, workers, partition_of, [1, 2, 3, 4], flights)
    a, b = report.workers
    # A: intervals all 2 min → typical 120 s. The 08:58 → 09:30 gap (32 min > 20) starts a second session.
    #    session 1: 08:58 − 08:00 + 2 min = 60 min; session 2: 09:58 − 09:30 + 2 min = 30 min → 1.5 h;
    #    45 geotags / 1.5 h = 30 per worker-hour.
    assert report.typical_interval_s["A"] == 120.0
    assert (a.name, a.geotags, a.timed, a.sessions) == ("A", 45, 45, 2)
    assert a.worker_hours == pytest.approx(1.5)
    assert a.geotags_per_worker_hour == pytest.approx(30.0)
    # B: intervals all 3 min → typical 180 s; 09:07 → 09:40 (33 min) starts a second session.
    #    session 1: 09:07 − 08:10 + 3 min = 60 min; session 2: 10:07 − 09:40 + 3 min = 30 min → 1.5 h;
    #    30 timed geotags / 1.5 h = 20 per worker-hour (the untimed one is counted, not rated).
    assert report.typical_interval_s["B"] == 180.0
    assert (b.name, b.geotags, b.timed, b.sessions) == ("B", 31, 30, 2)
    assert b.worker_hours == pytest.approx(1.5)
    assert b.geotags_per_worker_hour == pytest.approx(20.0)
    # Overall: 75 timed geotags / (1.5 + 1.5) worker-hours = 25 per worker-hour; 2 people;
    #    elapsed 08:00 → 10:07 = 127 min = 2.1167 h.
    o = report.overall
    assert (o.geotags, o.timed, o.sessions, report.people) == (76, 75, 4, 2)
    assert o.worker_hours == pytest.approx(3.0)
    assert o.geotags_per_worker_hour == pytest.approx(25.0)
    assert report.elapsed_hours == pytest.approx(127 / 60)
    assert (report.first_utc, report.last_utc) == ("2026-05-20T08:00:00Z", "2026-05-20T10:07:00Z")
    # Partitions: 1 = A's first session (1 h, 30/h), 2 = A's second (0.5 h, 30/h), 3 = B's two sessions (1.5 h,
    #    20/h), 4 empty → 3 of 4 surveyed; B's untimed geotag lies outside.
    p1, p2, p3, p4 = report.partitions
    assert [p.worker_hours for p in (p1, p2, p3, p4)] == pytest.approx([1.0, 0.5, 1.5, 0.0])
    assert [p.geotags_per_worker_hour for p in (p1, p2, p3)] == pytest.approx([30.0, 30.0, 20.0])
    assert p4.geotags_per_worker_hour is None
    assert (report.partitions_surveyed, report.outside) == (3, 1)
    # The flight holds partitions 1 and 3: A's first session (1 h) + B's whole morning (1.5 h) = 2.5 h for 60.
    (f,) = report.flights
    assert (f.geotags, f.workers) == (60, 2)
    assert f.worker_hours == pytest.approx(2.5)
    assert f.geotags_per_worker_hour == pytest.approx(24.0)
    d = report.to_dict()
    assert d["coverage"] == {"partitions": 4, "partitions_with_geotags": 3, "geotags_outside_partitions": 1}
    assert d["overall"]["geotags_per_worker_hour"] == pytest.approx(25.0)
    json.dumps(d)  # plain JSON


def test_the_methods_labels_per_worker_hour():
    """The method labelled 12,524 frames with 55,600 labels "in about 12 hours with two people". Read as 12
    worker-hours — two people surveying 6 h each — it is 55,600 / (2 × 6 h) = 4,633.3 labels and 12,524 / 12 h =
    1,043.7 frames per worker-hour; read as 12 h of elapsed time with both at work throughout it would be 24
    worker-hours and half those rates (2,316.7 labels). The report counts worker-hours from the captures, so it
    never depends on that reading: here each person captures once a minute from 06:00 to 11:59 (360 captures,
    typical interval 60 s: 359 min + 1 min = 6 h each)."""
    times = every("06:00", 1, 360) * 2
    report = survey_report(times, ["1"] * 360 + ["2"] * 360, label_count=55_600, frame_count=12_524)
    assert report.people == 2
    assert report.overall.worker_hours == pytest.approx(12.0)
    assert report.elapsed_hours == pytest.approx(359 / 60)  # elapsed ≈ 6 h, not 12: the rates use worker-hours
    assert report.per_worker_hour(55_600) == pytest.approx(55_600 / 12) == pytest.approx(4633.33, abs=0.01)
    assert round(report.per_worker_hour(12_524), 1) == 1043.7
    assert report.to_dict()["overall"]["labels_per_worker_hour"] == pytest.approx(4633.33, abs=0.01)
    assert report.overall.geotags_per_worker_hour == pytest.approx(60.0)


def test_session_rule():
    t = np.array([0, 60, 120, 3000, 3060, 9000], dtype=float)  # gaps of 48 min and 99 min split it in three
    assert [len(s) for s in sessions(t, 1200)] == [3, 2, 1]
    # n captures count n intervals; a single capture counts one: (120 + 60) + (60 + 60) + (0 + 60) = 360 s.
    assert working_seconds(t, 60.0, 1200) == 360.0
    assert working_seconds(t[::-1], 60.0, 1200) == 360.0  # order does not matter
    assert sessions([], 1200) == []


def test_one_worker_without_a_name_and_single_capture_sessions():
    """A layer without a worker field is one unnamed worker; a worker whose sessions are single captures takes
    the pooled typical interval."""
    times = every("08:00", 5, 4) + [clock("12:00"), clock("14:00")]
    report = survey_report(times, [None] * 4 + ["late"] * 2)
    assert report.typical_interval_s == {"": 300.0, "late": 300.0}
    late = report.workers[1]
    assert (late.sessions, late.worker_hours) == (2, pytest.approx(600 / 3600))
    assert survey_report(times[:4]).workers[0].name == ""


def test_times_in_other_zones_and_bad_times():
    assert capture_seconds(["2026-05-20T10:00:00+02:00", "2026-05-20 08:00:00", ""])[:2].tolist() == \
        [capture_seconds(["2026-05-20T08:00:00Z"])[0]] * 2
    with pytest.raises(InputError, match="row 2.*not a date"):
        capture_seconds(["2026-05-20T08:00:00Z", "yesterday"], "geotags")
    with pytest.raises(InputError, match="none of the 2 geotag"):
        survey_report(["", None])
    with pytest.raises(InputError, match="longer than 0 s"):
        survey_report([clock("08:00")], session_gap_s=0)
    with pytest.raises(InputError, match="no two captures"):
        survey_report([clock("08:00"), clock("10:00")])


def test_label_counts_and_report_rate(tmp_path):
    (tmp_path / "summary.json").write_text(json.dumps({"n_labels": 55600, "n_frames_with_labels": 12524}))
    assert label_counts(tmp_path) == (55600, 12524)
    with pytest.raises(InputError, match="summary.json"):
        label_counts(tmp_path / "missing.json")
    times, workers, partition_of, flights = morning()
    path = tmp_path / "report.json"
    path.write_text(json.dumps(survey_report(times, workers).to_dict()))
    assert report_geotags_per_hour(path) == pytest.approx(25.0)
    with pytest.raises(InputError, match="Survey report"):
        report_geotags_per_hour(tmp_path / "summary.json")


# ------------------------------------------------------------------------------------------ partitions
#: An L-shaped field, 300 m × 200 m less its 200 m × 100 m north-east quarter: 4 ha, concave.
L_FIELD = np.array([[0, 0], [300, 0], [300, 100], [100, 100], [100, 200], [0, 200]], dtype=float) + [5e5, 6e6]


def test_partitions_of_a_concave_field():
    # 120 geotags/h at 100 targets/ha: 1.2 ha per hour; 4 ha → ceil(3.33) = 4 pieces, a multiple of 2 people.
    plan = partition_field([[L_FIELD]], 2)
    assert plan.area_m2 == pytest.approx(40_000)
    assert len(plan.pieces) == 4
    assert [p.area_m2 for p in plan.pieces] == pytest.approx([10_000] * 4)
    assert [p.expected_hours for p in plan.pieces] == pytest.approx([10_000 / 12_000] * 4)
    assert [p.expected_geotags for p in plan.pieces] == pytest.approx([100] * 4)
    assert [(p.worker, p.order) for p in plan.pieces] == [(1, 1), (1, 2), (2, 1), (2, 2)]
    # The long axis is the 300 m side (x); the cut positions give each strip 1 ha of the L.
    assert abs(plan.axis @ [1, 0]) == pytest.approx(1.0)
    polygons = [[L_FIELD - plan.origin]]
    below = [area_below(polygons, plan.axis, p.hi_m) for p in plan.pieces]
    assert below == pytest.approx([10_000, 20_000, 30_000, 40_000], rel=1e-9)
    # Three people: 4 pieces round up to 6, each 0.556 h.
    plan = partition_field([[L_FIELD]], 3)
    assert len(plan.pieces) == 6 and [p.worker for p in plan.pieces] == [1, 1, 2, 2, 3, 3]
    assert max(p.expected_hours for p in plan.pieces) <= 1.0


def test_a_hole_and_the_piece_size():
    outer = np.array([[0, 0], [400, 0], [400, 100], [0, 100]], dtype=float)
    hole = np.array([[150, 25], [250, 25], [250, 75], [150, 75]], dtype=float)
    # 4 ha − 0.5 ha = 3.5 ha; 60 geotags/h at 100/ha = 0.6 ha/h; half-hour pieces of 0.3 ha → ceil(11.67) = 12.
    plan = partition_field([[outer, hole]], 1, hours_per_piece=0.5, geotags_per_hour=60)
    assert plan.area_m2 == pytest.approx(35_000)
    assert len(plan.pieces) == 12 and {p.worker for p in plan.pieces} == {1}
    assert [p.order for p in plan.pieces] == list(range(1, 13))
    assert all(p.expected_hours == pytest.approx(35_000 / 12 / 6_000) for p in plan.pieces)
    strip = plan.strip(plan.pieces[0])
    assert strip.shape == (4, 2)


def test_long_axis_of_a_rotated_rectangle():
    angle = math.radians(30)
    u = np.array([math.cos(angle), math.sin(angle)])
    v = np.array([-u[1], u[0]])
    corners = np.array([a * 50 * u + b * 10 * v for a, b in ((0, 0), (1, 0), (1, 1), (0, 1))])
    assert abs(long_axis(corners) @ u) == pytest.approx(1.0)


def test_partition_inputs_refused():
    with pytest.raises(InputError, match="N_PEOPLE"):
        partition_field([[L_FIELD]], 0)
    with pytest.raises(InputError, match="TARGETS_PER_HA"):
        partition_field([[L_FIELD]], 2, targets_per_ha=0)
    with pytest.raises(InputError, match="no polygon"):
        partition_field([], 2)


def test_several_fields_number_on():
    small = np.array([[0, 0], [100, 0], [100, 100], [0, 100]], dtype=float)  # 1 ha: 1 piece → 2 for 2 people
    records = [r for _, _, r in partition_records([partition_field([[L_FIELD]], 2), partition_field([[small]], 2)])]
    assert [r["field"] for r in records] == [1, 1, 1, 1, 2, 2]
    assert [r["partition"] for r in records] == [1, 2, 3, 4, 5, 6]
    assert [(r["worker"], r["order"]) for r in records] == [(1, 1), (1, 2), (2, 1), (2, 2), (1, 3), (2, 3)]
    assert records[0]["area_ha"] == 1.0 and records[4]["area_ha"] == 0.5


def test_the_html_reads_as_figures():
    times, workers, partition_of, flights = morning()
    html = survey_report_html(survey_report(times, workers, partition_of, [1, 2, 3, 4], flights, label_count=55_600))
    assert "<td>Geotags per worker-hour</td><td>25.0</td>" in html
    assert "<td>Labels per worker-hour</td><td>18,533.3</td>" in html  # 55,600 / 3 worker-hours
    assert "<td>A</td><td>45</td><td>2</td><td>120</td><td>1.50</td><td>30.0</td>" in html
    assert "more than 20 min apart" in html and "3 of 4 partitions" in html
