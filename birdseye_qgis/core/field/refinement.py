"""Refining frame poses by structure from motion (pycolmap), aligned to the frames' GNSS positions.

A drone's metadata places its frames to a few metres and degrees; photogrammetry places them to a
fraction of a pixel, but only up to a similarity transform. So (docs/design.md#refinement):

1. SIFT features on each image, downscaled for extraction to ``match_size_px`` on its longer side
   (COLMAP scales the keypoints back to full resolution), at most ``max_features`` per image;
2. matching: every pair for small blocks, else each image with its ``spatial_neighbours`` nearest
   neighbours by the metadata positions (pose priors written into the database);
3. incremental mapping with the intrinsics *fixed* to the frame layer's calibration (DewarpData, a
   calibration file, an earlier solution): a flat nadir block cannot separate focal length from flying
   height, and a wrong focal with GNSS-fixed camera heights scales every label. ``refine_intrinsics``
   lets the block estimate focal length and distortion where relief, oblique views or ground control
   determine them. A camera that is only nominal (flag ``approx_intrinsics``: EXIF focal length, no
   calibration) is estimated, its focal length fixed by the flying height (:func:`_fix_focal`);
4. the robust weighted similarity (1/σ² of each frame's GNSS accuracy; :func:`.fit_similarity_robust`)
   from the reconstruction onto the frames' metadata camera centres; when those lie on one line, the
   metadata attitudes fix the rotation about it. Frames whose position disagrees with the block by more
   than :data:`OUTLIER_FACTOR` times the median residual (and more than 5 σ) are left out of the fit,
   which is redone until that set settles, and reported.

Frames the mapper cannot register keep their metadata pose; nothing is replaced silently.
"""
from __future__ import annotations

import math
import os
import shutil
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import Cancelled, InputError
from ..geometry.camera import CameraModel
from ..geometry.poses import indices_by_camera
from ..geometry.rigid import RigidTransform
from ..geometry.similarity import OUTLIER_FACTOR, Similarity, fit_similarity_robust
from .pose_log import RTK_FIXED, RTK_FLOAT, RTK_NONE
from .solutions.colmap import colmap_camera

#: GNSS standard deviation (m) assumed per rtk_status when the frame states none.
SIGMA_BY_RTK_STATUS = {RTK_FIXED: 0.03, RTK_FLOAT: 0.5, RTK_NONE: 3.0}
#: Tie points a frame must observe for its ground height to come from them.
MIN_GROUND_POINTS = 20
#: Frames (with a surveyed ground and tie points under them) needed to fix a focal length by the flying height.
MIN_FOCAL_FRAMES = 2
#: Below this camera-to-ground distance (m) a GNSS height error of decimetres is too large a share of it.
MIN_FOCAL_DEPTH_M = 3.0
#: Passes of fixing a focal length by the flying height, and the depth ratio off 1 that ends them.
FOCAL_PASSES, FOCAL_TOLERANCE = 4, 0.002
#: How the bundle adjustment treats the intrinsics: fixed, refined by the block alone, or nominal (estimated,
#: then the focal length fixed by the flying height or kept nominal).
FIXED, REFINED, NOMINAL = "fixed", "refined", "nominal"
#: Flag of a frame whose camera is nominal (EXIF focal length, no calibration).
APPROX_INTRINSICS_FLAG = "approx_intrinsics"


@dataclass
class RefineOptions:
    match_size_px: int = 2000
    max_features: int = 8192
    refine_intrinsics: bool = False
    exhaustive_up_to: int = 60
    spatial_neighbours: int = 20
    num_threads: int = 2


@dataclass
class FrameInput:
    """One frame as the metadata has it: camera centre and camera → local rotation, GNSS σ (m); the
    surveyed ground height under it (local z, NaN if unknown); whether its camera is only nominal."""

    image: Path | None
    camera: CameraModel
    centre: np.ndarray
    r_local_cam: np.ndarray
    sigma_m: float
    ground_z: float = math.nan
    approx_intrinsics: bool = False


@dataclass
class FocalFix:
    """A nominal camera's focal length (px): nominal, as the bundle adjustment left it, as used in the end;
    the block's and the GNSS camera-to-ground distances (m, medians) it was fixed by, or why it was not."""

    nominal_px: float
    adjusted_px: float
    final_px: float
    determined: bool
    block_depth_m: float = math.nan
    gnss_depth_m: float = math.nan
    reason: str = ""


@dataclass
class RefinedFrame:
    registered: bool
    reason: str = ""
    centre: np.ndarray | None = None
    r_local_cam: np.ndarray | None = None
    camera: CameraModel | None = None
    reprojection_rms_px: float = math.nan
    n_points: int = 0
    tie_points: np.ndarray | None = None
    ground_z_local: float = math.nan
    alignment_residual_m: float = math.nan
    used_in_alignment: bool = False
    position_change_m: float = math.nan
    rotation_change_deg: float = math.nan


@dataclass
class Refinement:
    frames: list
    similarity: Similarity | None = None
    alignment_rms_m: float = math.nan
    collinear: bool = False
    intrinsics: str = ""
    focal: FocalFix | None = None
    #: After alignment: the block's camera-to-ground distance over GNSS height minus ground height (median).
    depth_ratio: float = math.nan
    notes: list = field(default_factory=list)
    seconds: dict = field(default_factory=dict)

    @property
    def n_registered(self) -> int:
        return sum(f.registered for f in self.frames)

    @property
    def images_per_minute(self) -> float:
        total = sum(self.seconds.values())
        return 60.0 * len(self.frames) / total if total > 0 else math.nan


class _CancelWatch:
    """Polls the caller's cancel callback while pycolmap's C++ runs, and cancels its token."""

    def __init__(self, token, is_canceled):
        self.token, self.is_canceled = token, is_canceled
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self):
        while not self._stop.wait(0.2):
            if self.is_canceled():
                self.token.cancel()
                return

    def __enter__(self):
        if self.is_canceled is not None:
            self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join()
        if self.is_canceled is not None and self.is_canceled():
            raise Cancelled()


def _stage_images(frames: list[FrameInput], folder: Path) -> list[str | None]:
    """Link (or copy) each frame's image into one folder under a unique name; None where it is missing."""
    folder.mkdir(parents=True, exist_ok=True)
    names = []
    for k, frame in enumerate(frames):
        if frame.image is None or not Path(frame.image).is_file():
            names.append(None)
            continue
        name = f"{k:06d}_{Path(frame.image).name}"
        target = folder / name
        try:
            os.symlink(Path(frame.image).resolve(), target)
        except OSError:  # no symlinks (Windows without the privilege): copy
            shutil.copyfile(frame.image, target)
        names.append(name)
    return names


def refine_poses(frames: list[FrameInput], workdir, options: RefineOptions | None = None, progress=None,
                 is_canceled=None) -> Refinement:
    """Structure from motion over ``frames``' images, aligned to their metadata centres (local frame)."""
    import pycolmap

    options = options or RefineOptions()
    # COLMAP logs every image at INFO level to stderr; the report carries what a user needs.
    pycolmap.logging.minloglevel = max(pycolmap.logging.minloglevel, 1)
    workdir = Path(workdir)
    names = _stage_images(frames, workdir / "images")
    result = [RefinedFrame(False, "image file not found") if n is None else RefinedFrame(False) for n in names]
    usable = [k for k, n in enumerate(names) if n is not None]
    if len(usable) < 2:
        raise InputError(f"only {len(usable)} of {len(frames)} frame(s) have their image file; structure from "
                         "motion needs at least two overlapping images")
    database = workdir / "database.db"
    token = pycolmap.CancellationToken()
    seconds = {}

    def report(fraction):
        if progress is not None:
            progress(fraction)

    start = time.perf_counter()
    extraction = pycolmap.FeatureExtractionOptions()
    extraction.max_image_size = int(options.match_size_px)
    extraction.num_threads = options.num_threads
    extraction.sift.max_num_features = int(options.max_features)
    mode = REFINED if options.refine_intrinsics else NOMINAL if any(frames[k].approx_intrinsics for k in usable) \
        else FIXED
    with _CancelWatch(token, is_canceled):
        for group in indices_by_camera([frames[k].camera for k in usable]):
            members = [usable[j] for j in group]
            camera = frames[members[0]].camera
            # SIFT's first octave −1 doubles the image first: on a copy downscaled for speed it only chases
            # the detail the downscaling removed, at 4× the work (Brighton: 25 s → 7 s, 0.55 → 0.58 px).
            extraction.sift.first_octave = 0 if max(camera.width, camera.height) > options.match_size_px else -1
            model, params = _mapping_camera(camera, mode)
            reader = pycolmap.ImageReaderOptions()
            reader.camera_model = model
            reader.camera_params = ",".join(repr(float(p)) for p in params)
            pycolmap.extract_features(database, workdir / "images", image_names=[names[k] for k in members],
                                      camera_mode=pycolmap.CameraMode.SINGLE, reader_options=reader,
                                      extraction_options=extraction, device=pycolmap.Device.cpu,
                                      cancellation_token=token)
    seconds["features"] = time.perf_counter() - start
    report(0.3)

    start = time.perf_counter()
    matching = pycolmap.FeatureMatchingOptions()
    matching.num_threads = options.num_threads
    with _CancelWatch(token, is_canceled):
        if len(usable) <= options.exhaustive_up_to:
            pycolmap.match_exhaustive(database, matching_options=matching, device=pycolmap.Device.cpu,
                                      cancellation_token=token)
        else:
            _write_position_priors(database, {names[k]: frames[k].centre for k in usable})
            pairing = pycolmap.SpatialPairingOptions()
            pairing.max_num_neighbors = int(options.spatial_neighbours)
            pairing.ignore_z = False
            pycolmap.match_spatial(database, matching_options=matching, pairing_options=pairing,
                                   device=pycolmap.Device.cpu, cancellation_token=token)
    seconds["matching"] = time.perf_counter() - start
    report(0.6)

    start = time.perf_counter()
    mapping = pycolmap.IncrementalPipelineOptions()
    mapping.num_threads = options.num_threads
    mapping.ba_refine_focal_length = mode != FIXED
    mapping.ba_refine_extra_params = mode != FIXED
    mapping.ba_refine_principal_point = False
    registered = [0]

    def next_image():
        registered[0] += 1
        report(0.6 + 0.35 * min(registered[0] / len(usable), 1.0))

    (workdir / "sparse").mkdir(exist_ok=True)
    with _CancelWatch(token, is_canceled):
        models = pycolmap.incremental_mapping(database, workdir / "images", workdir / "sparse", options=mapping,
                                              next_image_callback=next_image, cancellation_token=token)
    seconds["mapping"] = time.perf_counter() - start
    refinement = Refinement(result, seconds=seconds, intrinsics=(
        "refined by the bundle adjustment (focal length and distortion; principal point fixed)"
        if mode == REFINED else
        "fixed to the frame layer's calibration: a flat nadir block cannot separate focal length from flying "
        "height, and a wrong focal length with GNSS-fixed camera heights would scale every label"))
    if not models:
        for k in usable:
            result[k].reason = "the block could not be reconstructed (too few matches between the images)"
        return refinement
    largest = max(models.values(), key=lambda rec: rec.num_reg_images())
    if len(models) > 1:
        refinement.notes.append(f"the images formed {len(models)} separate blocks; the largest "
                                f"({largest.num_reg_images()} images) was kept, the others do not overlap it")
    _collect(largest, frames, names, result)
    if mode == NOMINAL:
        start = time.perf_counter()
        with _CancelWatch(token, is_canceled):
            refinement.focal = _fix_focal(largest, frames, names, result, token)
        _collect(largest, frames, names, result)
        refinement.intrinsics = _focal_text(refinement.focal)
        if not refinement.focal.determined:
            refinement.notes.append(refinement.intrinsics)
        seconds["focal"] = time.perf_counter() - start
    for k in usable:
        if not result[k].registered and not result[k].reason:
            result[k].reason = ("not registered: too few matches with the block (blurred, featureless or "
                                "not overlapping)")
    align_to_gnss(refinement, frames)
    if mode != FIXED:
        done = [k for k, f in enumerate(result) if f.registered]
        refinement.depth_ratio = _depth_ratio([result[k].centre[2] for k in done],
                                              [result[k].ground_z_local for k in done], [frames[k] for k in done])
    report(1.0)
    return refinement


def _depth_ratio(camera_z, ground_z, frames) -> float:
    """Median over frames of the block's camera-to-ground distance (aligned camera height minus the median
    height of its tie points) over the GNSS one (GNSS height minus the surveyed ground); NaN if fewer than
    :data:`MIN_FOCAL_FRAMES` frames have both."""
    ratios = [(c - g) / (f.centre[2] - f.ground_z) for c, g, f in zip(camera_z, ground_z, frames)
              if math.isfinite(g) and math.isfinite(f.ground_z) and f.centre[2] - f.ground_z >= MIN_FOCAL_DEPTH_M]
    return float(np.median(ratios)) if len(ratios) >= MIN_FOCAL_FRAMES else math.nan


def _fix_focal(rec, frames, names, result, token) -> FocalFix:
    """The focal length of a nominal camera, from the flying height; the reconstruction re-adjusted to it.

    A flat nadir block images the same if focal length and every camera-to-ground distance grow by one
    factor k, while the horizontal baselines stay: the bundle adjustment cannot tell, and the similarity
    onto the GNSS positions takes its scale from those baselines. So, aligned, the block's camera-to-ground
    distance is k times the true one (GNSS height minus surveyed ground height) and the focal length is k
    times too long: f = f_adjusted / k. The block is then stretched along the vertical by 1/k (the
    image-preserving change for nadir frames; distortion coefficients rescaled for the normalised
    coordinates, which grow by k) and bundle-adjusted with the focal length fixed, and again while k
    stays off 1 by more than :data:`FOCAL_TOLERANCE` (tilts and distortion make one step inexact). Without
    a surveyed ground under enough frames k is unknown: the focal length goes back to the nominal one.
    """
    index_of = {n: k for k, n in enumerate(names) if n is not None}
    camera_of = {index_of[image.name]: image.camera_id for image in rec.images.values()
                 if image.has_pose and image.name in index_of}
    done = sorted(camera_of)
    nominal = {camera_of[k]: frames[k].camera.fx for k in done}
    adjusted = {cid: float(rec.cameras[cid].params[0]) for cid in nominal}
    first = next(iter(nominal))
    fix = None
    for _ in range(FOCAL_PASSES):
        ratio, block, gnss, sim = _provisional_depths(frames, result, done)
        if fix is None:
            fix = FocalFix(nominal[first], adjusted[first], math.nan, math.isfinite(ratio), block, gnss)
        if fix.determined:
            factor = {cid: ratio for cid in nominal}
        else:
            factor = {cid: adjusted[cid] / nominal[cid] for cid in nominal}
        if max(abs(f - 1.0) for f in factor.values()) <= FOCAL_TOLERANCE:
            break
        _readjust(rec, factor, sim, np.mean([result[k].centre for k in done], axis=0),
                  float(np.median([factor[camera_of[k]] for k in done])), token)
        _collect(rec, frames, names, result)
        if not fix.determined:
            break
    fix.final_px = float(rec.cameras[first].params[0])
    if not fix.determined:
        fix.reason = (f"fewer than {MIN_FOCAL_FRAMES} registered frames have a surveyed ground height (the frames' "
                      f"ground heights, or geotags) at least {MIN_FOCAL_DEPTH_M:g} m below the camera and "
                      f"{MIN_GROUND_POINTS} tie points under them")
    return fix


def _provisional_depths(frames, result, done):
    """The depth ratio (:func:`_depth_ratio`) of the block as it stands, the median block and GNSS
    camera-to-ground distances (m), and the similarity onto the GNSS positions it was measured with."""
    if len(done) < 2:
        return math.nan, math.nan, math.nan, None
    fit = fit_similarity_robust(np.array([result[k].centre for k in done]), np.array([frames[k].centre for k in done]),
                                np.array([frames[k].sigma_m for k in done]),
                                rotation_pairs=(np.array([result[k].r_local_cam for k in done]),
                                                np.array([frames[k].r_local_cam for k in done])))
    sim = fit.similarity
    use = [k for j, k in enumerate(done) if fit.inliers[j] and len(result[k].tie_points) >= MIN_GROUND_POINTS
           and math.isfinite(frames[k].ground_z)]
    camera_z = np.array([sim.apply(result[k].centre)[2] for k in use])
    ground_z = np.array([np.median(sim.apply(result[k].tie_points)[:, 2]) for k in use])
    ratio = _depth_ratio(camera_z, ground_z, [frames[k] for k in use])
    if not math.isfinite(ratio):
        return ratio, math.nan, math.nan, sim
    return (ratio, float(np.median(camera_z - ground_z)),
            float(np.median([frames[k].centre[2] - frames[k].ground_z for k in use])), sim)


def _readjust(rec, factor: dict, sim, origin, stretch: float, token) -> None:
    """Depths divided by ``factor[camera_id]``: cameras rescaled, the block stretched, bundle-adjusted."""
    import pycolmap

    if sim is not None:
        _stretch_vertically(rec, sim.rotation.T @ np.array([0.0, 0.0, 1.0]), origin, 1.0 / stretch)
    for cid, k in factor.items():
        camera = rec.cameras[cid]
        camera.params = _rescaled_params(camera.model.name, np.asarray(camera.params, dtype=float), k)
    adjust = pycolmap.BundleAdjustmentOptions()
    adjust.refine_focal_length = False
    adjust.refine_principal_point = False
    adjust.refine_extra_params = True
    pycolmap.bundle_adjustment(rec, adjust, cancellation_token=token)


def _stretch_vertically(rec, up: np.ndarray, origin: np.ndarray, factor: float) -> None:
    """Scale every height above ``origin`` along ``up`` (unit, SfM frame) by ``factor``: points and camera
    centres move, camera orientations stay."""
    import pycolmap

    def moved(x):
        return x + (factor - 1.0) * float(np.dot(x - origin, up)) * up

    for point in rec.points3D.values():
        point.xyz = moved(np.asarray(point.xyz, dtype=float))
    for frame in rec.frames.values():
        if not frame.has_pose:
            continue
        pose = frame.rig_from_world
        world_from_rig = RigidTransform(pose.rotation.matrix(), pose.translation).inverse()
        stretched = RigidTransform(world_from_rig.rotation, moved(world_from_rig.translation))
        frame.rig_from_world = pycolmap.Rigid3d(pose.rotation, stretched.inverse().translation)


def _rescaled_params(model: str, params: np.ndarray, k: float) -> np.ndarray:
    """COLMAP camera parameters for depths divided by ``k``: focal length / k; the normalised coordinates
    grow by k, so a term of order n in them is divided by kⁿ⁻¹ (an equidistant fisheye's angles do not
    scale that way: the bundle adjustment refines its coefficients from where they were)."""
    out = params.copy()
    if model == "RADIAL":
        out[0] /= k
        out[3:5] /= np.array([k ** 2, k ** 4])
    else:
        out[:2] /= k
    if model in ("OPENCV", "FULL_OPENCV"):
        out[4:8] /= np.array([k ** 2, k ** 4, k, k])
        if model == "FULL_OPENCV":
            out[8] /= k ** 6
    return out


def _focal_text(fix: FocalFix) -> str:
    if fix.determined:
        return (f"estimated (the camera is only nominal): distortion by the bundle adjustment; the focal length, "
                f"which a flat block cannot separate from the flying height, fixed so that the block's "
                f"camera-to-ground distance ({fix.block_depth_m:.2f} m before) matches GNSS height minus ground "
                f"height ({fix.gnss_depth_m:.2f} m): {fix.nominal_px:.1f} px nominal, {fix.adjusted_px:.1f} px "
                f"from the bundle adjustment, {fix.final_px:.1f} px fixed")
    return (f"the camera is only nominal and this block cannot determine its focal length ({fix.reason}): the "
            f"nominal {fix.nominal_px:.1f} px was kept, distortion estimated by the bundle adjustment")


def _mapping_camera(camera: CameraModel, mode: str) -> tuple[str, list]:
    """COLMAP camera model and parameters to map with. A nominal camera maps as RADIAL (one focal length,
    k1 k2): a free aspect ratio and tangential terms would only give a weak block more ways to bend."""
    if mode == NOMINAL and not camera.fisheye and not any(camera.dist[2:]) and not camera.k4:
        return "RADIAL", [camera.fx, camera.cx + 0.5, camera.cy + 0.5, *camera.dist[:2]]
    return colmap_camera(camera)


def _write_position_priors(database: Path, centres: dict) -> None:
    import pycolmap

    db = pycolmap.Database.open(str(database))
    try:
        if db.num_pose_priors():
            return
        for image in db.read_all_images():
            if image.name in centres:
                prior = pycolmap.PosePrior(position=np.asarray(centres[image.name], dtype=float),
                                           coordinate_system=pycolmap.PosePriorCoordinateSystem.CARTESIAN,
                                           corr_data_id=image.data_id)
                db.write_pose_prior(prior)
    finally:
        db.close()


def _collect(rec, frames, names, result) -> None:
    """Registered frames' SfM poses, reprojection RMS and observed points (still in the SfM frame)."""
    index_of = {n: k for k, n in enumerate(names) if n is not None}
    for image in rec.images.values():
        k = index_of.get(image.name)
        if k is None or not image.has_pose:
            continue
        cam_from_world = RigidTransform.from_matrix(image.cam_from_world().matrix())
        camera = rec.cameras[image.camera_id]
        observed = [p for p in image.points2D if p.has_point3D()]
        xyz = np.array([rec.points3D[p.point3D_id].xyz for p in observed]).reshape(-1, 3)
        xy = np.array([p.xy for p in observed]).reshape(-1, 2)
        in_cam = cam_from_world.apply(xyz)
        projected = np.asarray(camera.img_from_cam(np.ascontiguousarray(in_cam), False)).reshape(-1, 2)
        rms = float(np.sqrt(np.mean(np.sum((projected - xy) ** 2, axis=1)))) if len(xy) else math.nan
        frame = result[k]
        frame.registered, frame.reason = True, ""
        world_from_cam = cam_from_world.inverse()
        frame.r_local_cam = world_from_cam.rotation  # SfM frame until _align
        frame.centre = world_from_cam.translation
        frame.reprojection_rms_px = rms
        frame.n_points = len(xyz)
        frame.camera = _refined_camera(frames[k].camera, camera)
        frame.tie_points = xyz


def _refined_camera(original: CameraModel, colmap_cam) -> CameraModel:
    from dataclasses import replace

    from .solutions.colmap import camera_from_colmap

    solved = camera_from_colmap(colmap_cam.model.name, colmap_cam.width, colmap_cam.height, colmap_cam.params,
                                original.source)
    if solved == replace(original, T_cam_imu=np.eye(4), t_imu_rad=None):
        return original
    return replace(solved, T_cam_imu=original.T_cam_imu, t_imu_rad=original.t_imu_rad,
                   source=f"{original.source} (refined by structure from motion)")


def align_to_gnss(refinement: Refinement, frames) -> None:
    """Similarity from the SfM frame onto the metadata centres; refined poses, ground and changes."""
    done = [k for k, f in enumerate(refinement.frames) if f.registered]
    if len(done) < 2:
        for k in done:
            refinement.frames[k] = RefinedFrame(False, "the only registered image: nothing to align it with")
        return
    source = np.array([refinement.frames[k].centre for k in done])
    target = np.array([frames[k].centre for k in done])
    sigma = np.array([frames[k].sigma_m for k in done])
    pairs = (np.array([refinement.frames[k].r_local_cam for k in done]),
             np.array([frames[k].r_local_cam for k in done]))
    fit = fit_similarity_robust(source, target, sigma, rotation_pairs=pairs)
    refinement.collinear = fit.line
    sim, residual, use = fit.similarity, fit.residual, fit.inliers
    refinement.similarity = sim
    refinement.alignment_rms_m = float(np.sqrt(np.mean(residual[use] ** 2)))
    if (~use).any():
        refinement.notes.append(f"{int((~use).sum())} frame(s) have a GNSS position that disagrees with the block by "
                                f"more than {OUTLIER_FACTOR:g}× the median residual; they were left out of the "
                                "alignment (field alignment_residual_m)")
    for j, k in enumerate(done):
        frame, meta = refinement.frames[k], frames[k]
        frame.centre = sim.apply(frame.centre)
        frame.r_local_cam = sim.rotation @ frame.r_local_cam
        frame.alignment_residual_m = float(residual[j])
        frame.used_in_alignment = bool(use[j])
        frame.tie_points = sim.apply(frame.tie_points)
        if len(frame.tie_points) >= MIN_GROUND_POINTS:
            frame.ground_z_local = float(np.median(frame.tie_points[:, 2]))
        frame.position_change_m = float(np.linalg.norm(frame.centre - meta.centre))
        change = meta.r_local_cam.T @ frame.r_local_cam
        frame.rotation_change_deg = float(np.degrees(np.arccos(np.clip((np.trace(change) - 1) / 2, -1, 1))))


#: Per-frame fields of a refined frame layer, after the frame-layer fields.
REFINE_FIELDS = [
    ("registered", "bool", "the structure from motion registered the image (else: the metadata pose, unchanged)"),
    ("reprojection_rms_px", "double", "RMS reprojection error of the frame's tie points (px)"),
    ("n_points", "int", "tie points the frame observes"),
    ("position_change_m", "double", "camera centre moved from the metadata (m)"),
    ("rotation_change_deg", "double", "camera orientation turned from the metadata (deg)"),
    ("alignment_residual_m", "double", "GNSS position minus the aligned block (m)"),
]
#: Flags of a refined frame layer.
REFINED_FLAG, NOT_REFINED_FLAG = "refined", "not_refined"


def gnss_sigma_m(frames) -> np.ndarray:
    """Per frame, the GNSS position σ (m): the DJI RtkStd fields where given, else by RTK status."""
    stds = [frames.extra.get(name) for name in ("rtk_std_lon_m", "rtk_std_lat_m", "rtk_std_hgt_m")]
    by_status = np.array([SIGMA_BY_RTK_STATUS.get(int(s), SIGMA_BY_RTK_STATUS[RTK_NONE]) for s in frames.rtk_status])
    if any(s is None for s in stds):
        return by_status
    stated = np.sqrt(np.mean(np.square(np.column_stack(stds)), axis=1))
    return np.where(np.isfinite(stated) & (stated > 0), np.maximum(stated, 0.01), by_status)


def refine_frames(frames, workdir, options: RefineOptions | None = None, progress=None, is_canceled=None,
                  geotag_heights=None):
    """Refined :class:`.frames.Frames` (registered frames moved, flagged ``refined``; the others unchanged,
    flagged ``not_refined``), the :class:`Refinement`, and per-frame :data:`REFINE_FIELDS` values.

    The surveyed ground that fixes a nominal camera's focal length: a level plane at the median of
    ``geotag_heights`` (ellipsoidal, m) when given, else each frame's own ground height.
    """
    from dataclasses import replace

    from ..geometry.geodesy import LocalFrame
    from ..geometry.poses import FrameGeometry, body_pose_from_camera

    local = LocalFrame.around(frames.lat, frames.lon, frames.height)
    centres, rotations = np.zeros((len(frames), 3)), np.zeros((len(frames), 3, 3))
    for idx in indices_by_camera(frames.cameras):
        geometry = FrameGeometry(frames.poses(idx), local)
        centres[idx], rotations[idx] = geometry.C, geometry.R_local_cam
    sigma = gnss_sigma_m(frames)
    surveyed = None if geotag_heights is None else np.asarray(geotag_heights, dtype=float)
    if surveyed is not None and np.isfinite(surveyed).any():
        ground_h = np.full(len(frames), float(np.nanmedian(surveyed)))
    else:
        ground_h = frames.ground_h
    ground_z = local.from_geodetic(frames.lat, frames.lon, ground_h)[:, 2]
    inputs = [FrameInput(Path(frames.image[i]) if frames.image[i] else None, frames.cameras[i], centres[i],
                         rotations[i], float(sigma[i]), float(ground_z[i]), APPROX_INTRINSICS_FLAG in frames.flags[i])
              for i in range(len(frames))]
    refinement = refine_poses(inputs, workdir, options, progress, is_canceled)
    out = replace(frames, lat=frames.lat.copy(), lon=frames.lon.copy(), height=frames.height.copy(),
                  quat=frames.quat.copy(), ground_h=frames.ground_h.copy(), cameras=list(frames.cameras),
                  flags=[list(f) for f in frames.flags], euler_deg=None if frames.euler_deg is None
                  else frames.euler_deg.copy())
    values = []
    for i, r in enumerate(refinement.frames):
        values.append({"registered": r.registered, "reprojection_rms_px": _finite(r.reprojection_rms_px),
                       "n_points": r.n_points, "position_change_m": _finite(r.position_change_m),
                       "rotation_change_deg": _finite(r.rotation_change_deg),
                       "alignment_residual_m": _finite(r.alignment_residual_m)})
        if not r.registered:
            out.flags[i].append(NOT_REFINED_FLAG)
            continue
        lat, lon, h, quat = body_pose_from_camera(local, r.centre[None], r.r_local_cam[None], r.camera)
        out.lat[i], out.lon[i], out.height[i], out.quat[i] = lat[0], lon[0], h[0], quat[0]
        out.cameras[i] = r.camera
        if math.isfinite(r.ground_z_local):
            # The tie points' median height: the ground the block saw, in the frames' own vertical reference.
            out.ground_h[i] = float(local.to_geodetic(np.array([[*r.centre[:2], r.ground_z_local]]))[2][0])
        if out.euler_deg is not None:
            out.euler_deg[i] = np.nan  # derived again from the refined quaternion
        out.flags[i].append(REFINED_FLAG)
    if out.euler_deg is not None and np.isnan(out.euler_deg).any():
        from .frame_records import euler_degrees

        redo = np.flatnonzero(np.isnan(out.euler_deg).any(axis=1))
        out.euler_deg[redo] = np.column_stack(euler_degrees(out.quat[redo]))
    return out, refinement, values


def _finite(x):
    return None if x is None or not math.isfinite(float(x)) else float(x)


def refinement_report_html(refinement: Refinement, frames, values, source: str = "") -> str:
    """The run's report: what was registered and why not, residuals, the alignment, the intrinsics rule."""
    import html

    from ..scoring.reports import html_page, html_table

    reg = [v for v in values if v["registered"]]
    rms = [v["reprojection_rms_px"] for v in reg if v["reprojection_rms_px"] is not None]
    sim = refinement.similarity
    body = [f"<p>{html.escape(source)}</p>",
            f"<p><b>{refinement.n_registered} of {len(values)}</b> frames registered"
            + (f"; mean reprojection error {np.mean(rms):.2f} px (max {np.max(rms):.2f} px)" if rms else "")
            + f". {refinement.images_per_minute:.1f} images per minute "
            + "(" + ", ".join(f"{k} {v:.1f} s" for k, v in refinement.seconds.items()) + ").</p>",
            f"<p>Intrinsics: {html.escape(refinement.intrinsics)}.</p>"]
    if math.isfinite(refinement.depth_ratio):
        body.append(f"<p>Check of the focal length against the flying height: the block's camera-to-ground distance "
                    f"is {refinement.depth_ratio:.4f} × GNSS height minus ground height (median over frames; 1 when "
                    "the two agree, a focal length off by the same factor otherwise).</p>")
    if sim is not None:
        body.append(f"<p>Alignment to the frames' GNSS positions (weighted by their accuracy): scale "
                    f"{sim.scale:.6f}, residual RMS {refinement.alignment_rms_m:.3f} m"
                    + ("; the camera centres lie on one line (or stray from it by less than their GNSS accuracy "
                       "resolves), so the metadata attitudes fixed the rotation about it" if refinement.collinear
                       else "") + ".</p>")
    body += [f"<p class='note'>{html.escape(n)}</p>" for n in refinement.notes]
    rows = []
    for i, (r, v) in enumerate(zip(refinement.frames, values)):
        rows.append([str(frames.image[i]).replace("\\", "/").rsplit("/", 1)[-1], "yes" if r.registered else "no",
                     v["reprojection_rms_px"], v["n_points"], v["position_change_m"], v["rotation_change_deg"],
                     v["alignment_residual_m"], r.reason or ("" if r.used_in_alignment or not r.registered
                                                             else "left out of the alignment")])
    body.append(html_table(["image", "registered", "reprojection RMS (px)", "tie points", "moved (m)",
                            "turned (°)", "GNSS residual (m)", "reason / note"], rows))
    return html_page("BirdsEye — pose refinement", "".join(body))
