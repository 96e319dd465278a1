"""Parameters shared by the platform-design algorithms (``sensorbound``, ``montecarlobound``,
``terrainslope``): the camera, the pose sigmas and the camera mount, altitudes and the tolerance.

Units at this interface: intrinsics in px, altitudes in metres above the ground, sigmas x, y, z in
metres and roll, pitch, yaw in degrees (turned into camera rotations by the mount,
``core.design.sensor_bound.CameraMount``), tolerance r in px at 3σ.
"""
from __future__ import annotations

import math
from pathlib import Path

from qgis.core import (
    QgsProcessingException,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFile,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
)

from ...birdseye_qgis.core.design.number_lists import SIGMAS_HINT, format_number_list, parse_altitudes, parse_sigmas
from ...birdseye_qgis.core.design.platforms import DEPLOYED, PLATFORMS
from ...birdseye_qgis.core.design.sensor_bound import MOUNTS, Intrinsics
from ...birdseye_qgis.core.errors import InputError
from ...birdseye_qgis.core.geometry.camera import CALIBRATION_FILE_FILTER, load_calibration
from ...birdseye_qgis.qgis_enums import FILE_BEHAVIOR_FILE, NUMBER_DOUBLE, NUMBER_INTEGER

# The platform the BirdsEye method was deployed on (camera calibration, INS and altimeter budget).
DEPLOYED_CAMERA = DEPLOYED.camera
DEPLOYED_SIGMAS = DEPLOYED.sigmas
DEPLOYED_TOLERANCE_PX = DEPLOYED.tolerance_px
DEPLOYED_ALTITUDES_M = DEPLOYED.altitudes_m


class DesignParametersMixin:
    """Parameter definitions and readers for the platform-design algorithms.

    Mixed into a ``BirdsEyeAlgorithm`` subclass; every reader raises ``QgsProcessingException`` with a
    message that names the parameter.
    """

    PLATFORM = "PLATFORM"
    CALIBRATION = "CALIBRATION"
    FX, FY, CX, CY, WIDTH, HEIGHT = "FX", "FY", "CX", "CY", "WIDTH", "HEIGHT"
    ALTITUDES = "ALTITUDES"
    SIGMAS = "SIGMAS"
    MOUNT = "MOUNT"
    TOLERANCE_PX = "TOLERANCE_PX"

    # ------------------------------------------------------------------ definitions
    def add_camera_parameters(self) -> None:
        """PLATFORM (a preset: camera and pose sigmas), CALIBRATION (optional file, overrides the camera)
        and FX, FY, CX, CY, WIDTH, HEIGHT (px)."""
        self.addParameter(QgsProcessingParameterEnum(
            self.PLATFORM, self.tr("Platform preset (Custom: the values below)"),
            options=[self.tr("Custom")] + [self.tr(p.name) for p in PLATFORMS], defaultValue=0))
        self.addParameter(QgsProcessingParameterFile(
            self.CALIBRATION, self.tr("Camera calibration (YAML)"),
            behavior=FILE_BEHAVIOR_FILE, fileFilter=CALIBRATION_FILE_FILTER, optional=True))
        cam = DEPLOYED_CAMERA
        for name, label, default in (
                (self.FX, "Focal length fx (px)", cam.fx), (self.FY, "Focal length fy (px)", cam.fy),
                (self.CX, "Principal point cx (px)", cam.cx), (self.CY, "Principal point cy (px)", cam.cy)):
            self.addParameter(QgsProcessingParameterNumber(
                name, self.tr(label), NUMBER_DOUBLE, defaultValue=default))
        for name, label, default in ((self.WIDTH, "Image width (px)", cam.width),
                                     (self.HEIGHT, "Image height (px)", cam.height)):
            self.addParameter(QgsProcessingParameterNumber(
                name, self.tr(label), NUMBER_INTEGER, defaultValue=default, minValue=1))

    def add_sigmas_parameter(self) -> None:
        """SIGMAS and MOUNT, which says how the roll, pitch and yaw sigmas turn the camera."""
        self.addParameter(QgsProcessingParameterString(
            self.SIGMAS, self.tr("Pose sigmas 1σ: x, y, z (m), roll, pitch, yaw (°)"),
            defaultValue=format_number_list(DEPLOYED_SIGMAS)))
        self.addParameter(QgsProcessingParameterEnum(
            self.MOUNT, self.tr("Camera mount"),
            options=[self.tr(m.name) for m in MOUNTS], defaultValue=MOUNTS.index(DEPLOYED.mount)))

    def add_altitudes_parameter(self, name: str = "ALTITUDES") -> None:
        self.addParameter(QgsProcessingParameterString(
            name, self.tr("Altitudes above the ground (m, comma-separated)"),
            defaultValue=format_number_list(DEPLOYED_ALTITUDES_M)))

    def add_tolerance_parameter(self) -> None:
        self.addParameter(QgsProcessingParameterNumber(
            self.TOLERANCE_PX, self.tr("Label tolerance r (px, label radius at 3σ)"),
            NUMBER_DOUBLE, defaultValue=DEPLOYED_TOLERANCE_PX))

    # ------------------------------------------------------------------ readers
    def camera_from_parameters(self, parameters, context, feedback):
        """A ``CameraModel`` from CALIBRATION when given, else ``Intrinsics`` from FX … HEIGHT.

        Distortion and extrinsics of a calibration are not used by the design algorithms.
        """
        path = self.parameterAsFile(parameters, self.CALIBRATION, context)
        preset = self.platform_from_parameters(parameters, context)
        if preset is not None and feedback is not None:
            feedback.pushInfo(self.tr("Platform {name}. Sources: {sources}.").format(name=preset.name,
                                                                                  sources=preset.sources))
            if self.parameterDefinition(self.SIGMAS) is not None:
                feedback.pushInfo(self.tr("Pose sigmas of the platform: {sigmas} ({hint}; the typed SIGMAS are "
                                          "ignored), camera mount: {mount} (the chosen {MOUNT} is ignored).").format(
                    sigmas=format_number_list(preset.sigmas), hint=SIGMAS_HINT, mount=self.tr(preset.mount.name),
                    MOUNT=self.MOUNT))
        if path:
            try:
                camera = load_calibration(path)
            except InputError as exc:
                raise QgsProcessingException(self.tr("{CALIBRATION}: {exc}").format(
                                                 CALIBRATION=self.CALIBRATION, exc=exc)) from exc
            if feedback is not None:
                feedback.pushInfo(self.tr(
                    "Camera from {file}: {w}×{h} px, fx {fx:.4f}, fy {fy:.4f}, cx {cx:.4f}, cy {cy:.4f} px "
                    "(the typed intrinsics are ignored).").format(
                    file=Path(path).name, w=camera.width, h=camera.height, fx=camera.fx, fy=camera.fy,
                    cx=camera.cx, cy=camera.cy))
            return camera
        if preset is not None:
            if feedback is not None:
                cam = preset.camera
                feedback.pushInfo(self.tr("Camera of the platform: {w}×{h} px, fx {fx:.4f}, fy {fy:.4f}, cx {cx:.4f}, "
                                          "cy {cy:.4f} px (the typed intrinsics are ignored).").format(
                    w=cam.width, h=cam.height, fx=cam.fx, fy=cam.fy, cx=cam.cx, cy=cam.cy))
            return preset.camera
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

    def platform_from_parameters(self, parameters, context):
        """The chosen platform preset, or None for Custom (the typed values)."""
        index = self.parameterAsEnum(parameters, self.PLATFORM, context)
        return PLATFORMS[index - 1] if index > 0 else None

    def sigmas_from_parameters(self, parameters, context) -> list[float]:
        preset = self.platform_from_parameters(parameters, context)
        if preset is not None:
            return list(preset.sigmas)
        return self._parsed(parse_sigmas, parameters, self.SIGMAS, context)

    def mount_from_parameters(self, parameters, context):
        """The platform's camera mount when a preset is chosen, else the one picked in MOUNT."""
        preset = self.platform_from_parameters(parameters, context)
        if preset is not None:
            return preset.mount
        return MOUNTS[self.parameterAsEnum(parameters, self.MOUNT, context)]

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
