"""birdseye:importgeotags — rover survey (file, point layer or a field survey package QField filled) → styled
PointZ geotag layer; a field package's decisions at the points it visited → the review's verdict log."""
from __future__ import annotations

import numpy as np
from qgis.core import (
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterCrs,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFile,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.field.field_survey import GEOTAG_TABLE
from ...birdseye_qgis.core.field.geotags import (
    FIX_RTK_FIXED,
    FORMATS,
    GEOTAG_FIELDS,
    ColumnMapping,
    geotags_from_layer,
    layer_fields,
    prepare_geotags,
    read_geotags,
)
from ...birdseye_qgis.core.geometry.heights import MAX_UNDULATION_M, metres_per_unit
from ...birdseye_qgis.core.review.field_decisions import plan_field_decisions
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, SOURCE_VECTOR_POINT, WKB_POINT_Z
from ...birdseye_qgis.qgis_io import collected_survey, layer_kinds, layers
from ..parameters.layer_parameters import source_parameter
from .base import BirdsEyeAlgorithm


class ImportGeotags(BirdsEyeAlgorithm):
    ALG_ID = "importgeotags"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("ImportGeotags", "Import geotags")
    GROUP = "field"
    INPUT = "INPUT"
    INPUT_LAYER = "INPUT_LAYER"
    FORMAT = "FORMAT"
    UNITS = "UNITS"
    GEOID_UNDULATION_M = "GEOID_UNDULATION_M"
    FIX_FILTER = "FIX_FILTER"
    MAX_H_ACCURACY_M = "MAX_H_ACCURACY_M"
    POLE_HEIGHT_M = "POLE_HEIGHT_M"
    OUTPUT_CRS = "OUTPUT_CRS"
    REVIEW_LOG = "REVIEW_LOG"
    OUTPUT = "OUTPUT"

    FORMAT_NAMES = ["Automatic (from the content)", "BirdsEye rover CSV (no header)", "CSV with a header",
                    "NMEA GGA log"]
    FIX_FILTERS = ["All geotags (float and no-RTK flagged)", "RTK fixed only"]
    #: UNITS choices and the unit each stands for (None: from the file).
    UNIT_CHOICES = (
        (QT_TRANSLATE_NOOP("ImportGeotags", "From the file (else metres)"), None),
        (QT_TRANSLATE_NOOP("ImportGeotags", "Metres"), "m"),
        (QT_TRANSLATE_NOOP("ImportGeotags", "International feet (0.3048 m)"), "ft"),
        (QT_TRANSLATE_NOOP("ImportGeotags", "US survey feet (1200/3937 m)"), "ftUS"))
    MAPPING = (("LAT_FIELD", "lat", "Latitude column (header CSV)"),
               ("LON_FIELD", "lon", "Longitude column (header CSV)"),
               ("HEIGHT_FIELD", "height", "Ellipsoidal height column/field"),
               ("MSL_FIELD", "msl", "MSL (orthometric) height column/field"),
               ("FIX_FIELD", "fix", "Fix quality column/field"),
               ("LABEL_FIELD", "label", "Label column/field"))

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterFile(
            self.INPUT, self.tr("Geotag file (CSV, NMEA or field GeoPackage)"), optional=True,
            fileFilter="Geotags (*.csv *.txt *.nmea *.log *.gga *.gpkg *.qgz);;All files (*)"))
        self.addParameter(source_parameter(
            self.INPUT_LAYER, self.tr("…or a point layer"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT], optional=True))
        self.addParameter(QgsProcessingParameterEnum(
            self.FORMAT, self.tr("File format"), options=self.FORMAT_NAMES, defaultValue=0))
        for name, _, text in self.MAPPING:
            self.addParameter(QgsProcessingParameterString(name, self.tr(text), optional=True))
        self.addParameter(QgsProcessingParameterEnum(
            self.UNITS, self.tr("Unit of heights and accuracies"),
            options=[self.tr(text) for text, _ in self.UNIT_CHOICES], defaultValue=0))
        self.addParameter(QgsProcessingParameterNumber(
            self.GEOID_UNDULATION_M, self.tr("Geoid undulation N (m; empty: EGM96)"),
            NUMBER_DOUBLE, None, optional=True, minValue=-MAX_UNDULATION_M, maxValue=MAX_UNDULATION_M))
        self.addParameter(QgsProcessingParameterEnum(
            self.FIX_FILTER, self.tr("Fix filter"), options=self.FIX_FILTERS, defaultValue=0))
        self.addParameter(QgsProcessingParameterNumber(
            self.MAX_H_ACCURACY_M, self.tr("Largest horizontal accuracy kept (m)"),
            NUMBER_DOUBLE, None, optional=True, minValue=0.001))
        self.addParameter(QgsProcessingParameterNumber(
            self.POLE_HEIGHT_M, self.tr("Antenna pole height (m), subtracted from heights"),
            NUMBER_DOUBLE, 0.0, minValue=0.0, maxValue=10.0))
        self.addParameter(QgsProcessingParameterCrs(
            self.OUTPUT_CRS, self.tr("Output CRS (empty: UTM zone of the site)"), optional=True))
        self.addParameter(QgsProcessingParameterFile(
            self.REVIEW_LOG, self.tr("Append field decisions to review (.gpkg)"), extension="gpkg",
            optional=True))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("Geotags"), SOURCE_VECTOR_POINT))
        for name, text in (("GEOTAG_COUNT", "Geotags written"), ("BAD_ROWS", "Bad rows left out"),
                           ("NOT_FIXED_DROPPED", "Geotags dropped by the fix filter"),
                           ("ACCURACY_DROPPED", "Geotags dropped by the accuracy filter"),
                           ("DUPLICATES", "Geotags flagged duplicate_2cm"),
                           ("DECISIONS_IMPORTED", "Field decisions appended to the review"),
                           ("VISITS_UNDECIDED", "Points to visit without a decision")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    def processAlgorithm(self, parameters, context, feedback):
        path = self.parameterAsFile(parameters, self.INPUT, context)
        source = self.parameterAsSource(parameters, self.INPUT_LAYER, context)
        if bool(path) == (source is not None):
            raise QgsProcessingException(self.tr(
                "Give either a geotag file (INPUT) or a point layer (INPUT_LAYER), not both and not neither."))
        mapping = {key: (self.parameterAsString(parameters, name, context) or "").strip() or None
                   for name, key, _ in self.MAPPING}
        chosen = self.run_core(layers.chosen_projected_crs, self.parameterAsCrs(parameters, self.OUTPUT_CRS, context))
        units = self.UNIT_CHOICES[self.parameterAsEnum(parameters, self.UNITS, context)][1]
        undulation = self._optional_number(parameters, self.GEOID_UNDULATION_M, context)
        max_accuracy = self._optional_number(parameters, self.MAX_H_ACCURACY_M, context)
        gpkg = collected_survey.package_geopackage(path) if path else None
        decisions = {"DECISIONS_IMPORTED": 0, "VISITS_UNDECIDED": 0}
        review_log = self.parameterAsFile(parameters, self.REVIEW_LOG, context)
        if gpkg is not None:
            survey = self.run_core(collected_survey.open_collected_survey, gpkg)
            feedback.pushInfo(self.tr("Reading: read as a BirdsEye field survey GeoPackage (QField): {path}, table "
                                      "'{table}'").format(path=survey.gpkg, table=GEOTAG_TABLE))
            # The decisions first: a package whose worker only visited points has no geotag to write.
            decisions = self._append_decisions(survey, review_log, context, feedback)
            layer = self.run_core(survey.layer, GEOTAG_TABLE)
            tags = self.run_core(self._from_layer, layer, layer.name(), context, mapping, units, undulation)
            self._report_survey(tags, feedback)
        elif path:
            fmt = FORMATS[self.parameterAsEnum(parameters, self.FORMAT, context)]
            tags = self.run_core(read_geotags, path, fmt, ColumnMapping(**mapping), units, undulation)
        else:
            tags = self.run_core(self._from_layer, source, source.sourceName(), context, mapping, units, undulation)
        if review_log and gpkg is None:
            feedback.pushWarning(self.tr("REVIEW_LOG is not used: only a field survey package (its GeoPackage) has "
                                         "decisions to append to a review."))
        feedback.setProgress(40)
        for note in tags.notes:
            feedback.pushInfo(self.tr("Reading: {note}").format(note=note))
        if len(tags) == 0:
            first = f" The first: {tags.problems[0]}" if tags.problems else ""
            appended = self.tr(" Its {n} field decision(s) were appended to the review all the same.").format(
                n=decisions["DECISIONS_IMPORTED"]) if decisions["DECISIONS_IMPORTED"] else ""
            raise QgsProcessingException(self.tr("The input holds no usable geotag.") + first + appended)
        if tags.problems:  # a warning: the run goes on with the good rows and its output loads
            examples = "; ".join(str(e) for e in tags.problems[:5])
            feedback.pushWarning(self.tr("{n_problems} bad row(s) left out; first: {examples}").format(
                                     n_problems=len(tags.problems), examples=examples))
        prepared = self.run_core(prepare_geotags, tags,
                                 fixed_only=self.parameterAsEnum(parameters, self.FIX_FILTER, context) == 1,
                                 pole_height_m=self.parameterAsDouble(parameters, self.POLE_HEIGHT_M, context),
                                 max_h_accuracy_m=max_accuracy)
        out = prepared.geotags
        feedback.pushInfo(self.tr("Fix quality of the input: {counts}").format(
            counts=", ".join(f"{k}: {v}" for k, v in prepared.counts_by_fix.items())))
        known = tags.h_acc[np.isfinite(tags.h_acc)]
        if known.size:
            feedback.pushInfo(self.tr("Horizontal accuracy of the input: median {median:.3f} m, worst {worst:.3f} m "
                                      "({n_known} of {n_tags} geotags give one)").format(
                median=float(np.median(known)), worst=float(known.max()), n_known=known.size, n_tags=len(tags)))
        if prepared.dropped_not_fixed:
            feedback.pushWarning(self.tr("{dropped_not_fixed} geotag(s) without an RTK fixed "
                                         "solution were left out (fix filter: RTK fixed only)").format(
                                     dropped_not_fixed=prepared.dropped_not_fixed))
        if prepared.dropped_accuracy:
            feedback.pushWarning(self.tr("{dropped} geotag(s) with a horizontal accuracy worse than {limit:g} m "
                                         "were left out (MAX_H_ACCURACY_M)").format(
                                     dropped=prepared.dropped_accuracy, limit=max_accuracy))
        if prepared.unknown_accuracy:
            feedback.pushWarning(self.tr("{unknown} geotag(s) have no horizontal accuracy in the input and were kept "
                                         "(MAX_H_ACCURACY_M cannot judge them)").format(
                                     unknown=prepared.unknown_accuracy))
        if prepared.duplicates:
            feedback.pushWarning(self.tr("{duplicates} geotag(s) lie within 2 cm of an earlier "
                                         "one (flag duplicate_2cm)").format(duplicates=prepared.duplicates))
        if len(out) == 0:
            raise QgsProcessingException(self.tr("No geotag is left to write (all were filtered out)."))
        crs_core, crs = self.run_core(layers.output_crs, chosen, out.lat, out.lon)
        feedback.pushInfo(self.tr("Output CRS: {value}").format(value=crs.authid() or crs.description()))
        x, y = crs_core.from_geodetic(out.lat, out.lon)
        fields = layers.qgs_fields(GEOTAG_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, self.OUTPUT, context, fields, WKB_POINT_Z, crs)
        z = [h if h == h else 0.0 for h in out.height.tolist()]
        n = self.run_core(layers.write_records, sink, fields, out.records(),
                          (layers.point_z(*p) for p in zip(x.tolist(), y.tolist(), z)),
                          feedback, 50.0, 100.0, len(out))
        layers.style_on_load(context, dest_id, "geotags.qml")
        return {"OUTPUT": dest_id, "GEOTAG_COUNT": n, "BAD_ROWS": len(tags.problems),
                "NOT_FIXED_DROPPED": prepared.dropped_not_fixed, "ACCURACY_DROPPED": prepared.dropped_accuracy,
                "DUPLICATES": prepared.duplicates, **decisions}

    def _optional_number(self, parameters, name, context):
        """An optional number parameter's value, None when left empty."""
        return None if parameters.get(name) in (None, "") else self.parameterAsDouble(parameters, name, context)

    @staticmethod
    def _from_layer(source, name, context, mapping, units, undulation):
        """Geotags from a point layer (or feature source) named ``name``: its fields by meaning
        (``core.field.geotags.layer_fields``: the mapped ones, else heights, accuracies, fix, label, capture time
        and worker by name), read by ``geotags_from_layer``; heights and accuracies in ``units`` (None: metres),
        an orthometric-only height converted with N = ``undulation`` (None: EGM96)."""
        fields = layer_fields(source.fields().names(), ColumnMapping(**mapping))
        cols = layers.read_point_layer(source, context.transformContext(), list(fields.values()), name)
        return geotags_from_layer(cols, fields, name, metres_per_unit(units or "m"), undulation)

    def _report_survey(self, tags, feedback):
        """What a field package's geotags hold, for the log: fixes, accuracies, capture times and workers."""
        workers = sorted({w for w in tags.worker.tolist() if w})
        feedback.pushInfo(self.tr(
            "Field survey: {n_tags} geotag(s), {n_fixed} RTK fixed, {n_accuracy} with a horizontal accuracy, {n_time} "
            "with a capture time; recorded by {workers}").format(
                n_tags=len(tags), n_fixed=int(np.count_nonzero(tags.fix_quality == FIX_RTK_FIXED)),
                n_accuracy=int(np.count_nonzero(np.isfinite(tags.h_acc))),
                n_time=sum(1 for t in tags.time_utc.tolist() if t),
                workers=", ".join(workers) if workers else self.tr("no named worker")))

    def _append_decisions(self, survey, review_log, context, feedback) -> dict:
        """Append the package's decided visits to the review's verdict log (``review_log``, else the one the
        package names when that file exists), report them, and return the outputs DECISIONS_IMPORTED and
        VISITS_UNDECIDED."""
        visits, problems = self.run_core(collected_survey.read_package_visits, survey, context.transformContext())
        for problem in problems:
            feedback.pushWarning(self.tr("Point to visit left out: {problem}").format(problem=problem))
        log = review_log or survey.review_log
        plan = plan_field_decisions(visits, ())
        stored = []
        if plan.verdicts and not review_log and log is not None and not log.is_file():
            feedback.pushWarning(self.tr("The review the package came from, {log}, is not there (moved?): give it as "
                                         "REVIEW_LOG to append the field decisions to it.").format(log=log))
        elif plan.verdicts and log is not None:
            plan, stored = self.run_core(collected_survey.append_field_decisions, log, visits)
        elif plan.verdicts:
            feedback.pushWarning(self.tr("{n} review unit(s) have a field decision, but the package names no review "
                                         "and REVIEW_LOG is empty: the decisions are not written.").format(
                                     n=len(plan.verdicts)))
        if plan.plain:
            feedback.pushInfo(self.tr("{n} decided point(s) to visit are not review units (no unit keys), so "
                                      "their decisions are not written to a review: {visits}").format(
                n=len(plan.plain), visits=", ".join(f"{v.visit_id} ({v.decision})" for v in plan.plain)))
        if plan.undecided:
            feedback.pushInfo(self.tr("{n} point(s) to visit have no decision (not visited)").format(
                n=plan.undecided))
        for note in plan.notes:
            feedback.pushWarning(self.tr("Field decisions: {note}").format(note=note))
        if plan.already:
            feedback.pushInfo(self.tr("{n} review unit(s) already hold the field's decision from the same worker "
                                      "(imported before): not appended again").format(n=len(plan.already)))
        if stored:
            feedback.pushInfo(self.tr("Field decisions: {n} verdict(s) appended to the review {log} as "
                                      "{reviewers}").format(
                n=len(stored), log=log, reviewers=", ".join(sorted({row["reviewer"] for row in stored}))))
        return {"DECISIONS_IMPORTED": len(stored), "VISITS_UNDECIDED": plan.undecided}
