"""The surveyed area (SURVEYED_AREA, SURVEY_MARGIN_M) of the algorithms that write negative tiles only where the
survey searched (Write labels, Write labels on a raster): one definition, :func:`core.field.surveyed_area
.surveyed_area`."""
from __future__ import annotations

from qgis.core import QgsProcessingParameterNumber

from ...birdseye_qgis.core.field.surveyed_area import DEFAULT_SURVEY_MARGIN_M, surveyed_area
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, SOURCE_VECTOR_POLYGON
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from .layer_parameters import source_parameter


class SurveyedAreaParametersMixin:
    """Mixed into a ``BirdsEyeAlgorithm``."""

    SURVEYED_AREA = "SURVEYED_AREA"
    SURVEY_MARGIN_M = "SURVEY_MARGIN_M"

    def add_surveyed_area_parameters(self) -> None:
        self.addParameter(source_parameter(
            self.SURVEYED_AREA, self.tr("Surveyed area (polygons)"),
            layer_kinds.AREAS, [SOURCE_VECTOR_POLYGON], optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.SURVEY_MARGIN_M, self.tr("Margin around the geotags' hull (m)"),
            NUMBER_DOUBLE, DEFAULT_SURVEY_MARGIN_M, minValue=0.0, maxValue=1000.0))

    def surveyed(self, parameters, context, feedback, survey):
        """The surveyed area: SURVEYED_AREA's polygons, else the survey's hull grown by SURVEY_MARGIN_M."""
        drawn = self.parameterAsSource(parameters, self.SURVEYED_AREA, context)
        rings = None if drawn is None else self.run_core(layers.read_polygon_rings, drawn, context.transformContext())
        area = self.run_core(surveyed_area, survey.lat, survey.lon,
                             self.parameterAsDouble(parameters, self.SURVEY_MARGIN_M, context), rings, survey.height)
        feedback.pushInfo(self.tr("Surveyed area: {area}. Negative tiles only where it holds the tile's whole "
                                  "ground; positives anywhere.").format(area=area.describe()))
        return area
