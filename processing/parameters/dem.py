"""The optional DEM ground model, shared by writelabels, detect and the importers.

Parameters: ``DEM`` (raster layer, optional), ``DEM_VERTICAL_DATUM`` (what the DEM's heights are
measured from) and ``GEOID_UNDULATION_M`` (N, ellipsoidal = MSL + N, needed for an MSL DEM). Without a
DEM every algorithm keeps the level plane at the altimeter depth, unchanged.
"""
from __future__ import annotations

import numpy as np
from qgis.core import (
    QgsProcessingException,
    QgsProcessingParameterEnum,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterLayer,
)

from ...birdseye_qgis.__about__ import tr
from ...birdseye_qgis.core.errors import InputError
from ...birdseye_qgis.core.geometry.dem import VERTICAL_DATUMS, DemGround, DemRaster
from ...birdseye_qgis.qgis_io import layers

DATUM_LABELS = ("Ellipsoidal (WGS84), like RTK and INS heights",
                "Mean sea level (give the geoid undulation N)",
                "Unknown: check it against the altimeter's ground")


class DemParametersMixin:
    """Adds and reads the DEM parameters; ``dem_ground`` gives the ground-model factory."""

    DEM = "DEM"
    DEM_VERTICAL_DATUM = "DEM_VERTICAL_DATUM"
    GEOID_UNDULATION_M = "GEOID_UNDULATION_M"

    def add_dem_parameters(self) -> None:
        self.addParameter(QgsProcessingParameterRasterLayer(
            self.DEM, self.tr("Terrain model (DEM/DSM raster, projected CRS in metres; empty: level ground)"),
            optional=True))
        self.addParameter(QgsProcessingParameterEnum(
            self.DEM_VERTICAL_DATUM, self.tr("DEM heights are measured from"), options=list(DATUM_LABELS),
            defaultValue=2))
        self.addParameter(QgsProcessingParameterNumber(
            self.GEOID_UNDULATION_M, self.tr("Geoid undulation N at the site (m; ellipsoidal = MSL + N)"),
            QgsProcessingParameterNumber.Double, None, optional=True, minValue=-120.0, maxValue=120.0))

    def read_dem(self, parameters, context) -> DemRaster | None:
        layer = self.parameterAsRasterLayer(parameters, self.DEM, context)
        if layer is None:
            return None
        datum = VERTICAL_DATUMS[self.parameterAsEnum(parameters, self.DEM_VERTICAL_DATUM, context)]
        undulation = (self.parameterAsDouble(parameters, self.GEOID_UNDULATION_M, context)
                      if parameters.get(self.GEOID_UNDULATION_M) not in (None, "") else None)
        try:
            return layers.read_dem(layer, datum, undulation)
        except InputError as exc:
            raise QgsProcessingException(str(exc)) from exc

    @staticmethod
    def dem_ground(dem: DemRaster | None, pose_heights_datum: str = "ellipsoidal", tolerance_m: float = 5.0):
        """A ground-model factory (``geometry -> GroundModel``) for core code, or None for the level plane.

        RTK/INS poses are ellipsoidal; the DEM's datum is checked against them and, where the frames
        have one, against their ground height (``tolerance_m``, median over the frames).
        """
        if dem is None:
            return None
        return lambda geometry: DemGround.from_dem(geometry, dem, pose_heights_datum, tolerance_m)

    @staticmethod
    def report_dem(feedback, dem: DemRaster | None) -> None:
        if dem is None:
            return
        z = dem.heights
        feedback.pushInfo(tr("DEM {source}: {value}×{value2} cells of {cell_size_m:g} m, heights "
                             "{value3:.1f}…{value4:.1f} m ({vertical_datum})").format(
                              source=dem.source, value=z.shape[1], value2=z.shape[0], cell_size_m=dem.cell_size_m,
                              value3=np.nanmin(z), value4=np.nanmax(z), vertical_datum=dem.vertical_datum))
