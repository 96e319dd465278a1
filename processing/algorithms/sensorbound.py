"""``birdseye:sensorbound`` — which pose-noise budget keeps every label inside its tolerance."""
from __future__ import annotations

import json
from pathlib import Path

from qgis.core import (
    QgsProcessingException,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.design.bound_report import altitude_summary, write_report
from ...birdseye_qgis.core.design.sensor_bound import evaluate_bounds, frame_grid, lmax_field
from ...birdseye_qgis.qgis_enums import NUMBER_INTEGER
from ..parameters.design import DesignParametersMixin
from .base import BirdsEyeAlgorithm


class SensorBoundAlgorithm(DesignParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "sensorbound"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("SensorBoundAlgorithm", "Sensor bound (pose-noise budget)")
    GROUP = "design"

    STRIDE_PX = "STRIDE_PX"
    OUTPUT_JSON = "OUTPUT_JSON"
    OUTPUT_REPORT = "OUTPUT_REPORT"
    OUTPUT_RASTER = "OUTPUT_RASTER"

    def initAlgorithm(self, config=None):
        self.add_camera_parameters()
        self.add_altitudes_parameter()
        self.add_sigmas_parameter()
        self.add_tolerance_parameter()
        self.addParameter(QgsProcessingParameterNumber(
            self.STRIDE_PX, self.tr("Grid stride (px; 1: every pixel)"), NUMBER_INTEGER,
            defaultValue=1, minValue=1))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_JSON, self.tr("Results (JSON)"), "JSON files (*.json)"))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_REPORT, self.tr("Report with plots (HTML)"), "HTML files (*.html)", optional=True,
            createByDefault=True))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_RASTER, self.tr("λ_max field (GeoTIFF)"),
            "GeoTIFF files (*.tif *.tiff)", optional=True, createByDefault=False))

    def processAlgorithm(self, parameters, context, feedback):
        camera = self.camera_from_parameters(parameters, context, feedback)
        altitudes = self.altitudes_from_parameters(parameters, context)
        sigmas = self.sigmas_from_parameters(parameters, context)
        mount = self.mount_from_parameters(parameters, context)
        tolerance = self.tolerance_from_parameters(parameters, context)
        stride = self.parameterAsInt(parameters, self.STRIDE_PX, context)
        json_path = self.parameterAsFileOutput(parameters, self.OUTPUT_JSON, context)
        report_path = self.parameterAsFileOutput(parameters, self.OUTPUT_REPORT, context)
        raster_path = self.parameterAsFileOutput(parameters, self.OUTPUT_RASTER, context)
        calibration = self.parameterAsFile(parameters, self.CALIBRATION, context)

        progress, is_canceled = self.progress_callbacks(feedback, 0, 70 if (report_path or raster_path) else 100)
        result = self.run_core(evaluate_bounds, camera, altitudes, sigmas, tolerance, stride,
                               progress=progress, is_canceled=is_canceled, mount=mount)
        result["inputs"]["calibration"] = calibration or None
        preset = self.platform_from_parameters(parameters, context)
        result["inputs"]["platform"] = None if preset is None else preset.key
        for entry in result["altitudes"]:
            feedback.pushInfo(altitude_summary(entry))
        Path(json_path).parent.mkdir(parents=True, exist_ok=True)
        with open(json_path, "w", encoding="utf-8") as handle:
            json.dump(result, handle, indent=2)
        outputs = {self.OUTPUT_JSON: json_path, self.OUTPUT_REPORT: None, self.OUTPUT_RASTER: None}

        if report_path:
            self.check_canceled(feedback)
            source = (Path(calibration).name if calibration else preset.name if preset is not None
                      else "typed intrinsics")
            outputs[self.OUTPUT_REPORT] = self.run_core(write_report, report_path, result,
                                                        title="BirdsEye sensor bound", source=source)
            feedback.setProgress(90 if raster_path else 100)
        if raster_path:
            outputs[self.OUTPUT_RASTER] = self._write_lmax_raster(raster_path, camera, altitudes, sigmas, mount,
                                                                  tolerance, stride, feedback)
            feedback.setProgress(100)
        return outputs


    def _write_lmax_raster(self, path, camera, altitudes, sigmas, mount, tolerance, stride, feedback) -> str:
        """One Float32 band of λ_max (px²) per altitude on the regular part of the frame grid.

        Pixel coordinates, no CRS: map x = u + 0.5 and y = −(v + 0.5), the way QGIS places an image
        without georeferencing (its pixel i spans x ∈ [i, i+1]), so at stride 1 the raster lies exactly
        over the frame opened in QGIS.
        """
        from osgeo import gdal

        us, vs = frame_grid(camera, stride)
        n_u, n_v = (int(camera.width) - 1) // stride + 1, (int(camera.height) - 1) // stride + 1
        if (n_u, n_v) != (us.size, vs.size):
            feedback.pushWarning(self.tr(
                "{name}: with the stride {stride} px the raster's regular grid does not reach the last pixel, so it "
                "stops at the last multiple of the stride; the JSON suprema still include the frame edges.").format(
                name=self.OUTPUT_RASTER, stride=stride))
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        dataset = gdal.GetDriverByName("GTiff").Create(
            str(path), n_u, n_v, len(altitudes), gdal.GDT_Float32,
            options=["COMPRESS=DEFLATE", "PREDICTOR=3", "TILED=YES"])
        if dataset is None:
            raise QgsProcessingException(self.tr("{name}: cannot create the GeoTIFF {path}").format(
                name=self.OUTPUT_RASTER, path=path))
        dataset.SetGeoTransform((0.5 - stride / 2.0, float(stride), 0.0, stride / 2.0 - 0.5, 0.0, -float(stride)))
        dataset.SetMetadata({"QUANTITY": "lambda_max of the linearised label covariance", "UNITS": "px^2",
                             "TOLERANCE_PX": f"{tolerance:g}", "STRIDE_PX": str(stride),
                             "SIGMAS": ",".join(f"{s:g}" for s in sigmas), "MOUNT": mount.key,
                             "COORDINATES": "x = u + 0.5, y = -(v + 0.5); pixel (0,0) = centre of the top-left pixel"})
        for band_index, altitude in enumerate(altitudes, start=1):
            self.check_canceled(feedback)
            field = self.run_core(lmax_field, camera, altitude, sigmas, stride, mount=mount)[:n_v, :n_u]
            band = dataset.GetRasterBand(band_index)
            band.SetDescription(f"lambda_max_px2 at {altitude:g} m")
            band.WriteArray(field.astype("float32"))
        dataset.FlushCache()
        dataset = None  # closes the file
        return path
