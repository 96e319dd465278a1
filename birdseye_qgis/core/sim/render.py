"""Render simulated frames: every pixel's ray through the true pose and the lens, onto the field.

For each pixel the camera's own back-projection (:meth:`~.camera.CameraModel.pixel_rays`, the inverse
of the distortion the labels later apply) gives the camera-frame ray, computed once per camera and
reused for every frame. A frame's true pose (:class:`~.poses.FrameGeometry`) turns the rays into the
local frame, the terrain (:mod:`.terrain`) gives their ground points, and the field
(:mod:`.field`) their radiance. The camera then adds what a real one does: vignetting, exposure and
white-balance drift, defocus and motion blur (kernels symmetric about the pixel, so a target's centre
does not move), shot and read noise, a tone curve, and JPEG compression.

Geometry runs in float64 for the pose and float32 per pixel relative to the camera centre (ground
offsets of metres, rounding in micrometres); pixel (0, 0) is the centre of the top-left pixel.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..geometry.camera import CameraModel
from ..geometry.poses import FrameGeometry
from ..geometry.projection import project_pairs
from .field import FieldScene
from .terrain import Terrain

COARSE = 4            # the smooth layers are evaluated on a grid this many times coarser
FULL_WELL = 9000.0    # electrons at a linear value of 1.0 (shot noise)
READ_NOISE = 0.0025   # linear units
NOISE_PAD = 64        # the per-frame noise is a random window into a precomputed bank
TONE_MAX_LINEAR = 1.6  # the tone curve's input range is 0…this linear value; brighter clips


@dataclass
class Photometry:
    """Per-frame camera state: exposure gain, white balance (R, G, B), defocus σ (px), motion
    blur (px, image u and v over the exposure)."""

    gain: float
    white_balance: tuple
    defocus_px: float
    motion_px: tuple


def base_exposure_gain(scene: FieldScene) -> float:
    """The camera's exposure before auto-exposure reacts to the clouds: the field's mean soil at a
    linear value of 0.30 (about 150 of 255 through the tone curve)."""
    return 0.30 / float(np.mean(scene.style.soil_rgb))


def blur_kernels(defocus_px: float, motion_px):
    """Separable blur (kernel along u, kernel along v): a Gaussian of σ ``defocus_px`` swept over
    the motion's u and v extents (px over the exposure).

    Each 1-D kernel is odd-sized and symmetric about its centre (the sweep is centred on the
    exposure's mid-time), so blurring moves no centroid. Sweeping the u and v components separately
    blurs a box instead of the diagonal streak, which makes no visible difference for the pixel or
    two a survey flight smears.
    """
    sigma = max(float(defocus_px), 0.3)
    out = []
    for motion in (abs(float(motion_px[0])), abs(float(motion_px[1]))):
        half = int(math.ceil(3.0 * sigma + 0.5 * motion))
        x = np.arange(-half, half + 1, dtype=float)
        kernel = sum(np.exp(-(x - t * motion) ** 2 / (2.0 * sigma * sigma)) for t in np.linspace(-0.5, 0.5, 17))
        kernel = 0.5 * (kernel + kernel[::-1])
        out.append((kernel / kernel.sum()).astype(np.float32))
    return out[0], out[1]


def tone_curve(levels: int = 65536, max_linear: float = TONE_MAX_LINEAR) -> np.ndarray:
    """8-bit output (uint8 lookup table) for linear values 0…max_linear: sRGB gamma with a soft
    highlight shoulder, as a camera's picture profile does."""
    x = np.linspace(0.0, max_linear, levels)
    knee = 0.8
    y = np.where(x < knee, x, knee + (1.0 - knee) * np.tanh((x - knee) / (1.0 - knee)))
    srgb = np.where(y <= 0.0031308, 12.92 * y, 1.055 * np.power(np.maximum(y, 0.0031308), 1 / 2.4) - 0.055)
    return np.clip(np.round(srgb * 255.0), 0, 255).astype(np.uint8)


def tone_map(linear: np.ndarray, lut: np.ndarray, factor: float = 1.0) -> np.ndarray:
    """8-bit values (uint8) of linear values (float32; scaled by ``factor`` and clipped in place)
    through a :func:`tone_curve` lookup table."""
    linear *= np.float32(factor) * np.float32((len(lut) - 1) / TONE_MAX_LINEAR)
    np.clip(linear, 0, len(lut) - 1, out=linear)
    return lut[linear.astype(np.uint16)]


class FrameRenderer:
    """Renders frames of one camera over one field (see the module docstring)."""

    def __init__(self, camera: CameraModel, scene: FieldScene, terrain: Terrain, seed: int,
                 local_feature_xyz: np.ndarray):
        """``local_feature_xyz``: the scene features' ground points (M, 3) in the local frame, used to
        find which features a frame sees; ``seed`` seeds the sensor-noise bank."""
        self.camera = camera
        self.scene = scene
        self.terrain = terrain
        self.feature_xyz = np.asarray(local_feature_xyz, float)
        w, h = camera.width, camera.height
        v, u = np.mgrid[0:h, 0:w]
        rays = camera.pixel_rays(np.stack([u, v], -1).astype(float))
        self.xn = np.ascontiguousarray(rays[..., 0], dtype=np.float32)
        self.yn = np.ascontiguousarray(rays[..., 1], dtype=np.float32)
        # Coarse grid at the pixel positions cv2.resize maps back onto (centre of each COARSE block).
        hc, wc = -(-h // COARSE), -(-w // COARSE)
        vc, uc = np.mgrid[0:hc, 0:wc].astype(float)
        uc = (uc + 0.5) * (w / wc) - 0.5
        vc = (vc + 0.5) * (h / hc) - 0.5
        rays_c = camera.pixel_rays(np.stack([uc, vc], -1))
        self.xn_c = np.ascontiguousarray(rays_c[..., 0], dtype=np.float32)
        self.yn_c = np.ascontiguousarray(rays_c[..., 1], dtype=np.float32)
        # Vignetting: cos⁵ of the ray angle (cos⁴ natural falloff plus a little of the lens barrel),
        # about 16 % darker in the corners of the deployed lens.
        cos2 = 1.0 / (1.0 + rays[..., 0] ** 2 + rays[..., 1] ** 2)
        self.vignette = (cos2 ** 2.5).astype(np.float32)
        self.tone = tone_curve()
        rng = np.random.default_rng(seed)
        self.noise_bank = rng.standard_normal((3, h + NOISE_PAD, w + NOISE_PAD), dtype=np.float32)

    def ground_points(self, geometry: FrameGeometry, frame: int):
        """Full and coarse ground points (east, north float32 grids) of a frame's pixels."""
        c, r = geometry.C[frame], geometry.R_local_cam[frame]
        east, north = self.terrain.intersect_grid(c, r, self.xn, self.yn)
        if np.isnan(east[[0, 0, -1, -1], [0, -1, 0, -1]]).any() or np.isnan(east).any():
            raise ValueError(f"frame {frame}: some pixels do not meet the ground (above the horizon or "
                             "past the terrain); the simulator renders near-nadir views only")
        east_c, north_c = self.terrain.intersect_grid(c, r, self.xn_c, self.yn_c)
        return east, north, east_c, north_c

    def feature_windows(self, geometry: FrameGeometry, frame: int, gsd_m: float):
        """(feature index, row slice, column slice) of the features this frame sees."""
        cam = self.camera
        c = geometry.C[frame]
        reach = 0.75 * gsd_m * math.hypot(cam.width, cam.height) + 0.5
        candidates = self.scene.features_near(c[0], c[1], reach)
        if not len(candidates):
            return []
        proj = project_pairs(geometry, np.full(len(candidates), frame), self.feature_xyz[candidates])
        windows = []
        for k, idx in enumerate(candidates):
            if not proj.in_front[k]:
                continue
            u, v = proj.uv[k]
            half = self.scene.features.extent[idx] * math.sqrt(cam.fx * cam.fy) / proj.depth[k] * 1.1 + 3
            u0, u1 = int(max(0, math.floor(u - half))), int(min(cam.width, math.ceil(u + half) + 1))
            v0, v1 = int(max(0, math.floor(v - half))), int(min(cam.height, math.ceil(v + half) + 1))
            if u0 < u1 and v0 < v1:
                windows.append((int(idx), slice(v0, v1), slice(u0, u1)))
        return windows

    def render(self, geometry: FrameGeometry, frame: int, time_s: float, photometry: Photometry,
               rng: np.random.Generator) -> np.ndarray:
        """The frame as an 8-bit BGR image (H, W, 3), as OpenCV writes it."""
        import cv2

        f32 = np.float32
        depth = float(geometry.depth_below()[frame])
        gsd = depth / math.sqrt(self.camera.fx * self.camera.fy)
        east, north, east_c, north_c = self.ground_points(geometry, frame)
        windows = self.feature_windows(geometry, frame, gsd)
        # Optics: vignetting and exposure on the light, then defocus and motion blur.
        rgb = self.scene.radiance(east, north, east_c, north_c, gsd, time_s, windows,
                                  gain=self.vignette * f32(photometry.gain))
        kx, ky = blur_kernels(photometry.defocus_px, photometry.motion_px)
        # Sensor: shot noise (variance ∝ signal) and read noise, on the raw channels.
        h, w = self.camera.height, self.camera.width
        dv, du = rng.integers(0, NOISE_PAD + 1, 2)
        sign = f32(1.0 if rng.random() < 0.5 else -1.0)
        planes = []
        for c in (2, 1, 0):   # OpenCV's BGR order
            plane = cv2.sepFilter2D(rgb[c], -1, kx, ky, borderType=cv2.BORDER_REFLECT)
            sigma = np.maximum(plane, f32(0.0))
            sigma *= f32(1.0 / FULL_WELL)
            sigma += f32(READ_NOISE ** 2)
            np.sqrt(sigma, out=sigma)
            sigma *= self.noise_bank[c, dv:dv + h, du:du + w]
            plane += sigma if sign > 0 else -sigma
            # Processing: white balance, then the tone curve to 8 bits.
            planes.append(tone_map(plane, self.tone, photometry.white_balance[c]))
        return cv2.merge(planes)


def motion_blur_px(geometry: FrameGeometry, frame: int, velocity_local, exposure_s: float):
    """Image-plane blur (px along u, v) of the ground at the image centre during one exposure."""
    cam = geometry.camera
    depth = float(geometry.depth_below()[frame])
    v_cam = geometry.R_local_cam[frame].T @ np.asarray(velocity_local, float)
    # The ground moves opposite to the camera: du = −fx·vx·T/Z, dv = −fy·vy·T/Z.
    return (-cam.fx * v_cam[0] * exposure_s / depth, -cam.fy * v_cam[1] * exposure_s / depth)
