"""Parameters shared by the platform-design algorithms (``sensorbound``, ``montecarlobound``,
``terrainslope``) and the sensor-bound dock: the camera, the pose sigmas, altitudes and the tolerance.

Kept out of ``processing/algorithms`` on purpose: the provider (and its contract test) expect every
module there to be one algorithm named after its file.

Units at this interface: intrinsics in px, altitudes in metres above the ground, sigmas x, y, z in
metres and roll, pitch, yaw in degrees (``core.sensor_bound.AXIS_CONVENTION``), tolerance r in px at 3σ.
"""
from __future__ import annotations

import math
from pathlib import Path

from qgis.core import (
    QgsExpressionContextUtils,
    QgsProcessingException,
    QgsProcessingParameterFile,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
)

from ..birdseye_qgis.core.geometry.camera import load_calibration
from ..birdseye_qgis.core.errors import InputError
from ..birdseye_qgis.core.design.sensor_bound import AXES, SIGMA_UNITS, Intrinsics

# The platform the BirdsEye method was deployed on (camera calibration, INS and altimeter budget).
DEPLOYED_CAMERA = Intrinsics(fx=4264.4945, fy=4262.8927, cx=958.4594, cy=592.5033, width=1920, height=1200)
DEPLOYED_SIGMAS = (0.010, 0.010, 0.060, 0.04, 0.04, 0.13)
DEPLOYED_TOLERANCE_PX = 30.0
DEPLOYED_ALTITUDES_M = (10.0, 20.0)

# σ_label handed from the sensor-bound calculator to ``writelabels`` through the project (both places
# are written; a saved project keeps variables as text, so read with ``read_sigma_label_px``).
SIGMA_LABEL_SCOPE = "birdseye"
SIGMA_LABEL_KEY = "sigma_label_px"
SIGMA_LABEL_VARIABLE = "birdseye_sigma_label_px"

SIGMAS_HINT = "x, y, z in metres; roll, pitch, yaw in degrees"
CALIBRATION_FILTER = "Camera calibration (*.yaml *.yml);;All files (*)"


def format_number_list(values) -> str:
    """``[10.0, 20.0]`` → ``"10,20"``: the comma-separated form the list parameters take."""
    return ",".join(f"{float(v):g}" for v in values)


def parse_number_list(text, name: str, hint: str) -> list[float]:
    """Comma-separated numbers (spaces and ';' accepted as well); ``name`` prefixes every message.

    Raises ``InputError`` naming the offending item and what was expected (``hint``).
    """
    items = [item for item in str(text or "").replace(";", ",").replace(" ", ",").split(",") if item]
    if not items:
        raise InputError(f"{name}: no values given — expected comma-separated {hint}")
    values = []
    for position, item in enumerate(items, start=1):
        try:
            value = float(item)
        except ValueError:
            raise InputError(f"{name}: item {position} '{item}' is not a number — expected "
                             f"comma-separated {hint}") from None
        if not math.isfinite(value):
            raise InputError(f"{name}: item {position} '{item}' is not a finite number")
        values.append(value)
    return values


def parse_altitudes(text, name: str = "ALTITUDES") -> list[float]:
    """Altitudes above the ground (m), each > 0."""
    altitudes = parse_number_list(text, name, "altitudes above the ground in metres, e.g. 10,20")
    for altitude in altitudes:
        if altitude <= 0:
            raise InputError(f"{name}: altitude {altitude:g} m is not above the ground — every altitude "
                             "must be greater than 0 m")
    return altitudes


def parse_sigmas(text, name: str = "SIGMAS") -> list[float]:
    """The six pose sigmas (x, y, z in m; roll, pitch, yaw in degrees), each ≥ 0."""
    sigmas = parse_number_list(text, name, f"pose sigmas ({SIGMAS_HINT})")
    if len(sigmas) != len(AXES):
        raise InputError(f"{name}: expected {len(AXES)} sigmas ({SIGMAS_HINT}), got {len(sigmas)}")
    for axis, unit, sigma in zip(AXES, SIGMA_UNITS, sigmas):
        if sigma < 0:
            raise InputError(f"{name}: the {axis} sigma is negative ({sigma:g} {unit}) — sigmas are "
                             "standard deviations and must be 0 or more")
    return sigmas


def store_sigma_label_px(project, sigma_px: float) -> None:
    """Store σ_label (px) in ``project``: entry ``birdseye/sigma_label_px``, variable ``@birdseye_sigma_label_px``."""
    project.writeEntryDouble(SIGMA_LABEL_SCOPE, SIGMA_LABEL_KEY, float(sigma_px))
    QgsExpressionContextUtils.setProjectVariable(project, SIGMA_LABEL_VARIABLE, float(sigma_px))


def read_sigma_label_px(project):
    """σ_label (px) stored in ``project`` by the calculator, or None: the variable first, then the entry.

    The variable wins because users can edit it (Project ▸ Properties ▸ Variables).
    """
    value = QgsExpressionContextUtils.projectScope(project).variable(SIGMA_LABEL_VARIABLE)
    try:
        if value not in (None, ""):
            sigma = float(value)
            return sigma if sigma > 0 and math.isfinite(sigma) else None
    except (TypeError, ValueError):
        return None
    sigma, found = project.readDoubleEntry(SIGMA_LABEL_SCOPE, SIGMA_LABEL_KEY)
    return sigma if found and sigma > 0 and math.isfinite(sigma) else None


class DesignParametersMixin:
    """Parameter definitions and readers for the platform-design algorithms.

    Mixed into a ``BirdsEyeAlgorithm`` subclass; every reader raises ``QgsProcessingException`` with a
    message that names the parameter.
    """

    CALIBRATION = "CALIBRATION"
    FX, FY, CX, CY, WIDTH, HEIGHT = "FX", "FY", "CX", "CY", "WIDTH", "HEIGHT"
    ALTITUDES = "ALTITUDES"
    SIGMAS = "SIGMAS"
    TOLERANCE_PX = "TOLERANCE_PX"

    # ------------------------------------------------------------------ definitions
    def add_camera_parameters(self) -> None:
        """CALIBRATION (optional file, overrides the rest) and FX, FY, CX, CY, WIDTH, HEIGHT (px)."""
        self.addParameter(QgsProcessingParameterFile(
            self.CALIBRATION, self.tr("Camera calibration (Kalibr or OpenCV YAML; overrides the intrinsics below)"),
            behavior=QgsProcessingParameterFile.File, fileFilter=CALIBRATION_FILTER, optional=True))
        cam = DEPLOYED_CAMERA
        for name, label, default in (
                (self.FX, "Focal length fx [px]", cam.fx), (self.FY, "Focal length fy [px]", cam.fy),
                (self.CX, "Principal point cx [px]", cam.cx), (self.CY, "Principal point cy [px]", cam.cy)):
            self.addParameter(QgsProcessingParameterNumber(
                name, self.tr(label), QgsProcessingParameterNumber.Double, defaultValue=default))
        for name, label, default in ((self.WIDTH, "Image width [px]", cam.width),
                                     (self.HEIGHT, "Image height [px]", cam.height)):
            self.addParameter(QgsProcessingParameterNumber(
                name, self.tr(label), QgsProcessingParameterNumber.Integer, defaultValue=default, minValue=1))

    def add_sigmas_parameter(self) -> None:
        self.addParameter(QgsProcessingParameterString(
            self.SIGMAS, self.tr("Pose sigmas, 1σ (x, y, z in metres; roll, pitch, yaw in degrees)"),
            defaultValue=format_number_list(DEPLOYED_SIGMAS)))

    def add_altitudes_parameter(self, name: str = "ALTITUDES") -> None:
        self.addParameter(QgsProcessingParameterString(
            name, self.tr("Altitudes above the ground [m], comma-separated"),
            defaultValue=format_number_list(DEPLOYED_ALTITUDES_M)))

    def add_tolerance_parameter(self) -> None:
        self.addParameter(QgsProcessingParameterNumber(
            self.TOLERANCE_PX, self.tr("Label tolerance r [px] (label radius at 3σ)"),
            QgsProcessingParameterNumber.Double, defaultValue=DEPLOYED_TOLERANCE_PX))

    # ------------------------------------------------------------------ readers
    def camera_from_parameters(self, parameters, context, feedback):
        """A ``CameraModel`` from CALIBRATION when given, else ``Intrinsics`` from FX … HEIGHT.

        Distortion and extrinsics of a calibration are not used by the design algorithms.
        """
        path = self.parameterAsFile(parameters, self.CALIBRATION, context)
        if path:
            try:
                camera = load_calibration(path)
            except InputError as exc:
                raise QgsProcessingException(f"{self.CALIBRATION}: {exc}") from exc
            if feedback is not None:
                feedback.pushInfo(self.tr(
                    "Camera from {file}: {w}×{h} px, fx {fx:.4f}, fy {fy:.4f}, cx {cx:.4f}, cy {cy:.4f} px "
                    "(the typed intrinsics are ignored).").format(
                    file=Path(path).name, w=camera.width, h=camera.height, fx=camera.fx, fy=camera.fy,
                    cx=camera.cx, cy=camera.cy))
            return camera
        values = {name: self.parameterAsDouble(parameters, name, context)
                  for name in (self.FX, self.FY, self.CX, self.CY)}
        size = {name: self.parameterAsInt(parameters, name, context) for name in (self.WIDTH, self.HEIGHT)}
        for name in (self.FX, self.FY):
            if not (values[name] > 0 and math.isfinite(values[name])):
                raise QgsProcessingException(self.tr(
                    "{name}: the focal length must be greater than 0 px, got {value:g}").format(
                    name=name, value=values[name]))
        return Intrinsics(fx=values[self.FX], fy=values[self.FY], cx=values[self.CX], cy=values[self.CY],
                          width=size[self.WIDTH], height=size[self.HEIGHT])

    def sigmas_from_parameters(self, parameters, context) -> list[float]:
        return self._parsed(parse_sigmas, parameters, self.SIGMAS, context)

    def altitudes_from_parameters(self, parameters, context, name: str = "ALTITUDES") -> list[float]:
        return self._parsed(parse_altitudes, parameters, name, context)

    def tolerance_from_parameters(self, parameters, context) -> float:
        tolerance = self.parameterAsDouble(parameters, self.TOLERANCE_PX, context)
        if not (tolerance > 0 and math.isfinite(tolerance)):
            raise QgsProcessingException(self.tr("{name}: the label tolerance must be greater than 0 px, got {value:g}")
                                         .format(name=self.TOLERANCE_PX, value=tolerance))
        return tolerance

    def check_canceled(self, feedback) -> None:
        """Stop between stages when the user pressed Cancel."""
        if feedback is not None and feedback.isCanceled():
            raise QgsProcessingException(self.tr("Cancelled by the user."))

    def _parsed(self, parser, parameters, name, context):
        try:
            return parser(self.parameterAsString(parameters, name, context), name)
        except InputError as exc:
            raise QgsProcessingException(str(exc)) from exc
