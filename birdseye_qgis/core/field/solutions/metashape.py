"""Agisoft Metashape camera solutions: *Export Cameras* XML, projects (``.psx`` + ``.files/``) and archives (``.psz``).

Conventions converted here (Metashape manual, appendix "Camera models"; Agisoft knowledge base), checked
against real projects (tests/unit/field/test_metashape_real.py: surveyed markers against their pinned marks):

* ``camera/transform`` (4×4, row-major) maps camera coordinates into the chunk's internal frame: a
  camera → world transform. Metashape's camera axes are OpenCV's (x right, y down, z forward).
* One similarity (rotation, translation, scale) takes that internal frame to geocentric (ECEF)
  coordinates: the transform of the camera's *component* (Metashape 1.6+), else the chunk's. In real
  files the chunk's ``<transform>`` repeats the active component's — they are the same similarity, not
  two to compose (composing them puts the cameras thousands of kilometres away).
* Calibration: ``f`` (px), ``cx``/``cy`` measured from the image *centre*, and pixel coordinates whose
  origin is the top-left corner of the image (the centre of the top-left pixel is (0.5, 0.5)); so in
  OpenCV's pixel-centre convention ``cx_cv = w/2 + cx − 0.5``, and a marker's image mark ``x`` is
  ``x − 0.5`` there.
* ``u = w/2 + cx + x'·(f + b1) + y'·b2``, ``v = h/2 + cy + y'·f``: fx = f + b1, fy = f, skew = b2.
* Metashape's P1 multiplies ``r² + 2x²`` — OpenCV's p2 — and P2 is OpenCV's p1: they swap.
* k1–k4 are radial coefficients of r², r⁴, r⁶, r⁸ (k4 is not OpenCV's rational k4).
* A ``fisheye`` sensor is equidistant with the same radial polynomial in θ: OpenCV's fisheye model
  (tangential terms must be zero there).

Where the documents live: a ``.psx`` is a one-line XML naming ``{projectname}.files/project.zip``; that
zip's ``doc.xml`` lists the chunks (``0/chunk.zip``, relative to it), each chunk's ``doc.xml`` lists its
frames (``0/frame.zip``, relative to the chunk), and a frame's ``doc.xml`` holds each camera's photo path
and each marker's image marks. A ``.psz`` is a zip whose ``doc.xml`` is the document, with the same
references resolved inside the archive (or the elements inline). An export holds it all in one file.

Markers with a surveyed ``<reference>`` are read in the chunk's reference system (a geographic WGS 84
reference: longitude, latitude, ellipsoidal height); their ``pinned`` image marks — where a person
placed them — are the check of :mod:`...labels.mark_check`. Marks Metashape placed itself are its own
projection, not an observation, and are left out.
"""
from __future__ import annotations

import io
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path, PurePosixPath

import numpy as np

from ...errors import InputError
from ...geometry.camera import CameraModel
from ...geometry.geodesy import ensure_proj_data, on_python_thread
from ...geometry.heights import ELLIPSOIDAL_REFERENCE
from ..geotags import Geotags
from . import CameraSolution, ControlMarks, SolvedCamera

#: File suffixes of Metashape's solutions, for the dispatcher.
SUFFIXES = (".xml", ".psx", ".psz")
#: Names of WGS 84 in a geographic reference's WKT: its heights are ellipsoidal, no conversion needed.
_WGS84_NAMES = ("WGS 84", "WGS84", "World Geodetic System 1984")


def find_xml(folder: Path) -> Path | None:
    """The one Metashape export, else project, else archive in ``folder`` (None when none or several)."""
    found = sorted(folder.glob("*.xml")) or sorted(folder.glob("*.psx")) or sorted(folder.glob("*.psz"))
    return found[0] if len(found) == 1 else None


# ---------------------------------------------------------------------------------------- documents
class _Documents:
    """Reads a project's ``doc.xml`` documents by their relative paths, from a folder or a ``.psz`` archive."""

    def __init__(self, source: str, folder: Path | None = None, archive: zipfile.ZipFile | None = None):
        self.source, self.folder, self.archive = source, folder, archive

    def load(self, relative: PurePosixPath) -> ET.Element:
        where = f"{self.source} ({relative})"
        try:
            data = (self.archive.read(str(relative)) if self.archive is not None
                    else (self.folder / Path(*relative.parts)).read_bytes())
        except (OSError, KeyError) as exc:
            raise InputError(f"the project names {relative}, which is missing ({exc}); copy the whole project "
                             "folder (the .psx and its .files folder)", source=self.source) from None
        if data[:2] == b"PK":
            try:
                with zipfile.ZipFile(io.BytesIO(data)) as inner:
                    data = inner.read("doc.xml")
            except (zipfile.BadZipFile, KeyError) as exc:
                raise InputError(f"is not a Metashape document archive ({exc})", source=where) from None
        return _parse(data, where)


def _parse(data: bytes, source: str) -> ET.Element:
    try:
        return ET.fromstring(data)
    except ET.ParseError as exc:
        raise InputError(f"is not valid XML ({exc})", source=source) from None


def _resolve(documents: _Documents, elem: ET.Element, here: PurePosixPath) -> tuple[ET.Element, PurePosixPath]:
    """An element that may be a reference (``path="0/chunk.zip"``) → its document, and that document's folder."""
    path = elem.get("path")
    if not path:
        return elem, here
    relative = PurePosixPath(*(here / path).parts)
    return documents.load(relative), relative.parent


def _open(path: Path) -> tuple[_Documents, ET.Element, PurePosixPath]:
    """The document a path holds (export, project, archive) as (documents, root element, its folder)."""
    source = str(path)
    suffix = path.suffix.lower()
    if suffix == ".psz":
        try:
            archive = zipfile.ZipFile(path)
            root = _parse(archive.read("doc.xml"), source)
        except (zipfile.BadZipFile, KeyError, OSError) as exc:
            raise InputError(f"is not a Metashape archive (a zip holding doc.xml): {exc}", source=source) from None
        return _Documents(source, archive=archive), root, PurePosixPath()
    try:
        root = _parse(path.read_bytes(), source)
    except OSError as exc:
        raise InputError(f"cannot be read ({exc})", source=source) from None
    documents = _Documents(source, folder=path.parent)
    if suffix == ".psx" or (root.tag == "document" and root.get("path") and root.find("chunk") is None):
        project = PurePosixPath((root.get("path") or "").replace("{projectname}", path.stem))
        if not project.parts:
            raise InputError("is not a Metashape project: its <document> names no path", source=source)
        return documents, documents.load(project), project.parent
    return documents, root, PurePosixPath()


def _chunk(documents: _Documents, root: ET.Element, here: PurePosixPath, notes: list):
    """The active chunk of a document (an export holds one), resolved."""
    if root.tag == "chunk":
        return root, here
    chunks = root.find("chunks")
    candidates = list(chunks.findall("chunk")) if chunks is not None else list(root.findall("chunk"))
    if not candidates:
        raise InputError("is not a Metashape camera solution (expected a <chunk> with <sensors> and <cameras>)",
                         source=documents.source)
    active = chunks.get("active_id") if chunks is not None else None
    chosen = next((c for c in candidates if active is not None and c.get("id") == active), candidates[0])
    chunk, chunk_dir = _resolve(documents, chosen, here)
    if len(candidates) > 1:
        notes.append(f"the project has {len(candidates)} chunks; the active one, '{chunk.get('label') or active}', "
                     "was read")
    return chunk, chunk_dir


# ---------------------------------------------------------------------------------------- numbers
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
    calib = next((c for c in calibs if c.get("class") == "adjusted"), None)
    if calib is None:
        calib = calibs[0] if calibs else None
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


def _reference_wkt(chunk) -> str:
    return (chunk.findtext("reference") or "").strip()


def _is_geographic(chunk) -> bool:
    ref = _reference_wkt(chunk)
    return bool(ref) and not ref.lstrip().upper().startswith(("LOCAL_CS", "ENGCRS", "ENGINEERINGCRS"))


# ---------------------------------------------------------------------------------------- reading
def read_metashape(path) -> CameraSolution:
    """A Metashape export (``.xml``), project (``.psx``) or archive (``.psz``) → :class:`CameraSolution`."""
    path = Path(path)
    source = str(path)
    notes: list = []
    documents, root, here = _open(path)
    chunk, chunk_dir = _chunk(documents, root, here, notes)
    if chunk.find("cameras") is None:
        raise InputError("is not a Metashape camera solution (expected <document><chunk> with <sensors> and "
                         "<cameras>)", source=source)
    if not _is_geographic(chunk):
        raise InputError("names no geographic reference: its chunk is in a local coordinate system "
                         f"({_reference_wkt(chunk)[:40] or 'no <reference>'}), so its cameras cannot be placed "
                         "on the map. In Metashape, set the chunk's reference to a geographic or projected "
                         "system (Reference pane → Settings), georeference it with the cameras' GPS or ground "
                         "control, Update, then save (or export the cameras) again", source=source)
    similarities = _similarities(chunk, source)
    sensors = {s.get("id"): s for s in chunk.iter("sensor")}
    models: dict[str, CameraModel] = {}
    cameras, unaligned = [], []
    camera_names: dict[str, str] = {}
    for cam in chunk.find("cameras").iter("camera"):
        name = cam.get("label") or f"camera {cam.get('id')}"
        camera_names[cam.get("id")] = name
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
        to_ecef = similarities.of(cam)
        if to_ecef is None:
            raise InputError(f"camera '{name}' is in no georeferenced component and the chunk has no "
                             "<transform> to geocentric coordinates", source=source)
        pose = to_ecef @ _numbers(cam.findtext("transform"), 16, source, f"camera '{name}' transform").reshape(4, 4)
        scale = np.cbrt(np.linalg.det(pose[:3, :3]))
        cameras.append(SolvedCamera(name, models[sensor_id], pose[:3, :3] / scale, pose[:3, 3]))
    frame = _first_frame(documents, chunk, chunk_dir, notes)
    photos = _photo_paths(documents, frame[0], frame[1], camera_names) if frame is not None else {}
    marks = _control_marks(chunk, frame[0] if frame is not None else None, camera_names, source, notes)
    return CameraSolution("metashape", source, cameras, unaligned, notes=notes, reference=ELLIPSOIDAL_REFERENCE,
                          marks=marks, photos=photos)


class _Similarities:
    """Each camera's similarity to ECEF: its component's, else the chunk's (the same one in real files)."""

    def __init__(self, chunk_t, components, component_of):
        self.chunk_t, self.components, self.component_of = chunk_t, components, component_of

    def of(self, cam):
        component_id = cam.get("component_id") or self.component_of.get(cam.get("id"))
        found = self.components.get(component_id)
        return found if found is not None else self.chunk_t


def _similarities(chunk, source) -> _Similarities:
    chunk_elem = chunk.find("transform")
    chunk_t = None if chunk_elem is None else _similarity(chunk_elem, source, "chunk transform")
    components, component_of = {}, {}
    for comp in chunk.iter("component"):
        elem = comp.find("transform")
        if elem is not None:
            components[comp.get("id")] = _similarity(elem, source, f"component {comp.get('id')} transform")
        for cam_id in " ".join(ids.text or "" for ids in comp.iter("camera_ids")).split():
            component_of[cam_id] = comp.get("id")
    if chunk_t is None and not components:
        raise InputError("names no geographic reference: neither the chunk nor a component has a <transform> "
                         "to geocentric coordinates. Georeference the chunk in Metashape and save again",
                         source=source)
    return _Similarities(chunk_t, components, component_of)


def _first_frame(documents, chunk, chunk_dir, notes):
    frames = chunk.find("frames")
    listed = list(frames.findall("frame")) if frames is not None else []
    if not listed:
        return None
    if len(listed) > 1:
        notes.append(f"the chunk has {len(listed)} frames (a 4D chunk); the first was read")
    return _resolve(documents, listed[0], chunk_dir)


def _photo_paths(documents, frame, frame_dir, camera_names) -> dict:
    """Camera name → image file the project names, where that file exists (a project folder moved whole)."""
    if documents.folder is None:
        return {}
    found = {}
    for cam in frame.iter("camera"):
        photo = cam.find("photo")
        name = camera_names.get(cam.get("camera_id"))
        if photo is None or not photo.get("path") or name is None:
            continue
        candidate = (documents.folder / Path(*frame_dir.parts) / photo.get("path")).resolve()
        if candidate.is_file():
            found[name] = candidate
    return found


def _control_marks(chunk, frame, camera_names, source, notes) -> ControlMarks | None:
    """Markers with a surveyed reference, and their pinned image marks (OpenCV pixel-centre coordinates)."""
    markers = chunk.find("markers")
    if markers is None:
        return None
    ids, labels, xyz, checks = [], [], [], []
    for k, marker in enumerate(markers.iter("marker"), start=1):
        ref = marker.find("reference")
        values = [ref.get(a) if ref is not None else None for a in ("x", "y", "z")]
        if any(v in (None, "") for v in values[:2]):
            continue
        try:
            x, y = float(values[0]), float(values[1])
            z = float(values[2]) if values[2] not in (None, "") else np.nan
        except ValueError:
            raise InputError(f"marker '{marker.get('label')}' has a reference that is not a number: {values}",
                             source=source, row=k, field="marker/reference") from None
        ids.append(marker.get("id"))
        labels.append(marker.get("label") or f"marker {marker.get('id')}")
        xyz.append((x, y, z))
        checks.append(ref.get("enabled") in ("false", "0"))
    if not ids:
        return None
    lat, lon, h = _reference_to_wgs84(chunk, np.array(xyz), source)
    points = Geotags(np.arange(1, len(ids) + 1), lat, lon, h, labels, source=source,
                     flags=[["check_point" if c else "control_point"] for c in checks])
    index = {marker_id: i for i, marker_id in enumerate(ids)}
    point_idx, cams, uv = [], [], []
    unpinned = 0
    for marker in (frame.iter("marker") if frame is not None else ()):
        i = index.get(marker.get("marker_id"))
        if i is None:
            continue
        for loc in marker.iter("location"):
            if loc.get("pinned") not in ("true", "1"):
                unpinned += 1
                continue
            name = camera_names.get(loc.get("camera_id"))
            if name is None:
                continue
            try:
                u, v = float(loc.get("x")) - 0.5, float(loc.get("y")) - 0.5
            except (TypeError, ValueError):
                raise InputError(f"marker '{labels[i]}' has an image mark in camera '{name}' whose x/y is not a "
                                 "number", source=source, field="marker/location") from None
            point_idx.append(i)
            cams.append(name)
            uv.append((u, v))
    if unpinned:
        notes.append(f"{unpinned} marker projection(s) were placed by Metashape, not by a person (not pinned), "
                     "and are not used to check the labels")
    return ControlMarks(points, np.asarray(point_idx, dtype=np.int64), cams, np.asarray(uv, dtype=float).reshape(-1, 2))


@on_python_thread
def _reference_to_wgs84(chunk, xyz: np.ndarray, source: str):
    """Markers' reference coordinates → WGS 84 latitude, longitude and ellipsoidal height."""
    wkt = _reference_wkt(chunk)
    head = wkt.lstrip().upper()
    if head.startswith(("GEOGCS", "GEOGCRS", "GEODCRS")) and any(name.upper() in head for name in _WGS84_NAMES):
        return xyz[:, 1], xyz[:, 0], xyz[:, 2]
    ensure_proj_data()
    import pyproj

    try:
        transformer = pyproj.Transformer.from_crs(pyproj.CRS.from_wkt(wkt), "EPSG:4979", always_xy=True)
        lon, lat, h = transformer.transform(xyz[:, 0], xyz[:, 1], np.nan_to_num(xyz[:, 2]))
    except pyproj.exceptions.ProjError as exc:
        raise InputError(f"its markers' reference system cannot be converted to WGS 84 ({exc})",
                         source=source) from None
    lat, lon, h = (np.asarray(a, dtype=float) for a in (lat, lon, h))
    h[~np.isfinite(xyz[:, 2])] = np.nan
    return lat, lon, h
