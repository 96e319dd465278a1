"""Mission files a flight app opens: DJI WPML KMZ, QGroundControl ``.plan``, Litchi CSV, plain KML.

One :class:`MissionSpec` describes one flight (one battery): waypoints in WGS84 degrees with
altitudes in metres *relative to the take-off point*, the optional home (take-off and landing
point), speed, hover time and the capture mode. Every writer has a parser beside it, so the files
are tested by re-reading them, and one module owns each format's schema.

Formats (as documented by their owners):

* **DJI WPML** (DJI Pilot 2 / FlightHub 2, Matrice 300/350 RTK): a KMZ (zip) holding
  ``wpmz/template.kml`` (the editable waypoint template) and ``wpmz/waylines.wpml`` (what the
  aircraft executes), namespace ``http://www.dji.com/wpmz/1.0.2``. Heights are
  ``relativeToStartPoint``, heading follows the wayline, the aircraft stops at each waypoint, the
  gimbal is pitched to −90° (nadir) at the first waypoint, and the camera either takes one photo at
  each waypoint (``reachPoint`` action group) or shoots at a fixed interval over the whole route
  (``multipleTiming`` action group from the first to the last waypoint). ``finishAction`` is
  ``goHome``. Speeds lie in 1–15 m/s. ``wpml:index`` and ``wpml:actionGroupId`` run 0…65535 and a
  timed route with hovers has one group per waypoint plus the timed one, so a route holds at most
  65 535 waypoints; Pilot 2 needs at least two. tests/unit/plan/test_dji_wpml_spec.py checks every
  element and value against DJI's published WPML tables.
* **QGroundControl plan** (JSON, file version 1, mission version 2): take-off (MAV_CMD 22), speed
  (178), gimbal pitch (205, mount control), waypoints (16) in frame 3 =
  MAV_FRAME_GLOBAL_RELATIVE_ALT with the hover time as hold time (param 1), camera trigger
  (2000 image start capture: one image per waypoint, or an interval started before the first
  waypoint and stopped with 2001 after the last), return to launch (20). MAVSDK imports these plans
  and uploads them to a vehicle (tests/unit/plan/test_mission_clients.py).
* **Litchi CSV**: Litchi's standard 46-column header; altitude mode 0 (relative to take-off),
  gimbal mode 2 (interpolate) at −90°, actions "stay for" (0, ms) and "take photo" (1), or a photo
  time interval for timed capture. Litchi holds 2…99 waypoints per mission. litchi-wp (PyPI) reads
  these files back in the same test module.
* **Plain KML** for Google Earth: one ``Folder`` per mission holding the route line and one
  placemark per waypoint (``ExtendedData``: mission, order, altitude, geotag ids); all missions in
  one file.
"""
from __future__ import annotations

import csv
import json
import time
import xml.etree.ElementTree as ET
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..geometry.geodesy import geodetic_to_ecef, rotation_ecef_enu

KML_NS = "http://www.opengis.net/kml/2.2"
WPML_NS = "http://www.dji.com/wpmz/1.0.2"
ET.register_namespace("", KML_NS)
ET.register_namespace("wpml", WPML_NS)

CAPTURE_PHOTO = "photo"
CAPTURE_TIMED = "timed"

#: DJI ``droneEnumValue`` of the aircraft we write missions for (DJI Cloud API product table).
DJI_DRONES = {"Matrice 350 RTK": 89, "Matrice 300 RTK": 60}
#: DJI ``payloadEnumValue`` of the gimbal cameras these aircraft carry.
DJI_PAYLOADS = {"Zenmuse H20": 42, "Zenmuse H20T": 43, "Zenmuse H20N": 61, "Zenmuse H30": 82,
                "Zenmuse H30T": 83, "Zenmuse P1": 50, "Payload SDK camera": 65534}

#: (fewest, most) waypoints one mission may hold, per format; None = no limit of the format.
WAYPOINT_LIMITS = {"kmz": (2, 65535), "plan": (1, None), "litchi": (2, 99), "kml": (1, None)}
FORMAT_NAMES = {"kmz": "DJI Pilot 2 (WPML KMZ)", "plan": "QGroundControl", "litchi": "Litchi",
                "kml": "KML"}
#: WPML's autoFlightSpeed, waypointSpeed and globalTransitionalSpeed range [m/s].
DJI_SPEED_LIMITS_MS = (1.0, 15.0)
#: Litchi's "stay for" action holds at most 32 767 ms.
LITCHI_MAX_STAY_MS = 32767

LITCHI_COLUMNS = (
    ["latitude", "longitude", "altitude(m)", "heading(deg)", "curvesize(m)", "rotationdir",
     "gimbalmode", "gimbalpitchangle"]
    + [f"action{kind}{i}" for i in range(1, 16) for kind in ("type", "param")]
    + ["altitudemode", "speed(m/s)", "poi_latitude", "poi_longitude", "poi_altitude(m)",
       "poi_altitudemode", "photo_timeinterval", "photo_distinterval"])
LITCHI_STAY_FOR, LITCHI_TAKE_PHOTO, LITCHI_NO_ACTION = 0, 1, -1

# MAVLink commands and frames used in QGroundControl plans.
MAV_CMD_NAV_WAYPOINT = 16
MAV_CMD_NAV_RETURN_TO_LAUNCH = 20
MAV_CMD_NAV_TAKEOFF = 22
MAV_CMD_DO_CHANGE_SPEED = 178
MAV_CMD_DO_MOUNT_CONTROL = 205
MAV_CMD_IMAGE_START_CAPTURE = 2000
MAV_CMD_IMAGE_STOP_CAPTURE = 2001
MAV_FRAME_MISSION = 2
MAV_FRAME_GLOBAL_RELATIVE_ALT = 3
MAV_AUTOPILOT_PX4 = 12
MAV_TYPE_QUADROTOR = 2
MAV_MOUNT_MODE_MAVLINK_TARGETING = 2


@dataclass
class MissionSpec:
    """One flight: waypoints (degrees WGS84, altitude m relative to take-off) in flight order."""

    name: str
    lat: np.ndarray
    lon: np.ndarray
    altitude_m: np.ndarray
    speed_ms: float
    hover_s: float
    capture: str = CAPTURE_PHOTO
    capture_interval_s: float | None = None
    home: tuple[float, float] | None = None
    gimbal_pitch_deg: float = -90.0
    geotag_ids: list = field(default_factory=list)

    def __post_init__(self):
        self.lat = np.asarray(self.lat, dtype=float).reshape(-1)
        self.lon = np.asarray(self.lon, dtype=float).reshape(-1)
        self.altitude_m = np.broadcast_to(np.asarray(self.altitude_m, dtype=float),
                                          self.lat.shape).copy()
        if self.capture not in (CAPTURE_PHOTO, CAPTURE_TIMED):
            raise ValueError(f"capture must be '{CAPTURE_PHOTO}' or '{CAPTURE_TIMED}'")
        if self.capture == CAPTURE_TIMED and not (self.capture_interval_s or 0) > 0:
            raise ValueError("timed capture needs a positive capture_interval_s")
        if not self.geotag_ids:
            self.geotag_ids = [[] for _ in range(len(self.lat))]

    def __len__(self) -> int:
        return len(self.lat)

    def headings_deg(self) -> np.ndarray:
        """Bearing (degrees from true north, 0–360) from each waypoint to the next, in the local
        east-north-up frame of the waypoint; the last waypoint keeps the bearing of its leg."""
        n = len(self)
        if n < 2:
            return np.zeros(n)
        ecef = geodetic_to_ecef(self.lat, self.lon, np.zeros(n))
        enu = np.einsum("nji,nj->ni", rotation_ecef_enu(self.lat[:-1], self.lon[:-1]),
                        ecef[1:] - ecef[:-1])
        bearing = np.mod(np.degrees(np.arctan2(enu[:, 0], enu[:, 1])), 360.0)
        return np.append(bearing, bearing[-1])


def mission_file_paths(path, count: int) -> list[Path]:
    """Where ``count`` missions go: the path itself for one, ``<stem>_m1<ext>``, … for several."""
    path = Path(path)
    if count == 1:
        return [path]
    return [path.with_name(f"{path.stem}_m{i}{path.suffix}") for i in range(1, count + 1)]


def check_waypoint_limits(specs, formats) -> None:
    """Refuse missions a requested format cannot hold, before any file is written."""
    for fmt in formats:
        low, high = WAYPOINT_LIMITS[fmt]
        for spec in specs:
            n = len(spec)
            if high is not None and n > high:
                raise InputError(
                    f"mission '{spec.name}' has {n} waypoints but {FORMAT_NAMES[fmt]} holds at most"
                    f" {high} per mission: set MAX_WAYPOINTS to {high} or less (the plan is then split"
                    " into several missions), or do not ask for this file")
            if n < low:
                raise InputError(
                    f"mission '{spec.name}' has {n} waypoint(s) but {FORMAT_NAMES[fmt]} needs at least"
                    f" {low}: a single waypoint is written to the QGroundControl plan and the KML, not"
                    f" to this file — add geotags, lower MERGE_RADIUS_M, or do not ask for this file")


def _num(value: float, digits: int = 3) -> str:
    """A short decimal for XML/CSV: fixed digits with trailing zeros removed."""
    text = f"{float(value):.{digits}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _coord(value: float) -> str:
    """Degrees with 9 decimals (0.1 mm), well inside the 1e-7° round-trip tolerance."""
    return f"{float(value):.9f}"


# ---------------------------------------------------------------------- DJI WPML (KMZ)
def _w(tag: str) -> str:
    return f"{{{WPML_NS}}}{tag}"


def _k(tag: str) -> str:
    return f"{{{KML_NS}}}{tag}"


def _sub(parent, tag, text=None):
    el = ET.SubElement(parent, tag)
    if text is not None:
        el.text = str(text)
    return el


def _mission_config(parent, spec: MissionSpec, drone_enum: int, payload_enum: int) -> None:
    cfg = _sub(parent, _w("missionConfig"))
    _sub(cfg, _w("flyToWaylineMode"), "safely")
    _sub(cfg, _w("finishAction"), "goHome")
    _sub(cfg, _w("exitOnRCLost"), "executeLostAction")
    _sub(cfg, _w("executeRCLostAction"), "goBack")
    altitude = float(np.max(spec.altitude_m))
    _sub(cfg, _w("takeOffSecurityHeight"), _num(max(2.0, altitude)))
    _sub(cfg, _w("globalTransitionalSpeed"), _num(spec.speed_ms))
    _sub(cfg, _w("globalRTHHeight"), _num(max(2.0, altitude)))
    drone = _sub(cfg, _w("droneInfo"))
    _sub(drone, _w("droneEnumValue"), drone_enum)
    _sub(drone, _w("droneSubEnumValue"), 0)
    payload = _sub(cfg, _w("payloadInfo"))
    _sub(payload, _w("payloadEnumValue"), payload_enum)
    _sub(payload, _w("payloadSubEnumValue"), 0)
    _sub(payload, _w("payloadPositionIndex"), 0)


def _heading_param(parent, tag) -> None:
    heading = _sub(parent, _w(tag))
    _sub(heading, _w("waypointHeadingMode"), "followWayline")
    _sub(heading, _w("waypointHeadingAngle"), 0)
    _sub(heading, _w("waypointPoiPoint"), "0.000000,0.000000,0.000000")
    _sub(heading, _w("waypointHeadingPathMode"), "followBadArc")


def _action(group, action_id: int, func: str, params: dict) -> None:
    action = _sub(group, _w("action"))
    _sub(action, _w("actionId"), action_id)
    _sub(action, _w("actionActuatorFunc"), func)
    param = _sub(action, _w("actionActuatorFuncParam"))
    for key, value in params.items():
        _sub(param, _w(key), value)


def _gimbal_params(pitch_deg: float) -> dict:
    return {"gimbalHeadingYawBase": "north", "gimbalRotateMode": "absoluteAngle",
            "gimbalPitchRotateEnable": 1, "gimbalPitchRotateAngle": _num(pitch_deg),
            "gimbalRollRotateEnable": 0, "gimbalRollRotateAngle": 0, "gimbalYawRotateEnable": 0,
            "gimbalYawRotateAngle": 0, "gimbalRotateTimeEnable": 0, "gimbalRotateTime": 0,
            "payloadPositionIndex": 0}


def _action_groups(placemark, spec: MissionSpec, index: int, next_group_id: int) -> int:
    """Append the action groups that start at waypoint ``index``; returns the next free group id."""
    reach = []
    if index == 0:
        reach.append(("gimbalRotate", _gimbal_params(spec.gimbal_pitch_deg)))
    if spec.hover_s > 0:
        reach.append(("hover", {"hoverTime": _num(spec.hover_s)}))
    if spec.capture == CAPTURE_PHOTO:
        reach.append(("takePhoto", {"payloadPositionIndex": 0, "fileSuffix": f"wp{index + 1:04d}",
                                    "useGlobalPayloadLensIndex": 1}))
    groups = []
    if reach:
        groups.append((("reachPoint", None), index, index, reach))
    if spec.capture == CAPTURE_TIMED and index == 0:
        groups.append((("multipleTiming", spec.capture_interval_s), 0, len(spec) - 1,
                       [("takePhoto", {"payloadPositionIndex": 0, "fileSuffix": "timed",
                                       "useGlobalPayloadLensIndex": 1})]))
    for (trigger, trigger_param), start, end, actions in groups:
        group = _sub(placemark, _w("actionGroup"))
        _sub(group, _w("actionGroupId"), next_group_id)
        _sub(group, _w("actionGroupStartIndex"), start)
        _sub(group, _w("actionGroupEndIndex"), end)
        _sub(group, _w("actionGroupMode"), "sequence")
        trig = _sub(group, _w("actionTrigger"))
        _sub(trig, _w("actionTriggerType"), trigger)
        if trigger_param is not None:
            _sub(trig, _w("actionTriggerParam"), _num(trigger_param))
        for action_id, (func, params) in enumerate(actions):
            _action(group, action_id, func, params)
        next_group_id += 1
    return next_group_id


def _point(placemark, lat: float, lon: float) -> None:
    point = _sub(placemark, _k("Point"))
    _sub(point, _k("coordinates"), f"{_coord(lon)},{_coord(lat)}")


def _xml_bytes(root) -> bytes:
    """UTF-8 XML with the double-quoted declaration DJI's own files carry."""
    ET.indent(root, space="  ")
    return b'<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="utf-8") + b"\n"


def dji_template_kml(spec: MissionSpec, drone_enum: int, payload_enum: int) -> bytes:
    """``wpmz/template.kml``: the waypoint template DJI Pilot 2 shows and edits."""
    root = ET.Element(_k("kml"))
    doc = _sub(root, _k("Document"))
    now_ms = int(time.time() * 1000)
    _sub(doc, _w("author"), "BirdsEye")
    _sub(doc, _w("createTime"), now_ms)
    _sub(doc, _w("updateTime"), now_ms)
    _mission_config(doc, spec, drone_enum, payload_enum)
    folder = _sub(doc, _k("Folder"))
    _sub(folder, _w("templateType"), "waypoint")
    _sub(folder, _w("templateId"), 0)
    coord = _sub(folder, _w("waylineCoordinateSysParam"))
    _sub(coord, _w("coordinateMode"), "WGS84")
    _sub(coord, _w("heightMode"), "relativeToStartPoint")
    _sub(folder, _w("autoFlightSpeed"), _num(spec.speed_ms))
    _sub(folder, _w("globalHeight"), _num(float(np.max(spec.altitude_m))))
    _sub(folder, _w("gimbalPitchMode"), "usePointSetting")
    _heading_param(folder, "globalWaypointHeadingParam")
    _sub(folder, _w("globalWaypointTurnMode"), "toPointAndStopWithDiscontinuityCurvature")
    _sub(folder, _w("globalUseStraightLine"), 0)
    group_id = 0
    for i in range(len(spec)):
        pm = _sub(folder, _k("Placemark"))
        _point(pm, spec.lat[i], spec.lon[i])
        _sub(pm, _w("index"), i)
        # The template pairs an ellipsoid height with the height in heightMode's reference; for
        # heights relative to the take-off point WPML states the two are equal (the aircraft flies
        # executeHeight of waylines.wpml, relative to take-off).
        _sub(pm, _w("ellipsoidHeight"), _num(spec.altitude_m[i]))
        _sub(pm, _w("height"), _num(spec.altitude_m[i]))
        _sub(pm, _w("useGlobalHeight"), 0)
        _sub(pm, _w("useGlobalSpeed"), 1)
        _sub(pm, _w("useGlobalHeadingParam"), 1)
        _sub(pm, _w("useGlobalTurnParam"), 1)
        _sub(pm, _w("gimbalPitchAngle"), _num(spec.gimbal_pitch_deg))
        group_id = _action_groups(pm, spec, i, group_id)
    payload = _sub(folder, _w("payloadParam"))
    _sub(payload, _w("payloadPositionIndex"), 0)
    _sub(payload, _w("imageFormat"), "wide")
    return _xml_bytes(root)


def dji_waylines_wpml(spec: MissionSpec, drone_enum: int, payload_enum: int) -> bytes:
    """``wpmz/waylines.wpml``: the wayline the aircraft executes."""
    root = ET.Element(_k("kml"))
    doc = _sub(root, _k("Document"))
    _mission_config(doc, spec, drone_enum, payload_enum)
    folder = _sub(doc, _k("Folder"))
    _sub(folder, _w("templateId"), 0)
    _sub(folder, _w("executeHeightMode"), "relativeToStartPoint")
    _sub(folder, _w("waylineId"), 0)
    _sub(folder, _w("autoFlightSpeed"), _num(spec.speed_ms))
    group_id = 0
    for i in range(len(spec)):
        pm = _sub(folder, _k("Placemark"))
        _point(pm, spec.lat[i], spec.lon[i])
        _sub(pm, _w("index"), i)
        _sub(pm, _w("executeHeight"), _num(spec.altitude_m[i]))
        _sub(pm, _w("waypointSpeed"), _num(spec.speed_ms))
        _heading_param(pm, "waypointHeadingParam")
        turn = _sub(pm, _w("waypointTurnParam"))
        _sub(turn, _w("waypointTurnMode"), "toPointAndStopWithDiscontinuityCurvature")
        _sub(turn, _w("waypointTurnDampingDist"), 0)
        group_id = _action_groups(pm, spec, i, group_id)
    return _xml_bytes(root)


def write_dji_kmz(path, spec: MissionSpec, drone_enum: int = DJI_DRONES["Matrice 350 RTK"],
                  payload_enum: int = DJI_PAYLOADS["Zenmuse H20"]) -> Path:
    """Write a DJI Pilot 2 route (WPML KMZ) for one mission."""
    check_waypoint_limits([spec], ["kmz"])
    low, high = DJI_SPEED_LIMITS_MS
    if not low <= spec.speed_ms <= high:
        raise InputError(f"SPEED_MS = {spec.speed_ms:g} m/s but DJI routes (WPML) fly {low:g}–{high:g} m/s:"
                         " set SPEED_MS in that range, or do not ask for the KMZ")
    path = Path(path)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as kmz:
        kmz.writestr("wpmz/template.kml", dji_template_kml(spec, drone_enum, payload_enum))
        kmz.writestr("wpmz/waylines.wpml", dji_waylines_wpml(spec, drone_enum, payload_enum))
    return path


def _text(el, tag, default=None):
    child = el.find(tag)
    if child is None or child.text is None:
        if default is not None:
            return default
        raise InputError(f"element '{tag.split('}')[-1]}' is missing")
    return child.text.strip()


def _parse_lon_lat(placemark, source):
    text = _text(placemark, f"{_k('Point')}/{_k('coordinates')}")
    parts = text.replace("\n", " ").strip().split(",")
    try:
        return float(parts[1]), float(parts[0])
    except (IndexError, ValueError):
        raise InputError(f"coordinates '{text}' are not 'longitude,latitude'", source=source) from None


def _parse_wpml_document(data: bytes, source: str, height_tag: str):
    try:
        root = ET.fromstring(data)
    except ET.ParseError as exc:
        raise InputError(f"not valid XML ({exc})", source=source) from None
    doc = root.find(_k("Document"))
    if doc is None:
        raise InputError("no KML Document element", source=source)
    cfg = doc.find(_w("missionConfig"))
    folder = doc.find(_k("Folder"))
    if cfg is None or folder is None:
        raise InputError("missing wpml:missionConfig or Folder", source=source)
    out = {
        "finish_action": _text(cfg, _w("finishAction")),
        "drone_enum": int(_text(cfg, f"{_w('droneInfo')}/{_w('droneEnumValue')}")),
        "payload_enum": int(_text(cfg, f"{_w('payloadInfo')}/{_w('payloadEnumValue')}")),
        "transitional_speed": float(_text(cfg, _w("globalTransitionalSpeed"))),
        "speed": float(_text(folder, _w("autoFlightSpeed"))),
        "template_id": int(_text(folder, _w("templateId"))),
    }
    lat, lon, height, groups = [], [], [], []
    for k, pm in enumerate(folder.findall(_k("Placemark"))):
        index = int(_text(pm, _w("index")))
        if index != k:
            raise InputError(f"waypoint {k} has wpml:index {index}; indices must run 0, 1, 2, …",
                             source=source)
        la, lo = _parse_lon_lat(pm, source)
        lat.append(la)
        lon.append(lo)
        height.append(float(_text(pm, height_tag)))
        for group in pm.findall(_w("actionGroup")):
            trig = group.find(_w("actionTrigger"))
            param = trig.find(_w("actionTriggerParam"))
            actions = []
            for action in group.findall(_w("action")):
                params = {child.tag.split("}")[-1]: (child.text or "").strip()
                          for child in action.find(_w("actionActuatorFuncParam"))}
                actions.append((_text(action, _w("actionActuatorFunc")), params))
            groups.append({"id": int(_text(group, _w("actionGroupId"))),
                           "start": int(_text(group, _w("actionGroupStartIndex"))),
                           "end": int(_text(group, _w("actionGroupEndIndex"))),
                           "trigger": _text(trig, _w("actionTriggerType")),
                           "trigger_param": None if param is None else float(param.text),
                           "actions": actions})
    out.update(lat=np.array(lat), lon=np.array(lon), height=np.array(height), action_groups=groups)
    return out, folder


def parse_dji_kmz(path) -> dict:
    """Read back a WPML KMZ: ``{"template": {...}, "waylines": {...}}`` with waypoint arrays
    (``lat``, ``lon``, ``height``), enums, speeds, height modes and action groups."""
    path = Path(path)
    try:
        with zipfile.ZipFile(path) as kmz:
            names = set(kmz.namelist())
            missing = {"wpmz/template.kml", "wpmz/waylines.wpml"} - names
            if missing:
                raise InputError(f"not a DJI WPML route: missing {', '.join(sorted(missing))}",
                                 source=str(path))
            template_bytes = kmz.read("wpmz/template.kml")
            waylines_bytes = kmz.read("wpmz/waylines.wpml")
    except zipfile.BadZipFile:
        raise InputError("not a KMZ (zip) file", source=str(path)) from None
    template, tfolder = _parse_wpml_document(template_bytes, f"{path}:wpmz/template.kml", _w("height"))
    template["template_type"] = _text(tfolder, _w("templateType"))
    template["height_mode"] = _text(tfolder, f"{_w('waylineCoordinateSysParam')}/{_w('heightMode')}")
    template["gimbal_pitch"] = np.array([float(_text(pm, _w("gimbalPitchAngle")))
                                         for pm in tfolder.findall(_k("Placemark"))])
    waylines, wfolder = _parse_wpml_document(waylines_bytes, f"{path}:wpmz/waylines.wpml",
                                             _w("executeHeight"))
    waylines["execute_height_mode"] = _text(wfolder, _w("executeHeightMode"))
    waylines["wayline_id"] = int(_text(wfolder, _w("waylineId")))
    return {"files": sorted(names), "template": template, "waylines": waylines}


# ---------------------------------------------------------------------- QGroundControl .plan
def _plan_item(seq: int, command: int, frame: int, params) -> dict:
    item = {"autoContinue": True, "command": command, "doJumpId": seq, "frame": frame,
            "params": list(params), "type": "SimpleItem"}
    if frame == MAV_FRAME_GLOBAL_RELATIVE_ALT:
        item.update({"AMSLAltAboveTerrain": None, "Altitude": params[6], "AltitudeMode": 1})
    return item


def qgc_plan_dict(spec: MissionSpec) -> dict:
    """The QGroundControl plan (JSON v1) of one mission."""
    home_lat, home_lon = spec.home if spec.home is not None else (spec.lat[0], spec.lon[0])
    first_alt = float(spec.altitude_m[0])
    commands = [(MAV_CMD_NAV_TAKEOFF, MAV_FRAME_GLOBAL_RELATIVE_ALT,
                 [0, 0, 0, None, float(home_lat), float(home_lon), first_alt]),
                (MAV_CMD_DO_CHANGE_SPEED, MAV_FRAME_MISSION, [1, float(spec.speed_ms), -1, 0, 0, 0, 0]),
                (MAV_CMD_DO_MOUNT_CONTROL, MAV_FRAME_MISSION,
                 [float(spec.gimbal_pitch_deg), 0, 0, 0, 0, 0, MAV_MOUNT_MODE_MAVLINK_TARGETING])]
    if spec.capture == CAPTURE_TIMED:
        commands.append((MAV_CMD_IMAGE_START_CAPTURE, MAV_FRAME_MISSION,
                         [0, float(spec.capture_interval_s), 0, 0, 0, 0, 0]))
    for i in range(len(spec)):
        # NaN yaw (JSON null) keeps the vehicle's heading policy (nose along the leg).
        commands.append((MAV_CMD_NAV_WAYPOINT, MAV_FRAME_GLOBAL_RELATIVE_ALT,
                         [float(spec.hover_s), 0, 0, None, float(spec.lat[i]), float(spec.lon[i]),
                          float(spec.altitude_m[i])]))
        if spec.capture == CAPTURE_PHOTO:
            commands.append((MAV_CMD_IMAGE_START_CAPTURE, MAV_FRAME_MISSION, [0, 0, 1, 0, 0, 0, 0]))
    if spec.capture == CAPTURE_TIMED:
        commands.append((MAV_CMD_IMAGE_STOP_CAPTURE, MAV_FRAME_MISSION, [0, 0, 0, 0, 0, 0, 0]))
    commands.append((MAV_CMD_NAV_RETURN_TO_LAUNCH, MAV_FRAME_MISSION, [0, 0, 0, 0, 0, 0, 0]))
    items = [_plan_item(seq, cmd, frame, params) for seq, (cmd, frame, params) in enumerate(commands, 1)]
    return {
        "fileType": "Plan",
        "version": 1,
        "groundStation": "BirdsEye for QGIS",
        "mission": {"version": 2, "firmwareType": MAV_AUTOPILOT_PX4, "vehicleType": MAV_TYPE_QUADROTOR,
                    "globalPlanAltitudeMode": 1, "cruiseSpeed": float(spec.speed_ms),
                    "hoverSpeed": float(spec.speed_ms),
                    "plannedHomePosition": [float(home_lat), float(home_lon), 0],
                    "items": items},
        "geoFence": {"circles": [], "polygons": [], "version": 2},
        "rallyPoints": {"points": [], "version": 2},
    }


def write_qgc_plan(path, spec: MissionSpec) -> Path:
    check_waypoint_limits([spec], ["plan"])
    path = Path(path)
    path.write_text(json.dumps(qgc_plan_dict(spec), indent=2, allow_nan=False), encoding="utf-8")
    return path


def parse_qgc_plan(path) -> dict:
    """Read back a ``.plan``: the waypoints (command 16) as arrays, every item's command and frame."""
    path = Path(path)
    try:
        plan = json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise InputError(f"not valid JSON ({exc})", source=str(path)) from None
    if plan.get("fileType") != "Plan" or "mission" not in plan:
        raise InputError("not a QGroundControl plan (fileType 'Plan' with a mission)", source=str(path))
    items = plan["mission"]["items"]
    waypoints = [it for it in items if it["command"] == MAV_CMD_NAV_WAYPOINT]
    return {
        "version": plan["version"],
        "mission_version": plan["mission"]["version"],
        "home": plan["mission"]["plannedHomePosition"],
        "commands": [it["command"] for it in items],
        "frames": [it["frame"] for it in items],
        "items": items,
        "lat": np.array([it["params"][4] for it in waypoints], dtype=float),
        "lon": np.array([it["params"][5] for it in waypoints], dtype=float),
        "altitude": np.array([it["params"][6] for it in waypoints], dtype=float),
        "hold_s": np.array([it["params"][0] for it in waypoints], dtype=float),
    }


# ---------------------------------------------------------------------- Litchi CSV
def write_litchi_csv(path, spec: MissionSpec) -> Path:
    check_waypoint_limits([spec], ["litchi"])
    stay_ms = int(round(spec.hover_s * 1000))
    if stay_ms > LITCHI_MAX_STAY_MS:
        raise InputError(f"HOVER_S = {spec.hover_s:g} s but Litchi's 'stay for' action holds at most"
                         f" {LITCHI_MAX_STAY_MS / 1000:g} s")
    headings = spec.headings_deg()
    path = Path(path)
    with path.open("w", newline="", encoding="utf-8") as fh:
        writer = csv.writer(fh, lineterminator="\n")
        writer.writerow(LITCHI_COLUMNS)
        for i in range(len(spec)):
            actions = []
            if stay_ms > 0:
                actions.append((LITCHI_STAY_FOR, stay_ms))
            if spec.capture == CAPTURE_PHOTO:
                actions.append((LITCHI_TAKE_PHOTO, 0))
            actions += [(LITCHI_NO_ACTION, 0)] * (15 - len(actions))
            interval = spec.capture_interval_s if spec.capture == CAPTURE_TIMED else -1
            row = [_coord(spec.lat[i]), _coord(spec.lon[i]), _num(spec.altitude_m[i], 2),
                   _num(headings[i], 1), 0, 0, 2, _num(spec.gimbal_pitch_deg, 1)]
            row += [v for pair in actions for v in pair]
            row += [0, _num(spec.speed_ms, 2), 0, 0, 0, 0, _num(interval, 2), -1]
            writer.writerow(row)
    return path


def parse_litchi_csv(path) -> dict:
    """Read back a Litchi CSV: waypoint arrays and each row's actions as (type, param) pairs."""
    path = Path(path)
    with path.open(newline="", encoding="utf-8") as fh:
        reader = csv.reader(fh)
        header = next(reader, None)
        if header != LITCHI_COLUMNS:
            raise InputError("header is not Litchi's standard waypoint header", source=str(path), row=1)
        rows = []
        for r, row in enumerate(reader, start=2):
            if len(row) != len(LITCHI_COLUMNS):
                raise InputError(f"{len(row)} columns, expected {len(LITCHI_COLUMNS)}",
                                 source=str(path), row=r)
            rows.append(dict(zip(LITCHI_COLUMNS, row)))
    col = lambda name: np.array([float(r[name]) for r in rows])
    return {
        "header": header,
        "lat": col("latitude"), "lon": col("longitude"), "altitude": col("altitude(m)"),
        "heading": col("heading(deg)"), "gimbal_mode": col("gimbalmode"),
        "gimbal_pitch": col("gimbalpitchangle"), "altitude_mode": col("altitudemode"),
        "speed": col("speed(m/s)"), "photo_timeinterval": col("photo_timeinterval"),
        "actions": [[(int(r[f"actiontype{i}"]), float(r[f"actionparam{i}"])) for i in range(1, 16)
                     if int(r[f"actiontype{i}"]) != LITCHI_NO_ACTION] for r in rows],
    }


# ---------------------------------------------------------------------- plain KML
def write_kml(path, specs, document_name: str = "BirdsEye survey flight") -> Path:
    """All missions in one KML: a folder per mission with its route line and waypoints.

    Altitudes are written ``relativeToGround`` (the flight app's take-off-relative altitude over a
    level field), so Google Earth draws the route at flight height.
    """
    root = ET.Element(_k("kml"))
    doc = _sub(root, _k("Document"))
    _sub(doc, _k("name"), document_name)
    route_style = _sub(doc, _k("Style"))
    route_style.set("id", "route")
    line_style = _sub(route_style, _k("LineStyle"))
    _sub(line_style, _k("color"), "ff00aaff")  # KML colours are aabbggrr: orange
    _sub(line_style, _k("width"), 3)
    waypoint_style = _sub(doc, _k("Style"))
    waypoint_style.set("id", "waypoint")
    icon_style = _sub(waypoint_style, _k("IconStyle"))
    _sub(icon_style, _k("color"), "ff00aaff")
    _sub(icon_style, _k("scale"), "0.8")
    for number, spec in enumerate(specs, start=1):
        folder = _sub(doc, _k("Folder"))
        _sub(folder, _k("name"), spec.name)
        route = _sub(folder, _k("Placemark"))
        _sub(route, _k("name"), f"{spec.name} route")
        _sub(route, _k("styleUrl"), "#route")
        line = _sub(route, _k("LineString"))
        _sub(line, _k("altitudeMode"), "relativeToGround")
        pts = [(lo, la, al) for la, lo, al in zip(spec.lat, spec.lon, spec.altitude_m)]
        if spec.home is not None:
            home = (spec.home[1], spec.home[0], 0.0)
            pts = [home] + pts + [home]
        _sub(line, _k("coordinates"), " ".join(f"{_coord(lo)},{_coord(la)},{_num(al, 2)}"
                                               for lo, la, al in pts))
        if spec.home is not None:
            pm = _sub(folder, _k("Placemark"))
            _sub(pm, _k("name"), "Home")
            point = _sub(pm, _k("Point"))
            _sub(point, _k("coordinates"), f"{_coord(spec.home[1])},{_coord(spec.home[0])},0")
        for i in range(len(spec)):
            pm = _sub(folder, _k("Placemark"))
            _sub(pm, _k("name"), f"M{number}-{i + 1}")
            ids = ";".join(str(g) for g in spec.geotag_ids[i])
            _sub(pm, _k("description"), f"{len(spec.geotag_ids[i])} geotag(s): {ids}")
            _sub(pm, _k("styleUrl"), "#waypoint")
            data = _sub(pm, _k("ExtendedData"))
            for key, value in (("mission", number), ("order", i + 1),
                               ("altitude_m", _num(spec.altitude_m[i], 2)), ("geotag_ids", ids)):
                d = _sub(data, _k("Data"))
                d.set("name", key)
                _sub(d, _k("value"), value)
            point = _sub(pm, _k("Point"))
            _sub(point, _k("altitudeMode"), "relativeToGround")
            _sub(point, _k("coordinates"),
                 f"{_coord(spec.lon[i])},{_coord(spec.lat[i])},{_num(spec.altitude_m[i], 2)}")
    Path(path).write_bytes(_xml_bytes(root))
    return Path(path)


def parse_kml(path) -> list[dict]:
    """Read back our KML: per mission folder, the waypoints (from ExtendedData) and the route line."""
    path = Path(path)
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as exc:
        raise InputError(f"not valid XML ({exc})", source=str(path)) from None
    missions = []
    for folder in root.iter(_k("Folder")):
        waypoints, route = [], None
        for pm in folder.findall(_k("Placemark")):
            line = pm.find(_k("LineString"))
            if line is not None:
                route = np.array([[float(v) for v in tok.split(",")]
                                  for tok in _text(line, _k("coordinates")).split()])
                continue
            data = {d.get("name"): _text(d, _k("value"), "")
                    for d in pm.findall(f"{_k('ExtendedData')}/{_k('Data')}")}
            if "order" not in data:
                continue  # the home placemark
            lon, lat, alt = (float(v) for v in _text(pm, f"{_k('Point')}/{_k('coordinates')}").split(","))
            waypoints.append((int(data["mission"]), int(data["order"]), lat, lon, alt,
                              data["geotag_ids"]))
        waypoints.sort(key=lambda w: w[1])
        missions.append({
            "name": _text(folder, _k("name")),
            "mission": [w[0] for w in waypoints], "order": [w[1] for w in waypoints],
            "lat": np.array([w[2] for w in waypoints]), "lon": np.array([w[3] for w in waypoints]),
            "altitude": np.array([w[4] for w in waypoints]),
            "geotag_ids": [w[5] for w in waypoints], "route": route})
    return missions
