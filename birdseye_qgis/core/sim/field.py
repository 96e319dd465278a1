"""The simulated field: soil, crop rows, clutter and burrow targets, shaded at ground coordinates.

Everything here is a function of the ground point (local east, north in metres, the site's
:class:`~.geodesy.LocalFrame`), so a frame is rendered by evaluating :meth:`FieldScene.radiance` at the
ground points of its pixels (see :mod:`.render`). Layers, from the bottom:

* **soil** — colour and moisture at metre scale, patches at decimetre scale, grain and clods at
  millimetre–centimetre scale (band-limited noise textures, :mod:`.texture`), micro-relief lit by
  the sun, and shrinkage cracks (thin dark lines) in some patches;
* **features** — the targets (burrows: a dark hole with a lighter crescent of loose soil) and
  target-sized look-alikes that are *not* targets: dark moist patches, shaded depressions, loose-soil
  mounds without a hole, large stones with their cast shadow, dung. Drawn analytically in ground
  coordinates, each in a pixel window around it, with edges anti-aliased by analytic coverage over at
  least one pixel's ground footprint, so a drawn centre is unbiased;
* **scatter** — small stones, clods, dark specks, straw and weed seedlings, one at most per 10 cm cell
  of a rotated grid, evaluated per pixel (with cast shadows);
* **crop rows** — rows of rosette seedlings (leaf count, size, orientation and hue per plant, missing
  plants and longer gaps, lateral jitter) with textured leaves and their shadows on the soil;
* **light** — sky (ambient) plus sun (direct), moving cloud shadows on the direct part.

:meth:`FieldScene.radiance` returns linear RGB radiance (before exposure, vignetting, blur, noise and
tone curve, which :mod:`.render` applies).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .texture import GroundTexture, periodic_noise

# Feature kinds. Only BURROW is a target; the others exist so a detector must learn the target,
# not "a dark blob" or "a light mound".
BURROW, DARK_PATCH, DEPRESSION, LOOSE_MOUND, STONE, DUNG = range(6)
FEATURE_NAMES = {BURROW: "burrow", DARK_PATCH: "dark_patch", DEPRESSION: "depression",
                 LOOSE_MOUND: "loose_mound", STONE: "stone", DUNG: "dung"}
# Distractor densities (per m²) at a density factor of 1.
DISTRACTOR_DENSITY = {DARK_PATCH: 0.25, DEPRESSION: 0.12, LOOSE_MOUND: 0.08, STONE: 0.15, DUNG: 0.04}
# Scatter kinds (small clutter, one per grid cell at most).
S_NONE, S_STONE, S_CLOD, S_SPECK, S_STRAW, S_WEED = range(6)
SCATTER_CELL_M = 0.10
TARGET_CLEARANCE_M = 0.35   # no look-alike this close to a target's edge
TARGET_SPACING_M = 0.6      # least distance between two targets
TARGET_MARGIN_M = 0.3       # targets keep this far inside the field's edge

# Feature parameter columns.
P_R, P_ASPECT, P_ANGLE, P_A2, P_PH2, P_A4, P_PH4, P_CONTRAST, P_OUTER, P_MOUND, P_CDIR, P_CSTR, \
    P_EDGE, P_HEIGHT, P_TONE = range(15)
N_PARAMS = 15

SOIL_PALETTE = np.array([
    [0.30, 0.22, 0.15],   # brown loam
    [0.15, 0.13, 0.11],   # black cracking clay (vertosol)
    [0.33, 0.18, 0.11],   # red ferrosol
    [0.42, 0.35, 0.26],   # light sandy loam
    [0.24, 0.19, 0.15],   # grey-brown clay
])


@dataclass
class SceneStyle:
    """The look of one field, drawn from the seed (all lengths in metres, angles in radians)."""

    soil_rgb: np.ndarray
    sun_azimuth: float           # from true north, clockwise
    sun_elevation: float
    direct_fraction: float       # share of the sun in the light on a horizontal surface
    cloudiness: float            # 0 clear … 1 broken cloud (depth of moving cloud shadows)
    cloud_velocity: tuple        # east, north (m/s)
    moisture_contrast: float
    crack_strength: float
    relief: float                # micro-relief amplitude factor
    crop: bool
    row_azimuth: float
    row_spacing: float
    plant_spacing: float
    plant_radius: float
    plant_height: float
    gap_rate: float              # long gaps per metre of row
    leaf_rgb: np.ndarray
    scatter_prob: dict

    @property
    def sun_vector(self) -> np.ndarray:
        """Unit vector towards the sun (east, north, up)."""
        ce = math.cos(self.sun_elevation)
        return np.array([math.sin(self.sun_azimuth) * ce, math.cos(self.sun_azimuth) * ce,
                         math.sin(self.sun_elevation)])

    @property
    def shadow_per_height(self) -> np.ndarray:
        """Horizontal displacement (east, north) of a shadow per metre of height of its caster."""
        s = self.sun_vector
        return -s[:2] / s[2]

    def to_dict(self) -> dict:
        return {"soil_rgb": [round(float(c), 4) for c in self.soil_rgb],
                "sun_azimuth_deg": round(math.degrees(self.sun_azimuth), 2),
                "sun_elevation_deg": round(math.degrees(self.sun_elevation), 2),
                "direct_fraction": round(self.direct_fraction, 3), "cloudiness": round(self.cloudiness, 3),
                "crop": self.crop, "row_azimuth_deg": round(math.degrees(self.row_azimuth), 2),
                "row_spacing_m": round(self.row_spacing, 3), "plant_spacing_m": round(self.plant_spacing, 3),
                "plant_radius_m": round(self.plant_radius, 3),
                "crack_strength": round(self.crack_strength, 3),
                "scatter_cell_probability": {k: round(v, 3) for k, v in self.scatter_prob.items()}}


def draw_style(rng: np.random.Generator, field_axis_azimuth: float) -> SceneStyle:
    """A random but plausible field look: soil, sun, sky, crop stage, clutter."""
    w = rng.dirichlet(np.full(len(SOIL_PALETTE), 0.4))
    soil = (w @ SOIL_PALETTE) * rng.uniform(0.85, 1.15)
    crop = rng.random() > 0.15
    row_az = field_axis_azimuth + rng.normal(0.0, math.radians(3.0))
    if rng.random() < 0.3:
        row_az = rng.uniform(0.0, math.pi)
    residue = rng.uniform(0.0, 0.12)
    return SceneStyle(
        soil_rgb=soil, sun_azimuth=rng.uniform(0.0, 2 * math.pi),
        sun_elevation=math.radians(rng.uniform(32.0, 68.0)),
        direct_fraction=rng.uniform(0.55, 0.8), cloudiness=rng.choice([0.0, rng.uniform(0.2, 0.7)]),
        cloud_velocity=tuple(rng.normal(0.0, 2.0, 2)), moisture_contrast=rng.uniform(0.10, 0.30),
        crack_strength=rng.uniform(0.0, 0.55), relief=rng.uniform(0.7, 1.3), crop=bool(crop),
        row_azimuth=float(row_az), row_spacing=rng.uniform(0.6, 0.9),
        plant_spacing=rng.uniform(0.05, 0.14), plant_radius=rng.uniform(0.025, 0.13),
        plant_height=rng.uniform(0.03, 0.12), gap_rate=rng.uniform(0.05, 0.4),
        leaf_rgb=np.array([0.055, 0.13, 0.035]) * rng.uniform(0.8, 1.25)
        * np.array([rng.uniform(0.8, 1.4), 1.0, rng.uniform(0.8, 1.3)]),
        scatter_prob={S_STONE: rng.uniform(0.02, 0.12), S_CLOD: rng.uniform(0.05, 0.2),
                      S_SPECK: rng.uniform(0.02, 0.07), S_STRAW: residue, S_WEED: rng.uniform(0.0, 0.04)})


@dataclass
class Features:
    """Windowed objects: targets first (rows 0…n_targets−1), then look-alikes."""

    kind: np.ndarray      # (M,) int
    xy: np.ndarray        # (M, 2) local east, north (m)
    extent: np.ndarray    # (M,) bounding radius incl. shadow (m)
    params: np.ndarray    # (M, N_PARAMS)

    def __len__(self) -> int:
        return len(self.kind)


def _smoothstep01(x):
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x)


def _coverage(signed_dist_m, width_m):
    """Analytic anti-aliased coverage of an edge: 1 inside, 0 outside, linear over ``width_m``."""
    return np.clip(0.5 + signed_dist_m / width_m, 0.0, 1.0)


class FieldScene:
    """A procedural field over a rectangular domain (local metres); see the module docstring."""

    def __init__(self, seed: np.random.SeedSequence, domain, field_half_size, n_targets: int,
                 field_axis_azimuth: float = math.pi / 2, distractor_density: float = 1.0):
        """``seed``: the scene's own seed sequence (one child stream per layer, so e.g. the
        targets do not move when the texture code changes); ``domain`` = (east_min, east_max,
        north_min, north_max) the camera may see; ``field_half_size`` = (half width east, half
        length north) of the surveyed field, centred on the local origin, where the targets lie."""
        self.domain = tuple(float(v) for v in domain)
        self.field_half = tuple(float(v) for v in field_half_size)
        streams = [np.random.default_rng(s) for s in seed.spawn(6)]
        self.style = draw_style(streams[0], field_axis_azimuth)
        self._textures = None
        self._texture_rng = streams[1]
        self._make_rows(streams[2])
        targets = self._make_targets(streams[4], n_targets)
        self._make_scatter(streams[3], targets)
        self.features = self._add_distractors(streams[5], targets, distractor_density)
        self.n_targets = n_targets

    # ------------------------------------------------------------------ construction
    @property
    def textures(self):
        """(fine, medium, coarse, cloud) textures, made on first use (rendering only)."""
        if self._textures is None:
            rng = self._texture_rng
            grain = periodic_noise(rng, 1024, (2.0, 10.0), 0.5)
            aggregates = periodic_noise(rng, 1024, (3.0, 24.0), 1.0)
            leaf = periodic_noise(rng, 1024, (2.0, 8.0), 0.5)
            clods = periodic_noise(rng, 1024, (6.0, 50.0), 1.0)
            moist = periodic_noise(rng, 512, (20.0, 400.0), 1.5)
            patch = periodic_noise(rng, 512, (4.0, 40.0), 1.0)
            gate = periodic_noise(rng, 512, (10.0, 200.0), 1.0)
            hue = periodic_noise(rng, 512, (8.0, 200.0), 1.0)
            cloud = periodic_noise(rng, 256, (6.0, 128.0), 1.5)

            def tex(channels, texel, size):
                return GroundTexture(np.stack(channels, -1), texel, rng.uniform(0, 2 * math.pi),
                                     rng.uniform(0, size, 2))

            # Relief channels hold a noise n and its gradient; the surface is h ∝ |n| ("billows":
            # rounded aggregates and clods with sharp creases between them, where cracks open).
            self._textures = (
                tex([grain[0], aggregates[0], aggregates[1], aggregates[2]], 0.0025, 1024),
                tex([leaf[0], clods[0], clods[1], clods[2]], 0.006, 1024),
                tex([moist[0], patch[0], gate[0], hue[0]], 0.05, 512),
                tex([cloud[0]], 1.0, 256),
            )
        return self._textures

    def _row_axes(self):
        a = self.style.row_azimuth
        along = np.array([math.sin(a), math.cos(a)])
        across = np.array([math.cos(a), -math.sin(a)])
        return along, across

    def _domain_corners(self):
        e0, e1, n0, n1 = self.domain
        return np.array([[e0, n0], [e1, n0], [e1, n1], [e0, n1]])

    def _make_rows(self, rng):
        """Crop rows as a table of plant cells: row k, cell j along the row holds at most one plant.

        Columns: present, centre along the cell (fraction), lateral offset (m), radius (m), leaf
        count, leaf phase (rad), hue, leaf narrowness, leaf-length seed. A plant's radius is at most
        0.9 of a cell and its centre within 0.1 of the cell middle, so it reaches only into the
        half of each neighbouring cell next to it — two cells per pixel suffice to draw it.
        """
        st = self.style
        along, across = self._row_axes()
        corners = self._domain_corners()
        s_range = corners @ along
        u_range = corners @ across
        self.row_k0 = int(math.floor(u_range.min() / st.row_spacing)) - 1
        n_rows = int(math.ceil(u_range.max() / st.row_spacing)) + 2 - self.row_k0
        self.plant_cell = max(st.plant_spacing, 1.1 * st.plant_radius)
        self.row_s0 = float(s_range.min()) - 0.5
        n_cells = int(math.ceil((float(s_range.max()) + 0.5 - self.row_s0) / self.plant_cell)) + 1
        shape = (n_rows, n_cells)
        present = rng.random(shape) > 0.08
        if st.crop:
            for k in range(n_rows):
                for _ in range(rng.poisson(st.gap_rate * n_cells * self.plant_cell)):
                    j0 = rng.integers(0, n_cells)
                    present[k, j0:j0 + int(rng.uniform(0.3, 1.5) / self.plant_cell) + 1] = False
        else:
            present[:] = False
        radius = np.minimum(st.plant_radius * rng.lognormal(0.0, 0.3, shape), 0.9 * self.plant_cell)
        table = np.stack([present, rng.uniform(0.4, 0.6, shape), rng.normal(0.0, 0.012, shape), radius,
                          rng.integers(3, 9, shape), rng.uniform(0.0, 2 * math.pi, shape),
                          rng.normal(0.0, 1.0, shape), rng.uniform(1.5, 5.0, shape),
                          rng.uniform(0.0, 100.0, shape)], -1)
        table = table.reshape(-1, table.shape[-1]).astype(np.float32)
        self.row_table = table
        self.row_table_near = np.ascontiguousarray(table[:, :4])   # gathered for every candidate
        self.row_shape = shape
        self.has_plants = bool(present.any())

    def canopy_clearance(self, east, north) -> float:
        """Distance (m) from a ground point to the nearest plant's outer radius (≤ 0: under a plant)."""
        st = self.style
        along, across = self._row_axes()
        p = np.array([east, north], float)
        s, u = p @ along, p @ across
        k = int(math.floor(u / st.row_spacing + 0.5))
        j = int(math.floor((s - self.row_s0) / self.plant_cell))
        best = np.inf
        for kk in (k - 1, k, k + 1):
            for jj in range(j - 2, j + 3):
                row = min(max(kk - self.row_k0, 0), self.row_shape[0] - 1)
                col = min(max(jj, 0), self.row_shape[1] - 1)
                present, frac, off, radius = self.row_table[row * self.row_shape[1] + col, :4]
                if not present:
                    continue
                cs = self.row_s0 + (jj + frac) * self.plant_cell
                cu = kk * st.row_spacing + off
                best = min(best, math.hypot(s - cs, u - cu) - radius)
        return best

    def _make_scatter(self, rng, targets: "Features"):
        """Small clutter on a rotated 10 cm grid: at most one object per cell, fitted inside it.
        Cells over a target (its loose soil) stay empty."""
        st = self.style
        self.scatter_angle = rng.uniform(0.0, math.pi / 2)
        c, s = math.cos(self.scatter_angle), math.sin(self.scatter_angle)
        corners = self._domain_corners()
        p = corners @ np.array([c, s])
        q = corners @ np.array([-s, c])
        self.scatter_origin = (float(p.min()) - SCATTER_CELL_M, float(q.min()) - SCATTER_CELL_M)
        ni = int(math.ceil((p.max() - p.min()) / SCATTER_CELL_M)) + 3
        nj = int(math.ceil((q.max() - q.min()) / SCATTER_CELL_M)) + 3
        n = ni * nj
        kinds = np.zeros(n, np.int8)
        r = rng.random(n)
        acc = 0.0
        for kind in (S_STONE, S_CLOD, S_SPECK, S_STRAW, S_WEED):
            pk = st.scatter_prob[kind]
            kinds[(r >= acc) & (r < acc + pk)] = kind
            acc += pk
        a = np.zeros(n)
        aspect = rng.uniform(0.6, 1.0, n)
        height = np.zeros(n)
        tone = rng.normal(0.0, 1.0, n)
        for kind, lo, hi in ((S_STONE, 0.006, 0.022), (S_CLOD, 0.008, 0.025), (S_SPECK, 0.003, 0.011),
                             (S_STRAW, 0.015, 0.04), (S_WEED, 0.006, 0.02)):
            sel = kinds == kind
            a[sel] = np.exp(rng.uniform(math.log(lo), math.log(hi), sel.sum()))
        straw = kinds == S_STRAW
        aspect[straw] = 1.0 / rng.uniform(6.0, 14.0, straw.sum())
        lumpy = (kinds == S_STONE) | (kinds == S_CLOD)
        height[lumpy] = a[lumpy] * rng.uniform(0.3, 0.7, lumpy.sum())
        height[straw] = a[straw] * aspect[straw]
        shadow_len = height * float(np.hypot(*st.shadow_per_height))
        # Fit object + shadow into the cell (shrink if needed), then place its centre at random.
        limit = 0.45 * SCATTER_CELL_M
        scale = np.minimum(1.0, limit / np.maximum(a + shadow_len, 1e-9))
        a *= scale
        height *= scale
        shadow_len *= scale
        reach = np.where(kinds > 0, a + shadow_len + 0.002, 0.0)
        ox = rng.uniform(reach, SCATTER_CELL_M - reach)
        oy = rng.uniform(reach, SCATTER_CELL_M - reach)
        angle = rng.uniform(0.0, math.pi, n)
        jj, ii = np.divmod(np.arange(n), ni)
        centre_p = self.scatter_origin[0] + ii * SCATTER_CELL_M + ox
        centre_q = self.scatter_origin[1] + jj * SCATTER_CELL_M + oy
        for (te, tn), ext in zip(targets.xy, targets.extent):
            tp, tq = c * te + s * tn, -s * te + c * tn
            over = np.hypot(centre_p - tp, centre_q - tq) < ext + reach + 0.02
            kinds[over] = S_NONE
            reach[over] = 0.0
        self.scatter_shape = (nj, ni)
        # Pass-1 table (gathered for every pixel) and pass-2 table (only near objects).
        self.scatter_pos = np.stack([ox, oy, reach, np.zeros(n)], -1).astype(np.float32)
        self.scatter_par = np.stack([kinds, a, aspect, np.cos(angle), np.sin(angle), height, tone],
                                    -1).astype(np.float32)

    def _make_targets(self, rng, n_targets):
        """Burrows inside the field, at least ``TARGET_SPACING_M`` apart, in the inter-row soil
        (clear of the plants while that is possible; a dense crop then gets targets among plants)."""
        hw, hl = self.field_half[0] - TARGET_MARGIN_M, self.field_half[1] - TARGET_MARGIN_M
        # Random sequential packing of discs stalls near 55 % cover; refuse well before that.
        if hw <= 0 or hl <= 0 or n_targets * math.pi * (TARGET_SPACING_M / 2) ** 2 > 0.35 * 4 * hw * hl:
            raise ValueError(f"{n_targets} targets {TARGET_SPACING_M} m apart do not fit in a "
                             f"{2 * self.field_half[0]:.1f} × {2 * self.field_half[1]:.1f} m field; "
                             "use fewer targets or a larger field")
        xy, params = [], []
        budget = 500 * n_targets
        for attempt in range(4 * budget):
            if len(xy) == n_targets:
                break
            p = self._burrow_params(rng)
            pt = np.array([rng.uniform(-hw, hw), rng.uniform(-hl, hl)])
            if xy and np.min(np.hypot(*(np.asarray(xy) - pt).T)) < TARGET_SPACING_M:
                continue
            if attempt < budget and self.canopy_clearance(pt[0], pt[1]) < p[P_OUTER] + 0.02:
                continue
            xy.append(pt)
            params.append(p)
        else:
            raise ValueError(f"could not place {n_targets} targets {TARGET_SPACING_M} m apart in the field; "
                             "use fewer targets or a larger field")
        xy = np.asarray(xy, float).reshape(-1, 2)
        params = np.asarray(params, float).reshape(-1, N_PARAMS)
        extent = params[:, P_OUTER] * 1.25 + 0.01
        return Features(np.full(len(xy), BURROW), xy, extent, params)

    @staticmethod
    def _burrow_params(rng):
        p = np.zeros(N_PARAMS)
        r = math.exp(rng.uniform(math.log(0.03), math.log(0.08)))
        p[P_R] = r
        p[P_ASPECT] = rng.uniform(1.0, 1.25)
        p[P_ANGLE] = rng.uniform(0.0, math.pi)
        p[P_A2], p[P_A4] = rng.uniform(0.0, 0.06), rng.uniform(0.0, 0.05)
        p[P_PH2], p[P_PH4] = rng.uniform(0.0, math.pi), rng.uniform(0.0, math.pi / 2)
        p[P_CONTRAST] = rng.uniform(0.5, 0.95)
        p[P_OUTER] = r * rng.uniform(1.7, 2.8)
        p[P_MOUND] = rng.uniform(0.12, 0.45)
        p[P_CDIR] = rng.uniform(0.0, 2 * math.pi)
        p[P_CSTR] = rng.uniform(0.0, 0.9)
        p[P_EDGE] = rng.uniform(0.002, 0.006)
        p[P_HEIGHT] = rng.uniform(0.08, 0.3)
        p[P_TONE] = rng.normal(0.0, 1.0)
        return p

    def _add_distractors(self, rng, targets: Features, density: float) -> Features:
        e0, e1, n0, n1 = self.domain
        area = (e1 - e0) * (n1 - n0)
        kinds, xys, pars, extents = [], [], [], []
        for kind, dens in DISTRACTOR_DENSITY.items():
            count = rng.poisson(dens * density * area)
            xy = np.stack([rng.uniform(e0, e1, count), rng.uniform(n0, n1, count)], -1)
            for pt in xy:
                p = self._distractor_params(rng, kind)
                ext = p[P_OUTER] * 1.1 + 0.01
                if kind == STONE:
                    ext += p[P_HEIGHT] * float(np.hypot(*self.style.shadow_per_height))
                if len(targets) and np.min(np.hypot(*(targets.xy - pt).T) - targets.extent) < ext + TARGET_CLEARANCE_M:
                    continue
                kinds.append(kind)
                xys.append(pt)
                pars.append(p)
                extents.append(ext)
        return Features(np.concatenate([targets.kind, np.asarray(kinds, int)]),
                        np.concatenate([targets.xy, np.asarray(xys, float).reshape(-1, 2)]),
                        np.concatenate([targets.extent, np.asarray(extents, float)]),
                        np.concatenate([targets.params, np.asarray(pars, float).reshape(-1, N_PARAMS)]))

    @staticmethod
    def _distractor_params(rng, kind):
        p = np.zeros(N_PARAMS)
        p[P_ANGLE] = rng.uniform(0.0, math.pi)
        p[P_PH2], p[P_PH4] = rng.uniform(0.0, math.pi), rng.uniform(0.0, math.pi / 2)
        p[P_CDIR] = rng.uniform(0.0, 2 * math.pi)
        p[P_TONE] = rng.normal(0.0, 1.0)
        if kind == DARK_PATCH:
            r = rng.uniform(0.03, 0.12)
            p[P_ASPECT] = rng.uniform(1.0, 2.0)
            p[P_A2], p[P_A4] = rng.uniform(0.0, 0.2), rng.uniform(0.0, 0.15)
            p[P_CONTRAST] = rng.uniform(0.2, 0.6)
            p[P_EDGE] = rng.uniform(0.008, 0.03)
            p[P_OUTER] = r * (1.0 + p[P_A2] + p[P_A4]) * p[P_ASPECT] + p[P_EDGE]
        elif kind == DEPRESSION:
            r = rng.uniform(0.04, 0.12)
            p[P_ASPECT] = rng.uniform(1.0, 1.5)
            p[P_HEIGHT] = rng.uniform(0.25, 0.6)     # depth / radius
            p[P_OUTER] = r * p[P_ASPECT]
        elif kind == LOOSE_MOUND:
            r = rng.uniform(0.05, 0.16)
            p[P_ASPECT] = rng.uniform(1.0, 1.4)
            p[P_A2], p[P_A4] = rng.uniform(0.0, 0.12), rng.uniform(0.0, 0.08)
            p[P_MOUND] = rng.uniform(0.08, 0.35)
            p[P_HEIGHT] = rng.uniform(0.15, 0.4)
            p[P_OUTER] = r * (1.0 + p[P_A2] + p[P_A4]) * p[P_ASPECT]
        elif kind == STONE:
            r = rng.uniform(0.025, 0.08)
            p[P_ASPECT] = rng.uniform(1.0, 1.6)
            p[P_A2], p[P_A4] = rng.uniform(0.0, 0.1), rng.uniform(0.0, 0.06)
            p[P_HEIGHT] = r * rng.uniform(0.3, 0.7)   # metres
            p[P_CONTRAST] = rng.uniform(1.1, 1.9)     # albedo relative to the soil
            p[P_OUTER] = r * (1.0 + p[P_A2] + p[P_A4]) * p[P_ASPECT]
        else:  # DUNG
            r = rng.uniform(0.04, 0.1)
            p[P_ASPECT] = rng.uniform(1.0, 1.5)
            p[P_A2], p[P_A4] = rng.uniform(0.0, 0.15), rng.uniform(0.0, 0.1)
            p[P_CONTRAST] = rng.uniform(0.3, 0.6)
            p[P_EDGE] = rng.uniform(0.003, 0.01)
            p[P_OUTER] = r * (1.0 + p[P_A2] + p[P_A4]) * p[P_ASPECT] + p[P_EDGE]
        p[P_R] = r
        return p

    # ------------------------------------------------------------------ queries
    def features_near(self, east: float, north: float, radius: float) -> np.ndarray:
        """Indices of features whose extent reaches within ``radius`` of a ground point."""
        d = np.hypot(self.features.xy[:, 0] - east, self.features.xy[:, 1] - north)
        return np.flatnonzero(d < radius + self.features.extent)

    def cloud_factor(self, east, north, time_s) -> np.ndarray:
        """Direct-sun transmission (0…1) of the moving cloud layer at ground points (numpy)."""
        st = self.style
        cloud_tex = self.textures[3]
        e = np.asarray(east, float) - st.cloud_velocity[0] * time_s
        n = np.asarray(north, float) - st.cloud_velocity[1] * time_s
        return self._cloud_transmission(cloud_tex.sample_points(e, n)[:, 0])

    def _cloud_transmission(self, noise):
        st = self.style
        return 1.0 - st.cloudiness * _smoothstep01((noise - 0.1) / 1.2)

    # ------------------------------------------------------------------ shading
    def radiance(self, east, north, east_c, north_c, gsd_m: float, time_s: float, windows,
                 gain=None) -> np.ndarray:
        """Linear RGB radiance of the ground points of a frame's pixels, planar (3, H, W) float32.

        ``east, north``: full-resolution ground points (float32, H × W); ``east_c, north_c``: the same
        on a grid 4× coarser, for the smooth layers; ``gsd_m``: ground size of a pixel (sets the
        anti-aliasing widths and fades texture detail finer than the pixels); ``windows``: a list
        of (feature index, row slice, column slice) to draw; ``gain``: an optional per-pixel factor
        (H × W) folded into the final multiplication (the camera's vignetting and exposure).
        """
        import cv2

        st = self.style
        fine_t, mid_t, coarse_t, cloud_t = self.textures
        h, w = east.shape
        f32 = np.float32
        grain, aggregates, agg_du, agg_dv = cv2.split(fine_t.sample(east, north))
        leaf_noise, clods, clod_du, clod_dv = cv2.split(mid_t.sample(east, north))

        # Smooth layers on the coarse grid, then upsampled: soil brightness and hue, crack gate, cloud.
        coarse = coarse_t.sample(east_c, north_c)
        cloud = cloud_t.sample(east_c, north_c, shift_m=(st.cloud_velocity[0] * time_s,
                                                         st.cloud_velocity[1] * time_s))[..., 0]
        smooth = np.empty(coarse.shape, np.float32)
        smooth[..., 0] = np.exp(st.moisture_contrast * coarse[..., 0] + 0.08 * coarse[..., 1])
        smooth[..., 1] = 0.05 * coarse[..., 3]
        smooth[..., 2] = _smoothstep01(coarse[..., 2] * 1.5 - 0.3) * st.crack_strength
        smooth[..., 3] = self._cloud_transmission(cloud)
        lum_c, hue, crack_gate, cloud_f = cv2.split(cv2.resize(smooth, (w, h), interpolation=cv2.INTER_LINEAR))

        # Detail fades out where its shortest wavelength approaches the pixel size (no aliasing).
        def fade(wavelength_m):
            return float(np.clip((wavelength_m / gsd_m - 1.25) / 1.25, 0.0, 1.0))

        # Billowed relief h = a·|n|: its gradient is a·sign(n)·∇n.
        sun = st.sun_vector
        shade = self._relief_term(fine_t, agg_du, agg_dv, np.sign(aggregates),
                                  0.0009 * st.relief * fade(0.0075), sun)
        shade += self._relief_term(mid_t, clod_du, clod_dv, np.sign(clods), 0.0035 * st.relief * fade(0.036), sun)
        np.subtract(f32(1.0), shade, out=shade)
        np.clip(shade, 0.05, 2.5, out=shade)

        clod_abs = np.abs(clods)
        lum = grain * f32(0.10 * fade(0.005))
        lum += (clod_abs - f32(0.8)) * f32(0.10 * fade(0.036))
        lum += f32(1.0)
        lum *= lum_c
        # Shrinkage cracks along the creases between clods, in patches.
        crack_w = f32(0.10)
        crack = np.subtract(crack_w, clod_abs, out=clod_abs)
        np.maximum(crack, 0.0, out=crack)
        crack *= crack_gate * f32(fade(0.008) / 0.10 * 0.85)
        lum *= f32(1.0) - crack

        rgb = np.empty((3, h, w), np.float32)
        np.multiply(lum, f32(st.soil_rgb[1]), out=rgb[1])
        hue *= lum
        np.multiply(lum + hue, f32(st.soil_rgb[0]), out=rgb[0])
        np.multiply(lum - hue, f32(st.soil_rgb[2]), out=rgb[2])
        shadow = np.zeros((h, w), np.float32)

        for index, rows, cols in windows:
            self._draw_feature(index, east[rows, cols], north[rows, cols], gsd_m,
                               rgb[:, rows, cols], shade[rows, cols], shadow[rows, cols], grain[rows, cols],
                               aggregates[rows, cols])
        self._draw_scatter(east, north, east_c, north_c, gsd_m, rgb, shade, shadow, grain)
        canopy = self._canopy(east, north, east_c, north_c, gsd_m, leaf_noise)

        # Light = sky + sun·clouds·(relief, shadows); the canopy has its own leaf shading.
        direct = shade
        if canopy is None:
            direct *= f32(1.0) - shadow
        else:
            sel, leaf_cover, leaf_rgb, leaf_shade, canopy_shadow = canopy
            np.maximum(shadow, canopy_shadow, out=shadow)
            direct *= f32(1.0) - shadow
            flat_direct = direct.reshape(-1)
            d = flat_direct[sel]
            flat_direct[sel] = d + (leaf_shade - d) * leaf_cover
            flat_rgb = rgb.reshape(3, -1)
            c = flat_rgb[:, sel]
            flat_rgb[:, sel] = c + (leaf_rgb.T - c) * leaf_cover
        direct *= cloud_f
        direct *= f32(st.direct_fraction)
        direct += f32(1.0 - st.direct_fraction)
        if gain is not None:
            direct *= gain
        rgb *= direct
        return rgb

    @staticmethod
    def _relief_term(texture: GroundTexture, d_du, d_dv, sign, height_m: float, sun) -> np.ndarray:
        """∇h·l_xy / l_z for h = height_m·|n|, from the texture's gradient of n (per texel)."""
        lu, lv = texture.to_texture_axes(sun[:2])
        k = height_m / texture.texel_m / sun[2]
        term = d_du * np.float32(k * lu)
        term += d_dv * np.float32(k * lv)
        term *= sign
        return term

    # ------------------------------------------------------------------ canopy
    def _canopy(self, east, north, east_c, north_c, gsd_m, leaf_noise):
        """The pixels near plants (flat indices) with their leaf coverage (0…1), leaf colour and leaf
        shading, and the canopy's shadow on the soil (0…1, H × W); None when the field has no crop.

        Each plant is a rosette: ``n`` leaves whose outline radius follows |cos(n(θ − φ)/2)|^k,
        with per-leaf lengths, a brighter midrib and a leaf texture; its shadow is the same rosette
        displaced along the shadow vector. The coarse grid finds the pixels near a plant or its
        shadow first, so the full-resolution work is proportional to the canopy, not the frame.
        """
        import cv2

        st = self.style
        if not self.has_plants:
            return None
        f32 = np.float32
        along, across = self._row_axes()
        shift = st.shadow_per_height * st.plant_height
        shift_e, shift_n = f32(shift[0]), f32(shift[1])
        # Coarse pass: each coarse pixel stands for a block of up to ±2.5 px; test the three cells
        # along its row with that margin, for the plant and for its shadow.
        margin = f32(3.5 * gsd_m + 0.002)
        near_plant = self._near_plants(east_c.ravel(), north_c.ravel(), margin)
        near_shadow = self._near_plants(east_c.ravel() - shift_e, north_c.ravel() - shift_n, margin)
        h, w = east.shape
        # Shadows are soft: drawn on the coarse grid (4 px ≈ 1 cm) and interpolated.
        shadow_c = np.zeros(east_c.size, np.float32)
        idx = np.flatnonzero(near_shadow)
        if len(idx):
            shadow_c[idx] = self._plants_at(east_c.ravel()[idx] - shift_e, north_c.ravel()[idx] - shift_n,
                                            f32(4.0 * max(gsd_m, 0.0015)))[0]
        shadow = cv2.resize(shadow_c.reshape(east_c.shape), (w, h), interpolation=cv2.INTER_LINEAR)
        shadow *= f32(0.8)
        mask = near_plant.reshape(east_c.shape).astype(np.uint8)
        sel = np.flatnonzero(cv2.resize(mask, (w, h), interpolation=cv2.INTER_NEAREST))
        aa = f32(max(gsd_m, 0.0015))
        cover, shade, hue = self._plants_at(east.ravel()[sel], north.ravel()[sel], aa)
        noise = leaf_noise.ravel()[sel]
        leaf_shade = np.clip(shade * (f32(1.0) + f32(0.25) * noise), 0.2, 2.0)
        tint = np.array([0.15, 0.0, -0.12], np.float32)
        leaf_rgb = (st.leaf_rgb.astype(np.float32) * (f32(1.0) + tint * hue[:, None])
                    * (f32(1.0) + f32(0.08) * noise[:, None]))
        return sel, cover, leaf_rgb, leaf_shade, shadow

    def _near_plants(self, east, north, margin) -> np.ndarray:
        """True where a ground point (1-D) lies within ``margin`` of a plant's outer radius."""
        f32 = np.float32
        du, rows, s_rel = self._row_coords(east, north)
        j = np.floor(s_rel)
        near = np.zeros(len(du), bool)
        for dj in (-1.0, 0.0, 1.0):
            cell = rows + np.clip(j + f32(dj), 0, self.row_shape[1] - 1).astype(np.int32)
            present, frac, off, radius = self.row_table_near[cell].T
            dist = np.hypot((s_rel - j - f32(dj) - frac) * f32(self.plant_cell), du - off)
            near |= (present > 0) & (dist < radius + margin)
        return near

    def _row_coords(self, east, north):
        """For ground points (1-D float32): the offset across the nearest row (m), that row's base
        index in the row table, and the position along the row in plant cells."""
        f32 = np.float32
        along, across = self._row_axes()
        spacing = self.style.row_spacing
        u = east * f32(across[0]) + north * f32(across[1])
        k = np.floor(u * f32(1.0 / spacing) + f32(0.5))
        du = u - k * f32(spacing)
        rows = np.clip(k - f32(self.row_k0), 0, self.row_shape[0] - 1).astype(np.int32) * np.int32(self.row_shape[1])
        s_rel = east * f32(along[0] / self.plant_cell)
        s_rel += north * f32(along[1] / self.plant_cell)
        s_rel -= f32(self.row_s0 / self.plant_cell)
        return du, rows, s_rel

    def _plants_at(self, east, north, aa):
        """Leaf coverage, leaf shading and plant hue at ground points (1-D), from the plant of the
        point's own cell and of the neighbouring cell on its side (the only two that reach it)."""
        f32 = np.float32
        du, rows, s_rel = self._row_coords(east, north)
        j = np.floor(s_rel)
        n = len(du)
        best_cov = np.zeros(n, np.float32)
        best_shade = np.ones(n, np.float32)
        best_hue = np.zeros(n, np.float32)
        for jj in (j, np.where(s_rel - j > 0.5, j + 1, j - 1)):
            cell = rows + np.clip(jj, 0, self.row_shape[1] - 1).astype(np.int32)
            present, frac, off, radius = self.row_table_near[cell].T
            ds = (s_rel - jj - frac) * f32(self.plant_cell)
            dl = du - off
            inside = np.flatnonzero((present > 0) & (np.hypot(ds, dl) < radius + aa))
            if not len(inside):
                continue
            extra = self.row_table[cell[inside], 4:]
            cov, shade = self._rosette(extra, ds[inside], dl[inside], radius[inside], aa)
            better = cov > best_cov[inside]
            take = inside[better]
            best_cov[take] = cov[better]
            best_shade[take] = shade[better]
            best_hue[take] = extra[better, 2]
        return best_cov, best_shade, best_hue

    @staticmethod
    def _rosette(params, ds, dl, radius, aa):
        """Coverage and leaf shading of rosettes at offsets (ds along, dl across the row) from their
        centres; ``params`` = columns 4… of the row table (leaf count, phase, hue, narrowness, seed)."""
        f32 = np.float32
        n_leaves, phase, _, sharp, seed = params.T
        dist = np.hypot(ds, dl)
        theta = np.arctan2(dl, ds) - phase
        lobe = np.abs(np.cos(f32(0.5) * n_leaves * theta)) ** sharp
        leaf_index = np.floor(n_leaves * theta * f32(1 / (2 * math.pi)) + f32(0.5))
        # A cheap hash of the leaf index gives each leaf its own length.
        length = f32(0.65) + f32(0.35) * np.modf(np.abs(np.sin(leaf_index * f32(12.9898) + seed)
                                                        * f32(43758.5453)))[0]
        bound = radius * (f32(0.22) + f32(0.78) * lobe * length)
        cov = np.clip(f32(0.5) + (bound - dist) / aa, 0.0, 1.0)
        shade = f32(0.7) + f32(0.45) * lobe - f32(0.25) * np.clip(dist / radius, 0, 1)
        return cov, shade

    # ------------------------------------------------------------------ scatter
    def _scatter_cells(self, east, north):
        """Grid-frame offsets (p, q) of ground points (1-D) from their cell's corner, and the cell
        column and row (float32; cells of SCATTER_CELL_M on the scatter grid)."""
        f32 = np.float32
        c, s = math.cos(self.scatter_angle), math.sin(self.scatter_angle)
        p = east * f32(c) + north * f32(s) - f32(self.scatter_origin[0])
        q = north * f32(c) - east * f32(s) - f32(self.scatter_origin[1])
        ci = np.floor(p * f32(1.0 / SCATTER_CELL_M))
        cj = np.floor(q * f32(1.0 / SCATTER_CELL_M))
        p -= ci * f32(SCATTER_CELL_M)
        q -= cj * f32(SCATTER_CELL_M)
        return p, q, ci, cj

    def _scatter_index(self, ci, cj):
        nj, ni = self.scatter_shape
        return np.clip(cj, 0, nj - 1).astype(np.int32) * np.int32(ni) + np.clip(ci, 0, ni - 1).astype(np.int32)

    def _draw_scatter(self, east, north, east_c, north_c, gsd_m, rgb, shade, shadow, grain):
        """Draw the clutter into the full-resolution layers (modified in place). The coarse grid finds
        the pixels near an object first (with the margin of each coarse pixel's block)."""
        import cv2

        st = self.style
        f32 = np.float32
        c, s = math.cos(self.scatter_angle), math.sin(self.scatter_angle)
        p, q, ci, cj = self._scatter_cells(east_c.ravel(), north_c.ravel())
        margin = f32(3.5 * gsd_m)
        near = np.zeros(len(p), bool)
        # An object lies at least its reach inside its cell, so a point can only be near objects of
        # its own cell and of the three neighbours on the side of its quadrant (while the margin
        # stays under half a cell).
        if margin < 0.5 * SCATTER_CELL_M:
            step_p = np.where(p < f32(SCATTER_CELL_M / 2), f32(-1.0), f32(1.0))
            step_q = np.where(q < f32(SCATTER_CELL_M / 2), f32(-1.0), f32(1.0))
            neighbours = [(step_p * f32(a), step_q * f32(b)) for a, b in ((0, 0), (1, 0), (0, 1), (1, 1))]
        else:  # pixels of several centimetres (high flights): all eight neighbours
            neighbours = [(f32(a), f32(b)) for a in (-1, 0, 1) for b in (-1, 0, 1)]
        for di, dj in neighbours:
            pos = self.scatter_pos[self._scatter_index(ci + di, cj + dj)]
            dist = np.hypot(p - di * f32(SCATTER_CELL_M) - pos[:, 0], q - dj * f32(SCATTER_CELL_M) - pos[:, 1])
            near |= (pos[:, 2] > 0) & (dist < pos[:, 2] + margin)
        h, w = east.shape
        mask = cv2.resize(near.reshape(east_c.shape).astype(np.uint8), (w, h), interpolation=cv2.INTER_NEAREST)
        candidates = np.flatnonzero(mask)
        if not len(candidates):
            return
        p, q, ci, cj = self._scatter_cells(east.ravel()[candidates], north.ravel()[candidates])
        idx = self._scatter_index(ci, cj)
        pos = self.scatter_pos[idx]
        dx = p - pos[:, 0]
        dy = q - pos[:, 1]
        inside = np.flatnonzero(np.hypot(dx, dy) < pos[:, 2])
        if not len(inside):
            return
        sel = candidates[inside]
        dx, dy = dx[inside], dy[inside]
        par = self.scatter_par[idx[inside]]
        kind, a, aspect, ca, sa, height, tone = (par[:, i] for i in range(7))
        b = a * aspect
        # Object axes: rotate cell offsets (grid frame) into the object frame.
        x1 = dx * ca + dy * sa
        y1 = -dx * sa + dy * ca
        rho = np.sqrt((x1 / a) ** 2 + (y1 / b) ** 2)
        aa = max(gsd_m, 0.0015)
        cover = np.clip(0.5 + (1.0 - rho) * b / aa, 0.0, 1.0)
        # Cast shadow: the object's outline displaced by height × shadow vector (grid frame).
        sh = st.shadow_per_height
        sh_p, sh_q = c * sh[0] + s * sh[1], -s * sh[0] + c * sh[1]
        sx = dx - height * sh_p
        sy = dy - height * sh_q
        xs = sx * ca + sy * sa
        ys = -sx * sa + sy * ca
        rho_s = np.sqrt((xs / a) ** 2 + (ys / b) ** 2)
        cast = np.clip(0.5 + (1.0 - rho_s) * b / (2 * aa), 0.0, 1.0) * (1.0 - cover) * 0.9
        cast[height <= 0] = 0.0
        # Surface normal of a half-ellipsoid (in the grid frame) lit by the sun.
        nz = np.sqrt(np.clip(1.0 - rho * rho, 0.02, 1.0))
        gx, gy = x1 / (a * a), y1 / (b * b)
        gpx, gpy = gx * ca - gy * sa, gx * sa + gy * ca
        hgt = np.where(height > 0, height, 0.0)
        slope_x = hgt * gpx / nz
        slope_y = hgt * gpy / nz
        sun_g = (c * st.sun_vector[0] + s * st.sun_vector[1], -s * st.sun_vector[0] + c * st.sun_vector[1])
        obj_shade = np.clip((st.sun_vector[2] + slope_x * sun_g[0] + slope_y * sun_g[1])
                            / (np.sqrt(1 + slope_x ** 2 + slope_y ** 2) * st.sun_vector[2]), 0.05, 2.5)
        flat_rgb, flat_shade, flat_shadow = rgb.reshape(3, -1), shade.reshape(-1), shadow.reshape(-1)
        soil = flat_rgb[:, sel].T
        colour = np.empty_like(soil)
        g = grain.ravel()[sel][:, None]
        lum_soil = soil.mean(axis=1, keepdims=True) / max(float(st.soil_rgb.mean()), 1e-3)
        for kind_id in (S_STONE, S_CLOD, S_SPECK, S_STRAW, S_WEED):
            m = kind == kind_id
            if not m.any():
                continue
            t = tone[m][:, None]
            if kind_id == S_STONE:
                grey = np.array([0.36, 0.34, 0.31]) * (1 + 0.15 * t)
                col = (0.5 * grey + 0.5 * soil[m] * (1.3 + 0.2 * t)) * (1 + 0.05 * g[m])
            elif kind_id == S_CLOD:
                col = soil[m] * (1.05 + 0.15 * t) * (1 + 0.15 * g[m])
            elif kind_id == S_SPECK:
                col = soil[m] * np.clip(0.45 + 0.12 * t, 0.2, 0.8)
            elif kind_id == S_STRAW:
                col = np.array([0.55, 0.47, 0.30]) * (1 + 0.12 * t) * lum_soil[m] ** 0.3
            else:
                col = st.leaf_rgb * np.array([1.0, 1.1, 0.9]) * (1 + 0.15 * t) * (1 + 0.2 * g[m])
            colour[m] = col
        flat = (kind == S_SPECK) | (kind == S_WEED)
        obj_shade = np.where(flat, 1.0, obj_shade)
        cov = cover[:, None]
        flat_rgb[:, sel] = (soil + (colour - soil) * cov).T
        s0 = flat_shade[sel]
        flat_shade[sel] = s0 + (obj_shade - s0) * cover
        flat_shadow[sel] = np.maximum(flat_shadow[sel], cast)

    # ------------------------------------------------------------------ features
    def _draw_feature(self, index, east, north, gsd_m, rgb, shade, shadow, grain, aggregates):
        """Draw feature ``index`` into window views (modified in place; ``rgb`` planar, 3 × h × w)."""
        kind = int(self.features.kind[index])
        p = self.features.params[index]
        cx, cy = self.features.xy[index]
        dx = east - np.float32(cx)
        dy = north - np.float32(cy)
        aa = max(gsd_m, 0.0015)
        st = self.style
        sun = st.sun_vector
        # Elliptical polar coordinates of the outline, with even harmonics only (they keep the
        # outline's centroid on the feature centre).
        ca, sa = math.cos(p[P_ANGLE]), math.sin(p[P_ANGLE])
        u = dx * ca + dy * sa
        v = (-dx * sa + dy * ca) * p[P_ASPECT]
        d = np.hypot(u, v)
        th = np.arctan2(v, u)
        r_eff = p[P_R] * (1.0 + p[P_A2] * np.cos(2 * (th - p[P_PH2])) + p[P_A4] * np.cos(4 * (th - p[P_PH4])))
        dist = np.hypot(dx, dy)
        with np.errstate(invalid="ignore", divide="ignore"):
            radial_x = np.where(dist > 0, dx / dist, 0.0)
            radial_y = np.where(dist > 0, dy / dist, 0.0)
        sun_radial = radial_x * sun[0] + radial_y * sun[1]
        g, agg = grain, aggregates

        if kind == BURROW:
            width = max(p[P_EDGE], aa)
            hole = _coverage(r_eff - d, width)
            rho = np.clip(d / r_eff, 0.0, 1.0)
            # The hole: a dark tunnel mouth inside a shadowed, textured wall. Outline and shading are
            # centrally symmetric, so the drawn centre is unbiased.
            tunnel = _smoothstep01((0.8 - rho) / 0.35)
            wall = (1.0 - 0.55 * p[P_CONTRAST]) * (1.0 + 0.25 * g + 0.2 * (np.abs(agg) - 0.8))
            core = (1.0 - p[P_CONTRAST]) * (1.0 + 0.05 * g)
            inner = wall + (core - wall) * tunnel
            soil_mean = rgb.reshape(3, -1).mean(axis=1)[:, None, None]
            # Loose soil thrown out around it: a ring whose crest lies two thirds out (its inner face
            # rises gently from the rim), heaped on one side, lumpy, lighter and coarser than the soil.
            phi = np.arctan2(dy, dx)
            weight = 1.0 - p[P_CSTR] * 0.5 * (1.0 - np.cos(phi - p[P_CDIR]))
            lumps = 1.0 + 0.25 * np.sin(3 * phi + p[P_PH2] * 2) * np.sin(5 * phi + p[P_PH4] * 4)
            span = (p[P_OUTER] - p[P_R]) * (0.4 + 0.6 * weight) * lumps
            q = np.clip((d - r_eff) / span, 0.0, 1.0)
            bump = 6.75 * q * q * (1.0 - q)
            mound = 1.0 + p[P_MOUND] * bump * weight * (1.0 + 0.7 * g + 0.8 * (np.abs(agg) - 0.8))
            outside = 1.0 - hole
            rgb *= (mound * outside).astype(np.float32)
            rgb += ((inner * hole) * soil_mean).astype(np.float32)
            # Radial slope of the ring (height P_HEIGHT·span·bump): the sun-facing side is lit.
            slope = p[P_HEIGHT] * 6.75 * q * (2.0 - 3.0 * q) * weight * (q < 1.0)
            term = np.clip(1.0 - slope * sun_radial / sun[2], 0.45, 1.6)
            shade *= (term * outside).astype(np.float32)
            shade += (hole * (1.0 - 0.6 * p[P_CONTRAST])).astype(np.float32)
        elif kind == DARK_PATCH:
            cover = _smoothstep01(0.5 + (r_eff - d) / max(p[P_EDGE], aa))
            dark = 1.0 - p[P_CONTRAST] * cover * (1.0 + 0.15 * g)
            rgb *= (dark * np.array([1.0, 1.0, 1.06])[:, None, None] ** cover).astype(np.float32)
        elif kind == DEPRESSION:
            rho = d / p[P_R]
            inside = rho < 1.0
            # h = −depth (1 − ρ²)²: radial slope 4·depth·ρ(1 − ρ²)/r, pointing down towards the centre.
            depth = p[P_HEIGHT] * p[P_R]
            slope = np.where(inside, 4.0 * depth * rho * (1.0 - rho * rho) / p[P_R], 0.0)
            term = np.clip(1.0 + slope * sun_radial / sun[2], 0.0, 2.0)
            shade *= term.astype(np.float32)
            # The sun-side wall shadows the pit floor behind it.
            shadow_depth = np.clip(0.5 + (slope * 0.6 - sun[2] / max(np.hypot(sun[0], sun[1]), 1e-3)) * 4, 0, 1)
            np.maximum(shadow, (shadow_depth * inside * (sun_radial > 0)).astype(np.float32), out=shadow)
        elif kind == LOOSE_MOUND:
            rho = np.clip(d / r_eff, 0.0, 1.0)
            dome = (1.0 - rho * rho) ** 2
            cover = _coverage(r_eff - d, max(aa, 0.01))
            rgb *= (1.0 + p[P_MOUND] * cover * dome * (1.0 + 0.6 * g)).astype(np.float32)
            slope = p[P_HEIGHT] * 4.0 * rho * (1.0 - rho * rho)
            term = np.clip(1.0 - slope * sun_radial / sun[2], 0.3, 1.8)
            shade *= (1.0 + (term - 1.0) * cover).astype(np.float32)
        elif kind == STONE:
            cover = _coverage(r_eff - d, aa)
            rho = np.clip(d / r_eff, 0.0, 0.995)
            nz = np.sqrt(1.0 - rho * rho)
            slope = p[P_HEIGHT] / p[P_R] * rho / nz
            term = np.clip(1.0 - slope * sun_radial / sun[2], 0.15, 1.5)
            soil = rgb.reshape(3, -1).mean(axis=1)[:, None, None]
            grey = np.array([0.30, 0.29, 0.27])[:, None, None]
            colour = (0.35 * grey + 0.65 * soil * 1.15) * (1.0 + 0.12 * p[P_TONE]) * (1.0 + 0.12 * g + 0.1 * agg)
            rgb += ((colour - rgb) * cover).astype(np.float32)
            shade += ((term - shade) * cover).astype(np.float32)
            # Cast shadow: the outline displaced by height × shadow vector, off the stone itself.
            sh = st.shadow_per_height * p[P_HEIGHT] * 0.8
            ex, ey = dx - sh[0], dy - sh[1]
            us = ex * ca + ey * sa
            vs = (-ex * sa + ey * ca) * p[P_ASPECT]
            ds = np.hypot(us, vs)
            cast = _coverage(r_eff * 0.95 - ds, 2 * aa) * (1.0 - cover) * 0.9
            np.maximum(shadow, cast.astype(np.float32), out=shadow)
        else:  # DUNG
            cover = _coverage(r_eff - d, max(p[P_EDGE], aa))
            colour = np.array([0.12, 0.11, 0.07])[:, None, None] * (1.0 + 0.15 * p[P_TONE]) * (1.0 + 0.3 * g)
            rgb += ((colour - rgb) * (cover * (1.0 - p[P_CONTRAST] * 0.3))).astype(np.float32)
