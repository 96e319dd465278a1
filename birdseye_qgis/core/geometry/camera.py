"""Camera model: pinhole + Brown–Conrady distortion, and calibration loaders.

Conventions (docs/design.md#camera):

* Camera frame = OpenCV optical frame: x right, y down, z forward (along the optical axis).
* Pixel (0, 0) is the *centre* of the top-left pixel (OpenCV convention); u grows right, v down.
* Distortion is OpenCV's radial–tangential model ``k1 k2 p1 p2 k3`` applied to normalised
  coordinates, extended by ``k4``, the r⁸ radial term photogrammetry packages estimate (Metashape's K4;
  *not* OpenCV's rational k4); projection applies it, back-projection inverts it (Newton iterations).
* ``fisheye`` cameras use OpenCV's fisheye model instead (equidistant, ``θd = θ(1 + k1θ² + k2θ⁴ + k3θ⁶
  + k4θ⁸)``, θ the angle from the optical axis); their ``dist`` holds ``k1 k2 k3 k4``.
* ``skew`` (px) is the K-matrix element (0, 1): ``u = fx·xd + skew·yd + cx`` (Metashape's b2).
* ``T_cam_imu`` (Kalibr) maps points in the IMU/body frame into the camera frame:
  ``X_cam = T_cam_imu @ X_imu``.
* ``t_imu_rad`` is the radar altimeter's position in the IMU/body frame (metres), or None.
"""
from __future__ import annotations

import json
import re
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..errors import InputError
from .rigid import RigidTransform

#: Body → camera rotation (the rotation of ``T_cam_imu``) of a nadir camera with the image top towards the nose:
#: camera x = body right, camera y = −body forward, camera z = body down (docs/design.md#camera). The one mount
#: that design, planning and the simulator share.
NADIR_ROTATION = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])

#: File-dialog filter for the calibration files :func:`load_calibration` reads.
CALIBRATION_FILE_FILTER = "Camera calibration (*.yaml *.yml);;All files (*)"


class CalibrationError(InputError):
    """A calibration file or string that cannot be used; the message names file and field."""


@dataclass(frozen=True, eq=False)
class CameraModel:
    """A calibrated camera and its mounting on the body/IMU frame (equal when their JSON is equal)."""

    width: int
    height: int
    fx: float
    fy: float
    cx: float
    cy: float
    dist: tuple = (0.0, 0.0, 0.0, 0.0, 0.0)
    T_cam_imu: np.ndarray = field(default_factory=lambda: np.eye(4))
    t_imu_rad: tuple | None = None
    source: str = ""
    k4: float = 0.0
    skew: float = 0.0
    fisheye: bool = False

    def __post_init__(self):
        d = tuple(float(c) for c in self.dist) + (0.0,) * (5 - len(self.dist))
        object.__setattr__(self, "dist", d[:5])
        object.__setattr__(self, "k4", float(self.k4))
        object.__setattr__(self, "skew", float(self.skew))
        object.__setattr__(self, "fisheye", bool(self.fisheye))
        object.__setattr__(self, "T_cam_imu", np.asarray(self.T_cam_imu, dtype=float).reshape(4, 4))

    def __eq__(self, other) -> bool:
        return isinstance(other, CameraModel) and self.to_json() == other.to_json()

    def __hash__(self) -> int:
        return hash(self.to_json())

    # ------------------------------------------------------------------ intrinsics
    @property
    def K(self) -> np.ndarray:
        return np.array([[self.fx, self.skew, self.cx], [0.0, self.fy, self.cy], [0.0, 0.0, 1.0]])

    @property
    def has_distortion(self) -> bool:
        return self.fisheye or any(c != 0.0 for c in self.dist) or self.k4 != 0.0

    def distort(self, xn: np.ndarray) -> np.ndarray:
        """Distorted normalised coordinates (..., 2) from ideal ones (..., 2)."""
        if self.fisheye:
            return xn * self._fisheye_scale(np.hypot(xn[..., 0], xn[..., 1]))[..., None]
        k1, k2, p1, p2, k3 = self.dist
        x, y = xn[..., 0], xn[..., 1]
        r2 = x * x + y * y
        radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * (k3 + r2 * self.k4)))
        xd = x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x)
        yd = y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y
        return np.stack([xd, yd], axis=-1)

    def _fisheye_theta_d(self, theta: np.ndarray) -> np.ndarray:
        k1, k2, k3, k4 = self.dist[:4]
        t2 = theta * theta
        return theta * (1.0 + t2 * (k1 + t2 * (k2 + t2 * (k3 + t2 * k4))))

    def _fisheye_scale(self, r: np.ndarray) -> np.ndarray:
        """θd / r, the factor the fisheye model scales ideal normalised coordinates by (1 on the axis)."""
        theta = np.arctan(r)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(r > 1e-12, self._fisheye_theta_d(theta) / r, 1.0)

    def _fisheye_undistort(self, xd: np.ndarray, iterations: int, tol: float) -> np.ndarray:
        """Invert θd(θ) by Newton's method along each ray, then r = tan θ."""
        k1, k2, k3, k4 = self.dist[:4]
        theta_d = np.hypot(xd[..., 0], xd[..., 1])
        theta = theta_d.copy()
        for _ in range(iterations):
            residual = self._fisheye_theta_d(theta) - theta_d
            if np.nanmax(np.abs(residual), initial=0.0) < tol:
                break
            t2 = theta * theta
            slope = 1.0 + t2 * (3.0 * k1 + t2 * (5.0 * k2 + t2 * (7.0 * k3 + t2 * 9.0 * k4)))
            theta = theta - residual / slope
        with np.errstate(divide="ignore", invalid="ignore"):
            scale = np.where(theta_d > 1e-12, np.tan(theta) / theta_d, 1.0)
        return xd * scale[..., None]

    def _distort_jacobian(self, xn: np.ndarray) -> np.ndarray:
        k1, k2, p1, p2, k3 = self.dist
        k4 = self.k4
        x, y = xn[..., 0], xn[..., 1]
        r2 = x * x + y * y
        radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * (k3 + r2 * k4)))
        dradial = k1 + r2 * (2.0 * k2 + r2 * (3.0 * k3 + 4.0 * k4 * r2))  # d radial / d r2
        j = np.empty(xn.shape[:-1] + (2, 2))
        j[..., 0, 0] = radial + 2 * x * x * dradial + 2 * p1 * y + 6 * p2 * x
        j[..., 0, 1] = 2 * x * y * dradial + 2 * p1 * x + 2 * p2 * y
        j[..., 1, 0] = 2 * x * y * dradial + 2 * p1 * x + 2 * p2 * y
        j[..., 1, 1] = radial + 2 * y * y * dradial + 6 * p1 * y + 2 * p2 * x
        return j

    def undistort(self, xd: np.ndarray, iterations: int = 20, tol: float = 1e-12) -> np.ndarray:
        """Ideal normalised coordinates from distorted ones, by Newton's method.

        OpenCV's fixed-point iteration stalls near the corners of strongly distorted lenses; Newton
        with the analytic Jacobian converges to machine precision in a handful of steps.
        """
        xd = np.asarray(xd, dtype=float)
        if not self.has_distortion:
            return xd.copy()
        if self.fisheye:
            return self._fisheye_undistort(xd, iterations, tol)
        x = xd.copy()
        for _ in range(iterations):
            residual = self.distort(x) - xd
            if np.nanmax(np.abs(residual), initial=0.0) < tol:
                break
            # Explicit 2×2 inverse: batched np.linalg.solve costs twice the whole iteration here.
            j = self._distort_jacobian(x)
            det = j[..., 0, 0] * j[..., 1, 1] - j[..., 0, 1] * j[..., 1, 0]
            step_x = (j[..., 1, 1] * residual[..., 0] - j[..., 0, 1] * residual[..., 1]) / det
            step_y = (j[..., 0, 0] * residual[..., 1] - j[..., 1, 0] * residual[..., 0]) / det
            x = x - np.stack([step_x, step_y], axis=-1)
        return x

    def pixel_to_normalized(self, uv: np.ndarray) -> np.ndarray:
        """Ideal normalised coordinates (x/z, y/z) of pixels (..., 2) in the distorted image."""
        uv = np.asarray(uv, dtype=float)
        yd = (uv[..., 1] - self.cy) / self.fy
        xd = (uv[..., 0] - self.cx - self.skew * yd) / self.fx
        return self.undistort(np.stack([xd, yd], -1))

    def normalized_to_pixel(self, xn: np.ndarray) -> np.ndarray:
        xd = self.distort(np.asarray(xn, dtype=float))
        return np.stack([self.fx * xd[..., 0] + self.skew * xd[..., 1] + self.cx,
                         self.fy * xd[..., 1] + self.cy], -1)

    def project(self, points_cam: np.ndarray) -> np.ndarray:
        """Pixels (..., 2) of camera-frame points (..., 3); points behind the camera give NaN."""
        p = np.asarray(points_cam, dtype=float)
        z = p[..., 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            xn = p[..., :2] / np.where(z > 0, z, np.nan)[..., None]
        return self.normalized_to_pixel(xn)

    def pixel_rays(self, uv: np.ndarray) -> np.ndarray:
        """Camera-frame ray directions (..., 3) with z = 1 through pixels (..., 2)."""
        xn = self.pixel_to_normalized(uv)
        return np.concatenate([xn, np.ones(xn.shape[:-1] + (1,))], axis=-1)

    def in_frame(self, uv: np.ndarray, edge_buffer_px: float = 0.0) -> np.ndarray:
        """True where a pixel lies inside the image by at least ``edge_buffer_px``.

        The image spans [-0.5, W-0.5] × [-0.5, H-0.5] in the pixel-centre convention.
        """
        uv = np.asarray(uv, dtype=float)
        b = float(edge_buffer_px)
        with np.errstate(invalid="ignore"):
            return ((uv[..., 0] >= -0.5 + b) & (uv[..., 0] <= self.width - 0.5 - b)
                    & (uv[..., 1] >= -0.5 + b) & (uv[..., 1] <= self.height - 0.5 - b))

    def edge_margin(self, uv: np.ndarray) -> np.ndarray:
        """Distance in px from each pixel to the nearest image edge (negative outside)."""
        uv = np.asarray(uv, dtype=float)
        return np.minimum.reduce([uv[..., 0] + 0.5, self.width - 0.5 - uv[..., 0],
                                  uv[..., 1] + 0.5, self.height - 0.5 - uv[..., 1]])

    def corner_pixels(self) -> np.ndarray:
        """The four outer image corners, clockwise from top-left."""
        w, h = self.width - 0.5, self.height - 0.5
        return np.array([[-0.5, -0.5], [w, -0.5], [w, h], [-0.5, h]])

    def boundary_pixels(self, per_edge: int = 8) -> np.ndarray:
        """Pixels along the image border (clockwise); distorted edges are curved on the ground."""
        c = self.corner_pixels()
        pts = []
        for a, b in zip(c, np.roll(c, -1, axis=0)):
            t = np.linspace(0.0, 1.0, per_edge, endpoint=False)[:, None]
            pts.append(a + t * (b - a))
        return np.concatenate(pts)

    def resized(self, width: int, height: int) -> "CameraModel":
        """The same lens on the image resampled to ``width × height`` (pixel-centre convention kept)."""
        sx, sy = width / self.width, height / self.height
        return replace(self, width=int(width), height=int(height), fx=self.fx * sx, fy=self.fy * sy,
                       skew=self.skew * sx, cx=(self.cx + 0.5) * sx - 0.5, cy=(self.cy + 0.5) * sy - 0.5)

    # ------------------------------------------------------------------ extrinsics
    @property
    def T_imu_cam(self) -> np.ndarray:
        return RigidTransform.from_matrix(self.T_cam_imu).inverse().matrix

    # ------------------------------------------------------------------ (de)serialisation
    def to_dict(self) -> dict:
        d = {"width": self.width, "height": self.height, "fx": self.fx, "fy": self.fy,
             "cx": self.cx, "cy": self.cy, "dist": list(self.dist),
             "T_cam_imu": self.T_cam_imu.tolist(),
             "t_imu_rad": None if self.t_imu_rad is None else list(self.t_imu_rad),
             "source": self.source}
        # Written only when used, so frame layers of plain OpenCV cameras keep their JSON.
        d.update({name: value for name, value in (("k4", self.k4), ("skew", self.skew), ("fisheye", self.fisheye))
                  if value})
        return d

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), separators=(",", ":"))

    @classmethod
    def from_dict(cls, d: dict, source: str = "camera model") -> "CameraModel":
        try:
            return cls(width=int(d["width"]), height=int(d["height"]), fx=float(d["fx"]),
                       fy=float(d["fy"]), cx=float(d["cx"]), cy=float(d["cy"]),
                       dist=tuple(d.get("dist", (0.0,) * 5)),
                       T_cam_imu=np.asarray(d.get("T_cam_imu", np.eye(4)), dtype=float),
                       t_imu_rad=None if d.get("t_imu_rad") is None else tuple(d["t_imu_rad"]),
                       source=d.get("source", ""), k4=float(d.get("k4", 0.0)), skew=float(d.get("skew", 0.0)),
                       fisheye=bool(d.get("fisheye", False)))
        except (KeyError, TypeError, ValueError) as exc:
            raise CalibrationError(f"{source}: camera model is incomplete or malformed ({exc})") from exc

    @classmethod
    def from_json(cls, text: str, source: str = "camera model") -> "CameraModel":
        try:
            return cls.from_dict(json.loads(text), source)
        except json.JSONDecodeError as exc:
            raise CalibrationError(f"{source}: camera model is not valid JSON ({exc})") from exc


# ---------------------------------------------------------------------- loaders
def load_calibration(path) -> CameraModel:
    """Load a Kalibr camchain(-imucam) YAML or an OpenCV FileStorage YAML, whichever ``path`` is."""
    path = Path(path)
    if not path.is_file():
        raise CalibrationError(f"{path}: calibration file not found")
    text = path.read_text(encoding="utf-8", errors="replace")
    if re.search(r"^\s*camera_matrix\s*:", text, re.M):
        return load_opencv_yaml(path, text)
    if re.search(r"^cam\d+\s*:", text, re.M):
        return load_kalibr_yaml(path, text)
    raise CalibrationError(
        f"{path}: not a recognised calibration file — expected a Kalibr camchain YAML (a 'cam0:' block"
        " with 'intrinsics', 'distortion_coeffs', 'resolution') or an OpenCV YAML ('camera_matrix',"
        " 'distortion_coefficients', 'image_width', 'image_height')")


def _numbers(value, path, field_name, count=None):
    try:
        arr = np.asarray(value, dtype=float).ravel()
    except (TypeError, ValueError):
        raise CalibrationError(f"{path}: field '{field_name}' must be numbers, got {value!r}") from None
    if count is not None and arr.size not in (count if isinstance(count, tuple) else (count,)):
        raise CalibrationError(
            f"{path}: field '{field_name}' must have {count} values, got {arr.size}")
    if not np.all(np.isfinite(arr)):
        raise CalibrationError(f"{path}: field '{field_name}' contains a non-finite value")
    return arr


def _check_intrinsics(path, width, height, fx, fy, cx, cy):
    if width <= 0 or height <= 0:
        raise CalibrationError(f"{path}: resolution must be positive, got {width}×{height}")
    if fx <= 0 or fy <= 0:
        raise CalibrationError(f"{path}: focal lengths must be positive, got fx={fx}, fy={fy}")
    if not (-0.5 <= cx <= width - 0.5 and -0.5 <= cy <= height - 0.5):
        raise CalibrationError(
            f"{path}: principal point ({cx}, {cy}) lies outside the {width}×{height} image")


def _check_rigid(path, field_name, t):
    r = t[:3, :3]
    if not np.allclose(r @ r.T, np.eye(3), atol=1e-4) or not np.isclose(np.linalg.det(r), 1.0, atol=1e-4):
        raise CalibrationError(f"{path}: field '{field_name}' is not a rigid transform (rotation part"
                               " is not orthonormal with determinant +1)")


def load_kalibr_yaml(path, text: str | None = None, camera: str = "cam0") -> CameraModel:
    """Kalibr camchain / camchain-imucam YAML: intrinsics, radtan distortion, resolution, T_cam_imu.

    An optional ``T_rad_imu`` block (4×4, the radar altimeter in the IMU frame's inverse sense,
    i.e. mapping IMU points into the radar frame) gives the altimeter lever arm.
    """
    import yaml

    path = Path(path)
    text = path.read_text(encoding="utf-8", errors="replace") if text is None else text
    try:
        doc = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        raise CalibrationError(f"{path}: not valid YAML ({exc})") from exc
    if not isinstance(doc, dict) or camera not in doc or not isinstance(doc[camera], dict):
        raise CalibrationError(f"{path}: no '{camera}' block (Kalibr camchain expected)")
    cam = doc[camera]
    for key in ("intrinsics", "resolution"):
        if key not in cam:
            raise CalibrationError(f"{path}: field '{camera}.{key}' is missing")
    model = cam.get("camera_model", "pinhole")
    if model != "pinhole":
        raise CalibrationError(f"{path}: field '{camera}.camera_model' is '{model}', only 'pinhole' is supported")
    fx, fy, cx, cy = _numbers(cam["intrinsics"], path, f"{camera}.intrinsics", 4)
    width, height = (int(v) for v in _numbers(cam["resolution"], path, f"{camera}.resolution", 2))
    dist_model = cam.get("distortion_model", "radtan")
    if dist_model not in ("radtan", "equidistant", "none"):
        raise CalibrationError(f"{path}: field '{camera}.distortion_model' is '{dist_model}', expected 'radtan' or"
                               " 'equidistant'")
    dist = _numbers(cam.get("distortion_coeffs", [0, 0, 0, 0]), path, f"{camera}.distortion_coeffs",
                    4 if dist_model == "equidistant" else (4, 5))
    t_cam_imu = np.eye(4)
    if "T_cam_imu" in cam:
        t_cam_imu = _numbers(cam["T_cam_imu"], path, f"{camera}.T_cam_imu", 16).reshape(4, 4)
        _check_rigid(path, f"{camera}.T_cam_imu", t_cam_imu)
    t_imu_rad = None
    rad = doc.get("T_rad_imu", cam.get("T_rad_imu"))
    if rad is not None:
        t_rad_imu = _numbers(rad, path, "T_rad_imu", 16).reshape(4, 4)
        _check_rigid(path, "T_rad_imu", t_rad_imu)
        t_imu_rad = tuple(RigidTransform.from_matrix(t_rad_imu).inverse().translation)
    _check_intrinsics(path, width, height, fx, fy, cx, cy)
    return CameraModel(width, height, fx, fy, cx, cy, tuple(dist), t_cam_imu, t_imu_rad,
                       source=f"kalibr:{path.name}", fisheye=dist_model == "equidistant")


def load_opencv_yaml(path, text: str | None = None) -> CameraModel:
    """OpenCV FileStorage YAML (``camera_matrix``, ``distortion_coefficients``, image size)."""
    import yaml

    path = Path(path)
    text = path.read_text(encoding="utf-8", errors="replace") if text is None else text
    # FileStorage writes a %YAML:1.0 directive and !!opencv-matrix tags that PyYAML rejects.
    cleaned = re.sub(r"^%YAML.*$", "", text, flags=re.M)
    cleaned = re.sub(r"!!opencv-matrix", "", cleaned)
    try:
        doc = yaml.safe_load(cleaned)
    except yaml.YAMLError as exc:
        raise CalibrationError(f"{path}: not valid YAML ({exc})") from exc
    if not isinstance(doc, dict):
        raise CalibrationError(f"{path}: not an OpenCV calibration file")

    def matrix(key, count):
        if key not in doc:
            raise CalibrationError(f"{path}: field '{key}' is missing")
        value = doc[key]
        data = value.get("data") if isinstance(value, dict) else value
        if data is None:
            raise CalibrationError(f"{path}: field '{key}.data' is missing")
        return _numbers(data, path, key, count)

    k = matrix("camera_matrix", 9).reshape(3, 3)
    dist = matrix("distortion_coefficients", (4, 5, 8, 12, 14))
    if dist.size > 5 and np.any(dist[5:] != 0):
        raise CalibrationError(f"{path}: field 'distortion_coefficients' uses the rational/thin-prism"
                               " terms (k4…); only k1 k2 p1 p2 k3 are supported")
    for key in ("image_width", "image_height"):
        if key not in doc:
            raise CalibrationError(f"{path}: field '{key}' is missing")
    width, height = int(doc["image_width"]), int(doc["image_height"])
    fx, fy, cx, cy = k[0, 0], k[1, 1], k[0, 2], k[1, 2]
    _check_intrinsics(path, width, height, fx, fy, cx, cy)
    t_cam_imu = np.eye(4)
    if "T_cam_imu" in doc:
        t_cam_imu = matrix("T_cam_imu", 16).reshape(4, 4)
        _check_rigid(path, "T_cam_imu", t_cam_imu)
    return CameraModel(width, height, fx, fy, cx, cy, tuple(dist[:5]), t_cam_imu,
                       source=f"opencv:{path.name}", skew=k[0, 1])


def camera_from_dji_dewarp(dewarp: str, width: int, height: int, source: str = "DewarpData",
                           T_cam_imu: np.ndarray | None = None) -> CameraModel:
    """Camera from a DJI ``DewarpData`` XMP value ``date;fx,fy,cx,cy,k1,k2,p1,p2,k3``.

    DJI gives cx, cy as offsets from the image centre; they are converted to the OpenCV
    pixel-centre convention here.
    """
    text = (dewarp or "").strip()
    parts = text.split(";", 1)
    values = parts[1] if len(parts) == 2 else parts[0]
    try:
        nums = [float(v) for v in values.split(",")]
    except ValueError:
        raise CalibrationError(f"{source}: DewarpData '{text}' is not 'date;fx,fy,cx,cy,k1,k2,p1,p2,k3'") from None
    if len(nums) != 9:
        raise CalibrationError(f"{source}: DewarpData has {len(nums)} numbers, expected 9 (fx,fy,cx,cy,k1,k2,p1,p2,k3)")
    fx, fy, dcx, dcy, k1, k2, p1, p2, k3 = nums
    cx = (width - 1) / 2.0 + dcx
    cy = (height - 1) / 2.0 + dcy
    _check_intrinsics(source, width, height, fx, fy, cx, cy)
    return CameraModel(width, height, fx, fy, cx, cy, (k1, k2, p1, p2, k3),
                       np.eye(4) if T_cam_imu is None else T_cam_imu, source=f"dji:{source}")


def write_kalibr_yaml(camera: CameraModel, path) -> None:
    """Write a Kalibr camchain-imucam YAML that :func:`load_kalibr_yaml` reads back."""
    import yaml

    if camera.k4 or camera.skew:
        raise CalibrationError(f"{path}: a Kalibr camchain has no r⁸ radial term (k4) or skew; this camera has"
                               f" k4 {camera.k4:g}, skew {camera.skew:g} px")
    if camera.fisheye:
        model, coeffs = "equidistant", list(camera.dist[:4])
    else:
        model, coeffs = "radtan", list(camera.dist[:4]) + ([camera.dist[4]] if camera.dist[4] else [])
    cam = {"camera_model": "pinhole",
           "intrinsics": [camera.fx, camera.fy, camera.cx, camera.cy],
           "distortion_model": model,
           "distortion_coeffs": coeffs,
           "resolution": [camera.width, camera.height],
           "T_cam_imu": camera.T_cam_imu.tolist()}
    doc = {"cam0": cam}
    if camera.t_imu_rad is not None:
        # Only the altimeter's position is known: its frame is taken as the body's, moved to the lever arm.
        imu_from_rad = RigidTransform(np.eye(3), camera.t_imu_rad)
        doc["T_rad_imu"] = imu_from_rad.inverse().matrix.tolist()
    Path(path).write_text(yaml.safe_dump(doc, sort_keys=False), encoding="utf-8")
