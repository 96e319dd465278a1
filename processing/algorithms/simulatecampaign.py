"""birdseye:simulatecampaign — a deterministic synthetic campaign in the BirdsEye file formats."""
from __future__ import annotations

from qgis.core import (
    QgsProcessingOutputFile,
    QgsProcessingOutputFolder,
    QgsProcessingOutputNumber,
    QgsProcessingOutputRasterLayer,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFolderDestination,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.sim.campaign import (
    DEFAULT_SIDE_OVERLAP,
    ORTHO_PIXEL_RANGE_M,
    PLATFORMS,
    TERRAIN_KINDS,
    CampaignConfig,
    parse_sigmas,
    simulate_campaign,
)
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, NUMBER_INTEGER, PARAMETER_ADVANCED
from .base import BirdsEyeAlgorithm

DEFAULTS = CampaignConfig()
INT, DOUBLE = NUMBER_INTEGER, NUMBER_DOUBLE

# (name, label, type, default, min, max, advanced), in the dialog's order; the advanced ones follow
# the switches (SIGMAS, NOISE_OFF, RENDER).
NUMBERS = [
    ("SEED", "Random seed (same seed → identical files)", INT, DEFAULTS.seed, 0, 2147483647, False),
    ("N_TARGETS", "Number of targets (burrows)", INT, DEFAULTS.n_targets, 1, 5000, False),
    ("FIELD_WIDTH_M", "Field width, east–west (m)", DOUBLE, DEFAULTS.field_width_m, 2.0, 500.0, False),
    ("FIELD_LENGTH_M", "Field length, north–south (m)", DOUBLE, DEFAULTS.field_length_m, 2.0, 500.0, False),
    ("ALTITUDE_M", "Flying height above ground (m)", DOUBLE, DEFAULTS.altitude_m, 1.0, 120.0, False),
    ("SPEED_MS", "Flight speed (m/s)", DOUBLE, DEFAULTS.speed_ms, 0.2, 20.0, False),
    ("SITE_LAT", "Site latitude (deg, WGS84)", DOUBLE, DEFAULTS.site_lat, -80.0, 84.0, True),
    ("SITE_LON", "Site longitude (deg, WGS84)", DOUBLE, DEFAULTS.site_lon, -180.0, 180.0, True),
    ("GROUND_HEIGHT_M", "Ground height (m, WGS84 ellipsoidal)", DOUBLE, DEFAULTS.ground_height_m, -500.0, 9000.0, True),
    ("FPS", "Camera frame rate (frames/s)", DOUBLE, DEFAULTS.fps, 0.2, 60.0, True),
    ("INS_RATE_HZ", "INS message rate (Hz)", DOUBLE, DEFAULTS.ins_rate_hz, 1.0, 1000.0, True),
    ("IMAGE_WIDTH", "Image width (px)", INT, DEFAULTS.image_width, 32, 8192, True),
    ("IMAGE_HEIGHT", "Image height (px)", INT, DEFAULTS.image_height, 32, 8192, True),
    ("FORWARD_OVERLAP", "Forward overlap of a DJI drone's photos (fraction)", DOUBLE, DEFAULTS.forward_overlap,
     0.0, 0.95, True),
    ("RADALT_SIGMA_M", "Radar altimeter noise σ (m)", DOUBLE, DEFAULTS.radalt_sigma_m, 0.0, 10.0, True),
    ("RTK_SIGMA_M", "Rover RTK noise σ of the geotags (m)", DOUBLE, DEFAULTS.rtk_sigma_m, 0.0, 10.0, True),
    ("N_MISSED", "Targets not surveyed", INT, DEFAULTS.n_missed, 0, 5000, True),
    ("N_SPURIOUS", "Spurious geotags (no target)", INT, DEFAULTS.n_spurious, 0, 5000, True),
    ("RTK_FLOAT_EPISODES", "RTK-float episodes in the pose log", INT, DEFAULTS.rtk_float_episodes, 0, 100, True),
    ("ORTHO_PIXEL_M", "Orthomosaic pixel size (m)", DOUBLE, DEFAULTS.ortho_pixel_m, *ORTHO_PIXEL_RANGE_M, True),
    ("LOOK_ALIKE_DENSITY", "Look-alike density (× the default)", DOUBLE,
     DEFAULTS.look_alike_density, 0.0, 20.0, True),
]
PLATFORM_LABELS = ("RTK INS payload (pose log, altimeter)",
                   "DJI drone (poses in its JPEGs' metadata)")
# The terrain, after the TERRAIN choice (same layout as NUMBERS).
TERRAIN_LABELS = ("Flat (level ground)", "Plane (a uniform slope)", "Hills (the slope plus random hills)")
TERRAIN_NUMBERS = [
    ("SLOPE_DEG", "Terrain slope (deg; plane and hills)", DOUBLE, DEFAULTS.slope_deg, 0.0, 45.0, False),
    ("SLOPE_ASPECT_DEG", "Slope aspect, downhill (deg from north)", DOUBLE,
     DEFAULTS.slope_aspect_deg, 0.0, 360.0, False),
    ("RELIEF_M", "Hill relief, peak to peak (m; hills)", DOUBLE, DEFAULTS.relief_m, 0.0, 50.0, False),
    ("HILL_WAVELENGTH_M", "Hill wavelength (m; hills)", DOUBLE,
     DEFAULTS.hill_wavelength_m, 5.0, 1000.0, True),
]


class SimulateCampaign(BirdsEyeAlgorithm):
    ALG_ID = "simulatecampaign"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("SimulateCampaign", "Simulate a campaign")
    GROUP = "simulate"
    SIGMAS = "SIGMAS"
    NOISE_OFF = "NOISE_OFF"
    RENDER = "RENDER"
    PLATFORM = "PLATFORM"
    TERRAIN = "TERRAIN"
    SIDE_OVERLAP = "SIDE_OVERLAP"
    DJI_DEWARPED = "DJI_DEWARPED"
    GEOID_UNDULATION_M = "GEOID_UNDULATION_M"
    OUTPUT_FOLDER = "OUTPUT_FOLDER"
    DEM = "DEM"
    ORTHOMOSAIC = "ORTHOMOSAIC"
    FRAMES_FOLDER = "FRAMES_FOLDER"
    FRAME_COUNT = "FRAME_COUNT"

    def initAlgorithm(self, config=None):
        for advanced in (False, True):
            for name, label, kind, default, lo, hi, is_advanced in NUMBERS:
                if is_advanced == advanced:
                    number = QgsProcessingParameterNumber(name, self.tr(label), kind, default, minValue=lo, maxValue=hi)
                    if name in ("SITE_LAT", "SITE_LON"):  # degrees of a position: 6 decimals, 0.1 m
                        number.setMetadata({"widget_wrapper": {"decimals": 6}})
                    self._add(number, advanced)
            if not advanced:
                self.addParameter(QgsProcessingParameterString(
                    self.SIGMAS, self.tr("Pose noise Σ0: x, y, z (m), roll, pitch, yaw (deg)"),
                    ",".join(f"{s:g}" for s in DEFAULTS.sigmas)))
                self.addParameter(QgsProcessingParameterBoolean(
                    self.NOISE_OFF, self.tr("Noise off (ideal poses, altimeter and geotags)"), False))
                self.addParameter(QgsProcessingParameterBoolean(
                    self.RENDER, self.tr("Render frames and the orthomosaic"), True))
                self.addParameter(QgsProcessingParameterEnum(
                    self.PLATFORM, self.tr("Platform"), options=[self.tr(t) for t in PLATFORM_LABELS],
                    defaultValue=PLATFORMS.index(DEFAULTS.platform)))
                self.addParameter(QgsProcessingParameterEnum(
                    self.TERRAIN, self.tr("Terrain"), options=[self.tr(t) for t in TERRAIN_LABELS],
                    defaultValue=TERRAIN_KINDS.index(DEFAULTS.terrain)))
            for name, label, kind, default, lo, hi, is_advanced in TERRAIN_NUMBERS:
                if is_advanced == advanced:
                    self._add(QgsProcessingParameterNumber(
                        name, self.tr(label), kind, default, minValue=lo, maxValue=hi), advanced)
        self._add(QgsProcessingParameterNumber(
            self.SIDE_OVERLAP, self.tr("Side overlap (fraction; empty: {ins:g} payload, {dji:g} DJI)").format(
                **DEFAULT_SIDE_OVERLAP),
            DOUBLE, None, optional=True, minValue=0.0, maxValue=0.9), True)
        self._add(QgsProcessingParameterBoolean(
            self.DJI_DEWARPED, self.tr("DJI drone undistorts its JPEGs (DewarpFlag 1)"), DEFAULTS.dji_dewarped), True)
        geoid = QgsProcessingParameterNumber(
            self.GEOID_UNDULATION_M, self.tr("Geoid undulation N for altMSL (m; empty: EGM96)"),
            DOUBLE, None, optional=True, minValue=-120.0, maxValue=120.0)
        self._add(geoid, True)
        self.addParameter(QgsProcessingParameterFolderDestination(self.OUTPUT_FOLDER, self.tr("Output folder")))
        for name, text in (("GEOTAGS", "Geotags (rover CSV)"), ("FIELD", "Field boundary (field.geojson)"),
                           ("POSES", "Pose log (CSV)"),
                           ("IMAGES", "Image list (images.csv)"), ("CALIBRATION", "Calibration (Kalibr YAML)")):
            self.addOutput(QgsProcessingOutputFile(name, self.tr(text)))
        self.addOutput(QgsProcessingOutputRasterLayer(
            self.DEM, self.tr("Terrain model (truth/dem.tif, ellipsoidal heights; none for flat terrain)")))
        self.addOutput(QgsProcessingOutputRasterLayer(
            self.ORTHOMOSAIC, self.tr("Orthomosaic of the field (orthomosaic.tif; none without rendering)")))
        self.addOutput(QgsProcessingOutputFolder(self.FRAMES_FOLDER, self.tr("Frames folder")))
        self.addOutput(QgsProcessingOutputNumber(self.FRAME_COUNT, self.tr("Frames")))

    def _add(self, param, advanced: bool) -> None:
        if advanced:
            param.setFlags(param.flags() | PARAMETER_ADVANCED)
        self.addParameter(param)

    def processAlgorithm(self, parameters, context, feedback):
        values = {name: (self.parameterAsInt if kind == INT else self.parameterAsDouble)(parameters, name, context)
                  for name, _, kind, *_ in NUMBERS + TERRAIN_NUMBERS}
        terrain = TERRAIN_KINDS[self.parameterAsEnum(parameters, self.TERRAIN, context)]
        geoid = parameters.get(self.GEOID_UNDULATION_M)
        side = parameters.get(self.SIDE_OVERLAP)
        platform = PLATFORMS[self.parameterAsEnum(parameters, self.PLATFORM, context)]
        config = CampaignConfig(
            seed=values["SEED"], n_targets=values["N_TARGETS"], field_width_m=values["FIELD_WIDTH_M"],
            field_length_m=values["FIELD_LENGTH_M"], site_lat=values["SITE_LAT"], site_lon=values["SITE_LON"],
            ground_height_m=values["GROUND_HEIGHT_M"], altitude_m=values["ALTITUDE_M"],
            speed_ms=values["SPEED_MS"], fps=values["FPS"], ins_rate_hz=values["INS_RATE_HZ"],
            image_width=values["IMAGE_WIDTH"], image_height=values["IMAGE_HEIGHT"],
            sigmas=self.run_core(parse_sigmas, self.parameterAsString(parameters, self.SIGMAS, context)),
            radalt_sigma_m=values["RADALT_SIGMA_M"], rtk_sigma_m=values["RTK_SIGMA_M"],
            n_missed=values["N_MISSED"], n_spurious=values["N_SPURIOUS"],
            render=self.parameterAsBool(parameters, self.RENDER, context),
            noise_off=self.parameterAsBool(parameters, self.NOISE_OFF, context),
            side_overlap=None if side in (None, "") else self.parameterAsDouble(parameters, self.SIDE_OVERLAP, context),
            rtk_float_episodes=values["RTK_FLOAT_EPISODES"], platform=platform,
            forward_overlap=values["FORWARD_OVERLAP"],
            dji_dewarped=self.parameterAsBool(parameters, self.DJI_DEWARPED, context),
            geoid_undulation_m=None if geoid in (None, "")
            else self.parameterAsDouble(parameters, self.GEOID_UNDULATION_M, context),
            terrain=terrain, slope_deg=values["SLOPE_DEG"], slope_aspect_deg=values["SLOPE_ASPECT_DEG"],
            relief_m=values["RELIEF_M"], hill_wavelength_m=values["HILL_WAVELENGTH_M"],
            ortho_pixel_m=values["ORTHO_PIXEL_M"], look_alike_density=values["LOOK_ALIKE_DENSITY"])
        folder = self.parameterAsString(parameters, self.OUTPUT_FOLDER, context)
        feedback.pushInfo(self.tr("Simulating seed {seed}: {n_targets} targets in a "
                                  "{field_width_m:g} × {field_length_m:g} m field, flown at "
                                  "{altitude_m:g} m, {speed_ms:g} m/s, {fps:g} frames/s.").format(
                              seed=config.seed, n_targets=config.n_targets, field_width_m=config.field_width_m,
                              field_length_m=config.field_length_m, altitude_m=config.altitude_m,
                              speed_ms=config.speed_ms, fps=config.fps))
        if terrain == "flat" and (config.slope_deg or config.relief_m):
            feedback.pushWarning(self.tr("TERRAIN is flat: SLOPE_DEG and RELIEF_M are ignored "
                                         "(choose plane or hills)."))
        elif terrain == "plane" and config.relief_m:
            feedback.pushWarning(self.tr("TERRAIN is a plane: RELIEF_M is ignored (choose hills)."))
        elif terrain != "flat":
            feedback.pushInfo(f"Terrain: {terrain}, {config.slope_deg:g}° slope facing {config.slope_aspect_deg:g}°"
                              + (f", hills of {config.relief_m:g} m every {config.hill_wavelength_m:g} m"
                                 if terrain == "hills" else "") + "; the drone follows it.")
        if platform == "dji":
            feedback.pushInfo(self.tr("A DJI drone: photos on the lines with "
                                      "{forward_overlap:.0%} forward and "
                                      "{effective_side_overlap:.0%} side overlap; the pose in "
                                      "each JPEG's metadata carries heading, tilt and height "
                                      "errors (truth/dji_metadata_errors.csv).").format(
                                  forward_overlap=config.forward_overlap,
                                  effective_side_overlap=config.effective_side_overlap))
        progress, is_canceled = self.progress_callbacks(feedback, 2.0, 100.0)
        result = self.run_core(simulate_campaign, config, folder, progress=progress, is_canceled=is_canceled)
        log = "" if platform == "dji" else f"{result.n_poses} pose rows, "
        feedback.pushInfo(self.tr("Wrote {n_frames} frames, {log}{n_geotags} geotags to {folder}.").format(
                              n_frames=result.n_frames, log=log, n_geotags=result.n_geotags, folder=result.folder))
        return {"OUTPUT_FOLDER": str(result.folder), "GEOTAGS": str(result.files["geotags"]),
                "FIELD": str(result.files["field"]),
                "POSES": str(result.files.get("poses", "")), "IMAGES": str(result.files.get("images", "")),
                "CALIBRATION": str(result.files.get("calibration", "")), self.DEM: str(result.files.get("dem", "")),
                self.ORTHOMOSAIC: str(result.files.get("orthomosaic", "")),
                self.FRAMES_FOLDER: str(result.files.get("frames", "")),
                self.FRAME_COUNT: result.n_frames}
