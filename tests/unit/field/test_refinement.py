"""Pose refinement without QGIS: the alignment onto GNSS positions (synthetic, closed form), a nominal
camera's focal length fixed by the flying height (a synthetic COLMAP model where the answer is known) and
the pycolmap run on real DJI frames (cancel, missing images)."""
from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import Cancelled
from birdseye.birdseye_qgis.core.field.dji import import_dji_images
from birdseye.birdseye_qgis.core.field.refinement import (
    FrameInput,
    RefinedFrame,
    Refinement,
    align_to_gnss,
    gnss_sigma_m,
    refine_poses,
)
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.rotations import so3_exp

BRIGHTON = Path(__file__).resolve().parents[2] / "data" / "brighton_beach_960"
CAMERA = CameraModel(960, 540, 530.0, 530.0, 479.5, 269.5)
TRUE_ROTATION = so3_exp(np.array([0.02, -0.01, 1.3]))


def block(n=8, seed=0, line=False):
    """True camera centres/rotations (local frame) and the same block as SfM sees it (scaled, turned)."""
    rng = np.random.default_rng(seed)
    centres = np.column_stack([np.arange(n) * 8.0, np.zeros(n) if line else rng.uniform(-20, 20, n),
                               40 + rng.normal(scale=0.3, size=n)])
    rotations = np.stack([so3_exp(rng.normal(scale=0.05, size=3)) for _ in range(n)])
    # SfM frame: x_sfm = R_true^T (x_local - t) / s
    s, t = 4.0, np.array([100.0, -50.0, 3.0])
    sfm_centres = (centres - t) @ TRUE_ROTATION / s
    sfm_rotations = np.einsum("ji,njk->nik", TRUE_ROTATION, rotations)
    return centres, rotations, sfm_centres, sfm_rotations


def refinement_of(sfm_centres, sfm_rotations):
    frames = [RefinedFrame(True, centre=c.copy(), r_local_cam=r.copy(), camera=CAMERA,
                           tie_points=np.zeros((30, 3)) + c - [0, 0, 10.0])
              for c, r in zip(sfm_centres, sfm_rotations)]
    return Refinement(frames)


@pytest.mark.parametrize("line", [False, True])
def test_alignment_recovers_the_block_exactly(line):
    centres, rotations, sfm_c, sfm_r = block(line=line)
    # Metadata attitudes are off by a degree: the positions must still rule where they can.
    meta_r = np.stack([so3_exp(np.array([0.0, 0.017, 0.0])) @ r for r in rotations]) if not line else rotations
    inputs = [FrameInput(None, CAMERA, c, r, 0.03) for c, r in zip(centres, meta_r)]
    refinement = refinement_of(sfm_c, sfm_r)
    align_to_gnss(refinement, inputs)
    assert refinement.collinear == line
    for frame, c, r in zip(refinement.frames, centres, rotations):
        np.testing.assert_allclose(frame.centre, c, atol=1e-6)
        np.testing.assert_allclose(frame.r_local_cam, r, atol=1e-9)
        assert frame.position_change_m < 1e-6
    assert refinement.alignment_rms_m < 1e-6
    # Tie points 10 units along −z of the SfM frame from each camera: 4 × that vector, turned, in metres.
    below = 4.0 * TRUE_ROTATION @ np.array([0.0, 0.0, -10.0])
    assert refinement.frames[0].ground_z_local == pytest.approx(centres[0, 2] + below[2], abs=1e-6)


def test_a_gross_gnss_outlier_is_left_out_of_the_alignment():
    centres, rotations, sfm_c, sfm_r = block(n=10, seed=3)
    meta_c = centres.copy()
    meta_c[4] += [6.0, -3.0, 2.0]  # a single-point fix among RTK-fixed frames
    inputs = [FrameInput(None, CAMERA, c, r, 0.03) for c, r in zip(meta_c, rotations)]
    refinement = refinement_of(sfm_c, sfm_r)
    align_to_gnss(refinement, inputs)
    assert not refinement.frames[4].used_in_alignment
    assert refinement.frames[4].alignment_residual_m == pytest.approx(math.hypot(6, 3, 2), abs=1e-6)
    np.testing.assert_allclose(refinement.frames[4].centre, centres[4], atol=1e-6)
    assert "left out of the alignment" in " ".join(refinement.notes)


def test_gnss_sigma_from_dji_std_else_from_rtk_status():
    class FakeFrames:
        rtk_status = np.array([3, 2, 1, 3])
        extra = {"rtk_std_lon_m": np.array([0.02, np.nan, np.nan, 0.0]),
                 "rtk_std_lat_m": np.array([0.02, np.nan, np.nan, 0.0]),
                 "rtk_std_hgt_m": np.array([0.05, np.nan, np.nan, 0.0])}

    sigma = gnss_sigma_m(FakeFrames())
    assert sigma[0] == pytest.approx(math.sqrt((0.02 ** 2 * 2 + 0.05 ** 2) / 3))
    assert sigma[1:].tolist() == [0.5, 3.0, 0.03]


def brighton_inputs(tmp_path, drop=()):
    """The six real frames as importdjiimages places them; ``drop`` images are removed afterwards."""
    images = tmp_path / "images"
    shutil.copytree(BRIGHTON, images, ignore=shutil.ignore_patterns("*.md", "LICENSE"))
    frames = import_dji_images(images).frames
    for name in drop:
        (images / name).unlink()
    local = LocalFrame.around(frames.lat, frames.lon, frames.height)
    geometry = FrameGeometry(FramePoses(frames.frame_id, frames.lat, frames.lon, frames.height, frames.quat,
                                        frames.ground_h, frames.cameras[0]), local)
    return [FrameInput(Path(frames.image[i]), frames.cameras[i], geometry.C[i], geometry.R_local_cam[i], 3.0)
            for i in range(len(frames))]


def test_cancel_stops_the_structure_from_motion_before_its_next_stage(tmp_path):
    """Cancel asked for from the start: refine_poses raises Cancelled during feature extraction, and no later
    stage runs (no match in the database, no mapping folder). How soon it returns after the request is
    benchmarks/bench_refineposes.py's figure, not a test's."""
    import sqlite3

    import pycolmap  # noqa: F401  (refineposes needs it: a missing install fails here, not skips)
    inputs = brighton_inputs(tmp_path)
    asked = []
    with pytest.raises(Cancelled):
        refine_poses(inputs, tmp_path / "work", is_canceled=lambda: asked.append(1) or True)
    assert asked, "the cancel callback was never asked"
    assert not (tmp_path / "work" / "sparse").exists(), "incremental mapping started after the cancel"
    with sqlite3.connect(tmp_path / "work" / "database.db") as db:
        assert db.execute("SELECT COUNT(*) FROM two_view_geometries").fetchone()[0] == 0, "matching ran"


def test_frames_without_images_are_reported_not_guessed(tmp_path):
    import pycolmap  # noqa: F401  (refineposes needs it: a missing install fails here, not skips)
    inputs = brighton_inputs(tmp_path, drop=("DJI_0023.JPG",))
    refinement = refine_poses(inputs, tmp_path / "work")
    assert [f.registered for f in refinement.frames] == [True, True, True, True, True, False]
    assert refinement.frames[5].reason == "image file not found"
    assert refinement.intrinsics.startswith("fixed to the frame layer's calibration")


def test_large_blocks_match_spatially_on_the_metadata_positions(tmp_path):
    """Beyond ``exhaustive_up_to`` frames, pairs come from the metadata positions: with images that carry
    no GPS tags of their own (re-encoded without EXIF), BirdsEye writes the pose priors itself."""
    import cv2
    import pycolmap

    from birdseye.birdseye_qgis.core.field.refinement import RefineOptions

    inputs = brighton_inputs(tmp_path)
    bare = tmp_path / "bare"
    bare.mkdir()
    for frame in inputs:
        cv2.imwrite(str(bare / frame.image.name), cv2.imread(str(frame.image)))
        frame.image = bare / frame.image.name
    refinement = refine_poses(inputs, tmp_path / "work", RefineOptions(exhaustive_up_to=2, spatial_neighbours=3))
    database = pycolmap.Database.open(str(tmp_path / "work" / "database.db"))
    try:
        assert database.num_pose_priors() == 6
        assert database.num_matched_image_pairs() < 15  # not every pair
    finally:
        database.close()
    assert refinement.n_registered == 6


F_TRUE, K1_TRUE, W, H = 1000.0, -0.05, 1200, 900
NADIR = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]]).T  # camera → ENU: x east, z down


def quaternion_wxyz(r):
    from scipy.spatial.transform import Rotation

    x, y, z, w = Rotation.from_matrix(r).as_quat()
    return w, x, y, z


def ambiguous_block(folder, focal, depth_factor, seed=0):
    """A flat nadir block (15 frames, 40 m up, ground ±0.5 m) as a bundle adjustment could leave it with a
    nominal camera: the focal length ``focal`` and every height above the cameras' plane × ``depth_factor``
    (the images barely change), in an SfM frame of its own. Observations from the true camera (f 1000 px).
    Returns the true centres and rotations (local ENU)."""
    rng = np.random.default_rng(seed)
    gx, gy = np.meshgrid(np.arange(-30.0, 31.0, 15.0), [-20.0, 0.0, 20.0])
    centres = np.column_stack([gx.ravel(), gy.ravel(), 40.0 + rng.normal(scale=0.2, size=gx.size)])
    rotations = np.stack([so3_exp(rng.normal(scale=0.02, size=3)) @ NADIR for _ in centres])
    ground = np.column_stack([rng.uniform(-55, 55, 3000), rng.uniform(-45, 45, 3000), rng.uniform(-0.5, 0.5, 3000)])
    tracks = {p: [] for p in range(len(ground))}
    points2d = []
    for i, (c, r) in enumerate(zip(centres, rotations)):
        cam = (ground - c) @ r
        xn = cam[:, :2] / cam[:, 2:]
        uv = F_TRUE * xn * (1 + K1_TRUE * np.sum(xn ** 2, axis=1))[:, None] + [W / 2, H / 2]
        seen = np.flatnonzero((cam[:, 2] > 0) & (uv[:, 0] > 0) & (uv[:, 0] < W) & (uv[:, 1] > 0) & (uv[:, 1] < H))
        points2d.append([(uv[p], p) for p in seen])
        for j, p in enumerate(seen):
            tracks[p].append((i + 1, j))
    zc = centres[:, 2].mean()
    stretch = np.array([1.0, 1.0, depth_factor])
    sfm_rot, sfm_scale, sfm_t = so3_exp(np.array([0.4, -0.3, 2.0])), 0.25, np.array([3.0, -1.0, 7.0])

    def to_sfm(x):
        return sfm_scale * ((x - [0, 0, zc]) * stretch + [0, 0, zc]) @ sfm_rot.T + sfm_t

    folder.mkdir(parents=True)
    k1 = K1_TRUE * depth_factor ** 2
    (folder / "cameras.txt").write_text(f"1 RADIAL {W} {H} {focal} {W / 2} {H / 2} {k1} 0.0\n")
    lines = []
    for i, (c, r) in enumerate(zip(centres, rotations)):
        r_cw = (sfm_rot @ r).T
        t = -r_cw @ to_sfm(c)
        lines.append(" ".join(map(str, [i + 1, *quaternion_wxyz(r_cw), *t])) + f" 1 img{i:02d}.jpg")
        lines.append(" ".join(f"{uv[0]} {uv[1]} {p + 1 if len(tracks[p]) >= 2 else -1}" for uv, p in points2d[i]))
    (folder / "images.txt").write_text("\n".join(lines) + "\n")
    xyz = to_sfm(ground)
    (folder / "points3D.txt").write_text("".join(
        f"{p + 1} {xyz[p][0]} {xyz[p][1]} {xyz[p][2]} 0 0 0 0.5 "
        + " ".join(f"{i} {j}" for i, j in track) + "\n" for p, track in tracks.items() if len(track) >= 2))
    return centres, rotations


def ambiguous_inputs(tmp_path, focal=1150.0, depth_factor=1.15, ground_z=0.0):
    """The block of :func:`ambiguous_block` as COLMAP would hand it over, nominal camera 1100 px, each frame's
    ground at ``ground_z`` (local; NaN: none): the reconstruction, the inputs, the names and the collected
    frames."""
    import pycolmap

    from birdseye.birdseye_qgis.core.field.refinement import _collect

    centres, rotations = ambiguous_block(tmp_path / "model", focal, depth_factor)
    rec = pycolmap.Reconstruction(str(tmp_path / "model"))
    nominal = CameraModel(W, H, 1100.0, 1100.0, W / 2 - 0.5, H / 2 - 0.5)
    inputs = [FrameInput(None, nominal, c, r, 0.03, ground_z, True) for c, r in zip(centres, rotations)]
    names = [f"img{i:02d}.jpg" for i in range(len(centres))]
    result = [RefinedFrame(False) for _ in names]
    _collect(rec, inputs, names, result)
    return rec, inputs, names, result


@pytest.mark.parametrize("surveyed", [True, False])
def test_a_nominal_focal_length_is_fixed_by_the_flying_height(tmp_path, surveyed):
    """The block left the focal length 15 % long and every depth 15 % deep; GNSS height minus the surveyed
    ground (z = 0) brings both back: f within 0.3 % of the truth, the ground within 5 cm. Without a surveyed
    ground the block cannot tell, and the nominal focal length (1100 px) is kept, said so."""
    from birdseye.birdseye_qgis.core.field.refinement import _collect, _fix_focal

    rec, inputs, names, result = ambiguous_inputs(tmp_path, ground_z=0.0 if surveyed else math.nan)
    rec, (fix,), stopped = _fix_focal(rec, inputs, names, result, None)
    assert stopped == "" and fix.settled
    assert fix.determined == surveyed and fix.adjusted_px == pytest.approx(1150.0)
    _collect(rec, inputs, names, result)
    refinement = Refinement(result)
    align_to_gnss(refinement, inputs)
    if surveyed:
        assert fix.block_depth_m == pytest.approx(1.15 * fix.gnss_depth_m, rel=0.01)
        assert fix.final_px == pytest.approx(F_TRUE, rel=0.003)
        assert all(abs(f.ground_z_local) < 0.05 for f in refinement.frames)
    else:
        assert fix.final_px == pytest.approx(1100.0) and "no ground height" in fix.reason
        # Nominal focal 10 % long: the block's ground lies ~10 % too deep, as a nominal camera must leave it.
        assert np.median([f.ground_z_local for f in refinement.frames]) == pytest.approx(-4.0, abs=0.5)
    assert max(f.reprojection_rms_px for f in refinement.frames) < 0.1


def test_a_focal_length_far_off_is_fixed_in_bounded_passes(tmp_path, monkeypatch):
    """Focal length and depths 80 % too long: no pass stretches the block by more than MAX_FOCAL_STEP, and the
    passes still end at the true focal length."""
    from birdseye.birdseye_qgis.core.field import refinement as module

    rec, inputs, names, result = ambiguous_inputs(tmp_path, focal=1800.0, depth_factor=1.8)
    stretches = []
    readjust = module._readjust
    monkeypatch.setattr(module, "_readjust", lambda rec, factor, sim, origin, stretch: (
        stretches.append(stretch), readjust(rec, factor, sim, origin, stretch))[1])
    rec, (fix,), stopped = module._fix_focal(rec, inputs, names, result, None)
    assert stopped == "" and fix.determined and fix.settled
    assert len(stretches) >= 2 and max(max(s, 1 / s) for s in stretches) <= module.MAX_FOCAL_STEP + 1e-9
    assert fix.final_px == pytest.approx(F_TRUE, rel=0.003)


def test_a_depth_ratio_outside_the_range_keeps_the_nominal_focal_length(tmp_path):
    """A ground 20 m above the true one makes the block's camera-to-ground distance 2.3 × the GNSS one: the
    heights or the ground are wrong, so the nominal focal length comes back instead of one 2.3 × too short."""
    from birdseye.birdseye_qgis.core.field.refinement import _fix_focal

    rec, inputs, names, result = ambiguous_inputs(tmp_path, ground_z=20.0)
    rec, (fix,), _ = _fix_focal(rec, inputs, names, result, None)
    assert not fix.determined and "outside 0.5–2" in fix.reason
    assert fix.final_px == pytest.approx(1100.0, rel=0.003)


def test_a_pass_that_breaks_the_block_is_undone_with_the_reason(tmp_path, monkeypatch):
    """A bundle adjustment that leaves a point not finite (as the unseen Brighton frames' second pass did): the
    pass is undone, the block of the pass before kept, the reason returned; nothing raises."""
    from birdseye.birdseye_qgis.core.field import refinement as module

    rec, inputs, names, result = ambiguous_inputs(tmp_path)
    adjust = module._bundle_adjust

    def breaking(rec):
        summary = adjust(rec)
        next(iter(rec.points3D.values())).xyz = np.full(3, np.nan)
        return summary

    monkeypatch.setattr(module, "_bundle_adjust", breaking)
    kept, (fix,), stopped = module._fix_focal(rec, inputs, names, result, None)
    assert kept is not rec and "not finite" in stopped and "pass 1" in stopped
    assert fix.final_px == pytest.approx(1150.0) and not fix.settled
    assert np.isfinite([p.xyz for p in kept.points3D.values()]).all()


def two_lines(flip_first: bool):
    """Two parallel flight lines of six frames 12 m apart, 40 m up, single-point GNSS (σ 3 m: too coarse to fix the
    rotation about the lines, so the attitudes do); the SfM block as in :func:`block`. With ``flip_first`` the
    first line's metadata attitudes are turned 180° about the vertical, as a heading logged the wrong way."""
    along = np.arange(6) * 14.0
    centres = np.column_stack([np.concatenate([along, along]), np.repeat([0.0, 12.0], 6), np.full(12, 40.0)])
    rotations = np.stack([so3_exp(np.array([0.0, 0.0, 0.3])) @ NADIR for _ in centres])
    s, t = 4.0, np.array([100.0, -50.0, 3.0])
    sfm_centres = (centres - t) @ TRUE_ROTATION / s
    sfm_rotations = np.einsum("ji,njk->nik", TRUE_ROTATION, rotations)
    meta = rotations.copy()
    if flip_first:
        meta[:6] = np.einsum("ij,njk->nik", so3_exp(np.array([0.0, 0.0, math.pi])), rotations[:6])
    return centres, rotations, meta, sfm_centres, sfm_rotations


def test_a_flight_line_logged_180_degrees_off_is_left_out_of_the_rotation():
    """The real frames DJI_0024–0029 of Brighton Beach carry a gimbal yaw 180° off their images. Averaged with the
    other line's, their attitudes turn the block to no line's rotation (there: a mirror image, negative scale,
    which the focal-length fix then stretched to NaN); the attitudes that agree fix the rotation, the others
    are named."""
    from birdseye.birdseye_qgis.core.geometry.similarity import fit_similarity_robust

    centres, rotations, meta, sfm_c, sfm_r = two_lines(flip_first=True)
    naive = fit_similarity_robust(sfm_c, centres, np.full(12, 3.0), rotation_pairs=(sfm_r, meta))
    assert naive.line and abs(naive.similarity.scale - 4.0) > 1.0  # what both lines' attitudes together give
    inputs = [FrameInput(None, CAMERA, c, r, 3.0) for c, r in zip(centres, meta)]
    refinement = refinement_of(sfm_c, sfm_r)
    align_to_gnss(refinement, inputs)
    assert refinement.collinear and refinement.similarity.scale == pytest.approx(4.0)
    for frame, c, r in zip(refinement.frames, centres, rotations):
        np.testing.assert_allclose(frame.centre, c, atol=1e-6)
        np.testing.assert_allclose(frame.r_local_cam, r, atol=1e-9)
    assert [round(f.rotation_change_deg) for f in refinement.frames] == [180] * 6 + [0] * 6
    note = " ".join(refinement.notes)
    assert "6 frame(s) have a metadata attitude 180°" in note and "frame 1, frame 2" in note


def test_agreeing_attitudes_are_used_as_given():
    centres, rotations, meta, sfm_c, sfm_r = two_lines(flip_first=False)
    inputs = [FrameInput(None, CAMERA, c, r, 3.0) for c, r in zip(centres, meta)]
    refinement = refinement_of(sfm_c, sfm_r)
    align_to_gnss(refinement, inputs)
    assert refinement.collinear and not refinement.notes
    np.testing.assert_allclose([f.centre for f in refinement.frames], centres, atol=1e-6)
