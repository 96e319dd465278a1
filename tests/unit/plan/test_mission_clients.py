"""Our mission files opened by the software that flies them, or by readers written for it.

QGroundControl ``.plan``: MAVSDK (``mavsdk`` on PyPI, the MAVLink SDK behind many PX4 and ArduPilot
ground tools) imports the plan with ``MissionRaw.import_qgroundcontrol_mission`` and uploads it over
the MAVLink mission protocol. mavsdk 4 is a binding of the C library itself (no mavsdk_server), and
its MissionRaw plugin needs a discovered autopilot; the offline way there is a second MAVSDK instance
configured as the autopilot, the two linked through ``raw://`` connections whose bytes the test passes
across (no socket). That autopilot's MissionRawServer receives what the ground station uploads, so
the test sees the plan as a vehicle would.

Litchi CSV: the header is the metric column set Litchi's Mission Hub exports and imports (Litchi
Utilities' description of the format, https://www.litchiutilities.com/docs/litchiCsv.php: latitude
−90…90, longitude −180…180, altitude(m) relative to the take-off point −200…500 m, heading(deg)
0…360, curvesize(m), speed(m/s)); the file is then read by ``litchi-wp`` (PyPI), an independent
reader of the format, and every value must come back.
"""
from __future__ import annotations

import contextlib
import json
import math
import queue
import threading

import litchi_wp.waypoint as litchi_waypoint
import numpy as np
import pytest
from litchi_wp.enums import ActionType, AltitudeMode, GimbalMode
from mavsdk import ComponentType, Configuration, ConnectionResult, Mavsdk
from mavsdk.plugins.mission_raw import MissionRaw, MissionRawError
from mavsdk.plugins.mission_raw_server import MissionRawServer

from birdseye.birdseye_qgis.core.plan.mission_files import (
    CAPTURE_PHOTO,
    CAPTURE_TIMED,
    LITCHI_COLUMNS,
    MissionSpec,
    qgc_plan_dict,
    write_litchi_csv,
    write_qgc_plan,
)

HOME = (-34.9502, 138.5797)
# MAVLink mission items carry latitude and longitude as integers of 1e-7 degree.
DEGE7 = 1e7


def mission(capture: str) -> MissionSpec:
    lat = -34.95 + 1.3e-4 * np.arange(5)
    lon = 138.58 + 7e-5 * np.arange(5) ** 2
    return MissionSpec("field7", lat, lon, [12.0, 12.5, 13.0, 12.5, 12.0], 4.0, 2.5, capture=capture,
                       capture_interval_s=1.5 if capture == CAPTURE_TIMED else None, home=HOME)


def expected_items(spec: MissionSpec) -> list[tuple]:
    """(command, frame, param1…4, x, y, z) of each item, from the mission and the MAVLink command
    definitions (MAV_CMD 22 take-off, 178 speed, 205 mount, 16 waypoint, 2000/2001 image capture,
    20 return to launch; frame 3 global relative altitude, 2 mission)."""
    nan = math.nan
    items = [(22, 3, 0, 0, 0, nan, HOME[0] * DEGE7, HOME[1] * DEGE7, spec.altitude_m[0]),
             (178, 2, 1, spec.speed_ms, -1, 0, 0, 0, 0),
             (205, 2, -90, 0, 0, 0, 0, 0, 2)]  # pitch −90°, z = MAV_MOUNT_MODE_MAVLINK_TARGETING
    if spec.capture == CAPTURE_TIMED:
        items.append((2000, 2, 0, spec.capture_interval_s, 0, 0, 0, 0, 0))
    for lat, lon, alt in zip(spec.lat, spec.lon, spec.altitude_m):
        items.append((16, 3, spec.hover_s, 0, 0, nan, lat * DEGE7, lon * DEGE7, alt))
        if spec.capture == CAPTURE_PHOTO:
            items.append((2000, 2, 0, 0, 1, 0, 0, 0, 0))  # one image (param3 = 1)
    if spec.capture == CAPTURE_TIMED:
        items.append((2001, 2, 0, 0, 0, 0, 0, 0, 0))
    items.append((20, 2, 0, 0, 0, 0, 0, 0, 0))
    return items


def as_rows(items) -> np.ndarray:
    return np.array([(i.command, i.frame, i.param1, i.param2, i.param3, i.param4, i.x, i.y, i.z)
                     for i in items], dtype=float)


@contextlib.contextmanager
def ground_station_and_vehicle():
    """A MAVSDK ground station linked to a MAVSDK autopilot in this process; yields the ground
    station's view of the vehicle and the missions the vehicle received."""
    vehicle = Mavsdk(Configuration.create_with_component_type(ComponentType.AUTOPILOT))
    station = Mavsdk(Configuration.create_with_component_type(ComponentType.GROUND_STATION))
    stop = threading.Event()
    pumps = []
    try:
        for end in (vehicle, station):
            assert end.add_any_connection("raw://") == ConnectionResult.SUCCESS
        # Bytes cross on threads of their own: handing them over inside MAVSDK's send callback
        # would re-enter the other instance from its own I/O thread.
        for source, target in ((vehicle, station), (station, vehicle)):
            pipe = queue.Queue()
            source.subscribe_raw_bytes_to_be_sent(pipe.put)

            def pump(pipe=pipe, target=target):
                while not stop.is_set():
                    with contextlib.suppress(queue.Empty):
                        target.pass_received_raw_bytes(pipe.get(timeout=0.02))

            pumps.append(threading.Thread(target=pump, daemon=True))
            pumps[-1].start()
        received = []
        server = MissionRawServer(vehicle.server_component())
        server.subscribe_incoming_mission(lambda result, plan, _: received.append((result, plan)))
        system = station.first_autopilot(10.0)
        assert system is not None, "the ground station did not discover the in-process autopilot"
        yield system, received
    finally:
        stop.set()
        for thread in pumps:
            thread.join(timeout=2)
        station.destroy()
        vehicle.destroy()


@pytest.mark.parametrize("capture", [CAPTURE_PHOTO, CAPTURE_TIMED])
def test_mavsdk_imports_our_plan_and_a_vehicle_accepts_it(tmp_path, capture):
    spec = mission(capture)
    path = write_qgc_plan(tmp_path / "field7.plan", spec)
    expected = np.array(expected_items(spec), dtype=float)
    with ground_station_and_vehicle() as (system, received):
        plugin = MissionRaw(system)
        imported = plugin.import_qgroundcontrol_mission(str(path))
        rows = as_rows(imported.mission_items)
        assert rows.shape == expected.shape
        np.testing.assert_array_equal(rows[:, :2], expected[:, :2])  # commands and frames
        np.testing.assert_allclose(rows[:, 2:6], expected[:, 2:6], atol=1e-6, equal_nan=True)
        np.testing.assert_allclose(rows[:, 6:8], expected[:, 6:8], atol=1)  # 1e-7° integers
        np.testing.assert_allclose(rows[:, 8], expected[:, 8], atol=1e-6)
        assert imported.geofence_items == [] and imported.rally_items == []

        plugin.upload_mission(imported.mission_items)
        for _ in range(200):  # the server reports on its own thread
            if received:
                break
            threading.Event().wait(0.01)
        (result, plan), = received
        assert result == type(result).SUCCESS
        np.testing.assert_array_equal(as_rows(plan.mission_items), rows)
        np.testing.assert_array_equal(as_rows(plugin.download_mission()), rows)


def test_mavsdk_refuses_a_plan_it_cannot_read():
    """The import checks what it reads (so the test above could fail): QGroundControl plans are file
    version 1 with mission version 2."""
    spec = mission(CAPTURE_PHOTO)
    plan = qgc_plan_dict(spec)
    with ground_station_and_vehicle() as (system, _):
        plugin = MissionRaw(system)
        imported = plugin.import_qgroundcontrol_mission_from_string(json.dumps(plan))
        assert len(imported.mission_items) == len(expected_items(spec))
        plan["mission"]["version"] = 1
        with pytest.raises(MissionRawError, match="FAILED_TO_PARSE_QGC_PLAN"):
            plugin.import_qgroundcontrol_mission_from_string(json.dumps(plan))


# --------------------------------------------------------------------------- Litchi
MISSION_HUB_METRIC_HEADER = (
    ["latitude", "longitude", "altitude(m)", "heading(deg)", "curvesize(m)", "rotationdir", "gimbalmode",
     "gimbalpitchangle"]
    + [f"action{kind}{i}" for i in range(1, 16) for kind in ("type", "param")]
    + ["altitudemode", "speed(m/s)", "poi_latitude", "poi_longitude", "poi_altitude(m)", "poi_altitudemode",
       "photo_timeinterval", "photo_distinterval"])


@pytest.mark.parametrize("capture", [CAPTURE_PHOTO, CAPTURE_TIMED])
def test_litchi_csv_has_mission_hubs_metric_columns_and_reads_back_in_litchi_wp(tmp_path, capture):
    spec = mission(capture)
    path = write_litchi_csv(tmp_path / "field7.csv", spec)
    lines = path.read_text(encoding="utf-8").splitlines()
    assert lines[0].split(",") == MISSION_HUB_METRIC_HEADER == LITCHI_COLUMNS
    assert lines[0] == litchi_waypoint.Waypoint.get_header(line_break=None)

    waypoints = litchi_waypoint.Waypoint.from_file(str(path))  # skips (and prints) lines it rejects
    assert len(waypoints) == len(spec)
    np.testing.assert_allclose([w.lat for w in waypoints], spec.lat, atol=1e-9)
    np.testing.assert_allclose([w.lon for w in waypoints], spec.lon, atol=1e-9)
    np.testing.assert_allclose([w.altitude.value for w in waypoints], spec.altitude_m, atol=0.005)
    for i, w in enumerate(waypoints):
        assert w.altitude.mode == AltitudeMode.MSL  # 0: relative to the take-off point, not above ground
        assert -90 <= w.lat <= 90 and -180 <= w.lon <= 180 and -200 <= w.altitude.value <= 500
        assert 0 <= w.heading < 360
        assert w.gimbal.mode == GimbalMode.INTERPOLATE and w.gimbal.pitchangle == -90
        assert w.speed == spec.speed_ms  # m/s
        actions = [(a.type, a.param) for a in w.actions if a.type != ActionType.NO_ACTION]
        expected = [(ActionType.STAY_FOR, spec.hover_s * 1000)]  # milliseconds
        if capture == CAPTURE_PHOTO:
            expected.append((ActionType.TAKE_PHOTO, 0))
            assert w.photo.time_interval == -1
        else:
            assert w.photo.time_interval == spec.capture_interval_s  # seconds
        assert actions == expected, i
        assert w.photo.distance_interval == -1
    # the heading points along each leg (north = 0°, east = 90°): the first leg runs north-east
    assert 0 < waypoints[0].heading < 90
