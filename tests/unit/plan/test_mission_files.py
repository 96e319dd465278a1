"""Mission files re-parse with an XML parser, json and csv, and match the planned waypoints."""
import csv
import json
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.plan.flight_plan import FlightSettings, plan_flight
from birdseye.birdseye_qgis.core.plan.mission_files import (
    DJI_DRONES,
    DJI_PAYLOADS,
    LITCHI_STAY_FOR,
    LITCHI_TAKE_PHOTO,
    MissionSpec,
    check_waypoint_limits,
    mission_file_paths,
    parse_dji_kmz,
    parse_kml,
    parse_litchi_csv,
    parse_qgc_plan,
    write_dji_kmz,
    write_kml,
    write_litchi_csv,
    write_qgc_plan,
)

LAT0, LON0 = -34.95, 138.58
TOL_DEG = 1e-7
LITCHI_HUB_HEADER = (
    "latitude,longitude,altitude(m),heading(deg),curvesize(m),rotationdir,gimbalmode,gimbalpitchangle,"
    + ",".join(f"actiontype{i},actionparam{i}" for i in range(1, 16))
    + ",altitudemode,speed(m/s),poi_latitude,poi_longitude,poi_altitude(m),poi_altitudemode,"
    "photo_timeinterval,photo_distinterval")


def planned(capture="photo", n=40, max_waypoints=99, home=True, seed=4):
    xy = np.random.default_rng(seed).uniform(0, 250, (n, 2))
    lat, lon, _ = LocalFrame(LAT0, LON0, 0.0).to_geodetic(np.column_stack([xy, np.zeros(n)]))
    s = FlightSettings(capture=capture, capture_interval_s=1.5, max_waypoints=max_waypoints,
                       hover_s=2.5, speed_ms=4.0, altitude_m=15.0)
    plan = plan_flight(lat, lon, ids=[f"g{i}" for i in range(n)],
                       home=(LAT0, LON0) if home else None, settings=s)
    return plan, plan.mission_specs("field7")


def strict_json(text):
    def refuse(token):
        raise ValueError(f"non-JSON constant {token}")

    return json.loads(text, parse_constant=refuse)


@pytest.mark.parametrize("capture", ["photo", "timed"])
def test_dji_kmz_round_trip(tmp_path, capture):
    plan, (spec,) = planned(capture)
    path = write_dji_kmz(tmp_path / "m.kmz", spec, DJI_DRONES["Matrice 300 RTK"], DJI_PAYLOADS["Zenmuse P1"])
    with zipfile.ZipFile(path) as kmz:
        assert {"wpmz/template.kml", "wpmz/waylines.wpml"} <= set(kmz.namelist())
        for name in ("wpmz/template.kml", "wpmz/waylines.wpml"):
            root = ET.fromstring(kmz.read(name))  # well-formed XML
            assert root.tag == "{http://www.opengis.net/kml/2.2}kml"
    parsed = parse_dji_kmz(path)
    order = plan.missions[0].waypoints
    for part in ("template", "waylines"):
        got = parsed[part]
        assert np.allclose(got["lat"], plan.waypoint_lat[order], atol=TOL_DEG, rtol=0)
        assert np.allclose(got["lon"], plan.waypoint_lon[order], atol=TOL_DEG, rtol=0)
        assert np.allclose(got["height"], 15.0)
        assert got["drone_enum"] == 60 and got["payload_enum"] == 50
        assert got["speed"] == 4.0 and got["finish_action"] == "goHome"
        groups = got["action_groups"]
        assert len({g["id"] for g in groups}) == len(groups)
        first = [g for g in groups if g["start"] == 0 and g["trigger"] == "reachPoint"][0]
        gimbal = dict(first["actions"])["gimbalRotate"]
        assert float(gimbal["gimbalPitchRotateAngle"]) == -90.0
        reach = {g["start"]: [f for f, _ in g["actions"]] for g in groups if g["trigger"] == "reachPoint"}
        assert sorted(reach) == list(range(len(order)))
        assert all("hover" in funcs for funcs in reach.values())
        if capture == "photo":
            assert all(funcs[-1] == "takePhoto" for funcs in reach.values())
            assert not [g for g in groups if g["trigger"] == "multipleTiming"]
        else:
            assert not any("takePhoto" in funcs for funcs in reach.values())
            (timed,) = [g for g in groups if g["trigger"] == "multipleTiming"]
            assert (timed["start"], timed["end"]) == (0, len(order) - 1)
            assert timed["trigger_param"] == 1.5 and timed["actions"][0][0] == "takePhoto"
    assert parsed["template"]["height_mode"] == "relativeToStartPoint"
    assert parsed["template"]["template_type"] == "waypoint"
    assert np.all(parsed["template"]["gimbal_pitch"] == -90.0)
    assert parsed["waylines"]["execute_height_mode"] == "relativeToStartPoint"


@pytest.mark.parametrize("capture", ["photo", "timed"])
def test_qgc_plan_round_trip(tmp_path, capture):
    plan, (spec,) = planned(capture)
    path = write_qgc_plan(tmp_path / "m.plan", spec)
    raw = strict_json(path.read_text())  # no NaN/Infinity: valid JSON for QGroundControl
    assert raw["fileType"] == "Plan" and raw["version"] == 1 and raw["mission"]["version"] == 2
    parsed = parse_qgc_plan(path)
    order = plan.missions[0].waypoints
    assert np.allclose(parsed["lat"], plan.waypoint_lat[order], atol=TOL_DEG, rtol=0)
    assert np.allclose(parsed["lon"], plan.waypoint_lon[order], atol=TOL_DEG, rtol=0)
    assert np.allclose(parsed["altitude"], 15.0) and np.allclose(parsed["hold_s"], 2.5)
    cmds, frames = parsed["commands"], parsed["frames"]
    assert cmds[0] == 22 and cmds[-1] == 20
    assert all(f == 3 for c, f in zip(cmds, frames) if c == 16)
    assert [it["doJumpId"] for it in parsed["items"]] == list(range(1, len(cmds) + 1))
    assert parsed["items"][0]["params"][4:6] == [LAT0, LON0]
    assert 205 in cmds and parsed["items"][cmds.index(205)]["params"][0] == -90.0
    assert parsed["items"][cmds.index(178)]["params"][1] == 4.0
    if capture == "photo":
        # One image capture right after each waypoint.
        after = [cmds[k + 1] for k, c in enumerate(cmds) if c == 16]
        assert after == [2000] * len(order)
        assert all(it["params"][2] == 1 for it in parsed["items"] if it["command"] == 2000)
    else:
        first_wp, last_wp = cmds.index(16), len(cmds) - 1 - cmds[::-1].index(16)
        assert cmds.index(2000) < first_wp and cmds.index(2001) > last_wp
        assert parsed["items"][cmds.index(2000)]["params"][1] == 1.5


@pytest.mark.parametrize("capture", ["photo", "timed"])
def test_litchi_csv_round_trip(tmp_path, capture):
    plan, (spec,) = planned(capture, n=30)
    path = write_litchi_csv(tmp_path / "m.csv", spec)
    with path.open(newline="") as fh:
        rows = list(csv.reader(fh))
    # Litchi Mission Hub's own export header, verbatim.
    assert ",".join(rows[0]) == LITCHI_HUB_HEADER
    assert all(len(r) == 46 for r in rows)
    parsed = parse_litchi_csv(path)
    order = plan.missions[0].waypoints
    assert np.allclose(parsed["lat"], plan.waypoint_lat[order], atol=TOL_DEG, rtol=0)
    assert np.allclose(parsed["lon"], plan.waypoint_lon[order], atol=TOL_DEG, rtol=0)
    assert np.allclose(parsed["altitude"], 15.0)
    assert np.all(parsed["altitude_mode"] == 0) and np.all(parsed["gimbal_mode"] == 2)
    assert np.all(parsed["gimbal_pitch"] == -90.0) and np.all(parsed["speed"] == 4.0)
    for actions in parsed["actions"]:
        assert actions[0] == (LITCHI_STAY_FOR, 2500.0)
        assert ((LITCHI_TAKE_PHOTO, 0.0) in actions) == (capture == "photo")
    assert np.all(parsed["photo_timeinterval"] == (1.5 if capture == "timed" else -1.0))
    assert np.allclose(parsed["heading"][:-1], spec.headings_deg()[:-1], atol=0.05)


def test_kml_holds_every_mission_with_routes_closed_at_home(tmp_path):
    plan, specs = planned(n=60, max_waypoints=12)
    assert len(specs) >= 5
    path = write_kml(tmp_path / "all.kml", specs)
    ET.parse(path)  # well-formed
    missions = parse_kml(path)
    assert [m["name"] for m in missions] == [f"field7_m{k}" for k in range(1, len(specs) + 1)]
    for parsed, mission in zip(missions, plan.missions):
        w = mission.waypoints
        assert parsed["order"] == list(range(1, len(w) + 1))
        assert set(parsed["mission"]) == {mission.number}
        assert np.allclose(parsed["lat"], plan.waypoint_lat[w], atol=TOL_DEG, rtol=0)
        assert np.allclose(parsed["lon"], plan.waypoint_lon[w], atol=TOL_DEG, rtol=0)
        assert np.allclose(parsed["altitude"], 15.0)
        route = parsed["route"]
        assert np.allclose(route[0, :2], [LON0, LAT0], atol=TOL_DEG) and np.allclose(route[-1], route[0])
        expected_ids = [";".join(plan.geotag_ids[g] for g in plan.members[k]) for k in w]
        assert parsed["geotag_ids"] == expected_ids


def test_mission_file_paths_layout(tmp_path):
    assert mission_file_paths(tmp_path / "a.kmz", 1) == [tmp_path / "a.kmz"]
    assert mission_file_paths(tmp_path / "a.kmz", 3) == [tmp_path / f"a_m{k}.kmz" for k in (1, 2, 3)]


def test_limits_are_refused_with_a_clear_message(tmp_path):
    spec = MissionSpec("big", np.full(100, LAT0) + np.arange(100) * 1e-5, np.full(100, LON0), 12.0,
                       3.0, 1.0)
    with pytest.raises(InputError, match="100 waypoints but Litchi holds at most 99.*MAX_WAYPOINTS"):
        write_litchi_csv(tmp_path / "x.csv", spec)
    assert not (tmp_path / "x.csv").exists()
    check_waypoint_limits([spec], ["kmz", "plan", "kml"])  # DJI holds 65 535, QGC and KML no limit
    # One action group per waypoint plus the timed one must fit WPML's group ids 0…65535.
    huge = MissionSpec("huge", np.full(65536, LAT0), np.full(65536, LON0), 12.0, 3.0, 1.0)
    with pytest.raises(InputError, match="65536 waypoints but DJI Pilot 2 .* holds at most 65535"):
        check_waypoint_limits([huge], ["kmz"])
    single = MissionSpec("one", [LAT0], [LON0], 12.0, 3.0, 1.0)
    for writer, name in ((write_dji_kmz, "DJI Pilot 2"), (write_litchi_csv, "Litchi")):
        with pytest.raises(InputError, match=f"1 waypoint\\(s\\) but {name}.* needs at least 2"):
            writer(tmp_path / "one.out", single)
    write_qgc_plan(tmp_path / "one.plan", single)
    assert len(parse_qgc_plan(tmp_path / "one.plan")["lat"]) == 1
    long_hover = MissionSpec("h", [LAT0, LAT0 + 1e-4], [LON0, LON0], 12.0, 3.0, 40.0)
    with pytest.raises(InputError, match="HOVER_S = 40 s but Litchi"):
        write_litchi_csv(tmp_path / "h.csv", long_hover)


def test_headings_follow_the_legs():
    frame = LocalFrame(LAT0, LON0, 0.0)
    # North, then east, then south-west.
    xy = np.array([[0, 0], [0, 100], [100, 100], [0, 0]], dtype=float)
    lat, lon, _ = frame.to_geodetic(np.column_stack([xy, np.zeros(4)]))
    spec = MissionSpec("h", lat, lon, 10.0, 3.0, 0.0)
    headings = spec.headings_deg()
    assert np.all((headings >= 0) & (headings <= 360))
    circular_error = np.mod(headings - [0.0, 90.0, 225.0, 225.0] + 180.0, 360.0) - 180.0
    assert np.allclose(circular_error, 0.0, atol=0.01)


def test_parsers_refuse_foreign_files(tmp_path):
    (tmp_path / "x.plan").write_text('{"fileType": "Other"}')
    with pytest.raises(InputError, match="not a QGroundControl plan"):
        parse_qgc_plan(tmp_path / "x.plan")
    (tmp_path / "x.csv").write_text("lat,lon\n1,2\n")
    with pytest.raises(InputError, match="row 1: header is not Litchi"):
        parse_litchi_csv(tmp_path / "x.csv")
    with zipfile.ZipFile(tmp_path / "x.kmz", "w") as z:
        z.writestr("doc.kml", "<kml/>")
    with pytest.raises(InputError, match="missing wpmz/template.kml"):
        parse_dji_kmz(tmp_path / "x.kmz")
