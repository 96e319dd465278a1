"""The ground model, shared by writelabels, detect, the importers and the scoring algorithms: an optional
DEM, or the method's plane.

Parameters: ``DEM`` (raster layer, optional), ``DEM_VERTICAL_DATUM`` (what the DEM's heights are
measured from), ``GEOID_UNDULATION_M`` (N, ellipsoidal = MSL + N: the one N for every mean-sea-level height of
the run, the DEM's and the frames'; empty: PROJ's EGM96 grid where the frames name EGM96) and, in the
algorithms that place labels and detections (writelabels, detect, and the sweep and screening, which
detect again), ``GROUND_MODEL`` (advanced): without a DEM, the level plane at the tilt-corrected
altimeter depth (default) or the method's plane, normal to the optical axis at the raw altimeter range
(``core.geometry.ground.MethodPlaneGround``), to reproduce its figures. The importers (group ``field``)
drape footprints on the DEM. The algorithms that score detection layers take the ground each layer
records (``recorded_ground``): they need the DEM only for layers Detect placed on one.
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
from ...birdseye_qgis.core.geometry.dem import VERTICAL_DATUMS, DemGroundFactory, DemRaster, check_flight
from ...birdseye_qgis.core.geometry.ground import MethodPlaneGround
from ...birdseye_qgis.core.geometry.ground_record import GroundRecord
from ...birdseye_qgis.core.geometry.heights import MAX_UNDULATION_M
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, PARAMETER_ADVANCED
from ...birdseye_qgis.qgis_io import layers

DATUM_LABELS = ("Ellipsoid (WGS84), as RTK heights",
                "Mean sea level, as DJI and EXIF heights",
                "Unknown: check it against the frames")
GROUND_MODEL_LABELS = ("Level ground (tilt-corrected altimeter)",
                       "The method's plane (raw altimeter range)")
METHOD_PLANE = 1
# The window of the DEM read around a layer: its extent grown by this fraction of its larger side, and at
# least by DEM_WINDOW_MARGIN_M. Footprints stored on the level plane grow where the terrain drops below
# it, and rays of oblique frames reach past them; a generous window costs little next to the whole raster.
DEM_WINDOW_MARGIN = 0.5
DEM_WINDOW_MARGIN_M = 100.0


class DemParametersMixin:
    """Adds and reads the DEM parameters; ``dem_ground`` gives the ground-model factory."""

    DEM = "DEM"
    DEM_VERTICAL_DATUM = "DEM_VERTICAL_DATUM"
    GEOID_UNDULATION_M = "GEOID_UNDULATION_M"
    GROUND_MODEL = "GROUND_MODEL"
    # Set by read_dem for this run (Processing runs a fresh instance each time); dem_ground and
    # ground_record read them.
    method_plane = False
    dem_source = ""

    def add_dem_parameters(self, ground_model: bool = False) -> None:
        """DEM, DEM_VERTICAL_DATUM, GEOID_UNDULATION_M and, with ``ground_model`` (where labels or detections
        are placed), GROUND_MODEL."""
        self.addParameter(QgsProcessingParameterRasterLayer(
            self.DEM, self.tr("Terrain model (DEM; empty: level ground)"),
            optional=True))
        self.addParameter(QgsProcessingParameterEnum(
            self.DEM_VERTICAL_DATUM, self.tr("DEM heights are measured from"),
            options=[self.tr(label) for label in DATUM_LABELS], defaultValue=2))
        self.addParameter(QgsProcessingParameterNumber(
            self.GEOID_UNDULATION_M, self.tr("Geoid undulation N (m; empty: EGM96)"),
            NUMBER_DOUBLE, None, optional=True, minValue=-MAX_UNDULATION_M, maxValue=MAX_UNDULATION_M))
        if ground_model:
            choice = QgsProcessingParameterEnum(
                self.GROUND_MODEL, self.tr("Ground model without a DEM"),
                options=[self.tr(label) for label in GROUND_MODEL_LABELS], defaultValue=0)
            choice.setFlags(choice.flags() | PARAMETER_ADVANCED)
            self.addParameter(choice)

    def read_dem(self, parameters, context, covering=None, feedback=None) -> DemRaster | None:
        """The DEM, or None for a plane; also reads GROUND_MODEL, which a DEM excludes.

        ``covering`` (a feature source, e.g. the frame layer's footprints) limits the read to the cells
        around it: its extent grown by ``DEM_WINDOW_MARGIN`` (see there). ``feedback`` hears of a unit
        conversion (heights in feet).
        """
        self.method_plane = (self.parameterDefinition(self.GROUND_MODEL) is not None
                             and self.parameterAsEnum(parameters, self.GROUND_MODEL, context) == METHOD_PLANE)
        layer = self.parameterAsRasterLayer(parameters, self.DEM, context)
        if layer is None:
            return None
        self.dem_source = layer.source()
        if self.method_plane:
            raise QgsProcessingException(tr(
                "{GROUND_MODEL}: the method's plane stands in for the level ground; with a terrain model "
                "({DEM}) the terrain is the ground. Give one or the other.").format(
                GROUND_MODEL=self.GROUND_MODEL, DEM=self.DEM))
        datum = VERTICAL_DATUMS[self.parameterAsEnum(parameters, self.DEM_VERTICAL_DATUM, context)]
        undulation = (self.parameterAsDouble(parameters, self.GEOID_UNDULATION_M, context)
                      if parameters.get(self.GEOID_UNDULATION_M) not in (None, "") else None)
        try:
            extent = None if covering is None else layers.extent_in(covering, layer.crs(), context,
                                                                    DEM_WINDOW_MARGIN, DEM_WINDOW_MARGIN_M)
            return layers.read_dem(layer, datum, undulation, extent, feedback)
        except InputError as exc:
            raise QgsProcessingException(str(exc)) from exc

    def dem_ground(self, dem: DemRaster | None, pose_groups=(), feedback=None):
        """A ground-model factory (``geometry -> GroundModel``) for core code, or None for the level plane.

        Without a DEM: the method's plane when GROUND_MODEL asked for it (``read_dem`` reads it). With one: the
        DEM converted into the frames' vertical reference and checked against their ground
        (``dem.check_vertical_datum``) — once over the whole flight when its camera groups ``pose_groups``
        are given (the result said on ``feedback``), else on each geometry the factory is asked for.
        """
        if dem is None:
            return MethodPlaneGround if self.method_plane else None
        if not pose_groups:
            return DemGroundFactory(dem)
        check = self.run_core(check_flight, dem, pose_groups)
        if feedback is not None:
            feedback.pushInfo(tr("DEM against the frames: {check}").format(check=check.describe()))
        return DemGroundFactory(dem, vertical_offset_m=check.offset_m)

    def ground_record(self, dem: DemRaster | None) -> GroundRecord:
        """The ground this run places detections on, as the detection layer records it."""
        return GroundRecord.of(dem, self.dem_source, self.method_plane)

    def recorded_ground(self, detections, dem: DemRaster | None, feedback):
        """The ground-model factory a detection layer's detections were placed with (``detections.ground``),
        standing on ``dem`` where they were placed on a DEM. Refused, naming the layer and DEM, when the
        layer was placed on a DEM and none is given, or on a plane and one is given: the in-view test would
        stand on other ground, and the recall denominator change with it. A DEM other than the recorded
        one (another file or vertical datum) is warned about: it may hold the same terrain."""
        ground = self.run_core(detections.ground.factory, dem, detections.name, self.DEM)
        given = self.ground_record(dem)
        if dem is not None and given != detections.ground:
            feedback.pushWarning(tr("{layer}: its detections were placed on {recorded}; {DEM} is {given}. Check "
                                    "that both hold the same terrain in the same vertical reference.").format(
                layer=detections.name, recorded=detections.ground.describe(), DEM=self.DEM, given=given.describe()))
        return ground

    @staticmethod
    def report_dem(feedback, dem: DemRaster | None) -> None:
        if dem is None:
            return
        z = dem.heights
        feedback.pushInfo(tr("DEM {source}: {value}×{value2} cells of {cell_size_m:g} m, heights "
                             "{value3:.1f}…{value4:.1f} m ({vertical_datum})").format(
                              source=dem.source, value=z.shape[1], value2=z.shape[0], cell_size_m=dem.cell_size_m,
                              value3=np.nanmin(z), value4=np.nanmax(z), vertical_datum=dem.vertical_datum))
