"""``birdseye:montecarlobound`` — does the first-order sensor bound hold for this pose-noise budget?"""
from __future__ import annotations

import json
import math
import tempfile
from pathlib import Path

import numpy as np
from qgis.core import (
    QgsProcessingException,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.design.monte_carlo_bound import (
    ELLIPSE_SIGMAS,
    GROUND_SPACING_M,
    SKLD_CUTOFFS,
    SKLD_THRESHOLD,
    monte_carlo_check,
    plot_scaling_study,
    scaling_study,
)
from ...birdseye_qgis.core.design.number_lists import format_number_list, parse_skld_cutoffs
from ...birdseye_qgis.core.design.sensor_bound import AXES, evaluate_bound
from ..parameters.design import DesignParametersMixin
from .base import BirdsEyeAlgorithm


class MonteCarloBoundAlgorithm(DesignParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "montecarlobound"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("MonteCarloBoundAlgorithm", "Sensor bound: Monte Carlo check")
    GROUP = "design"

    GROUND_SPACING_M = "GROUND_SPACING_M"
    SKLD_CUTOFFS = "SKLD_CUTOFFS"
    N_SAMPLES = "N_SAMPLES"
    SEED = "SEED"
    SCALE_MIN = "SCALE_MIN"
    SCALE_MAX = "SCALE_MAX"
    SCALE_STEPS = "SCALE_STEPS"
    PER_AXIS = "PER_AXIS"
    OUTPUT_JSON = "OUTPUT_JSON"
    OUTPUT_PNG = "OUTPUT_PNG"

    def initAlgorithm(self, config=None):
        self.add_camera_parameters()
        self.add_altitudes_parameter()
        self.add_sigmas_parameter()
        self.add_tolerance_parameter()
        number = QgsProcessingParameterNumber
        self.addParameter(number(self.GROUND_SPACING_M, self.tr("Ground grid spacing (m)"), number.Double,
                                 defaultValue=GROUND_SPACING_M))
        self.addParameter(QgsProcessingParameterString(
            self.SKLD_CUTOFFS, self.tr("sKLD cut-offs (nats, comma-separated)"),
            defaultValue=format_number_list(SKLD_CUTOFFS)))
        self.addParameter(number(self.N_SAMPLES, self.tr("Monte Carlo samples"), number.Integer,
                                 defaultValue=20000, minValue=10))
        self.addParameter(number(self.SEED, self.tr("Random seed"), number.Integer, defaultValue=0, minValue=0))
        self.addParameter(number(self.SCALE_MIN, self.tr("Scaling study: smallest variance factor"), number.Double,
                                 defaultValue=0.1))
        self.addParameter(number(self.SCALE_MAX, self.tr("Scaling study: largest variance factor"), number.Double,
                                 defaultValue=100.0))
        self.addParameter(number(self.SCALE_STEPS, self.tr("Scaling study: number of factors (log-spaced)"),
                                 number.Integer, defaultValue=25, minValue=2))
        self.addParameter(QgsProcessingParameterBoolean(
            self.PER_AXIS, self.tr("Scaling study per axis as well (7× the work)"), defaultValue=False))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_JSON, self.tr("Results (JSON)"), "JSON files (*.json)"))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_PNG, self.tr("Scaling-study plot (PNG)"), "PNG files (*.png)",
            optional=True, createByDefault=True))

    def processAlgorithm(self, parameters, context, feedback):
        camera = self.camera_from_parameters(parameters, context, feedback)
        altitudes = self.altitudes_from_parameters(parameters, context)
        sigmas = self.sigmas_from_parameters(parameters, context)
        mount = self.mount_from_parameters(parameters, context)
        tolerance = self.tolerance_from_parameters(parameters, context)
        spacing = self._spacing(parameters, context)
        cutoffs = self._parsed(parse_skld_cutoffs, parameters, self.SKLD_CUTOFFS, context)
        n_samples = self.parameterAsInt(parameters, self.N_SAMPLES, context)
        seed = self.parameterAsInt(parameters, self.SEED, context)
        scales = self._scales(parameters, context)
        per_axis = self.parameterAsBool(parameters, self.PER_AXIS, context)
        json_path = self.parameterAsFileOutput(parameters, self.OUTPUT_JSON, context)
        png_path = self.parameterAsFileOutput(parameters, self.OUTPUT_PNG, context)
        _, is_canceled = self.progress_callbacks(feedback)

        entries, panels = [], []
        with tempfile.TemporaryDirectory(prefix="birdseye_mc_") as scratch:
            for k, altitude in enumerate(altitudes):
                bound = self.run_core(evaluate_bound, camera, altitude, sigmas, tolerance, mount=mount)
                check = self.run_core(monte_carlo_check, camera, altitude, sigmas, n_samples, spacing, seed=seed,
                                      mount=mount, skld_cutoffs=cutoffs, is_canceled=is_canceled)
                study = self.run_core(scaling_study, camera, altitude, sigmas, scales, per_axis, n_samples, spacing,
                                      seed=seed, is_canceled=is_canceled, mount=mount)
                kappa = bound.kappa_exact
                entries.append({
                    "altitude_m": altitude,
                    "kappa_exact": kappa if math.isfinite(kappa) else None,
                    "skld_threshold": SKLD_THRESHOLD,
                    "max_skld": check.summary()["max_skld"],
                    "linearisation_holds": check.linearisation_holds,
                    "check": check.to_json_dict(),
                    "scaling": study.to_json_dict(),
                })
                self._log(feedback, check, kappa, tolerance)
                if png_path:
                    panels.append(plot_scaling_study(study, Path(scratch) / f"panel_{k}.png", cutoffs, kappa=kappa))
                feedback.setProgress(100.0 * (k + 1) / len(altitudes))
            if png_path:
                self._stack_panels(panels, png_path)

        Path(json_path).parent.mkdir(parents=True, exist_ok=True)
        with open(json_path, "w", encoding="utf-8") as handle:
            json.dump({"altitudes": entries, "inputs": self._inputs(camera, sigmas, mount, tolerance, spacing, cutoffs,
                                                                     n_samples, seed, scales, per_axis, parameters,
                                                                     context)},
                      handle, indent=2)
        return {self.OUTPUT_JSON: json_path, self.OUTPUT_PNG: png_path or None}

    def _log(self, feedback, check, kappa, tolerance) -> None:
        """The altitude's summary in the user's words: the grid, the ellipses against r, the sKLD verdict."""
        summary = check.summary()
        grid = check.grid
        feedback.pushInfo(self.tr(
            "{alt:g} m: {n} ground points every {spacing:g} m ({rows} × {cols}). Label error ellipse at {k:g}σ: "
            "semi-major axis max {major_max:.3g} px, median {major_median:.3g} px (tolerance r {r:g} px); "
            "anisotropy (major/minor) max {ratio_max}, median {ratio_median}.").format(
            alt=check.altitude_m, n=summary["n_points"], spacing=grid.spacing_m, rows=grid.shape[0],
            cols=grid.shape[1], k=ELLIPSE_SIGMAS, major_max=summary["major_axis_px_max"],
            major_median=summary["major_axis_px_median"], r=tolerance,
            ratio_max=self._ratio(summary["anisotropy_max"]), ratio_median=self._ratio(summary["anisotropy_median"])))
        over = ", ".join(self.tr("{share:.1%} over {cutoff}").format(share=share, cutoff=cutoff)
                         for cutoff, share in summary["fraction_over_skld"].items())
        feedback.pushInfo(self.tr(
            "{alt:g} m: max sKLD at the deployed budget {skld:.3g} nats (threshold {thr:g}) → the linearised bound "
            "{verdict}; grid points over each sKLD cut-off: {over}; exact κ* = {kappa:.3g}.").format(
            alt=check.altitude_m, skld=check.max_skld, over=over, thr=SKLD_THRESHOLD, kappa=kappa,
            verdict=self.tr("holds") if check.linearisation_holds else self.tr("does NOT hold")))

    def _ratio(self, value) -> str:
        return self.tr("unbounded (labels move along one line)") if value is None else f"{value:.3g}"

    def _spacing(self, parameters, context) -> float:
        spacing = self.parameterAsDouble(parameters, self.GROUND_SPACING_M, context)
        if not (spacing > 0 and math.isfinite(spacing)):
            raise QgsProcessingException(self.tr("{name}: the ground grid spacing must be greater than 0 m, "
                                                 "got {value:g}").format(name=self.GROUND_SPACING_M, value=spacing))
        return spacing

    def _scales(self, parameters, context) -> np.ndarray:
        low = self.parameterAsDouble(parameters, self.SCALE_MIN, context)
        high = self.parameterAsDouble(parameters, self.SCALE_MAX, context)
        steps = self.parameterAsInt(parameters, self.SCALE_STEPS, context)
        if not low > 0:
            raise QgsProcessingException(self.tr("{name}: the smallest variance factor must be greater than 0, "
                                                 "got {value:g}").format(name=self.SCALE_MIN, value=low))
        if not high > low:
            raise QgsProcessingException(self.tr("{name}: the largest variance factor must exceed {other} "
                                                 "({low:g}), got {value:g}").format(
                name=self.SCALE_MAX, other=self.SCALE_MIN, low=low, value=high))
        return np.logspace(math.log10(low), math.log10(high), steps)

    def _inputs(self, camera, sigmas, mount, tolerance, spacing, cutoffs, n_samples, seed, scales, per_axis,
                parameters, context) -> dict:
        return {
            "intrinsics": {k: getattr(camera, k) for k in ("fx", "fy", "cx", "cy", "width", "height")},
            "calibration": self.parameterAsFile(parameters, self.CALIBRATION, context) or None,
            "sigmas": list(sigmas), "axes": list(AXES), "mount": mount.key, "axis_convention": mount.convention,
            "tolerance_px": tolerance, "ground_spacing_m": spacing, "skld_cutoffs": list(cutoffs),
            "ellipse_sigmas": ELLIPSE_SIGMAS, "n_samples": n_samples,
            "seed": seed, "scales": scales.tolist(), "per_axis": per_axis,
        }

    @staticmethod
    def _stack_panels(panels, path) -> None:
        """One PNG with the per-altitude plots (equal widths) stacked top to bottom."""
        from matplotlib import image

        Path(path).parent.mkdir(parents=True, exist_ok=True)
        image.imsave(str(path), np.vstack([image.imread(str(panel)) for panel in panels]))
