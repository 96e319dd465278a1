"""Band-limited periodic noise textures, sampled at ground coordinates.

The simulated field's soil, leaves and clouds are sums of noise "octaves". Each octave is a small
periodic texture made once per campaign (white noise shaped in the Fourier domain, so its spectrum
and its exact gradient are known) and sampled per pixel with ``cv2.remap`` at the pixel's ground
point — a GPU-style texture fetch, far cheaper than evaluating value noise in numpy. Every texture
is rotated and offset at random on the ground, so periodicities of different textures never line up.
"""
from __future__ import annotations

import math

import numpy as np


def periodic_noise(rng: np.random.Generator, size: int, wavelength_px: tuple[float, float],
                   slope: float = 1.0):
    """A zero-mean, unit-variance periodic noise (size × size) and its gradient (per texel).

    The amplitude spectrum is ``k^-slope`` between the wavelengths ``wavelength_px = (shortest,
    longest)`` (texels), with Gaussian roll-offs, so the texture has no content above Nyquist.
    Returns (value, d/du, d/dv) float64 arrays; u runs along columns, v along rows.
    """
    white = rng.standard_normal((size, size))
    spectrum = np.fft.rfft2(white)
    kv = np.fft.fftfreq(size)[:, None]
    ku = np.fft.rfftfreq(size)[None, :]
    k = np.hypot(ku, kv)
    k[0, 0] = 1.0
    short, long = wavelength_px
    amp = k ** (-slope) * np.exp(-(k * short / 2.0) ** 2) * (1.0 - np.exp(-(k * long) ** 2))
    amp[0, 0] = 0.0
    spectrum *= amp
    value = np.fft.irfft2(spectrum, s=(size, size))
    std = value.std()
    d_du = np.fft.irfft2(spectrum * (2j * math.pi * ku), s=(size, size)) / std
    d_dv = np.fft.irfft2(spectrum * (2j * math.pi * kv), s=(size, size)) / std
    return value / std, d_du, d_dv


class GroundTexture:
    """A periodic multi-channel texture laid on the ground with a texel size, rotation and offset.

    ``sample(east, north)`` returns the channels at ground points (float32 arrays of any 2-D shape),
    bilinearly interpolated; the wrap-around makes it tile the plane. ``to_texture_axes`` turns a
    ground vector into the texture's (u, v) axes (for gradient channels, which are per texel).
    """

    def __init__(self, data: np.ndarray, texel_m: float, angle_rad: float, offset_px):
        data = np.asarray(data, dtype=np.float32)
        if data.ndim == 2:
            data = data[..., None]
        # cv2.remap is several times faster on 1, 2 and 4 channels than on 3.
        if data.shape[2] == 3:
            data = np.concatenate([data, np.zeros_like(data[..., :1])], axis=2)
        self.data = np.ascontiguousarray(data)
        self.size = data.shape[0]
        self.texel_m = float(texel_m)
        self.cos, self.sin = math.cos(angle_rad), math.sin(angle_rad)
        self.offset = (float(offset_px[0]), float(offset_px[1]))

    def to_texture_axes(self, vec_east_north) -> tuple[float, float]:
        """(u, v) components of a ground vector (east, north)."""
        e, n = vec_east_north
        return self.cos * e + self.sin * n, -self.sin * e + self.cos * n

    def sample(self, east: np.ndarray, north: np.ndarray, shift_m=(0.0, 0.0)) -> np.ndarray:
        """Channels (…, C) at ground points ``(east − shift_e, north − shift_n)``."""
        import cv2

        k = np.float32(1.0 / self.texel_m)
        e0 = np.float32(self.offset[0] - k * (self.cos * shift_m[0] + self.sin * shift_m[1]))
        n0 = np.float32(self.offset[1] - k * (-self.sin * shift_m[0] + self.cos * shift_m[1]))
        u = east * np.float32(k * self.cos) + north * np.float32(k * self.sin) + e0
        v = north * np.float32(k * self.cos) - east * np.float32(k * self.sin) + n0
        n = np.float32(self.size)
        inv = np.float32(1.0 / self.size)
        # Wrapping in-range first keeps cv2.remap on its fast path (BORDER_WRAP only interpolates
        # across the seam then).
        u -= n * np.floor(u * inv)
        v -= n * np.floor(v * inv)
        out = cv2.remap(self.data, u, v, interpolation=cv2.INTER_LINEAR, borderMode=cv2.BORDER_WRAP)
        return out if out.ndim == 3 else out[..., None]

    def sample_points(self, east, north) -> np.ndarray:
        """Channels (N, C) at a few points (bilinear, in numpy; for per-frame scalars)."""
        east, north = np.atleast_1d(np.asarray(east, float)), np.atleast_1d(np.asarray(north, float))
        k = 1.0 / self.texel_m
        u = (self.cos * east + self.sin * north) * k + self.offset[0]
        v = (-self.sin * east + self.cos * north) * k + self.offset[1]
        u0, v0 = np.floor(u), np.floor(v)
        fu, fv = (u - u0)[:, None], (v - v0)[:, None]
        i0, j0 = u0.astype(np.int64) % self.size, v0.astype(np.int64) % self.size
        i1, j1 = (i0 + 1) % self.size, (j0 + 1) % self.size
        d = self.data
        return ((1 - fv) * ((1 - fu) * d[j0, i0] + fu * d[j0, i1])
                + fv * ((1 - fu) * d[j1, i0] + fu * d[j1, i1]))
