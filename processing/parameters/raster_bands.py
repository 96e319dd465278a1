"""How a raster's bands become the red, green and blue of 8-bit images (BANDS, VALUE_RANGE), for the algorithms
that read an orthomosaic window by window (Detect targets on a raster, Write labels on a raster)."""
from __future__ import annotations

from qgis.core import QgsProcessingParameterBand, QgsProcessingParameterRange

from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, PARAMETER_ADVANCED
from ...birdseye_qgis.qgis_io.raster_reader import band_choice, needs_value_range, statistics_value_range


class RasterBandsParametersMixin:
    """Mixed into a ``BirdsEyeAlgorithm`` whose raster parameter is ``RASTER``."""

    RASTER = "RASTER"
    BANDS = "BANDS"
    VALUE_RANGE = "VALUE_RANGE"

    def add_band_parameters(self) -> None:
        """BANDS and VALUE_RANGE, advanced."""
        bands = QgsProcessingParameterBand(self.BANDS, self.tr("Bands read as red, green, blue"), None,
                                           self.RASTER, optional=True, allowMultiple=True)
        value_range = QgsProcessingParameterRange(
            self.VALUE_RANGE, self.tr("Values mapped to 0–255 (not 8-bit)"), NUMBER_DOUBLE, optional=True)
        for advanced in (bands, value_range):
            advanced.setFlags(advanced.flags() | PARAMETER_ADVANCED)
            self.addParameter(advanced)

    def band_choice(self, parameters, context, layer) -> list[int]:
        """The bands read as red, green and blue (:func:`..qgis_io.raster_reader.band_choice`)."""
        return self.run_core(band_choice, layer, self.parameterAsInts(parameters, self.BANDS, context))

    def value_range(self, parameters, context, feedback, layer, bands, extent=None):
        """None for 8-bit bands; else per band the (low, high) mapped to 0..255: VALUE_RANGE when given, else the
        bands' 2–98 % cumulative cut over ``extent`` (None: the whole raster), said in the log."""
        if not needs_value_range(layer, bands):
            return None
        given = self.parameterAsRange(parameters, self.VALUE_RANGE, context) \
            if parameters.get(self.VALUE_RANGE) not in (None, "") else []
        if len(given) == 2 and given[1] > given[0]:
            ranges = [tuple(given)] * 3
        else:
            ranges = self.run_core(statistics_value_range, layer, bands, extent)
        feedback.pushInfo(self.tr("The raster is not 8-bit: values mapped to 0–255 from {ranges}.").format(
            ranges="; ".join(f"band {b}: {lo:g}–{hi:g}" for b, (lo, hi) in zip(bands, ranges))))
        return ranges
