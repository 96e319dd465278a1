"""Clustering and matching parameters (DEDUP_CM, EPS_M, MIN_SAMPLES, CORE_COUNT, EPS_PRED_M, EDGE_BUFFER_PX)
and the flights (detection layer + frame layer pairs) the scoring algorithms read."""
from __future__ import annotations

from functools import partial

from qgis.core import QgsProcessingException, QgsProcessingParameterEnum, QgsProcessingParameterNumber

from ...birdseye_qgis.core.detect.clustering import (
    CORE_COUNTS,
    DEFAULT_CORE_COUNT,
    DEFAULT_DEDUP_CM,
    DEFAULT_EPS_M,
    DEFAULT_MIN_SAMPLES,
)
from ...birdseye_qgis.core.geometry.ground_record import RASTER
from ...birdseye_qgis.core.scoring.evaluation import Flight
from ...birdseye_qgis.core.scoring.operating_point import DEFAULT_EDGE_BUFFER_PX, DEFAULT_EPS_PRED_M, OperatingPoint
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, NUMBER_INTEGER, PARAMETER_ADVANCED
from ...birdseye_qgis.qgis_io.detections import read_detections, read_pose_groups
from ...birdseye_qgis.qgis_io.raster_reader import covered_geotags

#: The CORE_COUNT choices, in the order of core.detect.clustering.CORE_COUNTS (the enum's index).
CORE_COUNT_LABELS = ("Detections in the cells within EPS", "Cells within EPS, one point each (the method's)")


class ClusteringParametersMixin:
    """Mixed into a ``BirdsEyeAlgorithm``: the method's clustering parameters with their defaults."""

    DEDUP_CM = "DEDUP_CM"
    EPS_M = "EPS_M"
    MIN_SAMPLES = "MIN_SAMPLES"
    CORE_COUNT = "CORE_COUNT"
    EPS_PRED_M = "EPS_PRED_M"
    EDGE_BUFFER_PX = "EDGE_BUFFER_PX"

    def add_clustering_parameters(self, with_prediction: bool = True, advanced: bool = False) -> None:
        """DEDUP_CM, EPS_M, MIN_SAMPLES, CORE_COUNT (and EPS_PRED_M, EDGE_BUFFER_PX) with the method's
        defaults; CORE_COUNT's is BirdsEye's (core.detect.clustering)."""
        self._add_number(QgsProcessingParameterNumber(
            self.DEDUP_CM, self.tr("De-duplication grid cell (cm)"), NUMBER_DOUBLE,
            DEFAULT_DEDUP_CM, minValue=0.1, maxValue=100.0), advanced)
        self._add_number(QgsProcessingParameterNumber(
            self.EPS_M, self.tr("DBSCAN radius EPS (m)"), NUMBER_DOUBLE, DEFAULT_EPS_M,
            minValue=0.001, maxValue=50.0), advanced)
        self._add_number(QgsProcessingParameterNumber(
            self.MIN_SAMPLES, self.tr("DBSCAN minimum points (itself included)"),
            NUMBER_INTEGER, DEFAULT_MIN_SAMPLES, minValue=1, maxValue=1000), advanced)
        self.add_core_count_parameter()
        if with_prediction:
            self.add_matching_parameters(advanced=advanced)

    def add_matching_parameters(self, edge_buffer: bool = True, advanced: bool = False) -> None:
        """EPS_PRED_M and EDGE_BUFFER_PX: when a geotag counts as seen and as matched by a cluster.
        ``edge_buffer=False`` where the algorithm has its own EDGE_BUFFER_PX (Write labels)."""
        self._add_number(QgsProcessingParameterNumber(
            self.EPS_PRED_M, self.tr("Geotag match radius EPS_PRED (m)"),
            NUMBER_DOUBLE, DEFAULT_EPS_PRED_M, minValue=0.001, maxValue=50.0), advanced)
        if edge_buffer:
            self._add_number(QgsProcessingParameterNumber(
                self.EDGE_BUFFER_PX, self.tr("Edge buffer of the in-view test (px)"), NUMBER_DOUBLE,
                DEFAULT_EDGE_BUFFER_PX, minValue=0.0, maxValue=1000.0), advanced)

    def add_core_count_parameter(self) -> None:
        """CORE_COUNT: what DBSCAN's minimum points count. Advanced everywhere: the default suits every
        survey; the method's reading is there to reproduce its tables (docs/user-guide.md)."""
        choice = QgsProcessingParameterEnum(
            self.CORE_COUNT, self.tr("Minimum points count"), options=[self.tr(label) for label in CORE_COUNT_LABELS],
            defaultValue=CORE_COUNTS.index(DEFAULT_CORE_COUNT))
        choice.setFlags(choice.flags() | PARAMETER_ADVANCED)
        self.addParameter(choice)

    def read_core_count(self, parameters, context) -> str:
        """The CORE_COUNT chosen, as core.detect.clustering names it ("detections" or "cells")."""
        return CORE_COUNTS[self.parameterAsEnum(parameters, self.CORE_COUNT, context)]

    def _add_number(self, param, advanced: bool) -> None:
        if advanced:
            param.setFlags(param.flags() | PARAMETER_ADVANCED)
        self.addParameter(param)

    def read_operating_point(self, parameters, context, threshold=None) -> OperatingPoint:
        """The operating point the dialog's clustering and matching parameters describe."""
        return self.run_core(OperatingPoint, threshold, self.parameterAsDouble(parameters, self.DEDUP_CM, context),
                             self.parameterAsDouble(parameters, self.EPS_M, context),
                             self.parameterAsInt(parameters, self.MIN_SAMPLES, context),
                             self.parameterAsDouble(parameters, self.EPS_PRED_M, context),
                             self.parameterAsDouble(parameters, self.EDGE_BUFFER_PX, context),
                             self.read_core_count(parameters, context))

    def read_flights(self, parameters, context, feedback, detections_name="DETECTIONS", frames_name="FRAMES",
                     ground_for=None):
        """Detection layers paired in order with frame layers (one flight each) as core Flights, each on the
        ground ``ground_for(detections)`` gives (a ground-model factory; without ``ground_for``, the level
        plane). A layer found on a raster needs no frame layer (its raster says which geotags are in view), so
        the frame layers pair either with every detection layer or with those found on frames alone."""
        det_layers = self.parameterAsLayerList(parameters, detections_name, context)
        frame_layers = self.parameterAsLayerList(parameters, frames_name, context)
        if not det_layers:
            raise QgsProcessingException(self.tr("{name}: give at least one detection layer.").format(
                name=detections_name))
        read = []
        for det_layer in det_layers:
            det, dropped = self.run_core(read_detections, det_layer, context, det_layer.name())
            if dropped:
                feedback.pushWarning(self.tr("{layer}: {n} detection(s) without a position or score left out").format(
                    layer=det_layer.name(), n=dropped))
            read.append((det_layer, det))
        on_frames = [det.ground.model != RASTER for _, det in read]
        if len(frame_layers) == len(det_layers):
            paired = list(frame_layers)
        elif len(frame_layers) == sum(on_frames):
            remaining = iter(frame_layers)
            paired = [next(remaining) if needed else None for needed in on_frames]
        else:
            raise QgsProcessingException(self.tr(
                "{name}: give one frame layer per detection layer found on frames, in the same order (got "
                "{detections} detection layer(s), {on_frames} of them found on frames, and {frames} frame "
                "layer(s)); a layer found on a raster needs none.").format(
                name=frames_name, detections=len(det_layers), on_frames=sum(on_frames), frames=len(frame_layers)))
        flights = []
        for (det_layer, det), frame_layer in zip(read, paired):
            groups = [] if frame_layer is None else self.run_core(read_pose_groups, frame_layer,
                                                                  frame_layer.name())[0]
            if det.ground.model == RASTER:  # found on a raster: the geotags in view are those it covers
                covers = partial(covered_geotags, det.ground.dem_source, transform_context=context.transformContext())
                flights.append(Flight(det, groups, det_layer.name(), covers=covers))
                continue
            flights.append(Flight(det, groups, det_layer.name(), None if ground_for is None else ground_for(det)))
        return flights
