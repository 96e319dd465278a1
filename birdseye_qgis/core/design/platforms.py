"""Platform presets for the sensor bound: a camera and the 1σ noise of the poses labels are made from.

Each preset is a camera (:class:`.sensor_bound.Intrinsics`, px), pose sigmas in the sensor bound's
interface order (x, y, z in metres; roll, pitch, yaw in degrees) and the camera mount that says how
roll, pitch and yaw turn the camera (:class:`.sensor_bound.CameraMount`), with the label tolerance and
altitudes it is judged at, and where its numbers come from.

* **Deployed platform** — the BirdsEye payload: its calibrated camera and the RTK INS + radar
  altimeter budget the method was deployed with, on the method's mount (attitude errors applied to
  the camera-frame rotation vector), so the calculator gives the method's table.
* **DJI RTK drone, poses from its image metadata** — what :mod:`..field.dji` reads from a DJI RTK
  drone's JPEGs, before any photogrammetric refinement:

  - camera: a Mavic 3 Enterprise wide camera (DJI specifications: 4/3 CMOS, 5280 × 3956 px, 84° field
    of view, 24 mm equivalent); fx = fy = (diagonal/2) / tan(42°) = 3664 px, principal point at the
    centre;
  - x, y: RTK fix, 1 cm + 1 ppm horizontal (the figure DJI states for the Mavic 3 Enterprise RTK
    module, the Matrice 300/350 RTK and the Phantom 4 RTK), at a 1 km baseline: 1.1 cm;
  - z: 1.5 cm + 1 ppm vertical (same sources), at 1 km: 1.6 cm. The depth the importer uses is
    ``RelativeAltitude``, a fused height for which DJI states no accuracy (only a hovering accuracy of
    ±0.1 m with RTK); a real flight read 1.45 m low, far outside any budget;
  - roll, pitch, yaw: DJI states the gimbal's angular vibration (±0.01° or better) but not the
    accuracy of the attitude the metadata reports, which is the aircraft's IMU and compass heading
    estimate the gimbal stabilises against. The sigmas are those we measured on a real DJI RTK flight
    against photogrammetry-refined poses (camera tilted 0.4–0.9° where the metadata said 0.1°,
    heading off by up to 1.8°): 0.5° in roll and pitch, 1.0° in yaw;
  - mount: the camera looks straight down with the image top towards the nose (gimbal at −90°
    following the aircraft's heading). Roll and pitch share one sigma, so on the method's mount the
    figures would be the same.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .sensor_bound import METHOD_MOUNT, NADIR_MOUNT, CameraMount, Intrinsics


@dataclass(frozen=True)
class Platform:
    """A camera, its pose-noise budget (1σ: x, y, z in m; roll, pitch, yaw in degrees) and its mount."""

    key: str
    name: str
    camera: Intrinsics
    sigmas: tuple
    mount: CameraMount
    tolerance_px: float
    altitudes_m: tuple
    sources: str


DEPLOYED = Platform(
    key="deployed", name="Deployed platform (BirdsEye method)",
    camera=Intrinsics(fx=4264.4945, fy=4262.8927, cx=958.4594, cy=592.5033, width=1920, height=1200),
    sigmas=(0.010, 0.010, 0.060, 0.04, 0.04, 0.13), mount=METHOD_MOUNT, tolerance_px=30.0, altitudes_m=(10.0, 20.0),
    sources="calibrated payload camera; RTK INS and radar altimeter budget of the deployed method")

# Mavic 3 Enterprise wide camera: 5280 × 3956 px, 84° diagonal field of view.
_M3E_SIZE = (5280, 3956)
# To 0.1 mpx, the precision the calculator dock shows (so it recognises the preset it set).
_M3E_FOCAL_PX = round(0.5 * math.hypot(*_M3E_SIZE) / math.tan(math.radians(84.0 / 2.0)), 4)
#: RTK fix accuracy DJI states (m, m/m): 1 cm + 1 ppm horizontal, 1.5 cm + 1 ppm vertical.
DJI_RTK_HORIZONTAL = (0.010, 1e-6)
DJI_RTK_VERTICAL = (0.015, 1e-6)
RTK_BASELINE_M = 1000.0

DJI_METADATA = Platform(
    key="dji_metadata", name="DJI RTK drone, poses from its image metadata",
    camera=Intrinsics(fx=_M3E_FOCAL_PX, fy=_M3E_FOCAL_PX, cx=(_M3E_SIZE[0] - 1) / 2.0, cy=(_M3E_SIZE[1] - 1) / 2.0,
                      width=_M3E_SIZE[0], height=_M3E_SIZE[1]),
    sigmas=(DJI_RTK_HORIZONTAL[0] + DJI_RTK_HORIZONTAL[1] * RTK_BASELINE_M,
            DJI_RTK_HORIZONTAL[0] + DJI_RTK_HORIZONTAL[1] * RTK_BASELINE_M,
            DJI_RTK_VERTICAL[0] + DJI_RTK_VERTICAL[1] * RTK_BASELINE_M,
            0.5, 0.5, 1.0),
    mount=NADIR_MOUNT, tolerance_px=30.0, altitudes_m=(10.0, 20.0),
    sources="DJI specifications (Mavic 3 Enterprise camera; RTK 1 cm + 1 ppm H, 1.5 cm + 1 ppm V at a 1 km "
            "baseline); attitude as measured on a real DJI RTK flight (DJI states none)")

PLATFORMS = (DEPLOYED, DJI_METADATA)


def platform(key: str) -> Platform:
    """The preset called ``key``; KeyError naming the known ones otherwise."""
    for preset in PLATFORMS:
        if preset.key == key:
            return preset
    raise KeyError(f"no platform preset {key!r}; known: {', '.join(p.key for p in PLATFORMS)}")
