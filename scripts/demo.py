"""`make demo`: the whole BirdsEye chain on simulated flights, ending in birdseye-demo/birdseye_demo.qgz.

Runs in a standalone QGIS application (no desktop): initialises Processing, registers the BirdsEye
provider and runs the steps of :func:`build_steps` in order through the Processing registry — exactly
what the toolbox, the Graphical Modeler and ``qgis_process`` run:

1. simulate two training flights and one held-out flight, each over its own field — three paddocks
   side by side on one farm — with an orthomosaic of each field (``simulatecampaign``);
2. import each flight's rover geotags and flight log (``importgeotags``, ``importflightlog``);
3. write training labels, with tiles, for the training flights (``writelabels``);
4. detect targets on the held-out flight with the bundled model (``detect``);
5. cluster the detections and score them against the survey (``clusterdetections``,
   ``evaluatedetections``); detect on the held-out field's orthomosaic too (``detectraster``) and compare
   frames and mosaic over the same geotags (``comparedetectors``);
6. plan the next flight over the held-out field's geotags, with its mission files (``planflight``);
7. the sensor bound of the simulated platform's pose noise (``sensorbound``).

Every layer an algorithm writes is loaded into a project, styled by the algorithm's own post-processor
(``layers.style_on_load``, which Processing calls when it loads an output), put in its group (survey,
flight, labels, detections, clusters, plan) and saved with relative paths, so the folder can be moved.
The fields' orthomosaics form the farm map under everything else, with an OpenStreetMap basemap below
them that starts hidden (it needs the internet; the project draws without it). The project opens on
the farm.
The project is then read back and every layer checked valid. A step that fails stops the demo with a
non-zero exit status; a missing algorithm or model is reported before anything runs.

    .venv/bin/python scripts/demo.py [--out birdseye-demo] [--size full|small] [--model FILE.onnx]
"""
from __future__ import annotations

import argparse
import json
import math
import os
import re
import shutil
import sys
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[1]
PLUGIN_PATH = REPO_ROOT / "build" / "pluginpath"
QGIS_PYTHON_PLUGINS = "/usr/share/qgis/python/plugins"
BUNDLED_MODEL = REPO_ROOT / "models" / "birdseye_demo_heatmap.onnx"
PROJECT_NAME = "birdseye_demo.qgz"
SUMMARY_NAME = "demo_summary.json"
GROUP_ORDER = ["survey", "flight", "labels", "detections", "clusters", "plan", "farm map"]
FARM_MAP = "farm map"
# OpenStreetMap's standard tiles as QGIS's own XYZ connection reads them; context when zoomed out.
OSM_SOURCE = "type=xyz&url=https://tile.openstreetmap.org/{z}/{x}/{y}.png&zmin=0&zmax=19"
OSM_NAME = "OpenStreetMap (web)"
OSM_RIGHTS = "© OpenStreetMap contributors, ODbL (https://www.openstreetmap.org/copyright)"

SIGMAS = "0.01,0.01,0.06,0.04,0.04,0.13"  # the deployed platform's pose noise Σ0 (m, m, m, °, °, °)
ALTITUDE_M = 10.0  # flying height of the simulated flights and of the sensor bound (m above ground)
HELD_OUT_ORTHO_PIXEL_M = 0.005  # the held-out field's orthomosaic: finer than the bundled model's 1 cm/px


@dataclass(frozen=True)
class Flight:
    """One simulated flight: ``key`` names its files and steps, ``title`` the progress lines and summary,
    ``tag`` its layers ("Frames · training 1")."""

    key: str
    title: str
    tag: str
    seed: int
    training: bool
    field_offset: int  # fields lie side by side, this many field spacings east of the first (a farm's paddocks)


@dataclass(frozen=True)
class DemoSize:
    """How big the simulated flights are. ``full`` matches the bundled model's training flights
    (8 m × 6 m fields with 20 burrows, 1920 × 1200 frames at 10 m); ``small`` is a quick check."""

    n_targets: int
    field_width_m: float
    field_length_m: float
    image_width: int
    image_height: int
    training_fps: float
    held_out_fps: float
    tile_size: int
    field_spacing_m: float  # between neighbouring fields' centres, east–west


# Each field's simulated ground (every point its frames see: the field, the flight's run-outs and
# turns) is 21.5 m east–west at full size and 13.3 m small; the spacings leave a 2.5 m and a 1.7 m
# track between neighbouring paddocks, so no flight overlaps another's field.
SIZES = {
    "full": DemoSize(20, 8.0, 6.0, 1920, 1200, 5.0, 5.0, 448, 24.0),
    "small": DemoSize(6, 4.0, 3.0, 480, 300, 1.0, 2.0, 112, 15.0),
}
FLIGHTS = [
    Flight("train1", "training flight 1", "training 1", 11, True, 0),
    Flight("train2", "training flight 2", "training 2", 12, True, 1),
    Flight("heldout", "held-out flight", "held-out", 13, False, 2),
]
# What a loaded layer is called, "<kind> · <tag>": the kind first and short, so the Layers panel shows the whole
# name (or at least the part that tells two layers apart) at its default width; the algorithms' own output
# names are longer ("Frames with label counts").
LAYER_KINDS = {
    ("importgeotags", "OUTPUT"): "Geotags",
    ("importflightlog", "OUTPUT"): "Frames",
    ("importflightlog", "OUTPUT_TRACK"): "Flight line",
    ("writelabels", "OUTPUT_FRAMES"): "Labels",
    ("writelabels", "OUTPUT_GEOTAGS"): "Sightings",
    ("detect", "OUTPUT"): "Detections",
    ("clusterdetections", "OUTPUT"): "Clusters",
    ("clusterdetections", "OUTPUT_POINTS"): "Points",
    ("planflight", "OUTPUT_WAYPOINTS"): "Waypoints",
    ("planflight", "OUTPUT_ROUTE"): "Route",
    ("comparedetectors", "OUTPUT"): "Changes",
    ("partitionfield", "OUTPUT"): "Partitions",
}
# Warnings the simulation causes on purpose: (a regular expression matching the start of the message, why it is
# expected). The demo prints them as notes saying why; any other warning stays a warning.
SIMULATED_RTK_FLOAT = (r"\d+ frame\(s\) have no RTK fixed solution",
                       "the simulator puts an RTK-float episode into every flight")
SIMULATED_ALTIMETER_DROPOUT = (r"\d+ frame\(s\) had an altimeter reading below SNR",
                               "the simulated radar altimeter has a low-SNR burst about once a minute")
FLIGHT_LOG_EXPECTED = (SIMULATED_RTK_FLOAT, SIMULATED_ALTIMETER_DROPOUT)
PLAN_EXPECTED = (
    (r"the camera footprint at \S+ m keeps geotags in view",
     "the demo flies at 10 m, where a frame keeps less than the default 2 m around a waypoint in view"),
    (r"no HOME given", "the demo plans without a take-off point"),
)
SITE_LAT, SITE_LON = -27.55, 151.95


def field_longitude(offset_m: float) -> float:
    """Longitude of the point ``offset_m`` east of the site on its parallel (WGS84: a degree of
    longitude is (π/180)·N·cos φ, N the prime vertical radius of curvature)."""
    a, e2 = 6378137.0, 6.69437999014e-3
    phi = math.radians(SITE_LAT)
    prime_vertical = a / math.sqrt(1.0 - e2 * math.sin(phi) ** 2)
    return SITE_LON + math.degrees(offset_m / (prime_vertical * math.cos(phi)))


@dataclass(frozen=True)
class Step:
    """One algorithm run: ``birdseye:<alg_id>`` with ``params``; its layers go into ``group``.

    ``name`` is how later steps refer to this step's outputs, e.g. ``"{campaign_heldout[CALIBRATION]}"``;
    ``{out}`` is the demo folder. Loaded layers are named "<kind> · <tag>", the kind from ``kinds`` (output
    name → kind), else :data:`LAYER_KINDS`, else the output's description; the outputs named in ``hidden``
    start unticked in the Layers panel (they repeat what other layers show), those in ``legend`` with their
    legend open (what the map opens on needs reading). ``maps`` names outputs that are files rather than layer
    destinations, with their kinds, to load as rasters into ``map_group``.
    ``expected`` lists the warnings the step gives on purpose (:data:`FLIGHT_LOG_EXPECTED`).
    """

    name: str
    alg_id: str
    title: str
    params: dict = field(default_factory=dict)
    group: str | None = None
    tag: str = ""
    kinds: dict = field(default_factory=dict)
    hidden: tuple = ()
    legend: tuple = ()
    maps: tuple = ()
    map_group: str | None = None
    expected: tuple = ()

    def layer_name(self, output: str, description: str) -> str:
        kind = self.kinds.get(output) or LAYER_KINDS.get((self.alg_id, output)) or description
        return f"{kind} · {self.tag}" if self.tag else kind


def build_steps(size: DemoSize, model: Path | None) -> list[Step]:
    """The chain, in order (see the module docstring)."""
    held_out = next(f for f in FLIGHTS if not f.training)
    steps = []
    for flight in FLIGHTS:
        steps.append(Step(f"campaign_{flight.key}", "simulatecampaign", f"Simulate the {flight.title}", {
            "SEED": flight.seed, "N_TARGETS": size.n_targets, "FIELD_WIDTH_M": size.field_width_m,
            "FIELD_LENGTH_M": size.field_length_m, "ALTITUDE_M": ALTITUDE_M, "SPEED_MS": 2.5,
            "FPS": size.training_fps if flight.training else size.held_out_fps,
            "IMAGE_WIDTH": size.image_width, "IMAGE_HEIGHT": size.image_height, "SIGMAS": SIGMAS,
            "SITE_LAT": SITE_LAT, "SITE_LON": field_longitude(flight.field_offset * size.field_spacing_m),
            "OUTPUT_FOLDER": f"{{out}}/campaigns/{flight.key}",
            # The held-out field's map finer than the model's resolution, as the frames are: detection on
            # the mosaic is then compared with detection on the frames at one resolution.
            **({} if flight.training else {"ORTHO_PIXEL_M": HELD_OUT_ORTHO_PIXEL_M})},
            tag=flight.tag, maps=(("ORTHOMOSAIC", "Mosaic"),), map_group=FARM_MAP))
    for flight in FLIGHTS:
        campaign = f"campaign_{flight.key}"
        steps.append(Step(f"geotags_{flight.key}", "importgeotags", f"Import the geotags of the {flight.title}", {
            "INPUT": f"{{{campaign}[GEOTAGS]}}", "OUTPUT": f"{{out}}/survey/geotags_{flight.key}.gpkg"},
            group="survey", tag=flight.tag, legend=() if flight.training else ("OUTPUT",)))
        steps.append(Step(f"flight_{flight.key}", "importflightlog", f"Import the {flight.title}'s log", {
            "POSE_LOG": f"{{{campaign}[POSES]}}", "IMAGES": f"{{{campaign}[OUTPUT_FOLDER]}}",
            "CALIBRATION": f"{{{campaign}[CALIBRATION]}}",
            "FPS": size.training_fps if flight.training else size.held_out_fps,
            "OUTPUT": f"{{out}}/flight/frames_{flight.key}.gpkg",
            "OUTPUT_TRACK": f"{{out}}/flight/track_{flight.key}.gpkg"}, group="flight", tag=flight.tag,
            hidden=("OUTPUT",) if flight.training else (),  # the map shows the held-out flight's frames
            expected=FLIGHT_LOG_EXPECTED))
    for flight in FLIGHTS:
        if flight.training:
            steps.append(Step(f"labels_{flight.key}", "writelabels", f"Write labels for the {flight.title}", {
                "GEOTAGS": f"{{geotags_{flight.key}[OUTPUT]}}", "FRAMES": f"{{flight_{flight.key}[OUTPUT]}}",
                "SIGMA_PX": 10.0, "EDGE_BUFFER_PX": 20.0, "WRITE_TILES": True, "TILE_SIZE": size.tile_size,
                "NEGATIVE_RATIO": 1.5, "OUTPUT_FOLDER": f"{{out}}/labels/{flight.key}",
                "OUTPUT_FRAMES": f"{{out}}/labels/frames_labelled_{flight.key}.gpkg",
                "OUTPUT_GEOTAGS": f"{{out}}/labels/geotags_seen_{flight.key}.gpkg"},
                group="labels", tag=flight.tag, hidden=("OUTPUT_FRAMES", "OUTPUT_GEOTAGS")))
    h = held_out.key
    steps += [
        Step("partitions", "partitionfield", f"Partition the {held_out.title}'s field for two people", {
            "AREA": f"{{campaign_{h}[FIELD]}}", "N_PEOPLE": 2, "OUTPUT": "{out}/survey/partitions.gpkg"},
            group="survey", tag=held_out.tag),
        Step("field_package", "preparefieldsurvey", f"Prepare the next walk over the {held_out.title} (QField)", {
            "OUTPUT_FOLDER": "{out}/field_survey", "PROJECT_NAME": "next_walk", "CLASSES": "burrow",
            "GEOTAGS": f"{{geotags_{h}[OUTPUT]}}", "AREA": "{partitions[OUTPUT]}",
            "BACKGROUND": f"{{campaign_{h}[ORTHOMOSAIC]}}"}),
    ]
    detect = {"FRAMES": f"{{flight_{h}[OUTPUT]}}", "OUTPUT": "{out}/detections/detections.gpkg"}
    mosaic = {"RASTER": f"{{campaign_{h}[ORTHOMOSAIC]}}", "OUTPUT": "{out}/detections/detections_mosaic.gpkg"}
    if model is not None:
        detect["MODEL"] = mosaic["MODEL"] = str(model)
    steps += [
        Step("detect", "detect", f"Detect targets on the {held_out.title}", detect, group="detections",
             tag=held_out.tag, legend=("OUTPUT",)),
        Step("clusters", "clusterdetections", "Cluster the detections", {
            "DETECTIONS": "{detect[OUTPUT]}", "GEOTAGS": f"{{geotags_{h}[OUTPUT]}}",
            "FRAMES": f"{{flight_{h}[OUTPUT]}}", "OUTPUT": "{out}/clusters/clusters.gpkg",
            "OUTPUT_POINTS": "{out}/clusters/cluster_points.gpkg"}, group="clusters", tag=held_out.tag,
            hidden=("OUTPUT_POINTS",), legend=("OUTPUT",)),
        Step("evaluation", "evaluatedetections", "Evaluate recall and GMCF against the survey", {
            "DETECTIONS": ["{detect[OUTPUT]}"], "GEOTAGS": f"{{geotags_{h}[OUTPUT]}}",
            "FRAMES": [f"{{flight_{h}[OUTPUT]}}"], "OUTPUT_JSON": "{out}/evaluation.json",
            "OUTPUT_REPORT": "{out}/evaluation.html"}),
        Step("detect_mosaic", "detectraster", f"Detect targets on the {held_out.title}'s orthomosaic", mosaic,
             group="detections", tag=held_out.tag, kinds={"OUTPUT": "On mosaic"}, hidden=("OUTPUT",)),
        Step("mosaic_vs_frames", "comparedetectors", "Compare detection on the frames and on the mosaic", {
            "DETECTIONS_OLD": "{detect[OUTPUT]}", "DETECTIONS_NEW": "{detect_mosaic[OUTPUT]}",
            "FRAMES": f"{{flight_{h}[OUTPUT]}}", "GEOTAGS": f"{{geotags_{h}[OUTPUT]}}",
            "OUTPUT": "{out}/detections/mosaic_changes.gpkg", "OUTPUT_JSON": "{out}/frames_vs_mosaic.json",
            "OUTPUT_REPORT": "{out}/frames_vs_mosaic.html"}, group="detections", tag=held_out.tag,
            kinds={"OUTPUT": "Mosaic diff"}, hidden=("OUTPUT",)),
        Step("plan", "planflight", f"Plan the next flight over the {held_out.title}'s geotags", {
            "GEOTAGS": f"{{geotags_{h}[OUTPUT]}}", "CAMERA": f"{{campaign_{h}[CALIBRATION]}}",
            "ALTITUDE_M": ALTITUDE_M, "OUTPUT_WAYPOINTS": "{out}/plan/waypoints.gpkg",
            "OUTPUT_ROUTE": "{out}/plan/route.gpkg", "OUTPUT_KMZ": "{out}/plan/mission.kmz",
            "OUTPUT_PLAN": "{out}/plan/mission.plan", "OUTPUT_LITCHI": "{out}/plan/mission_litchi.csv",
            "OUTPUT_KML": "{out}/plan/mission.kml"}, group="plan", tag="next flight", expected=PLAN_EXPECTED),
        Step("bound", "sensorbound", "Sensor bound for the simulated platform", {
            "CALIBRATION": f"{{campaign_{h}[CALIBRATION]}}", "ALTITUDES": f"{ALTITUDE_M:g}", "SIGMAS": SIGMAS,
            "OUTPUT_JSON": "{out}/sensor_bound.json", "OUTPUT_REPORT": "{out}/sensor_bound.html"}),
    ]
    return steps


class DemoError(RuntimeError):
    """A step failed or the demo cannot run; the message says which and why."""


def resolve(value, values: dict):
    """A parameter value with ``{out}`` and ``{step[OUTPUT]}`` filled in (lists element-wise)."""
    if isinstance(value, list):
        return [resolve(v, values) for v in value]
    if not isinstance(value, str) or "{" not in value:
        return value
    try:
        return value.format_map(values)
    except KeyError as exc:
        raise DemoError(f"a parameter refers to the outputs of step '{exc.args[0]}', which did not run") from None


# ------------------------------------------------------------------------------------------ terminal
class TerminalFeedback:
    """Factory for a QgsProcessingFeedback that draws a progress bar and prints messages, indented."""

    @staticmethod
    def create(expected=()):
        """``expected``: (regular expression, reason) of warnings the step gives on purpose; a warning whose
        start matches one is printed as a note with its reason, every other one as a warning."""
        from qgis.core import QgsProcessingFeedback

        class Feedback(QgsProcessingFeedback):
            def __init__(self):
                super().__init__()
                self.live = sys.stdout.isatty()
                self.last_shown = -10
                self.errors: list[str] = []
                self.expected = [(re.compile(pattern), reason) for pattern, reason in expected]
                self.progressChanged.connect(self.show_progress)

            def show_progress(self, percent: float) -> None:
                if self.live:
                    filled = int(percent / 100 * 30)
                    print(f"\r    [{'#' * filled}{'.' * (30 - filled)}] {percent:5.1f} %", end="", flush=True)
                elif percent >= self.last_shown + 25:
                    self.last_shown = percent - percent % 25
                    print(f"    {self.last_shown:.0f} %", flush=True)

            def end_line(self) -> None:
                if self.live:
                    print("\r" + " " * 48 + "\r", end="", flush=True)

            def pushInfo(self, info):
                if info.startswith("Results: "):  # processing.run's raw dict; the summary has the numbers
                    return
                self.end_line()
                print(f"    {info}", flush=True)

            def pushWarning(self, warning):
                self.end_line()
                reason = next((why for pattern, why in self.expected if pattern.match(warning)), None)
                if reason is None:
                    print(f"    warning: {warning}", flush=True)
                else:
                    print(f"    note: {warning} (expected: {reason})", flush=True)

            def reportError(self, error, fatalError=False):
                self.end_line()
                self.errors.append(error)
                print(f"    error: {error}", flush=True)

        return Feedback()


# ------------------------------------------------------------------------------------------ QGIS
def start_qgis():
    """A headless QgsApplication with Processing and the BirdsEye provider, settings kept in build/."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    os.environ["QGIS_CUSTOM_CONFIG_PATH"] = str(REPO_ROOT / "build" / "qgis-demo")
    PLUGIN_PATH.mkdir(parents=True, exist_ok=True)
    link = PLUGIN_PATH / "birdseye"
    if not link.is_symlink():
        link.symlink_to(REPO_ROOT, target_is_directory=True)
    # Our processing/ must never shadow QGIS's: the plugin is imported as `birdseye` via the link.
    sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != REPO_ROOT]
    sys.path[:0] = [str(PLUGIN_PATH), QGIS_PYTHON_PLUGINS]

    from qgis.core import QgsApplication

    QgsApplication.setPrefixPath("/usr", True)
    app = QgsApplication([], False)
    app.initQgis()
    from processing.core.Processing import Processing

    Processing.initialize()
    # The venv's matplotlib sees Debian's older mpl_toolkits and warns that 3-D plots are unavailable; the
    # reports draw 2-D plots only. Set after QGIS's start-up, whose qgis.utils puts a "default" filter first.
    warnings.filterwarnings("ignore", message="Unable to import Axes3D")
    from birdseye.processing.provider import BirdsEyeProvider

    provider = BirdsEyeProvider()
    QgsApplication.processingRegistry().addProvider(provider)
    return app, provider


def preflight(steps: list[Step], model: Path | None) -> None:
    """Everything the chain needs is there before minutes are spent simulating: each algorithm,
    each parameter name the demo passes, and the detector model."""
    from qgis.core import QgsApplication

    registry = QgsApplication.processingRegistry()
    problems = []
    for step in steps:
        algorithm = registry.algorithmById(f"birdseye:{step.alg_id}")
        if algorithm is None:
            problems.append(f"algorithm birdseye:{step.alg_id} is not registered (a module of "
                            "processing/algorithms failed to import? see the QGIS log)")
            continue
        unknown = sorted(set(step.params) - {p.name() for p in algorithm.parameterDefinitions()})
        if unknown:
            problems.append(f"step '{step.title}': birdseye:{step.alg_id} has no parameter(s) {', '.join(unknown)}")
    chosen = model or BUNDLED_MODEL
    if not chosen.is_file():
        problems.append(
            f"the detector model {chosen} is missing, so the held-out flight cannot be detected, clustered or "
            "evaluated. " + ("It is part of the plugin; rebuild it with `.venv/bin/python training/train_heatmap.py "
                             "demo` or run the demo with --model FILE.onnx." if model is None else ""))
    if problems:
        raise DemoError("the demo cannot run:\n  - " + "\n  - ".join(problems))


def layer_destinations(algorithm) -> set[str]:
    """Names of the parameters whose output is a map layer (those get loaded into the project)."""
    from qgis.core import (
        QgsProcessingParameterFeatureSink,
        QgsProcessingParameterRasterDestination,
        QgsProcessingParameterVectorDestination,
    )

    kinds = (QgsProcessingParameterFeatureSink, QgsProcessingParameterRasterDestination,
             QgsProcessingParameterVectorDestination)
    return {p.name() for p in algorithm.destinationParameterDefinitions() if isinstance(p, kinds)}


def run_step(step: Step, values: dict, project) -> tuple[dict, list]:
    """Run one step; returns (results, [(loaded and styled layer, hidden?, legend open?)]). Raises DemoError
    when it fails."""
    import processing
    from qgis.core import (
        QgsApplication,
        QgsProcessingContext,
        QgsProcessingException,
        QgsProcessingOutputLayerDefinition,
        QgsProcessingUtils,
    )

    algorithm = QgsApplication.processingRegistry().algorithmById(f"birdseye:{step.alg_id}")
    params = {name: resolve(value, values) for name, value in step.params.items()}
    to_load = layer_destinations(algorithm)
    for definition in algorithm.destinationParameterDefinitions():
        value = params.get(definition.name())
        if isinstance(value, str) and value:
            Path(value).parent.mkdir(parents=True, exist_ok=True)
            if definition.name() in to_load:
                # Loaded on completion, into this project: Processing then runs the algorithm's
                # post-processor, which applies its .qml style (layers.style_on_load).
                params[definition.name()] = QgsProcessingOutputLayerDefinition(value, project)

    context = QgsProcessingContext()
    context.setProject(project)
    feedback = TerminalFeedback.create(step.expected)
    try:
        # onFinish that does nothing: keep results as paths; the layers are loaded below.
        results = processing.run(algorithm, params, onFinish=lambda *_: None, feedback=feedback,
                                 context=context)
    except QgsProcessingException as exc:
        feedback.end_line()
        detail = "; ".join(feedback.errors[-3:]) or str(exc)
        raise DemoError(f"step '{step.title}' (birdseye:{step.alg_id}) failed: {detail}") from None
    feedback.end_line()

    layers = []
    for layer_ref, details in context.layersToLoadOnCompletion().items():
        layer = QgsProcessingUtils.mapLayerFromString(layer_ref, context)
        if layer is None or not layer.isValid():
            raise DemoError(f"step '{step.title}': its output {layer_ref} cannot be opened as a layer")
        context.temporaryLayerStore().takeMapLayer(layer)
        post_processor = details.postProcessor()
        if post_processor is not None:
            post_processor.postProcessLayer(layer, context, feedback)
        layer.setName(step.layer_name(details.outputName, details.name or layer.name()))
        layers.append((layer, details.outputName in step.hidden, details.outputName in step.legend))
    return dict(results), layers


def load_maps(step: Step, results: dict) -> list:
    """The rasters ``step.maps`` names, as (layer, hidden, legend open) triples. Raises DemoError when one cannot
    be opened."""
    from qgis.core import QgsRasterLayer

    layers = []
    for output, kind in step.maps:
        path = results.get(output) or ""
        layer = QgsRasterLayer(path, step.layer_name(output, kind))
        if not layer.isValid():
            raise DemoError(f"step '{step.title}': its output {output} ({path or 'not written'}) cannot be opened "
                            "as a raster layer")
        layers.append((layer, False, False))
    return layers


def osm_basemap():
    """OpenStreetMap as an XYZ tile layer, hidden: the project must draw offline."""
    from qgis.core import QgsRasterLayer

    layer = QgsRasterLayer(OSM_SOURCE, OSM_NAME, "wms")
    if not layer.isValid():
        raise DemoError(f"QGIS cannot make an XYZ tile layer of {OSM_SOURCE}")
    metadata = layer.metadata()
    metadata.setRights([OSM_RIGHTS])
    metadata.setAbstract("Online map tiles for context around the farm; not needed to draw the project.")
    layer.setMetadata(metadata)
    return layer, True, False


def draw_rank(layer) -> int:
    """Points over lines over polygons over the farm's maps over an online basemap, so nothing hides the
    survey points."""
    from birdseye.birdseye_qgis.qgis_enums import GEOMETRY_LINE, GEOMETRY_POINT, LAYER_VECTOR

    if layer.type() != LAYER_VECTOR:
        return 4 if layer.providerType() == "wms" else 3
    return {GEOMETRY_POINT: 0, GEOMETRY_LINE: 1}.get(layer.geometryType(), 2)


def add_to_group(project, group_name: str | None, layers: list[tuple], order=GROUP_ORDER) -> None:
    """Add (layer, hidden, legend open) triples under their group (``order``: the groups in workflow order),
    points first; hidden ones start unticked, the others as one line in the Layers panel unless their legend
    starts open."""
    root = project.layerTreeRoot()
    target = root
    if group_name:
        target = root.findGroup(group_name)
        if target is None:  # keep the groups in workflow order whatever order they are filled in
            position = sum(1 for g in order[:order.index(group_name)] if root.findGroup(g))
            target = root.insertGroup(position, group_name)
    for layer, hidden, legend in sorted(layers, key=lambda entry: draw_rank(entry[0])):
        project.addMapLayer(layer, False)
        node = target.addLayer(layer)
        node.setExpanded(legend)
        node.setItemVisibilityChecked(not hidden)


def finish_project(project, farm_layers: list, order=GROUP_ORDER, on_top=("survey", "plan")) -> None:
    """Drawing order points > lines > polygons > maps whatever the group; within each, the groups ``on_top``
    first (the survey, whose hollow rings keep the waypoints and detections on a geotag visible, then the plan),
    then later steps over earlier ones (clusters over frames). The project opens on the farm (``farm_layers``:
    its fields' maps)."""
    from qgis.core import QgsRectangle, QgsReferencedRectangle

    root = project.layerTreeRoot()
    position = {name: k - len(order) - len(on_top) for k, name in enumerate(on_top)}
    position.update({name: -k for k, name in enumerate(order) if name not in on_top})
    ordered = sorted(root.layerOrder(), key=lambda layer: (
        draw_rank(layer), position.get(root.findLayer(layer.id()).parent().name(), 1)))
    root.setHasCustomLayerOrder(True)
    root.setCustomLayerOrder(ordered)
    for group in root.findGroups():  # a group of unticked layers is one line until someone opens it
        group.setExpanded(any(node.itemVisibilityChecked() for node in group.findLayers()))
    extent = QgsRectangle()  # null on 3.22 and later: the first combine takes that extent (no setMinimal)
    for layer in farm_layers:
        extent.combineExtentWith(layer.extent())
    if not extent.isEmpty():
        project.viewSettings().setDefaultViewExtent(QgsReferencedRectangle(extent.buffered(2.0), project.crs()))
    project.writeEntryBool("Paths", "/Absolute", False)  # the demo folder can be moved


def check_saved_project(project_path: Path) -> list[str]:
    """Read the saved project back in a fresh QgsProject; the names of layers that are not valid."""
    from qgis.core import QgsProject

    reread = QgsProject()
    if not reread.read(str(project_path)):
        return [f"(the project itself: {reread.error()})"]
    return [layer.name() for layer in reread.mapLayers().values() if not layer.isValid()]


# ------------------------------------------------------------------------------------------ summary
def figures(values: dict, out: Path, project, model: Path | None) -> dict:
    """The key figures of the run, for the summary screen and demo_summary.json."""
    def get(step, key, default=None):
        return values.get(step, {}).get(key, default)

    bound = json.loads((out / "sensor_bound.json").read_text(encoding="utf-8"))
    held_out = next(f for f in FLIGHTS if not f.training)
    maps = {f.key: json.loads((out / "campaigns" / f.key / "truth" / "campaign.json").read_text(encoding="utf-8"))
            ["orthomosaic"] for f in FLIGHTS}
    return {
        "frames": {f.key: get(f"flight_{f.key}", "FRAME_COUNT") for f in FLIGHTS},
        "orthomosaics": {key: {k: m[k] for k in ("pixel_m", "size_px", "extent")} for key, m in maps.items()},
        "geotags": {f.key: get(f"geotags_{f.key}", "GEOTAG_COUNT") for f in FLIGHTS},
        "labels": {f.key: get(f"labels_{f.key}", "LABEL_COUNT") for f in FLIGHTS if f.training},
        "frames_with_labels": {f.key: get(f"labels_{f.key}", "FRAMES_WITH_LABELS") for f in FLIGHTS if f.training},
        "held_out": held_out.title,
        "detections": get("detect", "DETECTION_COUNT"),
        "frames_detected": get("detect", "FRAMES_PROCESSED"),
        "threshold": get("detect", "THRESHOLD_USED"),
        "model": (model or BUNDLED_MODEL).name,
        "model_digest": get("detect", "MODEL_DIGEST"),
        "clusters": get("clusters", "CLUSTER_COUNT"),
        "hit_clusters": get("clusters", "HIT_COUNT"),
        "n_in_view": get("evaluation", "N_IN_VIEW"),
        "n_recovered": get("evaluation", "N_RECOVERED"),
        "recall_pre": get("evaluation", "RECALL_PRE"),
        "gmcf_pre": get("evaluation", "GMCF_PRE"),
        "eval_clusters": get("evaluation", "N_CLUSTERS"),
        "eval_hit_clusters": get("evaluation", "N_HIT_CLUSTERS"),
        "mosaic_detections": get("detect_mosaic", "DETECTION_COUNT"),
        "frames_vs_mosaic": {"recall_pre": [get("mosaic_vs_frames", "RECALL_PRE_OLD"),
                                            get("mosaic_vs_frames", "RECALL_PRE_NEW")],
                             "gmcf_pre": [get("mosaic_vs_frames", "GMCF_PRE_OLD"),
                                          get("mosaic_vs_frames", "GMCF_PRE_NEW")]},
        "partitions": get("partitions", "PIECES"),
        "field_package": get("field_package", "PROJECT"),
        "waypoints": get("plan", "WAYPOINT_COUNT"),
        "route_length_m": get("plan", "ROUTE_LENGTH_M"),
        "flight_time_min": get("plan", "FLIGHT_TIME_MIN"),
        "mission_files": [Path(p).name for p in (get("plan", "MISSION_FILES") or "").split(";") if p],
        "sensor_bound": [{k: a[k] for k in ("altitude_m", "kappa_trace", "verdict_trace", "kappa_exact",
                                            "verdict_exact")} for a in bound["altitudes"]],
        "layers": {group.name(): [layer.name() for layer in group.findLayers()]
                   for group in project.layerTreeRoot().findGroups()},
    }


def fmt(value, digits: int = 3) -> str:
    if value is None:
        return "undefined"
    return f"{value:.{digits}f}" if isinstance(value, float) else str(value)


def summary(shown_out: str, numbers: dict, timings: list, elapsed: float) -> str:
    """The one-screen summary (at most 100 columns): what was made, where, and the key figures."""
    f = numbers
    slowest = max(timings, key=lambda t: t[1])
    n_layers = sum(len(names) for names in f["layers"].values())
    lines = [
        "", "=" * 78,
        f" BirdsEye demo finished in {elapsed / 60:.1f} min ({len(timings)} steps; slowest: {slowest[1]:.0f} s, "
        f"{slowest[0].lower()})",
        f" Everything is in {shown_out}/",
        "-" * 78,
        *[f" {'Simulated' if k == 0 else '':11} {fl.title:<18} {f['frames'][fl.key]:>4} frames, "
          f"{f['geotags'][fl.key]:>3} geotags → campaigns/{fl.key}/" for k, fl in enumerate(FLIGHTS)],
        f" Farm map    {len(f['orthomosaics'])} fields side by side, orthomosaics at "
        f"{100 * min(m['pixel_m'] for m in f['orthomosaics'].values()):g} cm/px; OpenStreetMap below (hidden)",
        f" Labels      {sum(f['labels'].values())} labels in {sum(f['frames_with_labels'].values())} frames of the "
        "training flights, with tiles → labels/",
        f" Detections  {f['detections']} in {f['frames_detected']} held-out frames ({f['model']}, "
        f"threshold {fmt(f['threshold'], 2)})",
        f" Clusters    {f['clusters']}, of which {f['hit_clusters']} on a geotag → clusters/",
        f" Evaluation  recall_pre {f['n_recovered']}/{f['n_in_view']} = {fmt(f['recall_pre'])}, "
        f"gmcf_pre {f['eval_hit_clusters']}/{f['eval_clusters']} = {fmt(f['gmcf_pre'])} → evaluation.html",
        f" Mosaic      {f['mosaic_detections']} detections on the held-out orthomosaic → frames_vs_mosaic.html",
        f"             frames | mosaic: recall_pre {fmt(f['frames_vs_mosaic']['recall_pre'][0])} | "
        f"{fmt(f['frames_vs_mosaic']['recall_pre'][1])}, gmcf_pre {fmt(f['frames_vs_mosaic']['gmcf_pre'][0])} | "
        f"{fmt(f['frames_vs_mosaic']['gmcf_pre'][1])}",
        f" Next walk   {f['partitions']} partitions for 2 people; QField package → "
        f"{Path(f['field_package']).parent.name}/{Path(f['field_package']).name}",
        f" Next flight {f['waypoints']} waypoints over the held-out geotags, route {f['route_length_m']:.1f} m, "
        f"{f['flight_time_min']:.1f} min → plan/",
    ]
    for entry in f["sensor_bound"]:
        lines.append(f" Sensor bound at {entry['altitude_m']:g} m: trace κ* {entry['kappa_trace']:.2f} "
                     f"{entry['verdict_trace']}, exact κ* {entry['kappa_exact']:.2f} {entry['verdict_exact']} "
                     "→ sensor_bound.html")
    lines += [
        "-" * 78,
        f" Project     {shown_out}/{PROJECT_NAME}: {n_layers} layers, styled, in {len(f['layers'])} groups",
        f"             {', '.join(f['layers'])}",
        f" Open it     qgis {shown_out}/{PROJECT_NAME}",
        "=" * 78,
    ]
    return "\n".join(lines)


def prepare_folder(out: Path, project_name: str = PROJECT_NAME, summary_name: str = SUMMARY_NAME,
                   kind: str = "demo") -> None:
    """An empty folder for a demo of ``kind``; a previous one there (its project, summary or campaigns)
    is replaced, anything else is left alone."""
    if out.exists():
        previous_demo = (out / project_name).exists() or (out / summary_name).exists() or (out / "campaigns").is_dir()
        if any(out.iterdir()) and not previous_demo:
            raise DemoError(f"{out} exists and is not a BirdsEye {kind} folder; choose another --out")
        print(f"Removing the previous {kind} in {out}/")
        shutil.rmtree(out)
    out.mkdir(parents=True)


def run(out: Path, size: DemoSize, model: Path | None) -> int:
    started = time.monotonic()
    app, _provider = start_qgis()
    from qgis.core import QgsProject

    steps = build_steps(size, model)
    try:
        preflight(steps, model)
        prepare_folder(out)
        project = QgsProject.instance()
        project.clear()
        project.setTitle("BirdsEye demo")
        values = {"out": str(out)}
        timings, farm_layers = [], []
        for number, step in enumerate(steps, 1):
            print(f"[{number}/{len(steps)}] {step.title} (birdseye:{step.alg_id})", flush=True)
            step_start = time.monotonic()
            results, layers = run_step(step, values, project)
            maps = load_maps(step, results)
            seconds = time.monotonic() - step_start
            values[step.name] = results
            add_to_group(project, step.group, layers)
            add_to_group(project, step.map_group, maps)
            if (layers or maps) and not project.crs().isValid():
                project.setCrs((layers or maps)[0][0].crs())
            farm_layers += [layer for layer, *_ in maps]
            timings.append((step.title, seconds))
            print(f"    done in {seconds:.1f} s", flush=True)

        add_to_group(project, FARM_MAP, [osm_basemap()])
        finish_project(project, farm_layers)
        project_path = out / PROJECT_NAME
        if not project.write(str(project_path)):
            raise DemoError(f"could not write {project_path}: {project.error()}")
        invalid = check_saved_project(project_path)
        if invalid:
            raise DemoError(f"{project_path} opens with invalid layers: {', '.join(invalid)}")
        numbers = figures(values, out, project, model)
        numbers["seconds"] = round(time.monotonic() - started, 1)
        numbers["steps"] = [{"title": t, "seconds": round(s, 1)} for t, s in timings]
        (out / SUMMARY_NAME).write_text(json.dumps(numbers, indent=2) + "\n", encoding="utf-8")
        shown = os.path.relpath(out) if not os.path.relpath(out).startswith("..") else str(out)
        print(summary(shown, numbers, timings, time.monotonic() - started))
        status = 0
    except DemoError as exc:
        print(f"\nBirdsEye demo FAILED: {exc}", file=sys.stderr, flush=True)
        status = 1
    QgsProject.instance().clear()
    app.exitQgis()
    return status


def main() -> int:
    parser = argparse.ArgumentParser(description="Run the BirdsEye chain on simulated flights.")
    parser.add_argument("--out", type=Path, default=Path("birdseye-demo"), help="output folder (default birdseye-demo)")
    parser.add_argument("--size", choices=sorted(SIZES), default="full",
                        help="full: flights like the bundled model's training flights; small: a quick check")
    parser.add_argument("--model", type=Path, default=None,
                        help="ONNX heatmap model for the detection step (default: the bundled demo model)")
    args = parser.parse_args()
    model = args.model.resolve() if args.model else None
    return run(args.out.resolve(), SIZES[args.size], model)


if __name__ == "__main__":
    sys.exit(main())
