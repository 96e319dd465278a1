"""Image chips: which frames (or which window of the raster) show a unit, the crop window, and the chip drawn
with detections and geotags."""
from __future__ import annotations

import threading
from collections import OrderedDict
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..field.geotags import Geotags
from ..geometry.geodesy import LocalFrame
from ..geometry.ground import LevelPlaneGround, placeable_frames
from ..geometry.poses import FrameGeometry, FramePoses
from ..geometry.projection import centre_gsd_m, project_in_view, project_pairs
from ..scoring.evaluation import local_frame_for
from .units import ReviewUnits, frame_key

DEFAULT_WINDOW_PX = 128
DEFAULT_MAX_CHIPS = 4


class FrameIndex:
    """Frames by id: their pose group, index and image, with the geometry and ground model of the frames
    the ground model ``ground`` (a factory as Detect takes it, the one the detections were placed with;
    None = the level plane) can place: with a plane, those with a ground height (the others were not
    processed by Detect); with a DEM, all."""

    def __init__(self, pose_groups: Sequence[FramePoses], images: Sequence[Sequence[str]], local: LocalFrame,
                 ground=None):
        self.local = local
        self.groups = []
        self.gsd_m = []   # per group, each frame's ground sample distance at the image centre (m/px)
        self.lookup: dict = {}
        for g, (poses, paths) in enumerate(zip(pose_groups, images)):
            keep = np.flatnonzero(placeable_frames(poses, ground))
            sub = poses.subset(keep)
            geometry = FrameGeometry(sub, local) if len(sub) else None
            model = (ground or LevelPlaneGround)(geometry) if geometry is not None else None
            self.groups.append((geometry, model))
            self.gsd_m.append(centre_gsd_m(geometry, model) if geometry is not None else np.empty(0))
            for i, k in enumerate(keep.tolist()):
                self.lookup[frame_key(poses.frame_id[k])] = (g, i, paths[k] or "")

    def __contains__(self, frame_id) -> bool:
        return frame_key(frame_id) in self.lookup


@dataclass
class ChipPlan:
    """One chip: a crop ``window`` (x0, y0, x1, y1; x1, y1 exclusive, px of the original image) of a
    frame — or of the raster detections were found on (``image`` its file, ``frame_id`` 0, the window in
    raster pixels) — with the detections (u, v, layer index) and geotags (u, v, label) inside, in window
    pixels."""

    key: str
    frame_id: object
    image: str
    window: tuple
    detections: list
    geotags: list
    score: float | None = None


def crop_window(u: float, v: float, size: int, width: int, height: int) -> tuple[int, int, int, int]:
    """A ``size``-pixel square around pixel (u, v), moved to lie inside a width × height image (and
    shrunk only when the image is smaller)."""
    w, h = min(size, width), min(size, height)
    x0 = int(round(u - (w - 1) / 2.0))
    y0 = int(round(v - (h - 1) / 2.0))
    x0 = min(max(x0, 0), width - w)
    y0 = min(max(y0, 0), height - h)
    return x0, y0, x0 + w, y0 + h


def _geotag_marks(frames: FrameIndex, g: int, i: int, window, geotag_local, geotag_labels, centre_xy, radius_m):
    if geotag_local is None or not len(geotag_local):
        return []
    near = np.flatnonzero(np.hypot(*(geotag_local[:, :2] - centre_xy).T) <= radius_m)
    if not len(near):
        return []
    geometry, ground = frames.groups[g]
    proj = project_pairs(geometry, np.full(len(near), i), geotag_local[near], ground)
    x0, y0, x1, y1 = window
    out = []
    for k, (u, v), front in zip(near.tolist(), proj.uv.tolist(), proj.in_front.tolist()):
        if front and x0 - 0.5 <= u <= x1 - 0.5 and y0 - 0.5 <= v <= y1 - 0.5:
            out.append((u - x0, v - y0, str(geotag_labels[k])))
    return out


def _radius_m(frames: FrameIndex, g: int, i: int, window_px: int) -> float:
    return float(frames.gsd_m[g][i]) * window_px * 0.75 + 0.5


def plan_unit_chips(units: ReviewUnits, unit: int, frames: FrameIndex, geotag_local=None, geotag_labels=(),
                    window_px: int = DEFAULT_WINDOW_PX, max_chips: int = DEFAULT_MAX_CHIPS) -> tuple[list, int]:
    """Chips of unit ``unit`` from the frames that detected it (highest score first), and how many
    frames detected it. Frames missing from the frame layer are skipped."""
    mine = np.flatnonzero(units.detection_unit == unit)
    by_frame: dict = {}
    for d in mine.tolist():
        by_frame.setdefault(frame_key(units.detection_frame[d]), []).append(d)
    ranked = sorted(by_frame.items(), key=lambda kv: (-max(units.detection_score[d] for d in kv[1]), str(kv[0])))
    plans = []
    for fid, dets in ranked:
        if fid not in frames.lookup:
            continue
        if len(plans) == max_chips:
            break
        g, i, image = frames.lookup[fid]
        camera = frames.groups[g][0].camera
        best = max(dets, key=lambda d: units.detection_score[d])
        window = crop_window(*units.detection_uv[best], window_px, camera.width, camera.height)
        marks = [(float(units.detection_uv[d, 0] - window[0]), float(units.detection_uv[d, 1] - window[1]),
                  int(units.detection_layer[d])) for d in dets]
        crosses = _geotag_marks(frames, g, i, window, geotag_local, geotag_labels, units.xy[unit],
                                _radius_m(frames, g, i, window_px))
        plans.append(ChipPlan(units.keys[unit], fid, image, window, marks, crosses,
                              float(units.detection_score[best])))
    return plans, len(by_frame)


def plan_point_chips(key: str, lat: float, lon: float, frames: FrameIndex, geotag_local=None, geotag_labels=(),
                     window_px: int = DEFAULT_WINDOW_PX, max_chips: int = DEFAULT_MAX_CHIPS) -> tuple[list, int]:
    """Chips of a ground point (an added target): the frames it is in view of, nearest the image
    centre first."""
    point = frames.local.from_geodetic([lat], [lon], [frames.local.h0])
    candidates = []
    for g, (geometry, ground) in enumerate(frames.groups):
        if geometry is None:
            continue
        proj = project_in_view(geometry, point, ground)
        centre = np.array([(geometry.camera.width - 1) / 2.0, (geometry.camera.height - 1) / 2.0])
        off_centre = np.hypot(*(proj.uv - centre).T)
        for i, uv, d in zip(proj.frame_idx.tolist(), proj.uv.tolist(), off_centre.tolist()):
            candidates.append((d, g, i, uv))
    candidates.sort(key=lambda c: c[0])
    by_position = {(g, i): fid for fid, (g, i, _) in frames.lookup.items()}
    plans = []
    for _, g, i, (u, v) in candidates[:max_chips]:
        fid = by_position[(g, i)]
        camera = frames.groups[g][0].camera
        window = crop_window(u, v, window_px, camera.width, camera.height)
        crosses = _geotag_marks(frames, g, i, window, geotag_local, geotag_labels, point[0, :2],
                                _radius_m(frames, g, i, window_px))
        plans.append(ChipPlan(key, fid, frames.lookup[fid][2], window, [(u - window[0], v - window[1], -1)],
                              crosses))
    return plans, len(candidates)


@dataclass
class RasterIndex:
    """The raster a review's detections were found on, as its chips need it: its file (``image``, as the
    detections record it in ``dem_source``), its size in pixels, and each geotag's pixel (``geotag_px`` (G, 2):
    column, row, pixel-centre convention; NaN where it lies off the raster) with its label. Made on the main
    thread (qgis_io.raster_reader.RasterPixels): the planning below needs no coordinate transform, so it runs
    in a worker."""

    image: str
    width: int
    height: int
    geotag_px: np.ndarray
    geotag_labels: Sequence[str] = ()

    def geotag_marks(self, window) -> list:
        """The geotags inside ``window`` (x0, y0, x1, y1), as (u, v, label) in window pixels."""
        x0, y0, x1, y1 = window
        px = np.asarray(self.geotag_px, dtype=float).reshape(-1, 2)
        inside = np.flatnonzero((px[:, 0] >= x0 - 0.5) & (px[:, 0] <= x1 - 0.5) &
                                (px[:, 1] >= y0 - 0.5) & (px[:, 1] <= y1 - 0.5))   # NaN: never inside
        return [(float(px[k, 0] - x0), float(px[k, 1] - y0), str(self.geotag_labels[k])) for k in inside.tolist()]

    def contains(self, col: float, row: float) -> bool:
        """Whether pixel (col, row) lies on the raster."""
        return bool(-0.5 <= col <= self.width - 0.5 and -0.5 <= row <= self.height - 0.5)


def plan_raster_unit_chips(units: ReviewUnits, unit: int, raster: RasterIndex,
                           window_px: int = DEFAULT_WINDOW_PX) -> tuple[list, int]:
    """The one chip of a unit found on a raster: a ``window_px`` square of raster pixels around its best
    detection (moved inside the raster), with the unit's detections and the geotags inside; and 1, the one
    image that shows it."""
    mine = np.flatnonzero(units.detection_unit == unit)
    best = max(mine.tolist(), key=lambda d: units.detection_score[d])
    window = crop_window(*units.detection_uv[best], window_px, raster.width, raster.height)
    marks = [(float(units.detection_uv[d, 0] - window[0]), float(units.detection_uv[d, 1] - window[1]),
              int(units.detection_layer[d])) for d in mine.tolist()]
    return [ChipPlan(units.keys[unit], units.detection_frame[best], raster.image, window, marks,
                     raster.geotag_marks(window), float(units.detection_score[best]))], 1


def plan_raster_point_chips(key: str, col: float, row: float, raster: RasterIndex,
                            window_px: int = DEFAULT_WINDOW_PX) -> tuple[list, int]:
    """The chip of a ground point (an added target) at raster pixel (``col``, ``row``): a ``window_px`` square
    of the raster around it, or none when it lies off the raster; and how many images show it (1 or 0)."""
    if not raster.contains(col, row):
        return [], 0
    window = crop_window(col, row, window_px, raster.width, raster.height)
    return [ChipPlan(key, 0, raster.image, window, [(col - window[0], row - window[1], -1)],
                     raster.geotag_marks(window))], 1


#: Colours (RGB) of detections by layer index; −1 = an added target.
LAYER_COLOURS = [(255, 196, 0), (0, 200, 255), (255, 80, 200), (120, 255, 80), (255, 120, 40)]
ADDED_COLOUR = (80, 255, 120)
GEOTAG_COLOUR = (255, 40, 40)


def render_chip(crop, plan: ChipPlan, out_px: int) -> np.ndarray:
    """The chip as an RGB array (out_px, out_px, 3): the window scaled to ``out_px`` (nearest pixel
    when enlarging, so single pixels stay sharp), detections as circles, geotags as crosses.
    ``crop`` is the pixels of ``plan.window`` as OpenCV reads an image (BGR or grey); None draws a grey
    "image missing" chip."""
    import cv2

    x0, y0, x1, y1 = plan.window
    if crop is None:
        chip = np.full((out_px, out_px, 3), 90, np.uint8)
        cv2.putText(chip, "image missing", (8, out_px // 2), cv2.FONT_HERSHEY_SIMPLEX, 0.45, (230, 230, 230), 1,
                    cv2.LINE_AA)
        return chip
    if crop.ndim == 2:
        crop = cv2.cvtColor(crop, cv2.COLOR_GRAY2RGB)
    else:
        crop = cv2.cvtColor(crop[:, :, :3], cv2.COLOR_BGR2RGB)
    w, h = x1 - x0, y1 - y0
    scale = out_px / max(w, h)
    chip = np.zeros((out_px, out_px, 3), np.uint8)
    resized = cv2.resize(crop, (max(1, round(w * scale)), max(1, round(h * scale))),
                         interpolation=cv2.INTER_NEAREST if scale >= 1 else cv2.INTER_AREA)
    chip[:resized.shape[0], :resized.shape[1]] = resized

    def at(u, v):  # window pixel (centre convention) → chip pixel
        return int(round((u + 0.5) * scale - 0.5)), int(round((v + 0.5) * scale - 0.5))

    # Rings wider than a target, so the target stays visible inside; one ring per layer that fired.
    radius = max(9, round(out_px * 0.12))
    for u, v, layer in sorted(plan.detections, key=lambda d: -d[2]):
        colour = ADDED_COLOUR if layer < 0 else LAYER_COLOURS[layer % len(LAYER_COLOURS)]
        r = radius + 4 * max(layer, 0)
        cv2.circle(chip, at(u, v), r, (0, 0, 0), 4, cv2.LINE_AA)
        cv2.circle(chip, at(u, v), r, colour, 2, cv2.LINE_AA)
    # Geotags: a diagonal cross with an open centre (the surveyed spot itself is left visible).
    inner, outer = max(4, radius // 2), max(8, radius - 3)
    for u, v, _ in plan.geotags:
        cx, cy = at(u, v)
        for thickness, colour in ((3, (0, 0, 0)), (1, GEOTAG_COLOUR)):
            for sx, sy in ((1, 1), (1, -1), (-1, 1), (-1, -1)):
                a = (round(cx + sx * inner * 0.7071), round(cy + sy * inner * 0.7071))
                b = (round(cx + sx * outer * 0.7071), round(cy + sy * outer * 0.7071))
                cv2.line(chip, a, b, colour, thickness, cv2.LINE_AA)
    return chip


class ImageCache:
    """A small thread-safe LRU of decoded frames (consecutive units share most of their frames)."""

    def __init__(self, capacity: int = 16):
        self.capacity = capacity
        self._images: OrderedDict = OrderedDict()
        self._lock = threading.Lock()

    def get(self, path: str):
        """The image (as OpenCV reads it), or None when the file is missing or unreadable."""
        import cv2

        with self._lock:
            if path in self._images:
                self._images.move_to_end(path)
                return self._images[path]
        image = cv2.imread(path, cv2.IMREAD_UNCHANGED) if path else None
        if image is not None and image.dtype != np.uint8:   # 16-bit frames: show them as 8-bit
            image = cv2.convertScaleAbs(image, alpha=255.0 / max(1.0, float(image.max())))
        with self._lock:
            self._images[path] = image
            while len(self._images) > self.capacity:
                self._images.popitem(last=False)
        return image

    def window(self, plan: ChipPlan):
        """The pixels of ``plan``'s window of its frame (as :meth:`get` reads it), None when the frame is missing."""
        image = self.get(plan.image)
        x0, y0, x1, y1 = plan.window
        return None if image is None else image[y0:y1, x0:x1]


def load_chips(plans: Sequence[ChipPlan], out_px: int, pixels) -> list[np.ndarray]:
    """Rendered chips (RGB arrays) for ``plans``, their pixels from ``pixels.window(plan)`` (BGR or grey, None
    when missing): an :class:`ImageCache` of the frames, or a raster's reader
    (qgis_io.raster_reader.RasterPixels), which reads the window alone."""
    return [render_chip(pixels.window(p), p, out_px) for p in plans]


def review_local_frame(pose_groups: Sequence[FramePoses], geotags: Geotags) -> LocalFrame:
    """The local frame of a review: the one ``evaluatedetections`` scores a flight in."""
    return local_frame_for(pose_groups, geotags)
