"""Agisoft Metashape "Export Cameras" XML (Metashape 1.x and 2.x, and PhotoScan's same format).

Conventions converted here (Metashape manual, appendix "Camera models"; Agisoft knowledge base):

* ``camera/transform`` (4×4, row-major) maps camera coordinates into the chunk's internal frame: a
  camera → world transform. Metashape's camera axes are OpenCV's (x right, y down, z forward).
* Metashape 2.x places each camera in a *component*: component transform (rotation, translation,
  scale), then the chunk transform, both into the chunk's frame; ``chunk/transform`` maps that frame to
  geocentric (ECEF) coordinates. The full pose is ``T_chunk · T_component · T_camera``.
* Calibration: ``f`` (px), ``cx``/``cy`` measured from the image *centre*, and pixel coordinates whose
  origin is the top-left corner of the image (the centre of the top-left pixel is (0.5, 0.5)); so in
  OpenCV's pixel-centre convention ``cx_cv = w/2 + cx − 0.5``.
* ``u = w/2 + cx + x'·(f + b1) + y'·b2``, ``v = h/2 + cy + y'·f``: fx = f + b1, fy = f, skew = b2.
* Metashape's P1 multiplies ``r² + 2x²`` — OpenCV's p2 — and P2 is OpenCV's p1: they swap.
* k1–k4 are radial coefficients of r², r⁴, r⁶, r⁸ (k4 is not OpenCV's rational k4).
* A ``fisheye`` sensor is equidistant with the same radial polynomial in θ: OpenCV's fisheye model
  (tangential terms must be zero there).
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from ...errors import InputError
from ...geometry.camera import CameraModel
from . import CameraSolution, SolvedCamera


def find_xml(folder: Path) -> Path | None:
    found = sorted(folder.glob("*.xml"))
    return found[0] if len(found) == 1 else None


def _numbers(text, count, source, what) -> np.ndarray:
    try:
        values = np.array([float(v) for v in (text or "").split()])
    except ValueError:
        raise InputError(f"{what} must be {count} numbers, got {text!r}", source=source) from None
    if values.size != count or not np.all(np.isfinite(values)):
        raise InputError(f"{what} must be {count} finite numbers, got {values.size}", source=source)
    return values


def _similarity(elem, source, what) -> np.ndarray:
    """A ``<transform>`` with rotation/translation/scale children (or 16 numbers) as a 4×4 matrix."""
    if elem is None:
        return np.eye(4)
    if all(elem.find(part) is None for part in ("rotation", "translation", "scale")):
        return _numbers(elem.text, 16, source, what).reshape(4, 4)
    t = np.eye(4)
    scale = float(elem.findtext("scale", "1") or 1)
    if elem.find("rotation") is not None:
        t[:3, :3] = scale * _numbers(elem.findtext("rotation"), 9, source, f"{what} rotation").reshape(3, 3)
    else:
        t[:3, :3] *= scale
    if elem.find("translation") is not None:
        t[:3, 3] = _numbers(elem.findtext("translation"), 3, source, f"{what} translation")
    return t


def _calibration(sensor, source) -> CameraModel:
    label = sensor.get("label") or f"sensor {sensor.get('id')}"
    calibs = sensor.findall("calibration")
    calib = next((c for c in calibs if c.get("class") == "adjusted"), None) or (calibs[0] if calibs else None)
    if calib is None:
        raise InputError(f"sensor '{label}' has no <calibration>", source=source)
    kind = calib.get("type") or sensor.get("type") or "frame"
    if kind not in ("frame", "fisheye"):
        raise InputError(f"sensor '{label}' is a {kind} camera; only frame and fisheye cameras are supported",
                         source=source)
    if sensor.find("rotation") is not None or sensor.get("master_id"):
        raise InputError(f"sensor '{label}' is a slave of a multi-camera rig; rigs are not supported",
                         source=source)
    res = calib.find("resolution") if calib.find("resolution") is not None else sensor.find("resolution")
    if res is None:
        raise InputError(f"sensor '{label}' has no <resolution>", source=source)
    width, height = int(res.get("width")), int(res.get("height"))

    def value(name):
        text = calib.findtext(name)
        try:
            return 0.0 if text is None else float(text)
        except ValueError:
            raise InputError(f"sensor '{label}' calibration <{name}> is not a number: {text!r}",
                             source=source) from None

    f = value("f")
    if f <= 0:
        raise InputError(f"sensor '{label}' calibration <f> must be positive, got {f}", source=source)
    if value("p3") or value("p4"):
        raise InputError(f"sensor '{label}' uses the higher-order tangential terms p3/p4, which no OpenCV-style "
                         "model has; re-align with them fixed at 0", source=source)
    k1, k2, k3, k4 = (value(k) for k in ("k1", "k2", "k3", "k4"))
    p1_ms, p2_ms = value("p1"), value("p2")
    common = dict(width=width, height=height, fx=f + value("b1"), fy=f, skew=value("b2"),
                  cx=width / 2.0 + value("cx") - 0.5, cy=height / 2.0 + value("cy") - 0.5,
                  source=f"metashape:{label}")
    if kind == "fisheye":
        if p1_ms or p2_ms:
            raise InputError(f"fisheye sensor '{label}' has tangential terms, which OpenCV's fisheye model "
                             "lacks", source=source)
        return CameraModel(dist=(k1, k2, k3, k4), fisheye=True, **common)
    return CameraModel(dist=(k1, k2, p2_ms, p1_ms, k3), k4=k4, **common)


def _is_geographic(chunk) -> bool:
    ref = chunk.findtext("reference") or ""
    return bool(ref.strip()) and not ref.lstrip().upper().startswith("LOCAL_CS")


def read_metashape_xml(path) -> CameraSolution:
    path = Path(path)
    source = str(path)
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as exc:
        raise InputError(f"is not valid XML ({exc})", source=source) from exc
    chunk = root.find("chunk") if root.tag == "document" else (root if root.tag == "chunk" else None)
    if chunk is None or chunk.find("cameras") is None:
        raise InputError("is not a Metashape camera export (expected <document><chunk> with <sensors> and "
                         "<cameras>)", source=source)
    if chunk.find("transform") is None or not _is_geographic(chunk):
        raise InputError("names no geographic reference: the chunk has no <transform> to geocentric coordinates "
                         "or its <reference> is a local coordinate system. Georeference the chunk in Metashape "
                         "(camera positions or ground control, a geographic CRS) and export the cameras again",
                         source=source)
    chunk_t = _similarity(chunk.find("transform"), source, "chunk transform")
    sensors = {s.get("id"): s for s in chunk.iter("sensor")}
    models: dict[str, CameraModel] = {}
    components, component_of = {}, {}
    for comp in chunk.iter("component"):
        components[comp.get("id")] = _similarity(comp.find("transform"), source,
                                                 f"component {comp.get('id')} transform")
        for cam_id in (comp.findtext("partition/camera_ids") or "").split():
            component_of[cam_id] = comp.get("id")
    cameras, unaligned = [], []
    for cam in chunk.find("cameras").iter("camera"):
        name = cam.get("label") or f"camera {cam.get('id')}"
        if cam.get("enabled") in ("false", "0"):
            unaligned.append((name, "disabled in the project"))
            continue
        if cam.find("transform") is None:
            unaligned.append((name, "not aligned (no transform)"))
            continue
        sensor_id = cam.get("sensor_id")
        if sensor_id not in sensors:
            raise InputError(f"camera '{name}' names sensor {sensor_id}, which the file does not define",
                             source=source)
        if sensor_id not in models:
            models[sensor_id] = _calibration(sensors[sensor_id], source)
        component_id = cam.get("component_id") or component_of.get(cam.get("id"))
        component = components.get(component_id, np.eye(4))
        pose = chunk_t @ component @ _numbers(cam.findtext("transform"), 16, source,
                                              f"camera '{name}' transform").reshape(4, 4)
        scale = np.cbrt(np.linalg.det(pose[:3, :3]))
        cameras.append(SolvedCamera(name, models[sensor_id], pose[:3, :3] / scale, pose[:3, 3]))
    return CameraSolution("metashape", source, cameras, unaligned, ellipsoidal=True)
