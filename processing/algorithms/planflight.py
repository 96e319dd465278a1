"""``birdseye:planflight`` — geotags on the farm map → the shortest survey flight and mission files."""
from __future__ import annotations

from pathlib import Path

import numpy as np
from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsGeometry,
    QgsLineString,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingOutputString,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterCrs,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterField,
    QgsProcessingParameterFile,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterNumber,
    QgsProcessingParameterPoint,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.field.surveyed_area import DEFAULT_SURVEY_MARGIN_M, surveyed_area
from ...birdseye_qgis.core.geometry.camera import load_calibration
from ...birdseye_qgis.core.plan.flight_plan import (
    ROUTE_FIELDS,
    WAYPOINT_FIELDS,
    FlightSettings,
    plan_flight,
    route_records,
    waypoint_records,
)
from ...birdseye_qgis.core.plan.mission_files import (
    CAPTURE_PHOTO,
    CAPTURE_TIMED,
    DJI_DRONES,
    DJI_PAYLOADS,
    FORMAT_NAMES,
    check_waypoint_limits,
    mission_file_paths,
    write_dji_kmz,
    write_kml,
    write_litchi_csv,
    write_qgc_plan,
)
from ...birdseye_qgis.qgis_enums import (
    NUMBER_DOUBLE,
    NUMBER_INTEGER,
    PARAMETER_ADVANCED,
    SOURCE_VECTOR_LINE,
    SOURCE_VECTOR_POINT,
    SOURCE_VECTOR_POLYGON,
    WKB_LINE_STRING,
    WKB_POINT_Z,
)
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from ..parameters.layer_parameters import source_parameter, vector_parameter
from ..parameters.review import ReviewParametersMixin
from .base import BirdsEyeAlgorithm


class PlanFlight(ReviewParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "planflight"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("PlanFlight", "Plan the survey flight")
    GROUP = "plan"
    GEOTAGS = "GEOTAGS"
    SELECTED_ONLY = "SELECTED_ONLY"
    ID_FIELD = "ID_FIELD"
    HOME = "HOME"
    CAMERA = "CAMERA"
    CAPTURE = "CAPTURE"
    FORCE = "FORCE"
    OUTPUT_CRS = "OUTPUT_CRS"
    OUTPUT_WAYPOINTS = "OUTPUT_WAYPOINTS"
    OUTPUT_ROUTE = "OUTPUT_ROUTE"
    MISSION_FILES = "MISSION_FILES"
    ALTITUDE_M = "ALTITUDE_M"
    SPEED_MS = "SPEED_MS"
    MERGE_RADIUS_M = "MERGE_RADIUS_M"
    HOVER_S = "HOVER_S"
    MAX_WAYPOINTS = "MAX_WAYPOINTS"
    MAX_FLIGHT_MIN = "MAX_FLIGHT_MIN"
    CAPTURE_INTERVAL_S = "CAPTURE_INTERVAL_S"
    FORWARD_OVERLAP_PCT = "FORWARD_OVERLAP_PCT"
    FOOTPRINT_MARGIN_PX = "FOOTPRINT_MARGIN_PX"
    DRONE = "DRONE"
    PAYLOAD = "PAYLOAD"
    UNRESOLVED_ONLY = "UNRESOLVED_ONLY"
    SURVEYED_AREA = "SURVEYED_AREA"
    SURVEY_MARGIN_M = "SURVEY_MARGIN_M"

    CAPTURE_OPTIONS = [(CAPTURE_PHOTO, "Photo at each waypoint"), (CAPTURE_TIMED, "Timed capture (interval)")]
    #: Mission file outputs: parameter, core format key, label, file filter.
    FILE_OUTPUTS = [("OUTPUT_KMZ", "kmz", "DJI Pilot 2 route (WPML KMZ)", "DJI WPML (*.kmz)"),
                    ("OUTPUT_PLAN", "plan", "QGroundControl plan", "QGroundControl plan (*.plan)"),
                    ("OUTPUT_LITCHI", "litchi", "Litchi mission (CSV)", "Litchi CSV (*.csv)"),
                    ("OUTPUT_KML", "kml", "Google Earth (KML)", "KML (*.kml)")]

    def initAlgorithm(self, config=None):
        self.addParameter(vector_parameter(
            self.GEOTAGS, self.tr("Geotags"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT]))
        self.addParameter(QgsProcessingParameterBoolean(
            self.SELECTED_ONLY, self.tr("Selected geotags only"), defaultValue=False))
        self.addParameter(QgsProcessingParameterField(
            self.ID_FIELD, self.tr("Geotag id field (empty: 'id')"),
            parentLayerParameterName=self.GEOTAGS, optional=True))
        self.addParameter(QgsProcessingParameterPoint(
            self.HOME, self.tr("Home: take-off and landing point"), optional=True))
        # Not bounded here: the plan's own check says why 2–120 m (rotor wash, the legal ceiling).
        self._number(self.ALTITUDE_M, "Flight altitude above take-off [m]", FlightSettings.altitude_m)
        self._number(self.SPEED_MS, "Flight speed [m/s]", 3.0, minimum=0.0)
        self._number(self.MERGE_RADIUS_M, "Merge radius of one waypoint [m]", 2.0, minimum=0.0)
        self.addParameter(QgsProcessingParameterFile(
            self.CAMERA, self.tr("Camera calibration (YAML)"), optional=True,
            fileFilter="Calibration (*.yaml *.yml);;All files (*)"))
        self._number(self.FOOTPRINT_MARGIN_PX, "Edge margin kept around geotags in the image [px]", 50.0,
                     minimum=0.0, advanced=True)
        self.addParameter(source_parameter(
            self.SURVEYED_AREA, self.tr("Surveyed area (polygons)"),
            layer_kinds.AREAS, [SOURCE_VECTOR_POLYGON], optional=True))
        self._number(self.SURVEY_MARGIN_M, "Margin around the geotags' hull [m]",
                     DEFAULT_SURVEY_MARGIN_M, minimum=0.0)
        self._number(self.HOVER_S, "Hover at each waypoint [s]", 2.0, minimum=0.0)
        self.addParameter(QgsProcessingParameterEnum(
            self.CAPTURE, self.tr("Capture"), options=[label for _, label in self.CAPTURE_OPTIONS], defaultValue=0))
        self._number(self.CAPTURE_INTERVAL_S, "Timed capture interval [s] (0: from the camera)", 2.0, minimum=0.0)
        self._number(self.FORWARD_OVERLAP_PCT, "Forward overlap for the suggested interval [%]", 80.0,
                     minimum=0.0, maximum=99.0, advanced=True)
        self._number(self.MAX_WAYPOINTS, "Most waypoints per mission", 99, integer=True, minimum=1)
        self._number(self.MAX_FLIGHT_MIN, "Longest flight per mission [min]", 20.0, minimum=0.0)
        self._enum(self.DRONE, "DJI aircraft (KMZ)", list(DJI_DRONES))
        self._enum(self.PAYLOAD, "DJI camera (KMZ)", list(DJI_PAYLOADS))
        force = QgsProcessingParameterBoolean(
            self.FORCE, self.tr("Plan even if the points spread over more than 10 km"), defaultValue=False)
        force.setFlags(force.flags() | PARAMETER_ADVANCED)
        self.addParameter(force)
        self.add_review_parameters(with_frames=True, edge_buffer=True)
        self.addParameter(QgsProcessingParameterBoolean(
            self.UNRESOLVED_ONLY, self.tr("With REVIEW: fly only to the unresolved clusters"), defaultValue=False))
        crs = QgsProcessingParameterCrs(self.OUTPUT_CRS, self.tr("Output CRS (empty: the site's UTM zone)"),
                                        optional=True)
        crs.setFlags(crs.flags() | PARAMETER_ADVANCED)
        self.addParameter(crs)
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT_WAYPOINTS, self.tr("Waypoints"), SOURCE_VECTOR_POINT))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT_ROUTE, self.tr("Route"), SOURCE_VECTOR_LINE))
        for name, _, label, file_filter in self.FILE_OUTPUTS:
            self.addParameter(QgsProcessingParameterFileDestination(
                name, self.tr(label), file_filter, optional=True, createByDefault=False))
        for name, label in (("ROUTE_LENGTH_M", "Route length [m]"), ("FLIGHT_TIME_MIN", "Estimated flight time [min]"),
                            ("WAYPOINT_COUNT", "Waypoints"), ("MISSION_COUNT", "Missions"),
                            ("GEOTAG_COUNT", "Geotags"),
                            ("UNRESOLVED_COUNT", "Unresolved clusters of the review")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(label)))
        self.addOutput(QgsProcessingOutputString(self.MISSION_FILES, self.tr("Mission files written")))

    def _number(self, name, label, default, minimum=None, maximum=None, integer=False, advanced=False):
        kind = NUMBER_INTEGER if integer else NUMBER_DOUBLE
        param = QgsProcessingParameterNumber(name, self.tr(label), kind, default)
        if minimum is not None:
            param.setMinimum(minimum)
        if maximum is not None:
            param.setMaximum(maximum)
        if advanced:
            param.setFlags(param.flags() | PARAMETER_ADVANCED)
        self.addParameter(param)

    def _enum(self, name, label, options):
        param = QgsProcessingParameterEnum(name, self.tr(label), options=options, defaultValue=0)
        param.setFlags(param.flags() | PARAMETER_ADVANCED)
        self.addParameter(param)

    # ------------------------------------------------------------------------------------------ run
    def processAlgorithm(self, parameters, context, feedback):
        layer = self.parameterAsVectorLayer(parameters, self.GEOTAGS, context)
        if layer is None:
            raise QgsProcessingException(self.tr("GEOTAGS: the geotag layer could not be opened."))
        selected_only = self.parameterAsBool(parameters, self.SELECTED_ONLY, context)
        if selected_only and layer.selectedFeatureCount() == 0:
            raise QgsProcessingException(self.tr(
                "SELECTED_ONLY is set but no geotag of layer '{}' is selected: select the geotags"
                " of the partition to fly, or clear SELECTED_ONLY.").format(layer.name()))
        geotags = self.run_core(layers.read_geotag_layer, layer, context.transformContext(),
                                self.parameterAsString(parameters, self.ID_FIELD, context) or "id", selected_only,
                                layer.name())
        if geotags.problems:
            raise QgsProcessingException(self.tr("{problem}: remove the feature or give it a position, so no "
                                                 "target is left out of the flight.").format(
                                                     problem=geotags.problems[0]))
        if len(geotags) == 0:
            raise QgsProcessingException(self.tr("GEOTAGS: layer '{}' has no features: there is nothing to fly"
                                                 " over.").format(layer.name()))
        drawn = self.parameterAsSource(parameters, self.SURVEYED_AREA, context)
        rings = None if drawn is None else self.run_core(layers.read_polygon_rings, drawn, context.transformContext())
        # The survey's own geotags (the selected ones with SELECTED_ONLY) outline the area, never the clusters.
        surveyed = self.run_core(surveyed_area, geotags.lat, geotags.lon,
                                 self.parameterAsDouble(parameters, self.SURVEY_MARGIN_M, context), rings,
                                 geotags.height)
        # Ground heights only feed the uneven-ground warning.
        ids, heights = [str(i) for i in geotags.ids], geotags.height
        lat, lon, origins = geotags.lat, geotags.lon, ["survey"] * len(ids)
        # Every geotag of the layer, selected or not, settles the clusters it matches.
        reviewed = self.read_reviewed_clusters(parameters, context, feedback, layer, None, 0.0, 30.0)
        unresolved = [c for c in reviewed or [] if c.is_unresolved]
        if self.parameterAsBool(parameters, self.UNRESOLVED_ONLY, context):
            if reviewed is None:
                raise QgsProcessingException(self.tr("UNRESOLVED_ONLY needs a review: give REVIEW and the "
                                                     "detection layers it judged (REVIEW_DETECTIONS)."))
            if not unresolved:
                raise QgsProcessingException(self.tr("The review left no cluster unresolved (uncertain, "
                                                     "unreviewed or with conflicting verdicts): there is "
                                                     "nothing to fly back to."))
            lat, lon, ids, heights, origins = np.empty(0), np.empty(0), [], np.empty(0), []
        if unresolved:
            lat = np.append(lat, [c.lat for c in unresolved])
            lon = np.append(lon, [c.lon for c in unresolved])
            ids = ids + [c.key for c in unresolved]
            heights = np.append(heights, np.full(len(unresolved), np.nan))
            origins = origins + [f"review:{c.outcome}" for c in unresolved]

        point = self.parameterAsPoint(parameters, self.HOME, context, QgsCoordinateReferenceSystem(layers.WGS84))
        home = None if point.isEmpty() else (point.y(), point.x())

        camera = None
        camera_path = self.parameterAsFile(parameters, self.CAMERA, context)
        if camera_path:
            camera = self.run_core(load_calibration, camera_path)
        settings = FlightSettings(
            altitude_m=self.parameterAsDouble(parameters, self.ALTITUDE_M, context),
            speed_ms=self.parameterAsDouble(parameters, self.SPEED_MS, context),
            merge_radius_m=self.parameterAsDouble(parameters, self.MERGE_RADIUS_M, context),
            hover_s=self.parameterAsDouble(parameters, self.HOVER_S, context),
            max_waypoints=self.parameterAsInt(parameters, self.MAX_WAYPOINTS, context),
            max_flight_min=self.parameterAsDouble(parameters, self.MAX_FLIGHT_MIN, context),
            capture=self.CAPTURE_OPTIONS[self.parameterAsEnum(parameters, self.CAPTURE, context)][0],
            capture_interval_s=self.parameterAsDouble(parameters, self.CAPTURE_INTERVAL_S, context),
            forward_overlap=self.parameterAsDouble(parameters, self.FORWARD_OVERLAP_PCT, context) / 100.0,
            footprint_margin_px=self.parameterAsDouble(parameters, self.FOOTPRINT_MARGIN_PX, context),
            force=self.parameterAsBool(parameters, self.FORCE, context))
        chosen_crs = self.run_core(layers.chosen_projected_crs,
                                   self.parameterAsCrs(parameters, self.OUTPUT_CRS, context))
        requested = {fmt: self.parameterAsFileOutput(parameters, name, context)
                     for name, fmt, _, _ in self.FILE_OUTPUTS}
        requested = {fmt: path for fmt, path in requested.items() if path}

        progress, is_canceled = self.progress_callbacks(feedback, 30.0 if reviewed is not None else 0.0, 80.0)
        plan = self.run_core(plan_flight, lat, lon, ids, home, settings, camera,
                             layer.name(), progress, is_canceled, ground_heights=heights, origins=origins,
                             surveyed=surveyed)
        for message in plan.warnings:
            feedback.pushWarning(message)
        if plan.suggested_interval_s is not None:
            feedback.pushInfo(self.tr(
                "With this camera at {alt:g} m and {v:g} m/s, one photo every {s:.2f} s gives {o:g} % forward"
                " overlap.").format(alt=settings.altitude_m, v=settings.speed_ms, s=plan.suggested_interval_s,
                                    o=100 * settings.forward_overlap))

        # Every requested mission file must be possible before anything is written.
        specs = {fmt: plan.mission_specs(Path(path).stem) for fmt, path in requested.items()}
        for fmt, fmt_specs in specs.items():
            self.run_core(check_waypoint_limits, fmt_specs, [fmt])
        crs_core, crs = self.run_core(layers.output_crs, chosen_crs, lat, lon)
        outputs = self._write_layers(parameters, context, feedback, plan, crs_core, crs)
        outputs.update(self._write_mission_files(specs, requested, parameters, context, feedback))
        outputs.update({"ROUTE_LENGTH_M": plan.total_length_m, "FLIGHT_TIME_MIN": plan.total_time_s / 60.0,
                        "WAYPOINT_COUNT": plan.waypoint_count, "MISSION_COUNT": len(plan.missions),
                        "GEOTAG_COUNT": len(ids) - len(unresolved), "UNRESOLVED_COUNT": len(unresolved)})
        self._log_summary(feedback, plan, len(ids) - len(unresolved), len(unresolved))
        feedback.setProgress(100)
        return outputs

    def _write_layers(self, parameters, context, feedback, plan, crs_core, crs):
        fields = layers.qgs_fields(WAYPOINT_FIELDS)
        sink, waypoints_id = self.parameterAsSink(parameters, self.OUTPUT_WAYPOINTS, context, fields,
                                                  WKB_POINT_Z, crs)
        records = waypoint_records(plan)
        x, y = crs_core.from_geodetic([r["lat"] for r in records], [r["lon"] for r in records])
        geometries = (layers.point_z(px, py, r["altitude"]) for px, py, r in zip(np.atleast_1d(x), np.atleast_1d(y),
                                                                                   records))
        self.run_core(layers.write_records, sink, fields, records, geometries, feedback, 80.0, 88.0, len(records))
        layers.style_on_load(context, waypoints_id, "waypoints.qml")

        route_fields = layers.qgs_fields(ROUTE_FIELDS)
        route_sink, route_id = self.parameterAsSink(parameters, self.OUTPUT_ROUTE, context, route_fields,
                                                    WKB_LINE_STRING, crs)
        lines = []
        for mission in plan.missions:
            lat, lon = plan.route_latlon(mission)
            lx, ly = crs_core.from_geodetic(lat, lon)
            # A single waypoint without home is no line: the feature keeps its attributes only.
            lines.append(QgsGeometry(QgsLineString(np.atleast_1d(lx).tolist(), np.atleast_1d(ly).tolist()))
                         if len(lat) > 1 else None)
        self.run_core(layers.write_records, route_sink, route_fields, route_records(plan), lines)
        layers.style_on_load(context, route_id, "route.qml")
        return {"OUTPUT_WAYPOINTS": waypoints_id, self.OUTPUT_ROUTE: route_id}

    def _write_mission_files(self, specs, requested, parameters, context, feedback):
        """Each requested format: one file per mission (suffixed _m1, _m2… when several), the KML
        one file for all; returns the output values (first file of each format, all files)."""
        drone = list(DJI_DRONES.values())[self.parameterAsEnum(parameters, self.DRONE, context)]
        payload = list(DJI_PAYLOADS.values())[self.parameterAsEnum(parameters, self.PAYLOAD, context)]
        writers = {"kmz": lambda p, s: write_dji_kmz(p, s, drone, payload),
                   "plan": write_qgc_plan, "litchi": write_litchi_csv}
        outputs, written = {}, []
        for name, fmt, _, _ in self.FILE_OUTPUTS:
            if fmt not in requested:
                continue
            if fmt == "kml":  # one file holds every mission
                paths = [self.run_core(write_kml, requested[fmt], specs[fmt], Path(requested[fmt]).stem)]
            else:
                paths = [self.run_core(writers[fmt], path, spec)
                         for path, spec in zip(mission_file_paths(requested[fmt], len(specs[fmt])), specs[fmt])]
            outputs[name] = str(paths[0])
            written += [str(p) for p in paths]
            feedback.pushInfo(self.tr("{fmt}: {files}").format(
                fmt=FORMAT_NAMES[fmt], files=", ".join(Path(p).name for p in paths)))
        outputs[self.MISSION_FILES] = ";".join(written)
        return outputs

    def _log_summary(self, feedback, plan, geotag_count, unresolved_count):
        s = plan.settings
        if unresolved_count:
            feedback.pushInfo(self.tr("{u} unresolved cluster(s) of the review are targets too (waypoint field "
                                      "provenance: review).").format(u=unresolved_count))
        feedback.pushInfo(self.tr(
            "{g} geotag(s) → {w} waypoint(s) in {m} mission(s); route {km:.2f} km; estimated flight time"
            " {t:.1f} min at {v:g} m/s and {alt:g} m.").format(
            g=geotag_count, w=plan.waypoint_count, m=len(plan.missions), km=plan.total_length_m / 1000.0,
            t=plan.total_time_s / 60.0, v=s.speed_ms, alt=s.altitude_m))
        for mission in plan.missions:
            feedback.pushInfo(self.tr("  mission {n}: {w} waypoint(s), {l:.0f} m, {t:.1f} min").format(
                n=mission.number, w=len(mission.waypoints), l=mission.length_m, t=mission.time_s / 60.0))
        self._log_surveyed(feedback, plan)

    def _log_surveyed(self, feedback, plan):
        """How much of the planned photos lies outside the surveyed area: Write labels takes no negative tiles
        there."""
        area = plan.surveyed.describe()
        if plan.outside_share is None:
            feedback.pushInfo(self.tr("Surveyed area: {area}. Give CAMERA to see how much of each planned photo "
                                      "lies outside it (field outside_pct).").format(area=area))
            return
        share = plan.outside_share
        partly = int(np.count_nonzero(share > 0))
        line = self.tr("Surveyed area: {area}. {k} of {w} planned photo(s) see ground outside it (at the worst "
                       "heading; largest share {pct:.0f} %, all photos {mean:.0f} % on average, field outside_pct): "
                       "Write labels takes no negative tiles from that ground.").format(
            area=area, k=partly, w=len(share), pct=100.0 * float(share.max()), mean=100.0 * float(share.mean()))
        (feedback.pushWarning if np.any(share >= 0.5) else feedback.pushInfo)(line)
