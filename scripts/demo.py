"""`make demo`: the BirdsEye chain on a simulated campaign, ending in birdseye-demo/birdseye_demo.qgz.

Runs in a standalone QGIS application (no desktop): initialises Processing, registers the BirdsEye
provider and runs :data:`STEPS` in order through the Processing registry — exactly what the toolbox
and ``qgis_process`` run. Every layer an algorithm writes is loaded into a project, styled by the
algorithm itself, under the step's layer-tree group, and the project is saved beside the outputs.

A step is one declarative :class:`Step` entry. Its parameter values may refer to the demo folder
(``{out}``) and to earlier steps' outputs (``{campaign[GEOTAGS]}``). A step whose algorithm is not
there yet, whose parameters do not match the algorithm, or whose inputs were not made is skipped
with a note; a step that fails is reported and the chain goes on without it.

    .venv/bin/python scripts/demo.py [--out birdseye-demo]
"""
from __future__ import annotations

import argparse
import os
import shutil
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[1]
PLUGIN_PATH = REPO_ROOT / "build" / "pluginpath"
QGIS_PYTHON_PLUGINS = "/usr/share/qgis/python/plugins"
PROJECT_NAME = "birdseye_demo.qgz"


@dataclass(frozen=True)
class Step:
    """One algorithm run: ``birdseye:<alg_id>`` with ``params``; its layers go into ``group``.

    ``name`` is how later steps refer to this step's outputs, e.g. ``"{campaign[CALIBRATION]}"``.
    """

    name: str
    alg_id: str
    title: str
    params: dict = field(default_factory=dict)
    group: str | None = None


SIGMAS = "0.01,0.01,0.06,0.04,0.04,0.13"  # the deployed platform's pose noise Σ0 (m, m, m, °, °, °)

STEPS = [
    Step("campaign", "simulatecampaign", "Simulate a survey campaign", {
        "SEED": 2024, "N_TARGETS": 8, "FIELD_WIDTH_M": 8, "FIELD_LENGTH_M": 6,
        "SIGMAS": SIGMAS, "OUTPUT_FOLDER": "{out}/campaign"}),
    Step("geotags", "importgeotags", "Import the rover geotags", {
        "INPUT": "{campaign[GEOTAGS]}", "OUTPUT": "{out}/survey/geotags.gpkg"}, group="survey"),
    Step("flight", "importflightlog", "Import the flight log and frames", {
        "POSE_LOG": "{campaign[POSES]}", "IMAGES": "{campaign[OUTPUT_FOLDER]}",
        "CALIBRATION": "{campaign[CALIBRATION]}", "OUTPUT": "{out}/flight/frames.gpkg",
        "OUTPUT_TRACK": "{out}/flight/track.gpkg"}, group="flight"),
    Step("labels", "writelabels", "Write training labels", {
        "GEOTAGS": "{geotags[OUTPUT]}", "FRAMES": "{flight[OUTPUT]}", "OUTPUT_FOLDER": "{out}/labels",
        "OUTPUT_FRAMES": "{out}/labels/frames_labelled.gpkg",
        "OUTPUT_GEOTAGS": "{out}/labels/geotags_seen.gpkg"}, group="labels"),
    Step("detections", "detect", "Detect targets (bundled model)", {
        "FRAMES": "{flight[OUTPUT]}", "OUTPUT": "{out}/detections/detections.gpkg",
        "OUTPUT_HEATMAPS": "{out}/detections/heatmaps"}, group="detections"),
    Step("clusters", "clusterdetections", "Cluster the detections", {
        "DETECTIONS": "{detections[OUTPUT]}", "GEOTAGS": "{geotags[OUTPUT]}", "FRAMES": "{flight[OUTPUT]}",
        "OUTPUT": "{out}/clusters/clusters.gpkg", "OUTPUT_POINTS": "{out}/clusters/points.gpkg"},
        group="clusters"),
    Step("evaluation", "evaluatedetections", "Evaluate recall and GMCF", {
        "DETECTIONS": ["{detections[OUTPUT]}"], "GEOTAGS": "{geotags[OUTPUT]}",
        "FRAMES": ["{flight[OUTPUT]}"], "OUTPUT_JSON": "{out}/evaluation.json",
        "OUTPUT_REPORT": "{out}/evaluation.html"}),
    Step("plan", "planflight", "Plan the next flight over the geotags", {
        "GEOTAGS": "{geotags[OUTPUT]}", "CAMERA": "{campaign[CALIBRATION]}",
        "OUTPUT_WAYPOINTS": "{out}/plan/waypoints.gpkg", "OUTPUT_ROUTE": "{out}/plan/route.gpkg",
        "OUTPUT_KMZ": "{out}/plan/mission.kmz", "OUTPUT_PLAN": "{out}/plan/mission.plan",
        "OUTPUT_LITCHI": "{out}/plan/litchi.csv", "OUTPUT_KML": "{out}/plan/mission.kml"}, group="plan"),
    Step("bound", "sensorbound", "Sensor bound for the simulated platform", {
        "CALIBRATION": "{campaign[CALIBRATION]}", "ALTITUDES": "10", "SIGMAS": SIGMAS,
        "OUTPUT_JSON": "{out}/sensor_bound.json", "OUTPUT_REPORT": "{out}/sensor_bound.html"}),
]
GROUP_ORDER = ["survey", "flight", "labels", "detections", "clusters", "plan"]


class MissingInput(KeyError):
    """A parameter refers to the output of a step that did not run."""


def resolve(value, values: dict):
    """A parameter value with ``{out}`` and ``{step[OUTPUT]}`` filled in (lists element-wise)."""
    if isinstance(value, list):
        return [resolve(v, values) for v in value]
    if not isinstance(value, str) or "{" not in value:
        return value
    try:
        return value.format_map(values)
    except KeyError as exc:
        raise MissingInput(exc.args[0]) from None


# ------------------------------------------------------------------------------------------ terminal
class TerminalFeedback:
    """Factory for a QgsProcessingFeedback that draws a progress bar and prints messages, indented."""

    @staticmethod
    def create():
        from qgis.core import QgsProcessingFeedback

        class Feedback(QgsProcessingFeedback):
            def __init__(self):
                super().__init__()
                self.live = sys.stdout.isatty()
                self.last_shown = -10
                self.progressChanged.connect(self.show_progress)

            def show_progress(self, percent: float) -> None:
                if self.live:
                    filled = int(percent / 100 * 30)
                    print(f"\r    [{'#' * filled}{'.' * (30 - filled)}] {percent:5.1f} %", end="", flush=True)
                elif percent >= self.last_shown + 10:
                    self.last_shown = percent - percent % 10
                    print(f"    {self.last_shown:.0f} %", flush=True)

            def end_line(self) -> None:
                if self.live:
                    print("\r" + " " * 48 + "\r", end="", flush=True)

            def pushInfo(self, info):  # noqa: N802 (QGIS API)
                if info.startswith("Results: "):  # processing.run's raw dict; the summary has the numbers
                    return
                self.end_line()
                print(f"    {info}", flush=True)

            def pushWarning(self, warning):  # noqa: N802
                self.end_line()
                print(f"    warning: {warning}", flush=True)

            def reportError(self, error, fatalError=False):  # noqa: N802, N803
                self.end_line()
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
    from birdseye.processing.provider import BirdsEyeProvider

    provider = BirdsEyeProvider()
    QgsApplication.processingRegistry().addProvider(provider)
    return app, provider


def layer_destinations(algorithm) -> set[str]:
    """Names of the parameters whose output is a map layer (those get loaded into the project)."""
    from qgis.core import (QgsProcessingParameterFeatureSink, QgsProcessingParameterRasterDestination,
                           QgsProcessingParameterVectorDestination)

    kinds = (QgsProcessingParameterFeatureSink, QgsProcessingParameterRasterDestination,
             QgsProcessingParameterVectorDestination)
    return {p.name() for p in algorithm.destinationParameterDefinitions() if isinstance(p, kinds)}


def run_step(step: Step, values: dict, project) -> tuple[str, dict, list]:
    """Run one step; returns (status, results, loaded layers). Status: ok / skipped: … / failed: …"""
    import processing
    from qgis.core import (QgsApplication, QgsProcessingContext, QgsProcessingException,
                           QgsProcessingOutputLayerDefinition, QgsProcessingUtils)

    algorithm = QgsApplication.processingRegistry().algorithmById(f"birdseye:{step.alg_id}")
    if algorithm is None:
        return f"skipped: birdseye:{step.alg_id} is not in the provider yet", {}, []
    known = {p.name() for p in algorithm.parameterDefinitions()}
    unknown = sorted(set(step.params) - known)
    if unknown:
        return f"skipped: scripts/demo.py passes parameters it does not have: {', '.join(unknown)}", {}, []
    try:
        params = {name: resolve(value, values) for name, value in step.params.items()}
    except MissingInput as exc:
        return f"skipped: needs the outputs of step '{exc.args[0]}', which did not run", {}, []

    to_load = layer_destinations(algorithm)
    for definition in algorithm.destinationParameterDefinitions():
        value = params.get(definition.name())
        if isinstance(value, str) and value:
            Path(value).parent.mkdir(parents=True, exist_ok=True)
            if definition.name() in to_load:
                params[definition.name()] = QgsProcessingOutputLayerDefinition(value, project)

    context = QgsProcessingContext()
    context.setProject(project)
    feedback = TerminalFeedback.create()
    try:
        # onFinish that does nothing: keep results as paths; the layers are loaded below.
        results = processing.run(algorithm, params, onFinish=lambda *_: None, feedback=feedback,
                                 context=context)
    except QgsProcessingException as exc:
        feedback.end_line()
        return f"failed: {exc}", {}, []
    feedback.end_line()

    layers = []
    for layer_ref, details in context.layersToLoadOnCompletion().items():
        layer = QgsProcessingUtils.mapLayerFromString(layer_ref, context)
        if layer is None or not layer.isValid():
            print(f"    note: output {layer_ref} could not be loaded as a layer")
            continue
        context.temporaryLayerStore().takeMapLayer(layer)
        if details.name:
            layer.setName(details.name)
        post_processor = details.postProcessor()
        if post_processor is not None:
            post_processor.postProcessLayer(layer, context, feedback)
        layers.append(layer)
    return "ok", dict(results), layers


def add_to_group(project, group_name: str | None, layers: list) -> None:
    root = project.layerTreeRoot()
    target = root
    if group_name:
        target = root.findGroup(group_name)
        if target is None:  # keep the groups in workflow order whatever order they are filled in
            position = sum(1 for g in GROUP_ORDER[:GROUP_ORDER.index(group_name)] if root.findGroup(g))
            target = root.insertGroup(position, group_name)
    for layer in layers:
        project.addMapLayer(layer, False)
        target.addLayer(layer)


# ------------------------------------------------------------------------------------------ summary
def numbers(results: dict) -> str:
    """The counts and scores an algorithm reports, e.g. 'FRAME_COUNT=96, LABEL_COUNT=812'."""
    shown = [f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
             for k, v in results.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
    return ", ".join(shown[:4])


def summary(out: Path, outcomes: list, project, project_path: Path, elapsed: float) -> str:
    lines = ["", "=" * 78, f"BirdsEye demo — {elapsed / 60:.1f} min, outputs in {out}/", "-" * 78]
    for step, status, seconds, results in outcomes:
        mark = {"ok": "done", "skipped": "skip", "failed": "FAIL"}[status.split(":")[0]]
        detail = numbers(results) if status == "ok" else status.split(": ", 1)[1]
        lines.append(f" {mark:4}  {step.title:<40} {seconds:6.1f} s  {detail}"[:160])
    lines.append("-" * 78)
    root = project.layerTreeRoot()
    for group in [root] + [g for g in (root.findGroup(n) for n in GROUP_ORDER) if g is not None]:
        names = [node.name() for node in group.children() if hasattr(node, "layerId")]
        if names:
            lines.append(f" {group.name() or '(top)'}: {', '.join(names)}")
    reports = sorted(p.name for p in out.glob("*.html")) + sorted(p.name for p in out.glob("*.json"))
    if reports:
        lines.append(f" reports: {', '.join(reports)}")
    lines.append(f" project: {project_path}  (open it with: qgis {project_path})")
    lines.append("=" * 78)
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description="Run the BirdsEye chain on a simulated campaign.")
    parser.add_argument("--out", type=Path, default=Path("birdseye-demo"), help="output folder")
    args = parser.parse_args()
    out = args.out.resolve()
    started = time.monotonic()

    app, _provider = start_qgis()
    from qgis.core import QgsProject

    if out.exists():
        print(f"Removing the previous demo in {out}/")
        shutil.rmtree(out)
    out.mkdir(parents=True)
    project = QgsProject.instance()
    project.clear()
    project.setTitle("BirdsEye demo")
    values = {"out": str(out)}
    outcomes = []
    for number, step in enumerate(STEPS, 1):
        print(f"[{number}/{len(STEPS)}] {step.title} (birdseye:{step.alg_id})", flush=True)
        step_start = time.monotonic()
        status, results, layers = run_step(step, values, project)
        seconds = time.monotonic() - step_start
        if status == "ok":
            values[step.name] = results
            add_to_group(project, step.group, layers)
            if layers and not project.crs().isValid():
                project.setCrs(layers[0].crs())
            print(f"    done in {seconds:.1f} s{': ' + numbers(results) if numbers(results) else ''}")
        else:
            print(f"    {status}")
        outcomes.append((step, status, seconds, results))

    project_path = out / PROJECT_NAME
    if not project.write(str(project_path)):
        print(f"error: could not write {project_path}: {project.error()}")
        return 1
    print(summary(out, outcomes, project, project_path, time.monotonic() - started))
    project.clear()
    app.exitQgis()
    return 1 if any(status.startswith("failed") for _, status, _, _ in outcomes) else 0


if __name__ == "__main__":
    sys.exit(main())
