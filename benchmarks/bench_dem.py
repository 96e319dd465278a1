"""Back-projecting 1,000,000 pixels onto a hilly 1 m DEM (500 m × 500 m) with the DEM ground model.

Goal: under 2 s. The pixels come from four frames 10–20 m above the terrain (tilts of a few
degrees, any heading), spread uniformly over the image. Baselines: a naive ray march at a fixed
0.1 m step along every ray (from the top of the terrain's height range, linear interpolation in the
last step; timed on a subset and scaled), and the level-plane ground model on the same pixels.
"""
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time

import _path  # noqa: F401
import numpy as np

from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.dem import DemGround, intersect_heightfield
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import pixel_to_ground
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from birdseye.birdseye_qgis.core.sim.terrain import synthetic_terrain

N_PIXELS = 1_000_000
GOAL_S = 2.0
SITE = (-27.55, 151.95, 400.0)
NAIVE_STEP_M = 0.1
NAIVE_SUBSET = 20_000


def campaign(seed=0, tilt_deg=3.0):
    """DEM, poses of four frames 10–20 m above the terrain (roll, pitch ~ N(0, tilt_deg)), and pixels."""
    rng = np.random.default_rng(seed)
    dem = synthetic_terrain(SITE[0], SITE[1], "hills", slope_deg=4.0, aspect_deg=200.0, relief_m=20.0,
                            base_height_m=SITE[2], size_m=500.0, cell_m=1.0, wavelength_m=60.0, seed=seed)
    t = np.eye(4)
    t[:3, :3] = [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]
    t[:3, 3] = [0.03, -0.08, 0.05]
    cam = CameraModel(1920, 1200, 4264.4945, 4262.8927, 958.4594, 592.5033,
                      (-0.08, 0.12, 4e-4, -3e-4, 0.0), t)
    local = LocalFrame(*SITE)
    n_frames = 4
    east, north = rng.uniform(-150, 150, n_frames), rng.uniform(-150, 150, n_frames)
    lat, lon, _ = local.to_geodetic(np.column_stack([east, north, np.zeros(n_frames)]))
    terrain = dem.sample_geodetic(lat, lon)
    agl = np.array([10.0, 13.0, 16.0, 20.0])
    q = rotmat_to_quat(euler_zyx_to_rotmat(np.radians(rng.normal(0, tilt_deg, n_frames)),
                                           np.radians(rng.normal(0, tilt_deg, n_frames)),
                                           np.radians(rng.uniform(0, 360, n_frames))))
    poses = FramePoses(np.arange(n_frames), lat, lon, terrain + agl, q, terrain, cam)
    frame_idx = rng.integers(0, n_frames, N_PIXELS)
    uv = rng.uniform([-0.5, -0.5], [cam.width - 0.5, cam.height - 0.5], (N_PIXELS, 2))
    return dem, poses, local, frame_idx, uv


def naive_march(hf, origins, directions, step_m=NAIVE_STEP_M):
    """Fixed steps of ``step_m`` along each ray from the slab top; linear interpolation in the last step."""
    speed = np.linalg.norm(directions, axis=1)
    t = np.maximum((hf.z_max - origins[:, 2]) / directions[:, 2], 0.0)
    dt = step_m / speed
    f_prev = np.full(len(origins), np.inf)
    t_hit = np.full(len(origins), np.nan)
    act = np.arange(len(origins))
    while len(act):
        p = origins[act] + t[act, None] * directions[act]
        f = p[:, 2] - hf.height_at(p[:, 0], p[:, 1])
        hit = f <= 0
        idx = act[hit]
        frac = np.where(np.isfinite(f_prev[idx]), f_prev[idx] / (f_prev[idx] - f[hit]), 1.0)
        t_hit[idx] = t[idx] - (1.0 - frac) * dt[idx]
        gone = np.isnan(f)
        f_prev[act] = f
        act = act[~(hit | gone)]
        t[act] += dt[act]
    return t_hit


def timed(fn, *args, repeat=3):
    """(result, wall s, CPU s), each the best of ``repeat`` runs: on a shared machine the CPU time is the
    fair figure, and the best run the one least disturbed."""
    walls, cpus = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn(*args)
        walls.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    return out, min(walls), min(cpus)


def main():
    dem, poses, local, frame_idx, uv = campaign()
    geom = FrameGeometry(poses, local)
    ground, t_build, _ = timed(DemGround.from_dem, geom, dem, repeat=1)
    hf = ground.heightfield
    gradient = np.hypot(*np.gradient(hf.z, hf.step))
    pixel_to_ground(geom, ground, frame_idx[:1000], uv[:1000])  # warm-up

    rays, t_rays, c_rays = timed(geom.rays, frame_idx, uv)
    hits, t_cast, c_cast = timed(intersect_heightfield, hf, geom.C[frame_idx], rays, ground.nadir_height[frame_idx])
    (pts, valid), t_total, c_total = timed(pixel_to_ground, geom, ground, frame_idx, uv)
    assert np.array_equal(valid, hits.valid)
    _, t_level, c_level = timed(pixel_to_ground, geom, LevelPlaneGround(geom), frame_idx, uv)

    sub = slice(0, NAIVE_SUBSET)
    t_naive_hit, t_naive, c_naive = timed(naive_march, hf, geom.C[frame_idx[sub]], rays[sub], repeat=1)
    scale = N_PIXELS / NAIVE_SUBSET
    naive_pts = geom.C[frame_idx[sub]] + t_naive_hit[:, None] * rays[sub]
    gap = np.linalg.norm(naive_pts - hits.points[sub], axis=1)

    slope_max, slope_median = np.degrees(np.arctan([np.nanmax(gradient), np.nanmedian(gradient)]))
    print(f"DEM {dem.heights.shape[1]} × {dem.heights.shape[0]} cells of {dem.cell_size_m:g} m, relief "
          f"{np.nanmax(dem.heights) - np.nanmin(dem.heights):.1f} m, slopes up to {slope_max:.0f}° "
          f"(median {slope_median:.0f}°); heightfield {hf.shape[1]} × {hf.shape[0]} nodes, tiles of "
          f"{hf.tile_cells} cells, built in {t_build:.2f} s (once per run)")
    print(f"back-projection of {N_PIXELS:,} pixels from {len(geom)} frames at "
          f"{', '.join(f'{h:.0f}' for h in geom.depth_below())} m (wall / CPU seconds; on a shared machine "
          "the CPU time is the fair figure; best of 3):")
    print(f"  total (pixel_to_ground): {t_total:.3f} / {c_total:.3f} s = {N_PIXELS / c_total / 1e6:.2f} M rays/s "
          f"(CPU) — {c_total / GOAL_S:.2f} of the {GOAL_S:g} s goal ({GOAL_S / c_total:.1f}x under)")
    print(f"    pixel rays (undistortion): {t_rays:.3f} / {c_rays:.3f} s; ray casting: {t_cast:.3f} / {c_cast:.3f} s "
          f"= {N_PIXELS / c_cast / 1e6:.2f} M rays/s")
    print(f"  valid {hits.valid.mean():.2%}; marched (not certifiable for the fast path) {hits.marched.mean():.2%}")
    print(f"  level-plane ground on the same pixels: {t_level:.3f} / {c_level:.3f} s "
          f"(the DEM costs {c_total / c_level:.2f}x)")
    print(f"  naive baseline, fixed {NAIVE_STEP_M:g} m march (on {NAIVE_SUBSET:,} rays, scaled): "
          f"{t_naive * scale:.1f} / {c_naive * scale:.1f} s for the casting alone; ours is "
          f"{c_naive * scale / c_cast:.0f}x faster (casting), {c_naive * scale / c_total:.0f}x (total); "
          f"max gap to ours {np.nanmax(gap) * 1e3:.2f} mm")

    # Stress: the same terrain seen obliquely (tilts ~25°), where many rays cannot be certified.
    dem, poses, local, frame_idx, uv = campaign(tilt_deg=25.0)
    geom = FrameGeometry(poses, local)
    ground = DemGround.from_dem(geom, dem)
    (_, valid), t_obl, c_obl = timed(pixel_to_ground, geom, ground, frame_idx, uv)
    hits = intersect_heightfield(ground.heightfield, geom.C[frame_idx], geom.rays(frame_idx, uv),
                                 ground.nadir_height[frame_idx])
    tilts = np.degrees(np.arccos(np.clip(geom.R_local_cam[:, 2, 2] * -1.0, -1, 1)))
    print(f"  oblique stress (optical axes {', '.join(f'{a:.0f}' for a in tilts)}° off nadir): "
          f"{t_obl:.3f} / {c_obl:.3f} s total; valid {valid.mean():.2%}, marched {hits.marched.mean():.2%}")


if __name__ == "__main__":
    main()
