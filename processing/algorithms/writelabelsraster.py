"""birdseye:writelabelsraster — the survey's targets on a raster layer (an orthomosaic), written as the training
set Train detector reads (:mod:`birdseye_qgis.core.labels.raster_labels`)."""
from __future__ import annotations

from qgis.core import (
    QgsProcessingOutputNumber,
    QgsProcessingParameterFolderDestination,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterLayer,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.errors import InputError
from ...birdseye_qgis.core.geometry.geodesy import ProjectedCRS
from ...birdseye_qgis.core.labels.raster_labels import RasterLabelRequest, write_raster_labels
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, NUMBER_INTEGER, SOURCE_VECTOR_POINT
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from ...birdseye_qgis.qgis_io.raster_reader import ProviderWindows, bounded_block_cache, raster_grid
from ..parameters.layer_parameters import source_parameter
from ..parameters.raster_bands import RasterBandsParametersMixin
from ..parameters.review import ReviewParametersMixin
from ..parameters.surveyed_area import SurveyedAreaParametersMixin
from .base import BirdsEyeAlgorithm

#: SIGMA_CM's default: a label of radius 3σ = 15 cm on the ground.
DEFAULT_SIGMA_CM = 5.0


class WriteLabelsRaster(ReviewParametersMixin, RasterBandsParametersMixin, SurveyedAreaParametersMixin,
                        BirdsEyeAlgorithm):
    ALG_ID = "writelabelsraster"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("WriteLabelsRaster", "Write training labels on a raster (orthomosaic)")
    GROUP = "labels"
    GEOTAGS = "GEOTAGS"
    SIGMA_CM = "SIGMA_CM"
    TILE_SIZE = "TILE_SIZE"
    NEGATIVE_RATIO = "NEGATIVE_RATIO"
    SEED = "SEED"
    OUTPUT_FOLDER = "OUTPUT_FOLDER"

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterRasterLayer(self.RASTER, self.tr("Raster (orthomosaic)")))
        self.addParameter(source_parameter(
            self.GEOTAGS, self.tr("Geotags (surveyed targets)"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT]))
        self.addParameter(QgsProcessingParameterNumber(
            self.SIGMA_CM, self.tr("Soft-label σ on the ground (cm)"), NUMBER_DOUBLE, DEFAULT_SIGMA_CM,
            minValue=0.1, maxValue=1000.0))
        self.addParameter(QgsProcessingParameterNumber(
            self.TILE_SIZE, self.tr("Tile size (px)"), NUMBER_INTEGER, 224, minValue=16, maxValue=4096))
        self.addParameter(QgsProcessingParameterNumber(
            self.NEGATIVE_RATIO, self.tr("Negative tiles kept per positive tile"),
            NUMBER_DOUBLE, 1.0, minValue=0.0, maxValue=100.0))
        self.addParameter(QgsProcessingParameterNumber(
            self.SEED, self.tr("Random seed for the negative-tile sample"), NUMBER_INTEGER, 0, minValue=0))
        self.add_surveyed_area_parameters()
        self.add_band_parameters()
        self.add_review_parameters(with_frames=True, edge_buffer=True)
        self.addParameter(QgsProcessingParameterFolderDestination(self.OUTPUT_FOLDER, self.tr("Label folder")))
        for name, text in (("LABEL_COUNT", "Labels written (targets per tile)"),
                           ("POSITIVE_TILES", "Tiles with a target"), ("NEGATIVE_TILES", "Negative tiles"),
                           ("GEOTAGS_NOT_LABELLED", "Geotags not labelled (outside, no data)"),
                           ("SIGMA_USED_PX", "σ used (px of the raster)"),
                           ("REVIEW_TARGETS", "Review targets (confirmed clusters no geotag matches)"),
                           ("HARD_NEGATIVES", "Hard-negative clusters")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    def processAlgorithm(self, parameters, context, feedback):
        layer = self.parameterAsRasterLayer(parameters, self.RASTER, context)
        if layer is None or not layer.isValid():
            raise self.user_error(InputError("no raster given, or it cannot be opened", field=self.RASTER))
        source = self.parameterAsSource(parameters, self.GEOTAGS, context)
        if source is None:
            raise self.user_error(InputError("no geotag layer given", field=self.GEOTAGS))
        grid = self.run_core(raster_grid, layer)
        bands = self.band_choice(parameters, context, layer)
        survey = self.run_core(layers.read_geotag_layer, source, context.transformContext())
        if survey.problems:  # a target without a position may lie in any negative tile
            raise self.user_error(InputError(
                f"{survey.problems[0]}: a target without a position may lie in any negative tile; give it its "
                "position or remove it", field=self.GEOTAGS))
        value_range = self.value_range(parameters, context, feedback, layer, bands)
        area = self.surveyed(parameters, context, feedback, survey)
        reviewed = self.read_reviewed_clusters(parameters, context, feedback, source, None, 0.0, 20.0)
        review_targets, hard, unresolved = self.review_label_inputs(feedback, reviewed, survey)
        geotags = survey + review_targets
        crs = self.run_core(ProjectedCRS, layers.pyproj_crs(layer.crs()))
        x, y = crs.from_geodetic(geotags.lat, geotags.lon)
        request = RasterLabelRequest(
            sigma_cm=self.parameterAsDouble(parameters, self.SIGMA_CM, context),
            tile_size=self.parameterAsInt(parameters, self.TILE_SIZE, context),
            negative_ratio=self.parameterAsDouble(parameters, self.NEGATIVE_RATIO, context),
            seed=self.parameterAsInt(parameters, self.SEED, context))
        sigma_px = request.sigma_px(grid)
        feedback.pushInfo(self.tr(
            "Raster {width} × {height} px at {gsd:.2f} cm/px, bands {bands} as red, green, blue; {n} geotag(s); "
            "σ = {cm:g} cm = {px:.2f} px (label radius 3σ = {radius:.1f} px), tiles of {tile} px.").format(
                width=grid.width, height=grid.height, gsd=grid.gsd_cm, bands=", ".join(str(b) for b in bands),
                n=len(geotags), cm=request.sigma_cm, px=sigma_px, radius=3 * sigma_px, tile=request.tile_size))
        if sigma_px < 1.0:
            feedback.pushWarning(self.tr("σ is {px:.2f} px, under one pixel of the raster: the labels are a dot or "
                                         "two. Give σ in cm large enough to cover the orthomosaic's error against "
                                         "the survey.").format(px=sigma_px))
        out_dir = self.parameterAsString(parameters, self.OUTPUT_FOLDER, context)
        progress, is_canceled = self.progress_callbacks(feedback, 20.0 if reviewed is not None else 0.0, 100.0)
        with bounded_block_cache():
            summary = self.run_core(
                write_raster_labels, out_dir, grid, ProviderWindows(layer, grid, bands), geotags, x, y, request,
                value_range, area, crs.to_geodetic, {"source": layer.source(), "crs": layer.crs().authid()},
                hard_negatives=crs.from_geodetic(hard.lat, hard.lon) if len(hard) else None,
                unresolved=crs.from_geodetic(unresolved.lat, unresolved.lon) if len(unresolved) else None,
                progress=progress, is_canceled=is_canceled)
        tiles = summary["tiles"]
        not_labelled = summary["geotags_outside_raster"] + summary["geotags_on_nodata"]
        feedback.pushInfo(self.tr(
            "{labels} label(s) of {in_view} of {n} geotag(s); tiles: {positive} with a target, {negative} negative "
            "written; skipped: {near} near a target not labelled, {outside} without a target not wholly inside the "
            "surveyed area, {empty} drawn without a pixel of data; {hard} negative(s) hold a hard negative. Each "
            "tile is one frame for Train detector, which reads the raster's GSD from summary.json.").format(
                labels=summary["n_labels"], in_view=summary["n_geotags_in_view"], n=len(geotags),
                positive=tiles["positive"], negative=tiles["negative"], near=tiles["skipped"]["unlabelled_target"],
                outside=tiles["skipped"]["outside_surveyed_area"], empty=tiles["skipped"]["no_data"],
                hard=tiles["hard_negative"]))
        for key, text in (("geotags_outside_raster", "{n} geotag(s) outside the raster: {ids}"),
                          ("geotags_on_nodata", "{n} geotag(s) on pixels without data (a hole in the orthomosaic; "
                                                "not labelled, no tile near them written): {ids}")):
            ids = summary[key]
            if ids:
                feedback.pushWarning(self.tr(text).format(
                    n=len(ids), ids=", ".join(str(i) for i in ids[:10]) + (" …" if len(ids) > 10 else "")))
        return {self.OUTPUT_FOLDER: out_dir, "LABEL_COUNT": summary["n_labels"], "POSITIVE_TILES": tiles["positive"],
                "NEGATIVE_TILES": tiles["negative"], "GEOTAGS_NOT_LABELLED": len(not_labelled),
                "SIGMA_USED_PX": summary["sigma_px"], "REVIEW_TARGETS": len(review_targets),
                "HARD_NEGATIVES": len(hard)}
