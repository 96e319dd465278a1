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
   calibration) is estimated, its focal length fixed by the flying height (:func:`_fix_focal`) above the
   ground :func:`choose_grounds` picks per camera;
4. the robust weighted similarity (1/σ² of each frame's GNSS accuracy; :func:`.fit_similarity_robust`)
   from the reconstruction onto the frames' metadata camera centres; when those lie on one line, the
   metadata attitudes fix the rotation about it, and attitudes that contradict the others (a flight line
   whose heading was logged 180° off) are left out of it (:func:`_gnss_fit`). Frames whose position
   disagrees with the block by more than :data:`OUTLIER_FACTOR` times the median residual (and more than
   5 σ) are left out of the fit, which is redone until that set settles, and reported.

Frames the mapper cannot register keep their metadata pose; nothing is replaced silently.
"""
from __future__ import annotations

import math
import os
import shutil
import threading
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import Cancelled, InputError
from ..geometry.camera import CameraModel
from ..geometry.heights import (
    ELLIPSOIDAL_REFERENCE,
    FLIGHT_HEIGHT,
    GIVEN,
    NO_GROUND,
    TAKEOFF,
    TIE_POINTS,
    UNKNOWN,
    height_shift,
)
from ..geometry.poses import indices_by_camera
from ..geometry.rigid import RigidTransform
from ..geometry.similarity import OUTLIER_FACTOR, RobustFit, Similarity, fit_similarity_robust
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
FOCAL_PASSES, FOCAL_TOLERANCE = 6, 0.002
#: Depth ratios (block / GNSS camera-to-ground distance) a focal length is fixed by. Outside, the heights or the
#: ground are wrong (or the block is), not the focal length, which stays nominal.
FOCAL_RATIO_RANGE = (0.5, 2.0)
#: The most one pass changes the depths by (the factor or its inverse); a larger ratio takes several passes,
#: each bundle-adjusted from a block near the one before.
MAX_FOCAL_STEP = 1.5
#: How much (px) one pass may raise the block's mean reprojection error above where the mapping left it: a pass
#: that does more has distorted the block rather than rescaled it, and is undone.
MAX_ERROR_GROWTH_PX = 0.5
#: Share of the observations a pass may drop (points behind a camera after the stretch) before it is undone.
MAX_DROPPED_OBSERVATIONS = 0.1
#: Metadata attitudes whose implied block rotations lie within this angle (deg) of each other agree; of the sets
#: of agreeing attitudes, this many of the largest are tried for the rotation about a flight line.
ATTITUDE_AGREEMENT_DEG, MAX_ATTITUDE_SETS = 15.0, 5
#: How the bundle adjustment treats the intrinsics: fixed, refined by the block alone, or nominal (estimated,
#: then the focal length fixed by the flying height or kept nominal).
FIXED, REFINED, NOMINAL = "fixed", "refined", "nominal"
#: Flag of a frame whose camera is nominal (EXIF focal length, no calibration).
APPROX_INTRINSICS_FLAG = "approx_intrinsics"
#: Which ground a camera's GNSS camera-to-ground distance is measured from (:class:`GroundChoice`).
OWN_GROUND, SURVEYED_GROUND, TERRAIN_GROUND = "own", "surveyed", "terrain"
#: A frame's terrain from a DEM: the median height of a grid of this many pixels (columns × rows) cast onto it,
#: at least half of them on the DEM (like the tie points' median height the block's distance is measured to).
TERRAIN_GRID, MIN_TERRAIN_SHARE = (9, 7), 0.5
#: A frame's own ground that is one height for the whole site, in words: the focal length fixed over it is off
#: by the share the terrain under the frames lies above or below it.
SITE_GROUND_WORDS = {TAKEOFF: "the take-off point's height", FLIGHT_HEIGHT: "the camera height minus the flight "
                     "height given at import", GIVEN: "a ground height given at import"}


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
    ground height under it that its GNSS camera-to-ground distance is measured from (local z, NaN if
    unknown); whether its camera is only nominal."""

    image: Path | None
    camera: CameraModel
    centre: np.ndarray
    r_local_cam: np.ndarray
    sigma_m: float
    ground_z: float = math.nan
    approx_intrinsics: bool = False


@dataclass
class FocalFix:
    """One nominal camera's focal length (px): nominal, as the bundle adjustment left it, as used in the end;
    whether the flying height determined it and the block's and GNSS camera-to-ground distances (m, medians over
    its frames) it was measured with; ``first_frame``: the index of its first registered frame; ``settled``: the
    depth ratio ended within :data:`FOCAL_TOLERANCE` of 1; ``reason``: why it was not determined."""

    nominal_px: float
    adjusted_px: float
    final_px: float
    determined: bool
    block_depth_m: float = math.nan
    gnss_depth_m: float = math.nan
    first_frame: int = -1
    settled: bool = False
    reason: str = ""


@dataclass(frozen=True)
class GroundChoice:
    """The ground one camera's frames (``frames``, indices) measure their GNSS camera-to-ground distance from.

    ``rtk``: at least half of them have an RTK fix; ``own_m``: their own ground (median, m, the frames' vertical
    reference; NaN: none) and where it came from (``own_source``, :data:`.heights.GROUND_SOURCES`); ``surveyed_m``:
    the geotags' ground converted into that reference (NaN: none or not comparable) and how (``conversion``);
    ``terrain_m``: the terrain a DEM holds in their view (median, m, that reference; NaN: no DEM, or it does not
    cover them); ``used``: :data:`TERRAIN_GROUND`, :data:`OWN_GROUND`, :data:`SURVEYED_GROUND` or "" (none);
    ``reason``: why, in words; ``warning``: set when the ground used is one height for the whole site (the
    take-off point) rather than the ground under the frames.
    """

    frames: tuple
    rtk: bool
    own_m: float
    own_source: str
    surveyed_m: float
    used: str
    reason: str
    warning: str = ""
    conversion: str = ""
    terrain_m: float = math.nan

    @property
    def difference_m(self) -> float:
        """Surveyed minus own ground (m; NaN unless both are known)."""
        return self.surveyed_m - self.own_m

    @property
    def used_m(self) -> float:
        return {OWN_GROUND: self.own_m, SURVEYED_GROUND: self.surveyed_m,
                TERRAIN_GROUND: self.terrain_m}.get(self.used, math.nan)


@dataclass(frozen=True)
class GnssFit:
    """The similarity onto the GNSS positions (:func:`_gnss_fit`) and, per frame, whether its metadata attitude
    contradicts the attitudes that fixed the rotation, and by how much (deg)."""

    fit: RobustFit
    contradicting: np.ndarray
    off_deg: np.ndarray


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
    """A run's outcome: per input frame a :class:`RefinedFrame`; the alignment; how the intrinsics were treated
    (``intrinsics``, in words) and, for nominal cameras, one :class:`FocalFix` each (``focal``); the ground each
    camera's focal length was measured from (``grounds``, :class:`GroundChoice`; filled by :func:`refine_frames`);
    notes for the user and seconds per stage."""

    frames: list
    similarity: Similarity | None = None
    alignment_rms_m: float = math.nan
    collinear: bool = False
    intrinsics: str = ""
    focal: list = field(default_factory=list)
    grounds: list = field(default_factory=list)
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


def _missing_images_text(frames: list[FrameInput], usable: list[int]) -> str:
    """Why structure from motion cannot start: how many frames have their image, where the others were looked
    for (the frame layer's ``image`` field), and how to give the frames their images."""
    found = set(usable)
    missing = [frame.image for k, frame in enumerate(frames) if k not in found]
    named = [str(image) for image in missing if image]
    looked = (f"the image field names files that do not exist, e.g. {named[0]}" if named else
              "the frames' image field is empty")
    if named and len(named) < len(missing):
        looked += f"; {len(missing) - len(named)} frame(s) name no image"
    return (f"only {len(usable)} of {len(frames)} frame(s) have their image file ({looked}); structure from motion "
            "needs at least two overlapping images. Import the frames again with their image folder: the IMAGES "
            "parameter of Import camera solution, Import drone images or Import flight log")


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
    # COLMAP logs every image, and its warnings, to stderr (qgis_process's output, QGIS's console); the report
    # carries what a user needs, so only its errors are let through.
    pycolmap.logging.minloglevel = max(pycolmap.logging.minloglevel, int(pycolmap.logging.ERROR))
    workdir = Path(workdir)
    names = _stage_images(frames, workdir / "images")
    result = [RefinedFrame(False, "image file not found") if n is None else RefinedFrame(False) for n in names]
    usable = [k for k, n in enumerate(names) if n is not None]
    if len(usable) < 2:
        raise InputError(_missing_images_text(frames, usable))
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
            largest, refinement.focal, stopped = _fix_focal(largest, frames, names, result, token)
        _collect(largest, frames, names, result)
        refinement.intrinsics = "; ".join(_focal_text(fix, frames) for fix in refinement.focal)
        refinement.notes += [_focal_text(fix, frames) for fix in refinement.focal if not fix.determined]
        if stopped:
            refinement.notes.append(stopped)
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
    height of its tie points) over the GNSS one (GNSS height minus the frame's ground); NaN if fewer than
    :data:`MIN_FOCAL_FRAMES` frames have both."""
    ratios = [(c - g) / (f.centre[2] - f.ground_z) for c, g, f in zip(camera_z, ground_z, frames)
              if math.isfinite(g) and math.isfinite(f.ground_z) and f.centre[2] - f.ground_z >= MIN_FOCAL_DEPTH_M]
    return float(np.median(ratios)) if len(ratios) >= MIN_FOCAL_FRAMES else math.nan


def _fix_focal(rec, frames, names, result, token):
    """The focal length of each nominal camera, from the flying height; the reconstruction re-adjusted to it.

    A flat nadir block images the same if focal length and every camera-to-ground distance grow by one
    factor k, while the horizontal baselines stay: the bundle adjustment cannot tell, and the similarity
    onto the GNSS positions takes its scale from those baselines. So, aligned, a camera's block
    camera-to-ground distance is k times the true one (GNSS height minus its frames' ground,
    :attr:`FrameInput.ground_z`) and its focal length is k times too long: f = f_adjusted / k, k measured per
    camera. A k outside :data:`FOCAL_RATIO_RANGE`, or too few frames to measure it, leaves the focal length
    undetermined: it goes back to the nominal one. Each pass stretches the block along the vertical by 1/k
    (the median over frames; the image-preserving change for nadir frames), rescales each camera by its own
    k (distortion coefficients for the normalised coordinates, which grow by k), k bounded to
    :data:`MAX_FOCAL_STEP` per pass, and bundle-adjusts with the focal lengths fixed; passes repeat (at most
    :data:`FOCAL_PASSES`) while k stays off 1 by more than :data:`FOCAL_TOLERANCE` (tilts and distortion make
    one step inexact). A pass whose adjustment does not converge, leaves a non-finite pose or point, raises
    the mean reprojection error by more than :data:`MAX_ERROR_GROWTH_PX` or drops more than
    :data:`MAX_DROPPED_OBSERVATIONS` of the observations, or fails, is undone, and the passes stop there.

    Returns the reconstruction to use (``rec``, or the copy of it after the last good pass), one
    :class:`FocalFix` per nominal camera, and why the passes stopped early, in words ("" if they did not).
    """
    import pycolmap

    index_of = {n: k for k, n in enumerate(names) if n is not None}
    camera_of = {index_of[image.name]: image.camera_id for image in rec.images.values()
                 if image.has_pose and image.name in index_of}
    done = sorted(camera_of)
    members: dict = {}
    for k in done:
        members.setdefault(camera_of[k], []).append(k)
    fixes = {cid: FocalFix(frames[ks[0]].camera.fx, float(rec.cameras[cid].params[0]), math.nan, False,
                           first_frame=ks[0]) for cid, ks in members.items()}
    depths, sim = _provisional_depths(frames, result, done, members)
    low, high = FOCAL_RATIO_RANGE
    for cid, fix in fixes.items():
        ratio, fix.block_depth_m, fix.gnss_depth_m = depths[cid]
        fix.determined = low <= ratio <= high
        if math.isfinite(ratio) and not fix.determined:
            fix.reason = (f"the block's camera-to-ground distance came out {ratio:.3g} × GNSS height minus ground "
                          f"height, outside {low:g}–{high:g}: the heights or the ground are wrong, not the focal "
                          "length")
        elif not any(math.isfinite(frames[k].ground_z) for k in members[cid]):
            fix.reason = ("its frames have no ground height: none of their own (no relative altitude, flight height "
                          "or DEM at import) and no geotags with surveyed heights")
        elif not fix.determined:
            fix.reason = (f"fewer than {MIN_FOCAL_FRAMES} registered frames have a ground height (their own, or "
                          f"geotags') at least {MIN_FOCAL_DEPTH_M:g} m below the camera and {MIN_GROUND_POINTS} "
                          "tie points under them")
    good = pycolmap.Reconstruction(rec)
    error_before = rec.compute_mean_reprojection_error()
    observations_before = rec.compute_num_observations()
    stopped = ""
    for done_passes in range(FOCAL_PASSES + 1):
        factor = {cid: depths[cid][0] if fix.determined else float(rec.cameras[cid].params[0]) / fix.nominal_px
                  for cid, fix in fixes.items()}
        if not all(math.isfinite(f) and f > 0 for f in factor.values()) or sim is None:
            stopped = (f"fixing the focal length stopped after {done_passes} pass(es): the block could not be "
                       "measured against the GNSS heights; the block as it stood was kept")
            break
        if max(abs(f - 1.0) for f in factor.values()) <= FOCAL_TOLERANCE:
            for fix in fixes.values():
                fix.settled = True
            break
        if done_passes == FOCAL_PASSES or (token is not None and token.is_cancelled):
            break
        step = {cid: float(np.clip(f, 1.0 / MAX_FOCAL_STEP, MAX_FOCAL_STEP)) for cid, f in factor.items()}
        try:
            summary = _readjust(rec, step, sim, np.mean([result[k].centre for k in done], axis=0),
                                float(np.median([step[camera_of[k]] for k in done])))
            problem = _adjustment_problem(rec, summary, error_before, observations_before)
        except (RuntimeError, ValueError) as exc:  # COLMAP's checks raise these from C++
            problem = f"its bundle adjustment failed ({exc})"
        if problem:
            rec = good
            stopped = (f"fixing the focal length stopped at pass {done_passes + 1}: {problem}; the block of the "
                       f"pass before was kept")
            break
        good = pycolmap.Reconstruction(rec)
        _collect(rec, frames, names, result)
        depths, sim = _provisional_depths(frames, result, done, members)
    for cid, fix in fixes.items():
        fix.final_px = float(rec.cameras[cid].params[0])
    return rec, list(fixes.values()), stopped


def _adjustment_problem(rec, summary, error_before: float, observations_before: int) -> str:
    """What is wrong with a pass's bundle adjustment, in words ("" if nothing)."""
    import pycolmap

    if summary.termination_type != pycolmap.BundleAdjustmentTerminationType.CONVERGENCE:
        return f"its bundle adjustment did not converge ({summary.termination_type.name.lower()})"
    centres = np.array([image.projection_center() for image in rec.images.values() if image.has_pose])
    points = np.array([point.xyz for point in rec.points3D.values()]).reshape(-1, 3)
    if not (np.isfinite(centres).all() and np.isfinite(points).all()):
        return "its bundle adjustment left camera centres or points that are not finite"
    dropped = 1.0 - rec.compute_num_observations() / max(observations_before, 1)
    if dropped > MAX_DROPPED_OBSERVATIONS:
        return f"it left {dropped:.0%} of the observations behind their cameras"
    error = rec.compute_mean_reprojection_error()
    if not error <= error_before + MAX_ERROR_GROWTH_PX:
        return f"it raised the mean reprojection error from {error_before:.2f} px to {error:.2f} px"
    return ""


def _provisional_depths(frames, result, done, members):
    """Per camera (``members``: camera id → frame indices), the depth ratio (:func:`_depth_ratio`) of the block as
    it stands and the median block and GNSS camera-to-ground distances (m); and the similarity onto the GNSS
    positions they were measured with (None when the block's centres are not finite or the fit is degenerate)."""
    unknown = {cid: (math.nan, math.nan, math.nan) for cid in members}
    centres = np.array([result[k].centre for k in done])
    if len(done) < 2 or not np.isfinite(centres).all():
        return unknown, None
    fit = _gnss_fit(centres, np.array([frames[k].centre for k in done]), np.array([frames[k].sigma_m for k in done]),
                    np.array([result[k].r_local_cam for k in done]),
                    np.array([frames[k].r_local_cam for k in done])).fit
    sim = fit.similarity
    if not (math.isfinite(sim.scale) and sim.scale > 0):
        return unknown, None
    inlier = {k: bool(fit.inliers[j]) for j, k in enumerate(done)}
    out = {}
    for cid, ks in members.items():
        use = [k for k in ks if inlier[k] and len(result[k].tie_points) >= MIN_GROUND_POINTS
               and math.isfinite(frames[k].ground_z)]
        camera_z = np.array([sim.apply(result[k].centre)[2] for k in use])
        ground_z = np.array([np.median(sim.apply(result[k].tie_points)[:, 2]) for k in use])
        ratio = _depth_ratio(camera_z, ground_z, [frames[k] for k in use])
        out[cid] = (ratio, math.nan, math.nan) if not math.isfinite(ratio) else (
            ratio, float(np.median(camera_z - ground_z)),
            float(np.median([frames[k].centre[2] - frames[k].ground_z for k in use])))
    return out, sim


def _readjust(rec, factor: dict, sim, origin, stretch: float):
    """Depths divided by ``factor[camera_id]``: cameras rescaled, the block stretched along the vertical of
    ``sim`` by 1 / ``stretch`` about ``origin``, bundle-adjusted (:func:`_bundle_adjust`); Ceres' summary."""
    _stretch_vertically(rec, sim.rotation.T @ np.array([0.0, 0.0, 1.0]), origin, 1.0 / stretch)
    for cid, k in factor.items():
        camera = rec.cameras[cid]
        camera.params = _rescaled_params(camera.model.name, np.asarray(camera.params, dtype=float), k)
    return _bundle_adjust(rec)


def _bundle_adjust(rec):
    """A global bundle adjustment of ``rec`` with focal lengths and principal points fixed, distortion refined,
    as ``pycolmap.bundle_adjustment`` runs it (observations behind a camera dropped, the gauge fixed by two
    cameras), returning Ceres' summary, which ``pycolmap.bundle_adjustment`` does not."""
    import pycolmap

    pycolmap.ObservationManager(rec).filter_observations_with_negative_depth()
    options = pycolmap.BundleAdjustmentOptions()
    options.refine_focal_length = False
    options.refine_principal_point = False
    options.refine_extra_params = True
    options.print_summary = False
    config = pycolmap.BundleAdjustmentConfig()
    for image_id in rec.reg_image_ids():
        config.add_image(image_id)
    config.fix_gauge(pycolmap.BundleAdjustmentGauge.TWO_CAMS_FROM_WORLD)
    summary = pycolmap.create_default_bundle_adjuster(options, config, rec).solve()
    rec.update_point_3d_errors()
    return summary


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


def _camera_label(image) -> str:
    """A camera in words, by the image of its first frame (None: unnamed)."""
    return f"camera of {Path(image).name}" if image else "camera"


def _focal_text(fix: FocalFix, frames) -> str:
    """How a nominal camera's focal length was treated, in words."""
    camera = _camera_label(frames[fix.first_frame].image)
    if fix.determined:
        text = (f"{camera}: estimated (the camera is only nominal): distortion by the bundle adjustment; the focal "
                f"length, which a flat block cannot separate from the flying height, fixed so that the block's "
                f"camera-to-ground distance ({fix.block_depth_m:.2f} m before) matches GNSS height minus ground "
                f"height ({fix.gnss_depth_m:.2f} m): {fix.nominal_px:.1f} px nominal, {fix.adjusted_px:.1f} px "
                f"from the bundle adjustment, {fix.final_px:.1f} px fixed")
        return text if fix.settled else text + f" (the depth ratio did not settle within {FOCAL_TOLERANCE:.1%} of 1)"
    kept = (f"the nominal {fix.nominal_px:.1f} px was kept" if abs(fix.final_px / fix.nominal_px - 1) <= FOCAL_TOLERANCE
            else f"{fix.final_px:.1f} px was kept (nominal {fix.nominal_px:.1f} px, {fix.adjusted_px:.1f} px from the "
                 "bundle adjustment)")
    return (f"{camera}: the camera is only nominal and this block cannot determine its focal length ({fix.reason}): "
            f"{kept}, distortion estimated by the bundle adjustment")


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


def _gnss_fit(source, target, sigma, r_source, r_target) -> GnssFit:
    """:func:`.fit_similarity_robust` of SfM camera centres ``source`` onto GNSS centres ``target`` (σ ``sigma``,
    m), with the SfM and metadata attitudes (``r_source``, ``r_target``) as rotation pairs for a flight line,
    robust to attitudes that contradict the block as it is to positions.

    Each frame's pair implies a rotation of the block (metadata · SfMᵀ); frames whose implied rotations lie
    within :data:`ATTITUDE_AGREEMENT_DEG` of each other agree, and fall into sets of agreeing frames (all in one
    when all agree: the pairs are used as given). Otherwise (a flight line whose heading was logged 180° off)
    each of the :data:`MAX_ATTITUDE_SETS` largest sets of two or more is tried: its frames keep their pairs,
    the others are given the attitude the set's mean rotation implies for them, which adds nothing to the
    rotation (the chordal mean of rotations together with copies of that mean is that mean). The set whose fit
    leaves the positions the least median σ-normalised residual wins; of sets within one σ of it (which
    positions cannot tell apart), the largest. A fit with a negative scale is a mirror image, not a similarity
    (a heading 180° off turns a flat block upside down and still fits its positions): it never wins. When no
    set gives a fit, the positions alone fix the rotation (:class:`.errors.InputError` if they lie on one
    line). A frame contradicts when its implied rotation lies more than :data:`ATTITUDE_AGREEMENT_DEG` from the
    fitted one.
    """
    from scipy.spatial.transform import Rotation

    implied = np.einsum("nij,nkj->nik", r_target, r_source)
    quat = Rotation.from_matrix(implied).as_quat()
    agree = np.degrees(2.0 * np.arccos(np.clip(np.abs(quat @ quat.T), 0.0, 1.0))) <= ATTITUDE_AGREEMENT_DEG
    n = len(source)
    sets, left = [], np.ones(n, dtype=bool)
    while left.any():
        seed = int(np.argmax((agree & left[None, :]).sum(axis=1) * left))
        sets.append(agree[seed] & left)
        left &= ~sets[-1]
    tried = []
    for members in [m for m in sets if m.sum() >= 2][:MAX_ATTITUDE_SETS]:
        if members.all():
            given = r_target
        else:
            mean = Rotation.from_matrix(implied[members]).mean().as_matrix()
            given = np.where(members[:, None, None], r_target, np.einsum("ij,njk->nik", mean, r_source))
        fit = fit_similarity_robust(source, target, sigma, rotation_pairs=(r_source, given))
        if fit.similarity.scale > 0:
            tried.append((float(np.median(fit.residual / sigma)), int(members.sum()), fit))
    if tried:
        least = min(cost for cost, _, _ in tried)
        fit = max((t for t in tried if t[0] <= least + 1.0), key=lambda t: t[1])[2]
    else:
        fit = fit_similarity_robust(source, target, sigma)
    off = np.degrees((Rotation.from_matrix(fit.similarity.rotation).inv() * Rotation.from_matrix(implied)).magnitude())
    return GnssFit(fit, off > ATTITUDE_AGREEMENT_DEG, off)


def align_to_gnss(refinement: Refinement, frames) -> None:
    """Similarity from the SfM frame onto the metadata centres (:func:`_gnss_fit`); refined poses, ground and
    changes. Frames whose metadata attitude contradicts the block's are named in a note."""
    done = [k for k, f in enumerate(refinement.frames) if f.registered]
    if len(done) < 2:
        for k in done:
            refinement.frames[k] = RefinedFrame(False, "the only registered image: nothing to align it with")
        return
    source = np.array([refinement.frames[k].centre for k in done])
    target = np.array([frames[k].centre for k in done])
    sigma = np.array([frames[k].sigma_m for k in done])
    gnss = _gnss_fit(source, target, sigma, np.array([refinement.frames[k].r_local_cam for k in done]),
                     np.array([frames[k].r_local_cam for k in done]))
    fit = gnss.fit
    refinement.collinear = fit.line
    sim, residual, use = fit.similarity, fit.residual, fit.inliers
    refinement.similarity = sim
    refinement.alignment_rms_m = float(np.sqrt(np.mean(residual[use] ** 2)))
    if (~use).any():
        refinement.notes.append(f"{int((~use).sum())} frame(s) have a GNSS position that disagrees with the block by "
                                f"more than {OUTLIER_FACTOR:g}× the median residual; they were left out of the "
                                "alignment (field alignment_residual_m)")
    if gnss.contradicting.any():
        off = list(np.flatnonzero(gnss.contradicting))
        names = ", ".join(Path(frames[done[j]].image).name if frames[done[j]].image else f"frame {done[j] + 1}"
                          for j in off[:6]) + (", …" if len(off) > 6 else "")
        how = ("the rotation about the flight line came from the other frames' attitudes" if fit.line
               else "the positions fixed the rotation")
        refinement.notes.append(
            f"{len(off)} frame(s) have a metadata attitude {np.median(gnss.off_deg[off]):.0f}° (median) off the one "
            f"the aligned block gives them ({names}): a heading logged the wrong way round, a drone flown tail first "
            f"where the heading came from its track, or a camera turned on its mount; {how} (field "
            "rotation_change_deg)")
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


def terrain_grounds(frames, dem):
    """Per frame the terrain height (m, in ``frames.reference``; NaN where the DEM does not cover at least
    :data:`MIN_TERRAIN_SHARE` of its view) a DEM holds where the frame looks — the median of a
    :data:`TERRAIN_GRID` of pixels cast onto it from the frame's metadata pose, as the block's ground is the
    median height of the tie points in view — and the DEM's check against the frames
    (:func:`..geometry.dem.check_vertical_datum`: converted into their reference, compared with their ground)."""
    from ..geometry.dem import DemGroundFactory, check_vertical_datum, terrain_in_view
    from ..geometry.geodesy import LocalFrame
    from ..geometry.poses import FrameGeometry

    check = check_vertical_datum(dem, frames.all_poses())
    local = LocalFrame.around(frames.lat, frames.lon, frames.height)
    terrain = np.full(len(frames), np.nan)
    factory = DemGroundFactory(dem, vertical_offset_m=check.offset_m)
    for idx in indices_by_camera(frames.cameras):
        geometry = FrameGeometry(frames.poses(idx), local)
        points = terrain_in_view(geometry, factory(geometry), TERRAIN_GRID)
        covered = np.isfinite(points[..., 2]).mean(axis=1) >= MIN_TERRAIN_SHARE
        for k in np.flatnonzero(covered):
            seen = points[k][np.isfinite(points[k, :, 2])]
            terrain[idx[k]] = float(np.median(local.to_geodetic(seen)[2]))
    return terrain, check


def choose_grounds(frames, geotag_heights=None, geoid_undulation_m: float | None = None, terrain=None):
    """Per frame, the ground height (m, in ``frames.reference``; NaN: none) its GNSS camera-to-ground distance is
    measured from, which fixes a nominal camera's focal length; and per camera group the :class:`GroundChoice`.

    The surveyed ground is a level plane at the median of ``geotag_heights`` (ellipsoidal, m), converted into the
    frames' vertical reference at each frame (:func:`.heights.height_shift`; ``geoid_undulation_m``: N at the site,
    ellipsoidal = MSL + N, else PROJ's grid of the geoid the frames name). A conversion that needs a missing grid
    or N is refused (:class:`.errors.InputError` naming it); frames in an unknown reference cannot be compared with
    geotags and keep their own ground, said so. Per camera group (frames of several drones in one layer):

    * at least half its frames with an RTK fix: the surveyed ground, since their absolute heights are good to
      centimetres;
    * otherwise its own ground where at least half its frames have one (DJI: the take-off point,
      AbsoluteAltitude − RelativeAltitude): a barometric or single-point height can be tens of metres off, but
      by the same amount as the take-off height derived from it, so height minus own ground stays right while
      height minus surveyed ground does not;
    * else the surveyed ground; without geotags, the own ground, or none;
    * but first, where ``terrain`` (per frame, :func:`terrain_grounds`: a DEM converted into the frames'
      reference and checked against their ground) covers at least half of a camera's frames: that terrain,
      measured under each frame, where a take-off point or a level plane of geotags is one height for the site.

    The choice warns when the ground used is one height for the site (:data:`SITE_GROUND_WORDS`): terrain under
    the frames above or below it scales the focal length by that difference over the flying height.
    """
    terrain = np.full(len(frames), np.nan) if terrain is None else np.asarray(terrain, dtype=float)
    surveyed = np.asarray([] if geotag_heights is None else geotag_heights, dtype=float)
    surveyed = surveyed[np.isfinite(surveyed)]
    ground = np.full(len(frames), np.nan)
    choices = []
    for idx in indices_by_camera(frames.cameras):
        own = frames.ground_h[idx]
        has_own = np.isfinite(own)
        own_m = float(np.median(own[has_own])) if has_own.any() else math.nan
        own_source = Counter(frames.ground_source[i] for i in idx[has_own]).most_common(1)[0][0] if has_own.any() \
            else NO_GROUND
        rtk = bool(np.mean(frames.rtk_status[idx] == RTK_FIXED) >= 0.5)
        surveyed_m, surveyed_z, conversion, comparable = math.nan, math.nan, "", True
        if len(surveyed) and frames.reference.kind == UNKNOWN:
            comparable = False
        elif len(surveyed):
            shift = height_shift(ELLIPSOIDAL_REFERENCE, frames.reference, frames.lat[idx], frames.lon[idx],
                                 geoid_undulation_m)
            surveyed_z = float(np.median(surveyed)) + shift.offset_m
            surveyed_m, conversion = float(np.median(surveyed_z)), shift.note
        mostly_own = has_own.mean() >= 0.5
        has_terrain = np.isfinite(terrain[idx])
        terrain_m = float(np.median(terrain[idx][has_terrain])) if has_terrain.any() else math.nan
        if has_terrain.mean() >= 0.5:
            used, reason = TERRAIN_GROUND, (
                "the DEM holds the terrain under each frame (converted into the frames' heights and checked against "
                "their ground), where the take-off point or the geotags give one height for the whole site")
        elif not len(surveyed) or not comparable:
            used = OWN_GROUND if has_own.any() else ""
            reason = "no geotags were given" if not len(surveyed) else (
                "the frames' heights are in an unstated vertical reference, so the geotags' ellipsoidal heights "
                "cannot be compared with them")
        elif rtk:
            used, reason = SURVEYED_GROUND, ("most frames have an RTK fix: their absolute heights are good to "
                                             "centimetres, and the geotags survey the ground itself")
        elif mostly_own:
            used, reason = OWN_GROUND, (
                "the frames have no RTK fix: their absolute heights can be tens of metres off (a barometric or "
                "single-point height), and their own ground, derived from the same heights, carries the same offset, "
                "which cancels in camera height minus ground")
        else:
            used, reason = SURVEYED_GROUND, "most frames have no ground of their own"
        if used == OWN_GROUND:
            ground[idx] = own
        elif used == SURVEYED_GROUND:
            ground[idx] = surveyed_z
        elif used == TERRAIN_GROUND:
            ground[idx] = terrain[idx]
        warning = ""
        if used == OWN_GROUND and own_source in SITE_GROUND_WORDS:
            warning = (f"the ground is only {SITE_GROUND_WORDS[own_source]}: where the terrain under the frames lies "
                       "above or below it, the focal length is off by that difference over the flying height (4 m "
                       "at 40 m: 10 %)" + ("" if math.isfinite(surveyed_m) else
                                           "; geotags with surveyed heights (GEOTAGS) would show by how much"))
        choices.append(GroundChoice(tuple(int(i) for i in idx), rtk, own_m, own_source, surveyed_m, used, reason,
                                    warning, conversion, terrain_m))
    return ground, choices


def ground_text(choice: GroundChoice, frames) -> str:
    """A :class:`GroundChoice` in words, for the log and the report."""
    reference = frames.reference.describe()
    camera = _camera_label(frames.image[choice.frames[0]])
    words = {OWN_GROUND: "the frames' own ground", SURVEYED_GROUND: "the geotags' surveyed ground",
             TERRAIN_GROUND: "the DEM's terrain under each frame"}
    parts = [f"{camera} ({len(choice.frames)} frames): "
             + (f"GNSS camera-to-ground distances measured from {words[choice.used]} ({choice.used_m:.2f} m "
                f"{reference})" if choice.used else "no ground to measure camera-to-ground distances from")
             + f", because {choice.reason}"]
    if math.isfinite(choice.own_m):
        parts.append(f"own ground {choice.own_m:.2f} m ({choice.own_source or 'source not stated'})")
    if math.isfinite(choice.surveyed_m):
        parts.append(f"surveyed ground {choice.surveyed_m:.2f} m ({choice.conversion or 'no conversion'})")
    if math.isfinite(choice.terrain_m):
        parts.append(f"the DEM's terrain in view {choice.terrain_m:.2f} m (median)"
                     + (f", {choice.terrain_m - choice.own_m:+.2f} m from the own ground" if math.isfinite(choice.own_m)
                        else ""))
    if math.isfinite(choice.difference_m):
        parts.append(f"the surveyed ground lies {abs(choice.difference_m):.2f} m "
                     f"{'above' if choice.difference_m >= 0 else 'below'} the own ground: an offset of the drone's "
                     "absolute heights, or terrain under the frames that much off the take-off point")
    return "; ".join(parts)


#: Flags describing where an import's ground height came from, which a ground from the tie points replaces.
IMPORT_GROUND_FLAGS = ("no_ground_height", "ground_from_flight_height", "ground_from_dem")


def refine_frames(frames, workdir, options: RefineOptions | None = None, progress=None, is_canceled=None,
                  geotag_heights=None, geoid_undulation_m: float | None = None, terrain=None):
    """Refined :class:`.frames.Frames` (registered frames moved, flagged ``refined``; the others unchanged,
    flagged ``not_refined``), the :class:`Refinement`, and per-frame :data:`REFINE_FIELDS` values.

    A nominal camera's focal length is fixed by the flying height above the ground :func:`choose_grounds` picks
    from the frames' own ground, ``geotag_heights`` (ellipsoidal, m; ``geoid_undulation_m`` as there) and
    ``terrain`` (per frame, :func:`terrain_grounds`); the choices are in :attr:`Refinement.grounds`. The refined
    frames keep ``frames.reference``; a registered frame with enough tie points gets their median height as its
    ground (ground source ``tie_points``), the others keep theirs.
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
    ground_h, grounds = choose_grounds(frames, geotag_heights, geoid_undulation_m, terrain)
    ground_z = local.from_geodetic(frames.lat, frames.lon, ground_h)[:, 2]
    inputs = [FrameInput(Path(frames.image[i]) if frames.image[i] else None, frames.cameras[i], centres[i],
                         rotations[i], float(sigma[i]), float(ground_z[i]), APPROX_INTRINSICS_FLAG in frames.flags[i])
              for i in range(len(frames))]
    refinement = refine_poses(inputs, workdir, options, progress, is_canceled)
    refinement.grounds = grounds
    out = replace(frames, lat=frames.lat.copy(), lon=frames.lon.copy(), height=frames.height.copy(),
                  quat=frames.quat.copy(), ground_h=frames.ground_h.copy(), cameras=list(frames.cameras),
                  flags=[list(f) for f in frames.flags], euler_deg=None if frames.euler_deg is None
                  else frames.euler_deg.copy(), ground_source=list(frames.ground_source))
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
            out.ground_source[i] = TIE_POINTS
            out.flags[i] = [f for f in out.flags[i] if f not in IMPORT_GROUND_FLAGS]
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
    if refinement.grounds:
        body.append(_grounds_html(refinement.grounds, frames))
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


def _grounds_html(grounds, frames) -> str:
    """The report's table of :class:`GroundChoice` per camera, with the reasons and warnings."""
    import html

    from ..scoring.reports import html_table

    words = {OWN_GROUND: "own", SURVEYED_GROUND: "surveyed (geotags)", TERRAIN_GROUND: "DEM terrain", "": "none"}
    rows = [[_camera_label(frames.image[g.frames[0]]), len(g.frames), "yes" if g.rtk else "no", _finite(g.own_m),
             g.own_source or None, _finite(g.surveyed_m), _finite(g.difference_m), _finite(g.terrain_m),
             words[g.used]] for g in grounds]
    reference = frames.reference.describe()
    out = [f"<p>Ground the GNSS camera-to-ground distances are measured from (heights in m, {html.escape(reference)}):"
           "</p>", html_table(["camera", "frames", "RTK fix", "own ground", "own ground from", "surveyed ground",
                               "surveyed − own", "DEM terrain in view", "used"], rows)]
    for g in grounds:
        camera = html.escape(_camera_label(frames.image[g.frames[0]]))
        out.append(f"<p>{camera}: {html.escape(g.reason)}"
                   + (f"; geotag heights {html.escape(g.conversion)}" if g.conversion else "") + ".</p>")
        if g.warning:
            out.append(f"<p class='note'><b>Warning</b> ({camera}): {html.escape(g.warning)}.</p>")
    return "".join(out)
