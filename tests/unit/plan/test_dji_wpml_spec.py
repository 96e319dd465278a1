"""Our DJI KMZ checked against DJI's published WPML specification (DJI Cloud API, "DJI WPML"):

* Common elements (droneInfo, payloadInfo, payloadParam, heading and turn parameters, action groups,
  triggers, actions and their parameters):
  https://developer.dji.com/doc/cloud-api-tutorial/en/api-reference/dji-wpml/common-element.html
* template.kml (creation information, missionConfig, the waypoint template's Folder and Placemark,
  waylineCoordinateSysParam):
  https://developer.dji.com/doc/cloud-api-tutorial/en/api-reference/dji-wpml/template-kml.html
* waylines.wpml (missionConfig, Folder with ``executeHeightMode``, Placemark with ``executeHeight``):
  https://developer.dji.com/doc/cloud-api-tutorial/en/api-reference/dji-wpml/waylines-wpml.html
* Product support, "Enumeration values of aircraft, RC and dock" (``droneEnumValue`` is the type,
  ``droneSubEnumValue`` the sub_type) and "Enumeration values of camera" (``payloadEnumValue`` is the
  type of type-subtype-gimbalindex):
  https://developer.dji.com/doc/cloud-api-tutorial/en/overview/product-support.html

The tables below transcribe, for every parent element our files use, the child elements the
specification lists there, their value sets and ranges, and which are required. Every element we
write must be one the specification lists under its parent (so a misspelt or misplaced element is
caught), every value must lie in its set or range, and the required elements must be there. Two
values come from outside those pages and say so where they are used.
"""
from __future__ import annotations

import re
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.plan.mission_files import (
    DJI_DRONES,
    DJI_PAYLOADS,
    KML_NS,
    WPML_NS,
    MissionSpec,
    dji_template_kml,
    dji_waylines_wpml,
    write_dji_kmz,
)

# --------------------------------------------------------------------------- the specification
#: Product support: aircraft (type, sub_type) and camera types.
SPEC_DRONES = {"Matrice 350 RTK": (89, 0), "Matrice 300 RTK": (60, 0)}
SPEC_CAMERAS = {"Zenmuse H20": 42, "Zenmuse H20T": 43, "Zenmuse H20N": 61, "Zenmuse H30": 82,
                "Zenmuse H30T": 83}
#: Not in the Cloud API's camera table (it lists only the payloads its cloud features support):
#: DJI Mobile SDK v5's own WPML enum, dji.sdk.wpmz.value.mission.WaylinePayloadType, has
#: ZENMUSE_P1(50) and PAYLOAD_CAMERA(65534) (a Payload SDK camera).
MSDK_WAYLINE_PAYLOAD_TYPES = {"Zenmuse P1": 50, "Payload SDK camera": 65534}
#: gimbalindex: 0, 1, 2 are the M300 RTK's left, right and upper gimbal ports, 7 the FPV camera.
GIMBAL_INDEX = {0, 1, 2, 7}

TURN_MODES = {"coordinateTurn", "toPointAndStopWithDiscontinuityCurvature",
              "toPointAndStopWithContinuityCurvature", "toPointAndPassWithContinuityCurvature"}
ACTUATOR_FUNCS = {"takePhoto", "startRecord", "stopRecord", "focus", "zoom", "customDirName",
                  "gimbalRotate", "rotateYaw", "hover", "gimbalEvenlyRotate", "accurateShoot",
                  "orientedShoot", "panoShot", "recordPointCloud"}
LENSES = {"wide", "zoom", "ir", "narrow_band", "visable"}


class Rule:
    """How a leaf element's text is checked."""

    def __init__(self, kind, values=None, low=None, high=None, low_open=False):
        self.kind, self.values, self.low, self.high, self.low_open = kind, values, low, high, low_open

    def problem(self, text: str) -> str | None:
        if self.kind == "enum":
            return None if text in self.values else f"'{text}' is not one of {sorted(self.values)}"
        if self.kind == "list":
            bad = [v for v in text.split(",") if v not in self.values]
            return f"{bad} not in {sorted(self.values)}" if bad else None
        if self.kind == "text":
            return None if text else "is empty"
        if self.kind == "poi":
            return None if re.fullmatch(r"-?[\d.]+,-?[\d.]+,-?[\d.]+", text) else "is not 'lat,lon,height'"
        try:
            value = float(text)
        except ValueError:
            return f"'{text}' is not a number"
        if self.kind in ("int", "bool") and not re.fullmatch(r"-?\d+", text):
            return f"'{text}' is not an integer"
        if self.kind == "bool" and value not in (0, 1):
            return f"'{text}' is not 0 or 1"
        if self.kind == "int" and self.values is not None and int(value) not in self.values:
            return f"{text} is not one of {sorted(self.values)}"
        if self.low is not None and (value <= self.low if self.low_open else value < self.low):
            return f"{text} is below the range {'(' if self.low_open else '['}{self.low:g}, …"
        if self.high is not None and value > self.high:
            return f"{text} is above the range …, {self.high:g}]"
        return None


def enum(*values):
    return Rule("enum", set(values))


def number(low=None, high=None, low_open=False):
    return Rule("float", low=low, high=high, low_open=low_open)


def integer(low=None, high=None, values=None):
    return Rule("int", values=values, low=low, high=high)


BOOL, TEXT, INDEX, SPEED = Rule("bool"), Rule("text"), integer(0, 65535), number(1, 15)
GROUP = object()  # an element with children, checked by its own table

# The allowed children of each parent (per file where the two files differ), and the required ones.
MISSION_CONFIG = {
    "flyToWaylineMode": enum("safely", "pointToPoint"),
    "finishAction": enum("goHome", "noAction", "autoLand", "gotoFirstWaypoint"),
    "exitOnRCLost": enum("goContinue", "executeLostAction"),
    "executeRCLostAction": enum("goBack", "landing", "hover"),
    "takeOffSecurityHeight": number(1.2, 1500),  # the remote-controller range ([8, 1500] on a dock)
    "globalTransitionalSpeed": SPEED,
    "globalRTHHeight": number(2, 1500),
    "droneInfo": GROUP, "payloadInfo": GROUP, "autoRerouteInfo": GROUP,
}
HEADING_PARAM = {
    "waypointHeadingMode": enum("followWayline", "manually", "fixed", "smoothTransition", "towardPOI"),
    "waypointHeadingAngle": number(-180, 180),
    "waypointPoiPoint": Rule("poi"),
    "waypointHeadingPathMode": enum("clockwise", "counterClockwise", "followBadArc"),
}
ACTION_GROUP = {"actionGroupId": INDEX, "actionGroupStartIndex": INDEX, "actionGroupEndIndex": INDEX,
                "actionGroupMode": enum("sequence"), "actionTrigger": GROUP, "action": GROUP}
TABLES = {
    "Document": {
        "template": {"author": TEXT, "createTime": integer(0), "updateTime": integer(0),
                     "missionConfig": GROUP, "Folder": GROUP},
        "waylines": {"missionConfig": GROUP, "Folder": GROUP},
    },
    "missionConfig": {
        "template": {**MISSION_CONFIG, "takeOffRefPoint": Rule("poi"), "takeOffRefPointAGLHeight": number()},
        "waylines": MISSION_CONFIG,
    },
    "droneInfo": {"droneEnumValue": integer(), "droneSubEnumValue": integer()},
    # payloadSubEnumValue is not in the table, but DJI Pilot 2 writes it into the routes it exports
    # (and DJI's Cloud API demo carries it): Pilot 2 reads what it writes.
    "payloadInfo": {"payloadEnumValue": integer(), "payloadPositionIndex": integer(values=GIMBAL_INDEX),
                    "payloadSubEnumValue": integer(0)},
    "Folder": {
        "template": {  # elements common to the templates, and those of the waypoint template
            "templateType": enum("waypoint", "mapping2d", "mapping3d", "mappingStrip"),
            "templateId": INDEX, "autoFlightSpeed": SPEED, "waylineCoordinateSysParam": GROUP,
            "payloadParam": GROUP, "globalWaypointTurnMode": Rule("enum", TURN_MODES),
            "globalUseStraightLine": BOOL, "gimbalPitchMode": enum("manual", "usePointSetting"),
            "globalHeight": number(), "globalWaypointHeadingParam": GROUP, "Placemark": GROUP},
        "waylines": {
            "templateId": INDEX, "waylineId": INDEX, "autoFlightSpeed": SPEED,
            "executeHeightMode": enum("WGS84", "relativeToStartPoint", "realTimeFollowSurface"),
            "Placemark": GROUP, "startActionGroup": GROUP},
    },
    "waylineCoordinateSysParam": {
        "coordinateMode": enum("WGS84"),
        "heightMode": enum("EGM96", "relativeToStartPoint", "aboveGroundLevel", "realTimeFollowSurface"),
        "positioningType": enum("GPS", "RTKBaseStation", "QianXun", "Custom"),
    },
    "payloadParam": {
        "payloadPositionIndex": integer(values=GIMBAL_INDEX), "focusMode": enum("firstPoint", "custom"),
        "meteringMode": enum("average", "spot"), "dewarpingEnable": BOOL,
        "returnMode": enum("singleReturnStrongest", "dualReturn", "tripleReturn"),
        "samplingRate": integer(values={60000, 80000, 120000, 160000, 180000, 240000}),
        "scanningMode": enum("repetitive", "nonRepetitive"), "modelColoringEnable": BOOL,
        "imageFormat": Rule("list", LENSES),
    },
    "globalWaypointHeadingParam": HEADING_PARAM,
    "waypointHeadingParam": HEADING_PARAM,
    "waypointTurnParam": {"waypointTurnMode": Rule("enum", TURN_MODES), "waypointTurnDampingDist": number(0)},
    "Placemark": {
        "template": {
            "isRisky": BOOL, "Point": GROUP, "index": INDEX, "useGlobalHeight": BOOL,
            "ellipsoidHeight": number(), "height": number(), "useGlobalSpeed": BOOL, "waypointSpeed": SPEED,
            "useGlobalHeadingParam": BOOL, "waypointHeadingParam": GROUP, "useGlobalTurnParam": BOOL,
            "waypointTurnParam": GROUP, "useStraightLine": BOOL, "gimbalPitchAngle": number(),
            "actionGroup": GROUP},
        "waylines": {
            "isRisky": BOOL, "Point": GROUP, "index": INDEX, "executeHeight": number(), "waypointSpeed": SPEED,
            "waypointHeadingParam": GROUP, "waypointTurnParam": GROUP, "useStraightLine": BOOL,
            "actionGroup": GROUP},
    },
    "Point": {"coordinates": GROUP},
    "actionGroup": ACTION_GROUP,
    "startActionGroup": ACTION_GROUP,
    "actionTrigger": {"actionTriggerType": enum("reachPoint", "betweenAdjacentPoints", "multipleTiming",
                                                "multipleDistance"),
                      "actionTriggerParam": number(0, low_open=True)},
    "action": {"actionId": INDEX, "actionActuatorFunc": Rule("enum", ACTUATOR_FUNCS),
               "actionActuatorFuncParam": GROUP},
}
#: The parameters of the actions we use (the specification has a table for each function).
ACTION_PARAMS = {
    "takePhoto": {"payloadPositionIndex": integer(values=GIMBAL_INDEX), "fileSuffix": TEXT,
                  "payloadLensIndex": Rule("list", LENSES), "useGlobalPayloadLensIndex": BOOL},
    "gimbalRotate": {
        "payloadPositionIndex": integer(values=GIMBAL_INDEX), "gimbalHeadingYawBase": enum("north"),
        "gimbalRotateMode": enum("absoluteAngle"), "gimbalPitchRotateEnable": BOOL,
        "gimbalPitchRotateAngle": number(), "gimbalRollRotateEnable": BOOL, "gimbalRollRotateAngle": number(),
        "gimbalYawRotateEnable": BOOL, "gimbalYawRotateAngle": number(), "gimbalRotateTimeEnable": BOOL,
        "gimbalRotateTime": number(0)},
    "hover": {"hoverTime": number(0, low_open=True)},
}
#: Required children (unconditionally, for the M300/M350 RTK), by parent and file.
REQUIRED = {
    ("missionConfig", None): {"flyToWaylineMode", "finishAction", "exitOnRCLost", "takeOffSecurityHeight",
                              "globalTransitionalSpeed", "globalRTHHeight", "droneInfo", "payloadInfo"},
    ("droneInfo", None): {"droneEnumValue", "droneSubEnumValue"},
    ("payloadInfo", None): {"payloadEnumValue", "payloadPositionIndex"},
    ("Folder", "template"): {"templateType", "templateId", "autoFlightSpeed", "globalWaypointTurnMode",
                             "gimbalPitchMode", "globalHeight"},
    ("Folder", "waylines"): {"templateId", "waylineId", "autoFlightSpeed", "executeHeightMode"},
    ("waylineCoordinateSysParam", None): {"coordinateMode", "heightMode"},
    ("payloadParam", None): {"payloadPositionIndex", "imageFormat"},
    ("Placemark", "template"): {"Point", "index", "useGlobalHeight", "useGlobalSpeed",
                                "useGlobalHeadingParam", "useGlobalTurnParam"},
    ("Placemark", "waylines"): {"Point", "index", "executeHeight"},
    ("globalWaypointHeadingParam", None): {"waypointHeadingMode", "waypointHeadingPathMode"},
    ("waypointHeadingParam", None): {"waypointHeadingMode", "waypointHeadingPathMode"},
    ("waypointTurnParam", None): {"waypointTurnMode"},
    ("actionGroup", None): {"actionGroupId", "actionGroupStartIndex", "actionGroupEndIndex",
                            "actionGroupMode", "actionTrigger"},
    ("actionTrigger", None): {"actionTriggerType"},
    ("action", None): {"actionId", "actionActuatorFunc"},
}
REQUIRED_ACTION_PARAMS = {
    "takePhoto": {"payloadPositionIndex", "fileSuffix", "useGlobalPayloadLensIndex"},
    "gimbalRotate": set(ACTION_PARAMS["gimbalRotate"]),
    "hover": {"hoverTime"},
}
# Required only when another element has a given value.
CONDITIONAL = [
    # (parent, child required, condition on the parent's children)
    ("missionConfig", "executeRCLostAction", lambda c: c.get("exitOnRCLost") == "executeLostAction"),
    ("Placemark", "ellipsoidHeight", lambda c: c.get("useGlobalHeight") == "0"),
    ("Placemark", "height", lambda c: c.get("useGlobalHeight") == "0"),
    ("Placemark", "waypointSpeed", lambda c: c.get("useGlobalSpeed") == "0"),
    ("Placemark", "waypointHeadingParam", lambda c: c.get("useGlobalHeadingParam") == "0"),
    ("Placemark", "waypointTurnParam", lambda c: c.get("useGlobalTurnParam") == "0"),
    ("waypointHeadingParam", "waypointHeadingAngle", lambda c: c.get("waypointHeadingMode") == "smoothTransition"),
    ("waypointHeadingParam", "waypointPoiPoint", lambda c: c.get("waypointHeadingMode") == "towardPOI"),
    ("waypointTurnParam", "waypointTurnDampingDist", lambda c: c.get("waypointTurnMode") == "coordinateTurn"),
    ("actionTrigger", "actionTriggerParam",
     lambda c: c.get("actionTriggerType") in ("multipleTiming", "multipleDistance")),
]


def local(tag: str) -> str:
    return tag.split("}")[-1]


def namespace(tag: str) -> str:
    return tag[1:].split("}")[0] if tag.startswith("{") else ""


def spec_problems(xml: bytes, kind: str, gimbal_pitch_mode: str | None = None) -> list[str]:
    """Every departure of a template.kml (``kind='template'``) or waylines.wpml from the tables."""
    root = ET.fromstring(xml)
    problems = []
    if root.tag != f"{{{KML_NS}}}kml":
        return [f"root is {root.tag}, not kml in {KML_NS}"]
    docs = list(root)
    if [local(d.tag) for d in docs] != ["Document"]:
        return ["kml must hold one Document"]

    def check(element, path):
        name = local(element.tag)
        if name == "actionActuatorFuncParam":
            return  # checked with its action, whose function decides the parameters
        table = TABLES.get(name)
        if isinstance(table, dict) and kind in table and isinstance(table[kind], dict):
            table = table[kind]
        children = {}
        for child in element:
            child_name = local(child.tag)
            child_path = f"{path}/{child_name}"
            kml_element = child_name in ("Document", "Folder", "Placemark", "Point", "coordinates")
            expected_ns = KML_NS if kml_element else WPML_NS
            if namespace(child.tag) != expected_ns:
                problems.append(f"{child_path}: namespace {namespace(child.tag)!r}, expected {expected_ns}")
            if child_name == "coordinates":
                lon_lat = (child.text or "").strip().split(",")
                lon, lat = (float(v) for v in lon_lat[:2])
                if not (-180 <= lon <= 180 and -90 <= lat <= 90) or len(lon_lat) != 2:
                    problems.append(f"{child_path}: '{child.text}' is not 'longitude,latitude' in range")
                continue
            rule = table.get(child_name) if table else None
            if rule is None:
                problems.append(f"{child_path}: not an element of {name} in the specification")
                continue
            children[child_name] = (child.text or "").strip()
            if rule is GROUP:
                check(child, child_path)
            elif (message := rule.problem(children[child_name])) is not None:
                problems.append(f"{child_path}: {message}")
        required = REQUIRED.get((name, kind), REQUIRED.get((name, None), set()))
        required = required | {c for parent, c, condition in CONDITIONAL if parent == name and condition(children)}
        if name == "Placemark" and kind == "template" and gimbal_pitch_mode == "usePointSetting":
            required = required | {"gimbalPitchAngle"}
        for missing in sorted(required - set(children)):
            problems.append(f"{path}: required element {missing} is missing")
        if name == "action":
            func = children.get("actionActuatorFunc")
            params = element.find(f"{{{WPML_NS}}}actionActuatorFuncParam")
            if func not in ACTION_PARAMS:
                problems.append(f"{path}: action {func} is not one this test knows the parameters of")
            elif params is not None:
                given = {}
                for p in params:
                    given[local(p.tag)] = (p.text or "").strip()
                    rule = ACTION_PARAMS[func].get(local(p.tag))
                    if rule is None:
                        problems.append(f"{path}/{local(p.tag)}: not a parameter of {func}")
                    elif (message := rule.problem(given[local(p.tag)])) is not None:
                        problems.append(f"{path}/{local(p.tag)}: {message}")
                for missing in sorted(REQUIRED_ACTION_PARAMS[func] - set(given)):
                    problems.append(f"{path}: {func} needs {missing}")

    check(docs[0], "Document")
    problems += action_group_problems(root)
    return problems


def action_group_problems(root) -> list[str]:
    """Ids unique in the file, 0 ≤ start ≤ end < number of waypoints, action ids unique in a group,
    and a timed or distance trigger driving takePhoto (the pairing the specification states)."""
    w = f"{{{WPML_NS}}}"
    placemarks = root.findall(f".//{{{KML_NS}}}Placemark")
    problems, group_ids = [], []
    for k, placemark in enumerate(placemarks):
        for group in placemark.findall(f"{w}actionGroup"):
            gid = int(group.findtext(f"{w}actionGroupId"))
            group_ids.append(gid)
            start = int(group.findtext(f"{w}actionGroupStartIndex"))
            end = int(group.findtext(f"{w}actionGroupEndIndex"))
            if not (0 <= start <= end < len(placemarks)):
                problems.append(f"action group {gid}: indices {start}…{end} outside 0…{len(placemarks) - 1}")
            if start != k:
                problems.append(f"action group {gid} sits on waypoint {k} but starts at {start}")
            action_ids = [int(a.findtext(f"{w}actionId")) for a in group.findall(f"{w}action")]
            if len(set(action_ids)) != len(action_ids):
                problems.append(f"action group {gid}: action ids {action_ids} repeat")
            trigger = group.findtext(f"{w}actionTrigger/{w}actionTriggerType")
            funcs = [a.findtext(f"{w}actionActuatorFunc") for a in group.findall(f"{w}action")]
            if trigger in ("multipleTiming", "multipleDistance") and funcs != ["takePhoto"]:
                problems.append(f"action group {gid}: {trigger} drives {funcs}, not takePhoto")
            if trigger == "betweenAdjacentPoints" and funcs != ["gimbalEvenlyRotate"]:
                problems.append(f"action group {gid}: betweenAdjacentPoints needs gimbalEvenlyRotate")
    if len(set(group_ids)) != len(group_ids):
        problems.append(f"action group ids repeat: {sorted(group_ids)}")
    return problems


# --------------------------------------------------------------------------- our files
def spec_mission(capture="photo", n=6, hover_s=2.0, speed_ms=4.0):
    lat = -34.95 + 1e-4 * np.arange(n)
    lon = 138.58 + 5e-5 * np.arange(n) ** 1.5
    return MissionSpec("field7", lat, lon, 12.0 + np.arange(n) % 3, speed_ms, hover_s, capture=capture,
                       capture_interval_s=1.5 if capture == "timed" else None)


def kmz_parts(tmp_path, spec, drone, payload):
    path = write_dji_kmz(tmp_path / "route.kmz", spec, DJI_DRONES[drone], DJI_PAYLOADS[payload])
    with zipfile.ZipFile(path) as kmz:
        return kmz.read("wpmz/template.kml"), kmz.read("wpmz/waylines.wpml")


def test_our_enumerations_are_the_published_ones():
    assert {name: (value, 0) for name, value in DJI_DRONES.items()} == SPEC_DRONES
    assert DJI_PAYLOADS == {**SPEC_CAMERAS, **MSDK_WAYLINE_PAYLOAD_TYPES}


@pytest.mark.parametrize("drone", sorted(DJI_DRONES))
@pytest.mark.parametrize("capture,hover_s", [("photo", 2.0), ("photo", 0.0), ("timed", 1.0), ("timed", 0.0)])
def test_routes_hold_only_what_the_specification_lists(tmp_path, drone, capture, hover_s):
    spec = spec_mission(capture, hover_s=hover_s)
    template, waylines = kmz_parts(tmp_path, spec, drone, "Zenmuse H20T")
    assert spec_problems(template, "template", gimbal_pitch_mode="usePointSetting") == []
    assert spec_problems(waylines, "waylines") == []

    w = f"{{{WPML_NS}}}"
    root_t, root_w = ET.fromstring(template), ET.fromstring(waylines)
    for root in (root_t, root_w):
        assert root.findtext(f".//{w}droneEnumValue") == str(SPEC_DRONES[drone][0])
        assert root.findtext(f".//{w}droneSubEnumValue") == str(SPEC_DRONES[drone][1])
        assert root.findtext(f".//{w}payloadEnumValue") == "43"
    # Heights relative to the take-off point in both files; the template's ellipsoid height equals
    # its height, as the specification states for heights relative to the take-off point.
    assert root_w.findtext(f".//{w}executeHeightMode") == "relativeToStartPoint"
    assert root_t.findtext(f".//{w}waylineCoordinateSysParam/{w}heightMode") == "relativeToStartPoint"
    template_heights = [float(p.findtext(f"{w}height")) for p in root_t.iter(f"{{{KML_NS}}}Placemark")]
    assert template_heights == [float(p.findtext(f"{w}ellipsoidHeight"))
                                for p in root_t.iter(f"{{{KML_NS}}}Placemark")]
    np.testing.assert_allclose([float(p.findtext(f"{w}executeHeight"))
                                for p in root_w.iter(f"{{{KML_NS}}}Placemark")], spec.altitude_m)
    np.testing.assert_allclose(template_heights, spec.altitude_m)
    assert root_t.findtext(f".//{w}templateId") == root_w.findtext(f".//{w}templateId")

    # The action groups do what the mission says: nadir gimbal first, then per waypoint a hover and
    # a photo (photo capture), or one timed photo group over the whole route.
    groups = [(int(g.findtext(f"{w}actionGroupStartIndex")), int(g.findtext(f"{w}actionGroupEndIndex")),
               g.findtext(f"{w}actionTrigger/{w}actionTriggerType"),
               g.findtext(f"{w}actionTrigger/{w}actionTriggerParam"),
               [a.findtext(f"{w}actionActuatorFunc") for a in g.findall(f"{w}action")])
              for g in root_w.iter(f"{w}actionGroup")]
    n = len(spec)
    per_point = (["hover"] if hover_s > 0 else []) + (["takePhoto"] if capture == "photo" else [])
    expected = [(0, 0, "reachPoint", None, ["gimbalRotate"] + per_point)]
    expected += [(i, i, "reachPoint", None, per_point) for i in range(1, n) if per_point]
    if capture == "timed":
        expected.insert(1, (0, n - 1, "multipleTiming", "1.5", ["takePhoto"]))
    assert groups == expected
    pitch = root_w.find(f".//{w}action/{w}actionActuatorFuncParam/{w}gimbalPitchRotateAngle")
    assert float(pitch.text) == -90.0


def test_the_checker_catches_what_the_specification_forbids(tmp_path):
    """The tables are not vacuous: a misplaced element, a value out of its set and one out of its
    range, a missing required element and a broken action group are each reported."""
    template, waylines = kmz_parts(tmp_path, spec_mission(), "Matrice 350 RTK", "Zenmuse H20")
    text = waylines.decode()
    broken = (text.replace("<wpml:executeHeightMode>relativeToStartPoint", "<wpml:executeHeightMode>AGL", 1)
              .replace("<wpml:autoFlightSpeed>4<", "<wpml:autoFlightSpeed>16<", 1)
              .replace("<wpml:waylineId>0</wpml:waylineId>", "<wpml:caliFlightEnable>0</wpml:caliFlightEnable>", 1)
              .replace("<wpml:actionGroupEndIndex>1<", "<wpml:actionGroupEndIndex>0<", 1)
              .replace("<wpml:hoverTime>2<", "<wpml:hoverTime>0<", 1))
    problems = spec_problems(broken.encode(), "waylines")
    assert any("executeHeightMode: 'AGL' is not one of" in p for p in problems), problems
    assert any("autoFlightSpeed: 16 is above the range" in p for p in problems), problems
    assert any("caliFlightEnable: not an element of Folder" in p for p in problems), problems
    assert any("required element waylineId is missing" in p for p in problems), problems
    assert any("indices 1…0 outside" in p for p in problems), problems
    assert any("hoverTime: 0 is below the range (0" in p for p in problems), problems
    assert len(problems) == 6, problems
    # the template's own calibration-flight element belongs to the mapping templates, not ours
    assert b"caliFlightEnable" not in template


def test_speeds_outside_the_specification_are_refused_before_writing(tmp_path):
    for speed in (0.8, 15.5):
        with pytest.raises(InputError, match=r"SPEED_MS = .* DJI .* 1–15 m/s"):
            write_dji_kmz(tmp_path / "slow.kmz", spec_mission(speed_ms=speed))
        assert not (tmp_path / "slow.kmz").exists()


def test_template_and_waylines_documents_stand_alone():
    """Each document also passes on its own (dji_template_kml / dji_waylines_wpml are public)."""
    spec = spec_mission("timed", hover_s=0.0)
    assert spec_problems(dji_template_kml(spec, 89, 42), "template", "usePointSetting") == []
    assert spec_problems(dji_waylines_wpml(spec, 89, 42), "waylines") == []
