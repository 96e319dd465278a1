"""Run an ONNX heatmap model over frames and put each detection on the ground.

Per frame (a generator, so memory does not grow with the number of frames):

1. **Resample** the frame from its own ground sample distance (image centre; level ground under the
   frame, or the DEM for a frame without a ground height) to the model's ``resolution``
   (cm/px, from the model metadata) — the JPEG decoder does the power-of-two part while reading
   (:func:`read_reduction`), :func:`resample` the rest: scale ``s = gsd_frame / resolution``, so a
   target covers as many pixels as in training. Pixel centres map as ``u = (u' + 0.5)·W/W' − 0.5``
   (OpenCV convention, pixel (0, 0) = centre of the top-left pixel).
2. **Normalise** once per frame: channel order from the metadata, ``(value/255 − mean)/std``, NCHW.
3. **Tile** (:func:`tile_spans`, the one place for the tiling math): stride = tile − overlap, the last
   tile flush with the border, and only each tile's *core* — its part up to the middle of each
   overlap — written back, so every kept heatmap pixel has at least ``overlap // 2`` px of context
   inside its tile (except at the image border, where the whole image has none either).
4. **Run** the tiles through ONNX Runtime in one batch, **stitch** the cores into the frame's
   heatmap (probabilities; logits go through a sigmoid).
5. **Peaks** (:func:`find_peaks`): a small Gaussian blur, a threshold, one detection per
   8-connected blob, located at the blob's intensity-weighted centroid (weights = smoothed value −
   threshold, so the blob's rim weighs nothing and the centroid is sub-pixel and unbiased for a
   symmetric hump); its score is the blob's maximum smoothed value. Keeping the detections with
   ``score ≥ t'`` only approximates a run at a higher threshold ``t'``: a blob whose humps meet above
   ``t`` but below ``t'`` is one detection at ``t`` and two at ``t'``, and the centroid weights change
   with the threshold; :func:`detect_frames_at_thresholds` runs the extraction at several thresholds
   on one heatmap.
6. **Back-project** each detection through its frame's pose onto the level ground
   (:func:`~.projection.pixel_to_ground` with :class:`~.ground.LevelPlaneGround`).

Detections within ``edge_buffer_px`` of the image border are dropped, as labels there are not
written as positives (``writelabels``' EDGE_BUFFER_PX).
"""
from __future__ import annotations

import hashlib
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Iterator

import numpy as np

from ..errors import InputError, check_cancel
from ..geometry.geodesy import LocalFrame
from ..geometry.ground import LevelPlaneGround, placeable_frames
from ..geometry.poses import FrameGeometry, FramePoses
from ..geometry.projection import centre_gsd_m, pixel_to_ground
from .model_metadata import DEEPNESS_SCHEMA, ModelMetadata

#: ONNX Runtime providers tried before the CPU, in order of preference.
GPU_PROVIDERS = ("CUDAExecutionProvider", "ROCMExecutionProvider", "DmlExecutionProvider",
                 "CoreMLExecutionProvider")


def file_digest(path) -> str:
    """SHA-256 (hex) of a file: the model's identity in every detection it makes."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


class HeatmapModel:
    """An ONNX heatmap model and its validated metadata, ready to run tiles.

    ``log`` receives one line saying which execution provider runs the model (a GPU provider when
    ONNX Runtime has one that starts, else the CPU, with the reason), and for a model read by Deepness's
    conventions (:mod:`.model_metadata`) one with the settings that gave.
    """

    def __init__(self, path, log: Callable[[str], None] | None = None, use_gpu: bool = True):
        try:
            import onnxruntime as ort
        except ImportError as exc:  # the plugin's requirements include it; say so if it is gone
            raise InputError("running a detector needs the Python package 'onnxruntime', which the Python QGIS "
                             "runs does not have; in QGIS choose BirdsEye › Install dependencies…") from exc
        self.path = Path(path)
        if not self.path.is_file():
            raise InputError("model file not found", source=str(path))
        self.name = self.path.name
        self.digest = file_digest(self.path)
        log = log or (lambda message: None)
        options = ort.SessionOptions()
        options.graph_optimization_level = ort.GraphOptimizationLevel.ORT_ENABLE_ALL
        available = ort.get_available_providers()
        gpu = [p for p in GPU_PROVIDERS if p in available][:1] if use_gpu else []
        self.session = None
        if gpu:
            try:
                with warnings.catch_warnings():  # ONNX Runtime warns of a missing provider; the log says it
                    warnings.simplefilter("ignore", UserWarning)
                    self.session = ort.InferenceSession(str(self.path), options,
                                                        providers=gpu + ["CPUExecutionProvider"])
            except Exception as exc:  # noqa: BLE001 — a broken GPU set-up must not stop the run
                log(f"GPU provider {gpu[0]} failed to start ({exc}); running on the CPU instead.")
                gpu = []
        if self.session is None:
            try:
                self.session = ort.InferenceSession(str(self.path), options, providers=["CPUExecutionProvider"])
            except Exception as exc:
                raise InputError(f"ONNX Runtime cannot load this model ({exc})", source=str(path)) from exc
        self.providers = self.session.get_providers()
        if gpu and gpu[0] in self.providers:
            log(f"Running the model on the GPU ({gpu[0]}).")
        elif gpu:
            log(f"GPU provider {gpu[0]} is installed but not usable; running on the CPU.")
        elif not use_gpu:
            log("Running the model on the CPU (GPU not requested).")
        elif not any(p in available for p in GPU_PROVIDERS):
            log("ONNX Runtime offers no GPU provider here; running on the CPU "
                f"(available: {', '.join(available)}).")
        inp = self.session.get_inputs()
        if len(inp) != 1:
            raise InputError(f"the model has {len(inp)} inputs; a heatmap model has one image input",
                             source=str(path))
        self.input_name = inp[0].name
        out_shape = self.session.get_outputs()[0].shape
        self.metadata = ModelMetadata.from_props(dict(self.session.get_modelmeta().custom_metadata_map),
                                                 inp[0].shape, out_shape, source=str(path))
        meta = self.metadata
        if meta.schema_version == DEEPNESS_SCHEMA:  # the defaults taken are the user's to know
            log(f"A Deepness segmentation model, read by Deepness's conventions: probabilities of output channel "
                f"{meta.output_channel} ({meta.class_names[meta.output_channel]}), default threshold "
                f"{meta.default_threshold:g}, tiles of {meta.tile_size} px overlapping {meta.tiles_overlap_pct:g} %.")
        batch_dim = inp[0].shape[0]
        self.max_batch = batch_dim if isinstance(batch_dim, int) and batch_dim > 0 else None

    def run(self, tiles: np.ndarray) -> np.ndarray:
        """Raw model output for a batch of normalised tiles (N, 3, T, T) → (N, T, T): the metadata's
        ``output_channel`` of an N×C×T×T output (the target of a background/target segmentor), or the
        N×T×T output as it is."""
        if self.max_batch is None or len(tiles) <= self.max_batch:
            out = self.session.run(None, {self.input_name: tiles})[0]
        else:
            out = np.concatenate([self.session.run(None, {self.input_name: tiles[i:i + self.max_batch]})[0]
                                  for i in range(0, len(tiles), self.max_batch)])
        if out.ndim == 4:
            out = out[:, self.metadata.output_channel]
        return out.reshape(len(tiles), tiles.shape[2], tiles.shape[3])


# ---------------------------------------------------------------------- tiling
def tile_spans(length: int, tile: int, overlap: int) -> np.ndarray:
    """Tiles along one axis of ``length`` px: rows ``(start, core_begin, core_end)``.

    Starts step by ``tile − overlap``; the last tile is flush with the border (a frame shorter than a
    tile gets one tile, padded). Neighbouring tiles split their overlap at its middle; the cores
    partition [0, length).
    """
    if tile <= overlap:
        raise ValueError(f"tile ({tile} px) must be larger than the overlap ({overlap} px)")
    if length <= tile:
        return np.array([[0, 0, length]])
    starts = list(range(0, length - tile + 1, tile - overlap))
    if starts[-1] + tile < length:
        starts.append(length - tile)
    starts = np.asarray(starts)
    bounds = (starts[1:] + starts[:-1] + tile) // 2
    return np.column_stack([starts, np.r_[0, bounds], np.r_[bounds, length]])


def cut_tiles(frame: np.ndarray, spans_y: np.ndarray, spans_x: np.ndarray, tile: int) -> np.ndarray:
    """Tiles (N, C, T, T) of a normalised frame (C, H, W), row-major; zero-padded beyond the frame."""
    c, h, w = frame.shape
    out = np.zeros((len(spans_y) * len(spans_x), c, tile, tile), dtype=np.float32)
    k = 0
    for y0, _, _ in spans_y:
        for x0, _, _ in spans_x:
            block = frame[:, y0:y0 + tile, x0:x0 + tile]
            out[k, :, :block.shape[1], :block.shape[2]] = block
            k += 1
    return out


def stitch(outputs: np.ndarray, spans_y: np.ndarray, spans_x: np.ndarray, shape) -> np.ndarray:
    """The frame's heatmap (H, W) from per-tile outputs (N, T, T): each tile's core only."""
    heat = np.empty(shape, dtype=np.float32)
    k = 0
    for y0, yb, ye in spans_y:
        for x0, xb, xe in spans_x:
            heat[yb:ye, xb:xe] = outputs[k, yb - y0:ye - y0, xb - x0:xe - x0]
            k += 1
    return heat


# ---------------------------------------------------------------------- frame preparation
def model_size(width: int, height: int, gsd_cm: float, resolution_cm: float) -> tuple[int, int]:
    """(width, height) in px of a frame of ``gsd_cm`` resampled to the model's ``resolution_cm``."""
    s = gsd_cm / resolution_cm
    return max(1, int(round(width * s))), max(1, int(round(height * s)))


def resample(image: np.ndarray, size: tuple[int, int]) -> np.ndarray:
    """``image`` resized to ``size`` = (width, height), pixel centres mapped as OpenCV does.

    Reductions halve by area averaging (2×2 means: anti-aliased, and OpenCV's fastest path) while
    the remaining factor is at least 2, then go bilinear for the rest; enlargements are bilinear.
    Every step maps pixel centres as ``x = (x' + 0.5)·s − 0.5``, so their composition does too, with
    ``s`` the overall factor (see :func:`to_frame_pixels`).
    """
    import cv2

    h, w = image.shape[:2]
    while w >= 2 * size[0] and h >= 2 * size[1] and w % 2 == 0 and h % 2 == 0:
        image = cv2.resize(image, (w // 2, h // 2), interpolation=cv2.INTER_AREA)
        h, w = image.shape[:2]
    if (w, h) == tuple(size):
        return image
    return cv2.resize(image, tuple(size), interpolation=cv2.INTER_LINEAR)


def to_frame_pixels(uv_model: np.ndarray, frame_size: tuple[int, int], model_size_wh: tuple[int, int]):
    """Pixels (N, 2) of the resampled frame → pixels of the original frame (pixel-centre convention)."""
    sx = frame_size[0] / model_size_wh[0]
    sy = frame_size[1] / model_size_wh[1]
    uv = np.asarray(uv_model, dtype=float).reshape(-1, 2)
    return np.column_stack([(uv[:, 0] + 0.5) * sx - 0.5, (uv[:, 1] + 0.5) * sy - 0.5])


def normalise(image_bgr: np.ndarray, meta: ModelMetadata) -> np.ndarray:
    """A BGR uint8 image (H, W, 3) as the model's input (3, H, W) float32 (:func:`normalise_tiles` of one)."""
    return normalise_tiles(np.asarray(image_bgr)[None], meta)[0]


def normalise_tiles(tiles_bgr: np.ndarray, meta: ModelMetadata) -> np.ndarray:
    """BGR uint8 tiles (N, T, T, 3) as the model's input (N, 3, T, T) float32: channel order, /255, mean,
    std."""
    order = (2, 1, 0) if meta.input_channel_order == "RGB" else (0, 1, 2)
    std = np.asarray(meta.standardization_std, dtype=np.float32)
    gain = (1.0 / (255.0 * std)).astype(np.float32)
    offset = (-np.asarray(meta.standardization_mean, dtype=np.float32) / std).astype(np.float32)
    out = np.empty((len(tiles_bgr), 3) + tiles_bgr.shape[1:3], dtype=np.float32)
    for c in range(3):
        out[:, c] = tiles_bgr[..., order[c]]
        out[:, c] *= gain[c]
        out[:, c] += offset[c]
    return out


def frame_heatmap(model: HeatmapModel, image_model_res: np.ndarray, batch: int | None = None) -> np.ndarray:
    """Probability heatmap (H, W) of a BGR frame already resampled to the model's resolution; its tiles are cut,
    normalised and run ``batch`` at a time (None: all at once — a frame's few dozen), so only those are ever
    held as floats. Exactly :func:`normalise` then :func:`cut_tiles` (beyond a frame smaller than a tile the
    input is 0, as there)."""
    meta = model.metadata
    image = np.ascontiguousarray(image_model_res)
    h, w = image.shape[:2]
    t = meta.tile_size
    spans_y = tile_spans(h, t, meta.overlap_px)
    spans_x = tile_spans(w, t, meta.overlap_px)
    origins = [(y0, x0) for y0, _, _ in spans_y for x0, _, _ in spans_x]
    step = len(origins) if batch is None else max(1, int(batch))
    outputs = np.empty((len(origins), t, t), dtype=np.float32)
    for i in range(0, len(origins), step):
        part = origins[i:i + step]
        block = np.zeros((len(part), t, t, 3), dtype=np.uint8)
        for k, (y0, x0) in enumerate(part):
            piece = image[y0:y0 + t, x0:x0 + t]
            block[k, :piece.shape[0], :piece.shape[1]] = piece
        tiles = normalise_tiles(block, meta)
        tiles[:, :, h:, :] = 0.0  # padding (a frame smaller than a tile): zero input, as cut_tiles pads
        tiles[:, :, :, w:] = 0.0
        outputs[i:i + len(part)] = model.run(tiles)
    heat = stitch(outputs, spans_y, spans_x, (h, w))
    if meta.output_kind == "logits":
        heat = _sigmoid(heat)
    return heat


def _sigmoid(x: np.ndarray) -> np.ndarray:
    out = np.negative(x, dtype=np.float32)
    np.exp(out, out=out)
    out += 1.0
    np.reciprocal(out, out=out)
    return out


# ---------------------------------------------------------------------- peaks
def find_peaks(heat: np.ndarray, threshold: float, blur_sigma_px: float = 1.0):
    """One detection per blob of the smoothed heatmap above ``threshold``.

    Returns ``(uv (N, 2), score (N,))``: uv is the intensity-weighted centroid (weights =
    smoothed − threshold) in the heatmap's pixels, score the blob's maximum smoothed value.
    """
    import cv2

    heat = np.asarray(heat, dtype=np.float32)
    if blur_sigma_px > 0:
        k = 2 * int(np.ceil(3.0 * blur_sigma_px)) + 1
        smooth = cv2.GaussianBlur(heat, (k, k), blur_sigma_px, borderType=cv2.BORDER_REPLICATE)
    else:
        smooth = heat
    mask = smooth > threshold
    if not mask.any():
        return np.empty((0, 2)), np.empty(0)
    n, labels = cv2.connectedComponents(mask.view(np.uint8), connectivity=8, ltype=cv2.CV_32S)
    ys, xs = np.nonzero(mask)
    lab = labels[ys, xs]
    val = smooth[ys, xs].astype(np.float64)
    w = val - threshold
    sw = np.bincount(lab, w, minlength=n)[1:]
    u = np.bincount(lab, w * xs, minlength=n)[1:] / sw
    v = np.bincount(lab, w * ys, minlength=n)[1:] / sw
    score = np.zeros(n)
    np.maximum.at(score, lab, val)
    return np.column_stack([u, v]), score[1:]


# ---------------------------------------------------------------------- frames → detections
@dataclass
class FrameDetections:
    """Detections of one frame: original-image pixels, scores and ground points.

    ``ground_local`` is in the run's :class:`~.geodesy.LocalFrame` (ENU, m); ``lat``/``lon``/
    ``height`` are WGS84 with ellipsoidal height. ``skipped`` says why a frame gave nothing
    (unreadable image, size mismatch), else None.
    """

    frame_index: int
    frame_id: object
    image: str
    uv: np.ndarray
    score: np.ndarray
    ground_local: np.ndarray
    lat: np.ndarray
    lon: np.ndarray
    height: np.ndarray
    gsd_cm: float = float("nan")
    n_edge: int = 0
    n_no_ground: int = 0
    skipped: str | None = None
    heatmap_path: str | None = None

    def __len__(self) -> int:
        return len(self.score)


@dataclass
class DetectRequest:
    """What to detect with: threshold (probability; None → the model's default), edge buffer (px of
    the original frame), optional heatmap folder (one 8-bit PNG per frame, original frame size)."""

    threshold: float | None = None
    edge_buffer_px: float = 0.0
    heatmap_dir: str | None = None


#: Reductions OpenCV's decoders can apply while reading (JPEG: in the DCT, nearly free).
_REDUCED_READ = {1: "IMREAD_COLOR", 2: "IMREAD_REDUCED_COLOR_2", 4: "IMREAD_REDUCED_COLOR_4",
                 8: "IMREAD_REDUCED_COLOR_8"}


def read_bgr(path: str, reduction: int = 1):
    """A colour image as BGR uint8, reduced ``reduction``× in each axis (1, 2, 4 or 8; each output
    pixel the mean of a reduction × reduction block), or None when it cannot be read.

    JPEG frames are reduced by the decoder itself (scaled inverse DCT: a fraction of the time of a
    full decode); other formats are decoded whole and halved by area averaging (OpenCV's reduced
    reading of PNG subsamples without averaging, which would alias).
    """
    import cv2

    path = str(path)
    if reduction > 1 and Path(path).suffix.lower() in (".jpg", ".jpeg"):
        return cv2.imread(path, getattr(cv2, _REDUCED_READ[reduction]))
    img = cv2.imread(path, cv2.IMREAD_COLOR)
    if img is None or reduction == 1:
        return img
    return resample(img, (img.shape[1] // reduction, img.shape[0] // reduction))


def read_reduction(width: int, height: int, size: tuple[int, int]) -> int:
    """The largest power-of-two reduction (≤ 8) that divides the frame exactly and stays at least
    ``size`` = (width, height): decoding does that much of the resampling."""
    r = 1
    while 2 * r in _REDUCED_READ and width % (2 * r) == 0 and height % (2 * r) == 0 \
            and width // (2 * r) >= size[0] and height // (2 * r) >= size[1]:
        r *= 2
    return r


def detect_frames(model: HeatmapModel, poses: FramePoses, images, request: DetectRequest | None = None,
                  local: LocalFrame | None = None,
                  read_image: Callable[[str, int], np.ndarray | None] = read_bgr,
                  progress=None, is_canceled=None, ground=None) -> Iterator[FrameDetections]:
    """Detections of every frame of ``poses`` (one camera), yielded frame by frame, in order.

    ``images[k]`` is the image path of frame k, read with ``read_image(path, reduction)`` (see
    :func:`read_bgr`). Detections go onto the level plane at each frame's altimeter depth, or, given
    ``ground`` (a factory ``FrameGeometry -> GroundModel``: ``MethodPlaneGround``, a DEM's
    ``DemGroundFactory``), onto that ground. A frame without a ground height is skipped (with the
    reason) when the ground model needs one (the planes, :func:`~.ground.needs_ground_height`); a DEM
    places it and gives its ground sample distance (one whose image centre it does not cover is
    skipped, with the reason).
    Progress is reported after each frame; cancel is checked before each.
    """
    request = request or DetectRequest()
    threshold = model.metadata.default_threshold if request.threshold is None else request.threshold
    for found in detect_frames_at_thresholds(model, poses, images, [threshold], request, local, read_image,
                                             progress, is_canceled, ground):
        yield found[0]


def detect_frames_at_thresholds(model: HeatmapModel, poses: FramePoses, images, thresholds,
                                request: DetectRequest | None = None, local: LocalFrame | None = None,
                                read_image: Callable[[str, int], np.ndarray | None] = read_bgr,
                                progress=None, is_canceled=None, ground=None) -> Iterator[list[FrameDetections]]:
    """:func:`detect_frames` with the peak extraction run at each of ``thresholds`` on every frame's
    heatmap, which is computed once: yields per frame one :class:`FrameDetections` per threshold, in
    the order given, each exactly what a run at that threshold alone gives (a blob that splits above a
    higher threshold gives its parts there). ``request.threshold`` is not used."""
    request = request or DetectRequest()
    meta = model.metadata
    thresholds = [float(t) for t in thresholds]
    for threshold in thresholds:
        if not 0.0 < threshold < 1.0:
            raise InputError(f"the threshold must be a probability between 0 and 1 (got {threshold})")
    local = local or LocalFrame.around(poses.lat, poses.lon, poses.height)
    has_ground = placeable_frames(poses, ground)
    geom = FrameGeometry(poses.subset(has_ground), local)
    ground = LevelPlaneGround(geom) if ground is None else ground(geom)
    geom_index = np.cumsum(has_ground) - 1
    gsd_cm = np.full(len(poses), np.nan)
    gsd_cm[has_ground] = centre_gsd_m(geom, ground) * 100.0
    cam = poses.camera
    heat_dir = Path(request.heatmap_dir) if request.heatmap_dir else None
    if heat_dir is not None:
        heat_dir.mkdir(parents=True, exist_ok=True)
    n = len(poses)
    for k in range(n):
        check_cancel(is_canceled)
        image_path = str(images[k])
        skipped = None
        if not has_ground[k]:
            skipped = ("the frame has no ground height (no altimeter reading, or no tie points in view), which "
                       "the level plane and the method's plane stand on: give a DEM to place it")
        elif not np.isfinite(gsd_cm[k]):
            skipped = ("the ground model does not cover the image centre and the frame has no ground height, "
                       "so its ground resolution is unknown (check that the DEM covers the flight)")
        else:
            size = model_size(cam.width, cam.height, gsd_cm[k], meta.resolution_cm)
            r = read_reduction(cam.width, cam.height, size)
            img = read_image(image_path, r)
            if img is None:
                skipped = f"image '{image_path}' cannot be read"
            elif img.shape[:2] != (cam.height // r, cam.width // r):
                skipped = (f"image '{image_path}' is {'about ' if r > 1 else ''}{img.shape[1] * r}×"
                           f"{img.shape[0] * r} px but the frame's camera model is {cam.width}×{cam.height} px")
        if skipped is None:
            yield _detect_one(model, resample(img, size), k, int(geom_index[k]), poses.frame_id[k], image_path,
                              gsd_cm[k], thresholds, request, geom, ground, local, heat_dir)
        else:
            found = _empty(k, poses.frame_id[k], image_path, gsd_cm[k])
            found.skipped = skipped
            yield [found] * len(thresholds)
        if progress is not None:
            progress((k + 1) / n)


def _empty(k, frame_id, image, gsd_cm) -> FrameDetections:
    e2, e1 = np.empty((0, 2)), np.empty(0)
    return FrameDetections(k, frame_id, image, e2, e1, np.empty((0, 3)), e1, e1, e1, float(gsd_cm))


def _detect_one(model, img_model_res, k, g, frame_id, image_path, gsd_cm, thresholds, request, geom, ground,
                local, heat_dir) -> list[FrameDetections]:
    """Detections of frame k (index g in ``geom``, which holds the frames with a ground height), one
    :class:`FrameDetections` per threshold, from one heatmap."""
    meta = model.metadata
    cam = geom.camera
    size = img_model_res.shape[1], img_model_res.shape[0]
    heat = frame_heatmap(model, img_model_res)
    heatmap_path = None if heat_dir is None else _write_heatmap(heat_dir, frame_id, heat, (cam.width, cam.height))
    out = []
    for threshold in thresholds:
        uv_model, score = find_peaks(heat, threshold, meta.peak_blur_sigma_px)
        uv = to_frame_pixels(uv_model, (cam.width, cam.height), size)
        keep = cam.in_frame(uv, request.edge_buffer_px)
        n_edge = int((~keep).sum())
        uv, score = uv[keep], score[keep]
        pts, valid = pixel_to_ground(geom, ground, np.full(len(uv), g), uv)
        n_no_ground = int((~valid).sum())
        uv, score, pts = uv[valid], score[valid], pts[valid]
        lat, lon, h = local.to_geodetic(pts) if len(pts) else (np.empty(0),) * 3
        out.append(FrameDetections(k, frame_id, image_path, uv, score, pts, np.asarray(lat), np.asarray(lon),
                                   np.asarray(h), float(gsd_cm), n_edge, n_no_ground, heatmap_path=heatmap_path))
    return out


def _write_heatmap(folder: Path, frame_id, heat: np.ndarray, frame_size) -> str:
    """The heatmap as an 8-bit PNG (255·probability) at the original frame's size."""
    import cv2

    path = folder / f"{frame_id}.png"
    up = resample(heat, frame_size)
    cv2.imwrite(str(path), np.clip(np.rint(up * 255.0), 0, 255).astype(np.uint8))
    return str(path)
