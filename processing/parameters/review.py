"""A review's verdicts and the clusters they judged (REVIEW, REVIEW_DETECTIONS, REVIEW_FRAMES and the
clustering parameters), read the way ``evaluatedetections`` reads them, for the algorithms that act on
what the review decided (Write labels, Plan the survey flight, Prepare field survey)."""
from __future__ import annotations

from qgis.core import (
    QgsProcessingException,
    QgsProcessingParameterMultipleLayers,
)

from ...birdseye_qgis.core.geometry.ground_record import DEM
from ...birdseye_qgis.core.labels.training_set import review_label_inputs
from ...birdseye_qgis.core.scoring.evaluation import Flight, evaluate_flights
from ...birdseye_qgis.core.scoring.reviewed_clusters import outcome_counts, reviewed_clusters
from ...birdseye_qgis.qgis_enums import SOURCE_VECTOR, SOURCE_VECTOR_POINT
from ...birdseye_qgis.qgis_io import layer_kinds
from ...birdseye_qgis.qgis_io.detections import read_detections, read_verdicts
from ...birdseye_qgis.qgis_io.layers import read_geotag_layer
from .clustering import ClusteringParametersMixin
from .layer_parameters import vector_parameter


class ReviewParametersMixin(ClusteringParametersMixin):
    """Mixed into a ``BirdsEyeAlgorithm`` after the algorithm's own parameters."""

    REVIEW = "REVIEW"
    REVIEW_DETECTIONS = "REVIEW_DETECTIONS"
    REVIEW_FRAMES = "REVIEW_FRAMES"

    def add_review_parameters(self, with_frames: bool, edge_buffer: bool) -> None:
        """REVIEW and REVIEW_DETECTIONS (and REVIEW_FRAMES when the algorithm has no frame layer of its
        own), then the clustering the review was scored with, as advanced parameters.
        ``edge_buffer=False`` where the algorithm's own EDGE_BUFFER_PX serves the in-view test."""
        self.addParameter(vector_parameter(
            self.REVIEW, self.tr("Review verdicts (birdseye_verdicts)"), layer_kinds.VERDICTS,
            [SOURCE_VECTOR], optional=True))
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.REVIEW_DETECTIONS, self.tr("Detection layers the review judged"),
            SOURCE_VECTOR_POINT, optional=True))
        if with_frames:
            self.addParameter(QgsProcessingParameterMultipleLayers(
                self.REVIEW_FRAMES, self.tr("Their frame layers (same order)"),
                SOURCE_VECTOR, optional=True))
        self.add_clustering_parameters(with_prediction=False, advanced=True)
        self.add_matching_parameters(edge_buffer=edge_buffer, advanced=True)

    def read_reviewed_clusters(self, parameters, context, feedback, geotag_source, pose_groups=None,
                               start: float = 0.0, end: float = 100.0, dem=None):
        """The clusters of the reviewed detection layers with their outcomes (``core.scoring
        .reviewed_clusters``), clustered and matched to ``geotag_source``'s geotags as ``evaluatedetections``
        does; None without REVIEW.

        ``pose_groups``: the frames of every detection layer when the algorithm has one frame layer
        (Write labels); otherwise REVIEW_FRAMES pairs a frame layer with each detection layer. The in-view
        test stands on the ground each layer's detections were placed on (:meth:`review_ground`)."""
        review = self.parameterAsVectorLayer(parameters, self.REVIEW, context)
        det_layers = self.parameterAsLayerList(parameters, self.REVIEW_DETECTIONS, context)
        if review is None:
            if det_layers:
                raise QgsProcessingException(self.tr(
                    "REVIEW_DETECTIONS is given without REVIEW: give the review's verdict table too, or leave "
                    "REVIEW_DETECTIONS empty."))
            return None
        if not det_layers:
            raise QgsProcessingException(self.tr(
                "REVIEW: give the detection layer(s) the review judged (REVIEW_DETECTIONS): the verdicts "
                "name spots, the clusters come from those detections."))
        log = self.run_core(read_verdicts, review, context)
        geotags = self.run_core(read_geotag_layer, geotag_source, context.transformContext())
        def ground_for(detections):
            return self.review_ground(detections, dem, feedback)

        if pose_groups is None:
            flights = self.read_flights(parameters, context, feedback, self.REVIEW_DETECTIONS, self.REVIEW_FRAMES,
                                        ground_for)
        else:
            flights = []
            for layer in det_layers:
                det, dropped = self.run_core(read_detections, layer, context, layer.name())
                if dropped:
                    feedback.pushWarning(self.tr("{layer}: {n} detection(s) without a position or score left "
                                                 "out").format(layer=layer.name(), n=dropped))
                flights.append(Flight(det, pose_groups, layer.name(), ground_for(det)))
        op = self.read_operating_point(parameters, context)
        progress, is_canceled = self.progress_callbacks(feedback, start, end)
        evaluation = self.run_core(evaluate_flights, flights, geotags, op, log, None, progress, is_canceled)
        for note in evaluation.review_notes:
            feedback.pushWarning(note)
        clusters = reviewed_clusters(evaluation, log)
        counts = outcome_counts(clusters)
        feedback.pushInfo(self.tr(
            "Review ({review}): {n} cluster(s) in {layers} detection layer(s); {hit} match a geotag; of the others "
            "{confirmed} confirmed real, {hard} hard negative, {conflicting} with conflicting verdicts, "
            "{uncertain} uncertain, {unreviewed} unreviewed.").format(
            review=review.name(), n=len(clusters), layers=len(flights), hit=counts["hit"],
            confirmed=counts["confirmed_real"], hard=counts["hard_negative"], conflicting=counts["conflicting"],
            uncertain=counts["uncertain"], unreviewed=counts["unreviewed"]))
        return clusters

    def review_label_inputs(self, feedback, reviewed, survey):
        """(targets, hard negatives, unresolved) a review adds to the labels of ``survey``
        (:func:`core.labels.training_set.review_label_inputs`; all empty for ``reviewed`` None), said in the log."""
        targets, hard, unresolved = review_label_inputs(reviewed or [], survey)
        if reviewed is not None:
            feedback.pushInfo(self.tr("From the review: {targets} target(s) nobody surveyed are labelled "
                                      "(provenance review); {hard} hard negative(s) put their tiles first "
                                      "in the negative sample; no tile near one of the {unresolved} unresolved "
                                      "cluster(s) is written.").format(targets=len(targets), hard=len(hard),
                                                                       unresolved=len(unresolved)))
        return targets, hard, unresolved

    def review_ground(self, detections, dem, feedback):
        """The ground the review's in-view test stands on: the one the layer's detections were placed on
        (``detections.ground``). A DEM record needs ``dem`` (the algorithm's own DEM, when it has one): without
        it the level plane stands in, with a warning: only which geotags count as in view can change, so a
        cluster may be kept as unresolved that the DEM would have settled by a geotag."""
        record = detections.ground
        if record.model == DEM and dem is None:
            feedback.pushWarning(self.tr(
                "{layer}: its detections were placed on {recorded}; the review's in-view test stands on the level "
                "plane here (this algorithm has no DEM, or none was given).").format(
                layer=detections.name, recorded=record.describe()))
            return None
        return self.run_core(record.factory, dem if record.model == DEM else None, detections.name)
