"""birdseye:detectraster — run an ONNX heatmap model over a raster layer (an orthomosaic) → detections."""
from __future__ import annotations

import numpy as np
from qgis.core import (
    QgsCoordinateTransform,
    QgsFeatureRequest,
    QgsGeometry,
    QgsPointXY,
    QgsProcessingOutputNumber,
    QgsProcessingOutputString,
    QgsProcessingParameterExtent,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterRasterLayer,
    QgsRectangle,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.detect.detector import HeatmapModel
from ...birdseye_qgis.core.detect.raster_detect import detect_raster
from ...birdseye_qgis.core.errors import InputError
from ...birdseye_qgis.core.geometry.ground_record import RASTER
from ...birdseye_qgis.qgis_enums import (
    SOURCE_VECTOR_POINT,
    SOURCE_VECTOR_POLYGON,
    WKB_POINT_Z,
)
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from ...birdseye_qgis.qgis_io.detections import DETECTION_FIELDS
from ...birdseye_qgis.qgis_io.raster_reader import ProviderWindows, bounded_block_cache, raster_grid
from ..parameters.layer_parameters import source_parameter
from ..parameters.model import ModelParametersMixin
from ..parameters.raster_bands import RasterBandsParametersMixin
from .base import BirdsEyeAlgorithm


class DetectRaster(ModelParametersMixin, RasterBandsParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "detectraster"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("DetectRaster", "Detect targets on a raster (orthomosaic)")
    GROUP = "detect"
    MASK = "MASK"
    EXTENT = "EXTENT"
    OUTPUT = "OUTPUT"

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterRasterLayer(self.RASTER, self.tr("Raster (orthomosaic)")))
        self.add_model_parameters()
        self.addParameter(source_parameter(
            self.MASK, self.tr("Only inside these polygons"), layer_kinds.AREAS, [SOURCE_VECTOR_POLYGON],
            optional=True))
        self.addParameter(QgsProcessingParameterExtent(
            self.EXTENT, self.tr("Only inside this extent"), optional=True))
        self.add_band_parameters()
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("Detections"), SOURCE_VECTOR_POINT))
        for name, text in (("DETECTION_COUNT", "Detections written"), ("WINDOWS_READ", "Windows read"),
                           ("THRESHOLD_USED", "Threshold used")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))
        self.addOutput(QgsProcessingOutputString("MODEL_DIGEST", self.tr("SHA-256 of the model")))

    def processAlgorithm(self, parameters, context, feedback):
        layer = self.parameterAsRasterLayer(parameters, self.RASTER, context)
        if layer is None or not layer.isValid():
            raise self.user_error(InputError("no raster given, or it cannot be opened", field=self.RASTER))
        grid = self.run_core(raster_grid, layer)
        bands = self.band_choice(parameters, context, layer)
        model_path, threshold = self.model_choice(parameters, context)
        model = self.run_core(HeatmapModel, model_path, log=feedback.pushInfo)
        meta = model.metadata
        used = meta.default_threshold if threshold is None else threshold
        area, extent = self._area(parameters, context, layer)
        value_range = self.value_range(parameters, context, feedback, layer, bands, extent)
        feedback.pushInfo(self.tr("Raster {width} × {height} px at {gsd:.2f} cm/px, bands {bands} as red, green, "
                                  "blue; model {name} (sha256 {digest}…) at {resolution:g} cm/px, threshold "
                                  "{used:g}.").format(
                              width=grid.width, height=grid.height, gsd=grid.gsd_cm,
                              bands=", ".join(str(b) for b in bands), name=model.name, digest=model.digest[:12],
                              resolution=meta.resolution_cm, used=used))
        if grid.gsd_cm > 1.5 * meta.resolution_cm:
            feedback.pushWarning(self.tr("The raster ({gsd:.2f} cm/px) is coarser than 1.5× the model's resolution "
                                         "of {resolution:g} cm/px: targets look smaller than in training, so expect "
                                         "fewer detections.").format(gsd=grid.gsd_cm, resolution=meta.resolution_cm))
        progress, is_canceled = self.progress_callbacks(feedback, 0.0, 95.0)
        window_needed, keep = (None, None) if area is None else self._area_tests(area)
        with bounded_block_cache():
            found = self.run_core(detect_raster, model, grid, ProviderWindows(layer, grid, bands), threshold,
                                  value_range, window_needed=window_needed, keep=keep, progress=progress,
                                  is_canceled=is_canceled)
        fields = layers.qgs_fields(DETECTION_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, self.OUTPUT, context, fields, WKB_POINT_Z, layer.crs())
        if sink is None:
            raise self.user_error(InputError("the detection output cannot be created", field=self.OUTPUT))
        # One raster is one "frame" (frame_id 0); u, v its pixels. Its surface carries no heights: Z is 0 and
        # height_ref says so.
        rows = ({"frame_id": 0, "u": float(c), "v": float(r), "score": float(s), "model": model.name,
                 "model_digest": model.digest, "threshold": used, "ground": RASTER,
                 "dem_source": layer.source(), "dem_datum": "unknown", "dem_n_m": None, "height_ref": "unknown"}
                for c, r, s in zip(found.col, found.row, found.score))
        geoms = (layers.point_z(float(x), float(y), 0.0) for x, y in zip(found.x, found.y))
        count = layers.write_records(sink, fields, rows, geoms)
        layers.style_on_load(context, dest_id, "detections.qml")
        feedback.setProgress(100.0)
        feedback.pushInfo(self.tr("{count} detections from {windows} windows ({skipped} outside the area asked for "
                                  "not read); {merged} found on a seam by two windows kept once.").format(
                              count=count, windows=found.windows, skipped=found.skipped_windows,
                              merged=found.merged))
        return {self.OUTPUT: dest_id, "DETECTION_COUNT": count, "WINDOWS_READ": found.windows,
                "THRESHOLD_USED": used, "MODEL_DIGEST": model.digest}

    def _area(self, parameters, context, layer):
        """(the polygon detections must lie in, in the raster's CRS, or None; its bounding box, or None)."""
        area = None
        source = self.parameterAsSource(parameters, self.MASK, context)
        if source is not None:
            to_raster = QgsCoordinateTransform(source.sourceCrs(), layer.crs(), context.transformContext())
            parts = []
            for feature in source.getFeatures(QgsFeatureRequest()):
                geometry = QgsGeometry(feature.geometry())
                if not geometry.isEmpty():
                    geometry.transform(to_raster)
                    parts.append(geometry)
            if not parts:
                raise self.user_error(InputError("the mask layer holds no polygon", field=self.MASK))
            area = QgsGeometry.unaryUnion(parts)
        if parameters.get(self.EXTENT) not in (None, ""):
            rectangle = self.parameterAsExtent(parameters, self.EXTENT, context, layer.crs())
            box = QgsGeometry.fromRect(rectangle)
            area = box if area is None else area.intersection(box)
        if area is not None and not area.intersects(QgsGeometry.fromRect(layer.extent())):
            raise self.user_error(InputError("the mask and extent asked for do not overlap the raster",
                                             field=self.MASK))
        return area, (None if area is None else area.boundingBox().intersect(layer.extent()))

    @staticmethod
    def _area_tests(area):
        """(window_needed, keep) of :func:`detect_raster` for the polygon ``area`` (prepared once)."""
        engine = QgsGeometry.createGeometryEngine(area.constGet())
        engine.prepareGeometry()

        # Each geometry is held in a name while the engine reads it: constGet() of a temporary would dangle.
        def window_needed(x0, y0, x1, y1) -> bool:
            box = QgsGeometry.fromRect(QgsRectangle(x0, y0, x1, y1))
            return engine.intersects(box.constGet())

        def keep(x, y) -> np.ndarray:
            points = [QgsGeometry.fromPointXY(QgsPointXY(a, b)) for a, b in zip(x, y)]
            return np.array([engine.contains(point.constGet()) for point in points], dtype=bool)

        return window_needed, keep
