"""``birdseye:preparefieldsurvey`` — a folder QField opens to record geotags with an RTK receiver and to
decide at the points a review left open (docs/design.md#field-survey)."""
from __future__ import annotations

from qgis.core import (
    QgsProcessingException,
    QgsProcessingOutputFile,
    QgsProcessingOutputNumber,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFolderDestination,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterLayer,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.field.field_survey import HEIGHT_ELLIPSOIDAL, HEIGHT_ORTHOMETRIC
from ...birdseye_qgis.core.review.units import UNIT_PREFIX, position_key
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, SOURCE_VECTOR_POINT, SOURCE_VECTOR_POLYGON
from ...birdseye_qgis.qgis_io import field_package, layer_kinds, layers
from ..parameters.layer_parameters import source_parameter, vector_parameter
from ..parameters.review import ReviewParametersMixin
from .base import BirdsEyeAlgorithm


class PrepareFieldSurvey(ReviewParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "preparefieldsurvey"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("PrepareFieldSurvey", "Prepare field survey")
    GROUP = "field"
    OUTPUT_FOLDER = "OUTPUT_FOLDER"
    PROJECT_NAME = "PROJECT_NAME"
    CLASSES = "CLASSES"
    LABEL_RADIUS_M = "LABEL_RADIUS_M"
    REQUIRE_RTK_FIXED = "REQUIRE_RTK_FIXED"
    MAX_H_ACCURACY_M = "MAX_H_ACCURACY_M"
    ACCURACY_ENFORCEMENT = "ACCURACY_ENFORCEMENT"
    HEIGHT_REFERENCE = "HEIGHT_REFERENCE"
    GEOTAGS = "GEOTAGS"
    VISIT_POINTS = "VISIT_POINTS"
    AREA = "AREA"
    BACKGROUND = "BACKGROUND"
    FRAMES = "FRAMES"
    PROJECT = "PROJECT"

    ENFORCEMENTS = (QT_TRANSLATE_NOOP("PrepareFieldSurvey", "Warn and flag the point"),
                    QT_TRANSLATE_NOOP("PrepareFieldSurvey", "Block saving"))
    #: HEIGHT_REFERENCE choices: what the user declares QField's altitude to be.
    HEIGHT_CHOICES = (
        (QT_TRANSLATE_NOOP("PrepareFieldSurvey", "Orthometric (QField: orthometric altitude on)"),
         HEIGHT_ORTHOMETRIC),
        (QT_TRANSLATE_NOOP("PrepareFieldSurvey", "Ellipsoidal (that setting off, no grid shift)"),
         HEIGHT_ELLIPSOIDAL))

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterFolderDestination(
            self.OUTPUT_FOLDER, self.tr("Package folder (copy it to the device)")))
        self.addParameter(QgsProcessingParameterString(
            self.PROJECT_NAME, self.tr("Project name"), defaultValue="birdseye_survey"))
        self.addParameter(QgsProcessingParameterString(
            self.CLASSES, self.tr("Classes (comma-separated; the first is the default)"), defaultValue="target"))
        self.addParameter(QgsProcessingParameterNumber(
            self.LABEL_RADIUS_M, self.tr("Label radius (m)"), NUMBER_DOUBLE, 0.05, minValue=0.005))
        self.addParameter(QgsProcessingParameterBoolean(
            self.REQUIRE_RTK_FIXED, self.tr("Require an RTK fixed solution"), defaultValue=True))
        # 0 turns the limit off: an optional number left empty would take its default instead.
        self.addParameter(QgsProcessingParameterNumber(
            self.MAX_H_ACCURACY_M, self.tr("Largest horizontal accuracy accepted (m; 0: any)"), NUMBER_DOUBLE,
            0.05, minValue=0.0))
        self.addParameter(QgsProcessingParameterEnum(
            self.ACCURACY_ENFORCEMENT, self.tr("A point that fails the requirement"),
            options=[self.tr(text) for text in self.ENFORCEMENTS], defaultValue=0))
        self.addParameter(QgsProcessingParameterEnum(
            self.HEIGHT_REFERENCE, self.tr("Height the receiver gives QField"),
            options=[self.tr(text) for text, _ in self.HEIGHT_CHOICES], defaultValue=0))
        self.addParameter(vector_parameter(
            self.GEOTAGS, self.tr("Geotags surveyed before"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT],
            optional=True))
        # Points drawn or imported by hand are point layers of no BirdsEye kind, which the geotag kind offers.
        self.addParameter(vector_parameter(
            self.VISIT_POINTS, self.tr("Points to visit"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT], optional=True))
        self.addParameter(source_parameter(
            self.AREA, self.tr("Survey area or partitions (polygons)"), layer_kinds.AREAS, [SOURCE_VECTOR_POLYGON],
            optional=True))
        self.addParameter(QgsProcessingParameterRasterLayer(
            self.BACKGROUND, self.tr("Orthomosaic (copied as GeoTIFF)"), optional=True))
        self.addParameter(source_parameter(
            self.FRAMES, self.tr("Frame layer (footprints as background)"), layer_kinds.FRAMES,
            [SOURCE_VECTOR_POLYGON], optional=True))
        self.add_review_parameters(with_frames=True, edge_buffer=True)
        self.addOutput(QgsProcessingOutputFile(self.PROJECT, self.tr("QField project (.qgz)")))
        for name, text in (("VISIT_COUNT", "Points to visit"), ("GEOTAG_COUNT", "Geotags surveyed before")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    # ------------------------------------------------------------------------------------------ run
    def processAlgorithm(self, parameters, context, feedback):
        folder = self.parameterAsString(parameters, self.OUTPUT_FOLDER, context)
        name = (self.parameterAsString(parameters, self.PROJECT_NAME, context) or "").strip()
        if not name or any(c in name for c in '/\\:*?"<>|'):
            raise QgsProcessingException(self.tr(
                "PROJECT_NAME: give a file name without a folder or any of / \\ : * ? \" < > | (got '{name}')."
            ).format(name=name))
        # Before the review is scored, so a refusal comes at once; write_package checks again.
        self.run_core(field_package.refuse_existing_package, folder, name)
        settings = self._settings(parameters, context)

        geotag_layer = self.parameterAsVectorLayer(parameters, self.GEOTAGS, context)
        if geotag_layer is None and self.parameterAsVectorLayer(parameters, self.REVIEW, context) is not None:
            raise QgsProcessingException(self.tr(
                "REVIEW needs GEOTAGS: the survey's geotags settle the clusters they match, so only the others are "
                "visited. Give the geotag layer the review was scored against."))
        surveyed = None
        if geotag_layer is not None:
            surveyed = self.run_core(layers.read_geotag_layer, geotag_layer, context.transformContext())
            self._warn_left_out(feedback, surveyed.problems)
        # Without REVIEW this reads no geotags: it returns None, or refuses REVIEW_DETECTIONS given alone.
        reviewed = self.read_reviewed_clusters(parameters, context, feedback, geotag_layer, None, 0.0, 40.0)
        # A cluster nobody judged has no unit in the log yet: the field's decision is written as a unit at its
        # centroid, which the scoring attaches to the cluster as it attaches the dock's units (within EPS_PRED_M).
        visits = [field_package.Visit(
            c.key, f"review:{c.outcome}",
            self.tr("Is there a target here? (review: {outcome})").format(outcome=c.outcome), c.lat, c.lon,
            c.unit_keys or (position_key(UNIT_PREFIX, c.lat, c.lon),)) for c in reviewed or [] if c.is_unresolved]
        visits += self._layer_visits(parameters, context, feedback)

        sources = field_package.PackageSources(
            surveyed=surveyed, area=self.parameterAsSource(parameters, self.AREA, context),
            frames=self.parameterAsSource(parameters, self.FRAMES, context),
            background=self.parameterAsRasterLayer(parameters, self.BACKGROUND, context))
        progress, is_canceled = self.progress_callbacks(feedback, 40.0, 100.0)
        project = self.run_core(field_package.write_package, folder, name, settings, visits, sources,
                                context.transformContext(), progress, is_canceled)
        geotag_count = 0 if surveyed is None else len(surveyed)
        feedback.pushInfo(self.tr(
            "Wrote {project}: {visits} point(s) to visit, {geotags} geotag(s) surveyed before. Copy the folder to "
            "the device and open the project in QField.").format(project=project, visits=len(visits),
                                                                  geotags=geotag_count))
        feedback.pushInfo(field_package.instructions(settings))
        return {self.PROJECT: str(project), "VISIT_COUNT": len(visits), "GEOTAG_COUNT": geotag_count}

    def _settings(self, parameters, context) -> field_package.SurveySettings:
        text = self.parameterAsString(parameters, self.CLASSES, context) or ""
        classes = tuple(dict.fromkeys(c.strip() for c in text.split(",") if c.strip()))
        if not classes:
            raise QgsProcessingException(self.tr(
                "CLASSES: give at least one class name the worker picks for a geotag, comma-separated (for example "
                "'burrow, nest')."))
        review = self.parameterAsVectorLayer(parameters, self.REVIEW, context)
        max_h_acc = self.parameterAsDouble(parameters, self.MAX_H_ACCURACY_M, context)
        return field_package.SurveySettings(
            classes=classes,
            label_radius_m=self.parameterAsDouble(parameters, self.LABEL_RADIUS_M, context),
            require_fixed=self.parameterAsBool(parameters, self.REQUIRE_RTK_FIXED, context),
            max_h_accuracy_m=max_h_acc if max_h_acc > 0 else None,
            block_inaccurate=self.parameterAsEnum(parameters, self.ACCURACY_ENFORCEMENT, context) == 1,
            height_reference=self.HEIGHT_CHOICES[self.parameterAsEnum(parameters, self.HEIGHT_REFERENCE, context)][1],
            review_log="" if review is None else layers.data_file(review))

    def _layer_visits(self, parameters, context, feedback) -> list:
        """VISIT_POINTS as visits, each named by the geotag id rule (its ``id`` field, else its row)."""
        layer = self.parameterAsVectorLayer(parameters, self.VISIT_POINTS, context)
        if layer is None:
            return []
        points = self.run_core(layers.read_geotag_layer, layer, context.transformContext())
        self._warn_left_out(feedback, points.problems)
        question = self.tr("Is there a target here? (from {layer})").format(layer=layer.name())
        return [field_package.Visit(str(i), f"layer:{layer.name()}", question, float(lat), float(lon))
                for i, lat, lon in zip(points.ids, points.lat, points.lon)]

    def _warn_left_out(self, feedback, problems) -> None:
        if problems:
            feedback.pushWarning(self.tr("{n} point(s) without a position left out; first: {first}").format(
                n=len(problems), first=problems[0]))
