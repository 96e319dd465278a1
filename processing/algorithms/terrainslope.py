"""``birdseye:terrainslope`` — how much slope the level-ground model tolerates before labels drift out."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
from qgis.core import QgsProcessingException, QgsProcessingParameterFileDestination, QgsProcessingParameterNumber
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.design.terrain_slope import (
    frame_distance_ratios,
    max_slope_deg,
    plot_slope_error,
    slope_error_grid,
)
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE
from ..parameters.design import DesignParametersMixin
from .base import BirdsEyeAlgorithm

# Grid of the study: slopes every half degree, ρ = d/h in 100 steps to 15 % beyond the frame corner.
SLOPE_STEP_DEG = 0.5
RATIO_STEPS = 101
RATIO_MARGIN = 1.15


class TerrainSlopeAlgorithm(DesignParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "terrainslope"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("TerrainSlopeAlgorithm", "Sensor bound: terrain-slope study")
    GROUP = "design"

    ALTITUDE_M = "ALTITUDE_M"
    MAX_SLOPE_DEG = "MAX_SLOPE_DEG"
    OUTPUT_JSON = "OUTPUT_JSON"
    OUTPUT_PNG = "OUTPUT_PNG"

    def initAlgorithm(self, config=None):
        self.add_camera_parameters()
        self.addParameter(QgsProcessingParameterNumber(
            self.ALTITUDE_M, self.tr("Altitude above the ground [m]"), NUMBER_DOUBLE,
            defaultValue=10.0))
        self.add_tolerance_parameter()
        self.addParameter(QgsProcessingParameterNumber(
            self.MAX_SLOPE_DEG, self.tr("Steepest slope studied [degrees]"), NUMBER_DOUBLE,
            defaultValue=45.0))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_JSON, self.tr("Results (JSON)"), "JSON files (*.json)"))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_PNG, self.tr("Contour plot (PNG)"), "PNG files (*.png)", optional=True,
            createByDefault=True))

    def processAlgorithm(self, parameters, context, feedback):
        camera = self.camera_from_parameters(parameters, context, feedback)
        altitude = self.parameterAsDouble(parameters, self.ALTITUDE_M, context)
        if not (altitude > 0 and math.isfinite(altitude)):
            raise QgsProcessingException(self.tr("{name}: the altitude must be greater than 0 m, got {value:g}")
                                         .format(name=self.ALTITUDE_M, value=altitude))
        tolerance = self.tolerance_from_parameters(parameters, context)
        steepest = self.parameterAsDouble(parameters, self.MAX_SLOPE_DEG, context)
        if not 0 < steepest < 90:
            raise QgsProcessingException(self.tr("{name}: the steepest slope must lie between 0° and 90° "
                                                 "(exclusive), got {value:g}").format(name=self.MAX_SLOPE_DEG,
                                                                                     value=steepest))
        json_path = self.parameterAsFileOutput(parameters, self.OUTPUT_JSON, context)
        png_path = self.parameterAsFileOutput(parameters, self.OUTPUT_PNG, context)

        frame = self.run_core(frame_distance_ratios, camera)
        slopes = np.linspace(0.0, steepest, int(math.ceil(steepest / SLOPE_STEP_DEG)) + 1)
        ratios = np.linspace(0.0, RATIO_MARGIN * frame["corner"], RATIO_STEPS)
        errors = self.run_core(slope_error_grid, camera, altitude, slopes, ratios)
        feedback.setProgress(40)

        points = {}
        for name, rho in frame.items():
            limit = self.run_core(max_slope_deg, camera, tolerance, rho)
            points[name] = {"distance_ratio": rho, "distance_m": rho * altitude, "max_slope_deg": limit}
            feedback.pushInfo(self.tr(
                "{where}: {d:.2f} m from the nadir point at {alt:g} m (ρ = {rho:.3f}) — labels stay within "
                "{tol:g} px up to a {limit:.1f}° uphill slope.").format(
                where=self._describe(name), d=rho * altitude, alt=altitude, rho=rho, tol=tolerance, limit=limit))
        self.check_canceled(feedback)

        Path(json_path).parent.mkdir(parents=True, exist_ok=True)
        with open(json_path, "w", encoding="utf-8") as handle:
            json.dump({
                "altitude_m": altitude, "tolerance_px": tolerance,
                "slopes_deg": slopes.tolist(), "distance_ratios": ratios.tolist(),
                "error_px": [[None if math.isnan(e) else float(e) for e in row] for row in errors],
                "frame_points": points,
                "inputs": {"intrinsics": {k: getattr(camera, k) for k in ("fx", "fy", "cx", "cy", "width", "height")},
                           "calibration": self.parameterAsFile(parameters, self.CALIBRATION, context) or None},
            }, handle, indent=1)
        feedback.setProgress(60)
        if png_path:
            Path(png_path).parent.mkdir(parents=True, exist_ok=True)
            self.run_core(plot_slope_error, camera, altitude, png_path, tolerance, slopes, ratios)
        feedback.setProgress(100)
        return {self.OUTPUT_JSON: json_path, self.OUTPUT_PNG: png_path or None}

    def _describe(self, name: str) -> str:
        return {"edge_u": self.tr("Farthest left/right edge midpoint"),
                "edge_v": self.tr("Farthest top/bottom edge midpoint"),
                "corner": self.tr("Farthest frame corner")}[name]
