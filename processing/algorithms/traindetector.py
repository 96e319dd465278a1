"""birdseye:traindetector — train a heatmap detector on Write-labels folders, in a separate Python process.

PyTorch is never imported here: the training runs in a child process (``python -m
birdseye_qgis.core.train.child``, :mod:`birdseye_qgis.core.train.protocol`) in a Python that has torch
(:func:`birdseye_qgis.dependencies.find_training_python`), and streams its progress back line by line.
"""
from __future__ import annotations

import tempfile
import time
from pathlib import Path

from qgis.core import (
    QgsApplication,
    QgsProcessingException,
    QgsProcessingOutputFile,
    QgsProcessingOutputNumber,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFile,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis import dependencies
from ...birdseye_qgis.core.errors import Cancelled, InputError
from ...birdseye_qgis.core.labels.raster_labels import raster_record
from ...birdseye_qgis.core.train.choices import BACKBONES, SPLITS
from ...birdseye_qgis.core.train.job import Source, TrainJob
from ...birdseye_qgis.core.train.preset import PRESETS
from ...birdseye_qgis.core.train.protocol import TrainingFailed, run_child
from ...birdseye_qgis.qgis_enums import (
    FILE_BEHAVIOR_FILE,
    NUMBER_DOUBLE,
    NUMBER_INTEGER,
    PARAMETER_ADVANCED,
    SOURCE_FILE,
    SOURCE_VECTOR,
)
from ...birdseye_qgis.qgis_io.layers import read_frame_layer
from .base import BirdsEyeAlgorithm

#: PRESET's choices, in the order of core.train.preset.PRESETS (their titles, for translation).
PRESET_LABELS = (
    QT_TRANSLATE_NOOP("TrainDetector", "Fast (default)"),
    QT_TRANSLATE_NOOP("TrainDetector", "Method (EfficientNetV2, two stages, AdamW)"),
)


class TrainDetector(BirdsEyeAlgorithm):
    ALG_ID = "traindetector"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("TrainDetector", "Train detector (heatmap model from training labels)")
    GROUP = "labels"
    LABELS = "LABELS"
    FRAMES = "FRAMES"
    GSD_CM = "GSD_CM"
    PRESET = "PRESET"
    BACKBONE = "BACKBONE"
    WEIGHTS = "WEIGHTS"
    INIT = "INIT"
    MINUTES = "MINUTES"
    RESOLUTION_CM = "RESOLUTION_CM"
    VALIDATION = "VALIDATION"
    VALIDATION_FRACTION = "VALIDATION_FRACTION"
    SEED = "SEED"
    THRESHOLD = "THRESHOLD"
    THREADS = "THREADS"
    PYTHON = "PYTHON"
    OUTPUT_MODEL = "OUTPUT_MODEL"
    MODEL_CARD = "MODEL_CARD"
    PLOT = "PLOT"
    CHECKPOINT = "CHECKPOINT"
    #: Seconds a cancelled training process gets to write its checkpoint before it is killed.
    GRACE_S = 15.0

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.LABELS, self.tr("Write-labels folders (with tiles)"), SOURCE_FILE))
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.FRAMES, self.tr("Frame layers (GSD and pose of each frame)"),
            SOURCE_VECTOR, optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.GSD_CM, self.tr("Or one GSD for every frame (cm/px)"), NUMBER_DOUBLE, optional=True,
            minValue=0.001))
        self.addParameter(QgsProcessingParameterEnum(
            self.PRESET, self.tr("Training preset"), options=[self.tr(label) for label in PRESET_LABELS],
            defaultValue=0))
        self.addParameter(QgsProcessingParameterEnum(
            self.BACKBONE, self.tr("Network (the Method preset sets its own)"), list(BACKBONES),
            defaultValue=0))
        self.addParameter(QgsProcessingParameterFile(
            self.WEIGHTS, self.tr("ImageNet weights of the encoder (.pth)"),
            FILE_BEHAVIOR_FILE, fileFilter="PyTorch weights (*.pth *.pt)", optional=True))
        self.addParameter(QgsProcessingParameterFile(
            self.INIT, self.tr("Earlier model to fine-tune (.pt, .onnx)"),
            FILE_BEHAVIOR_FILE, fileFilter="BirdsEye models (*.pt *.onnx)", optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.MINUTES, self.tr("Training time budget (minutes)"), NUMBER_DOUBLE, 20.0, minValue=0.05))
        self.addParameter(QgsProcessingParameterNumber(
            self.RESOLUTION_CM, self.tr("Model resolution (cm/px; empty: automatic)"),
            NUMBER_DOUBLE, optional=True, minValue=0.01))
        self.addParameter(QgsProcessingParameterEnum(
            self.VALIDATION, self.tr("Validation: hold out"),
            [self.tr("Spatial blocks (no target shared with training)"),
             self.tr("Whole flights (labels folders)"), self.tr("Nothing (threshold not validated)")], defaultValue=0))
        self.addParameter(QgsProcessingParameterNumber(
            self.VALIDATION_FRACTION, self.tr("Share of the targets held out (0–0.5)"), NUMBER_DOUBLE,
            0.15, minValue=0.0, maxValue=0.5))
        self.addParameter(QgsProcessingParameterNumber(
            self.SEED, self.tr("Random seed"), NUMBER_INTEGER, 0, minValue=0))
        advanced = [
            QgsProcessingParameterNumber(
                self.THRESHOLD, self.tr("Default threshold (empty: from validation)"), NUMBER_DOUBLE,
                optional=True, minValue=0.0, maxValue=1.0),
            QgsProcessingParameterNumber(
                self.THREADS, self.tr("CPU threads for training (0: all cores)"), NUMBER_INTEGER, 0, minValue=0),
            QgsProcessingParameterFile(
                self.PYTHON, self.tr("Python with PyTorch"),
                FILE_BEHAVIOR_FILE, fileFilter="All files (*)", optional=True),
        ]
        for parameter in advanced:
            parameter.setFlags(parameter.flags() | PARAMETER_ADVANCED)
            self.addParameter(parameter)
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_MODEL, self.tr("Trained model (ONNX)"), "ONNX models (*.onnx)"))
        self.addOutput(QgsProcessingOutputFile(self.MODEL_CARD, self.tr("Model card (Markdown)")))
        self.addOutput(QgsProcessingOutputFile(self.PLOT, self.tr("Loss curves (PNG)")))
        self.addOutput(QgsProcessingOutputFile(self.CHECKPOINT, self.tr("Weights to fine-tune from (.pt)")))
        for name, text in (("TILES", "Training tiles"), ("THRESHOLD_USED", "Default threshold of the model"),
                           ("TRAIN_SECONDS", "Training time (s)"), ("TILES_PER_SECOND", "Training throughput "
                                                                                         "(tiles/s)"),
                           ("VALIDATION_RECALL", "Recall of the held-out geotags at the default threshold"),
                           ("VALIDATION_GMCF", "GMCF on the held-out frames at the default threshold")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    # ------------------------------------------------------------------ inputs
    def _label_folders(self, parameters, context) -> list[Path]:
        # parameterAsFileList resolves what the Graphical Modeler and expressions pass (a list, an expression's
        # array or text); text may still join several paths with ";" or new lines.
        values = [part.strip() for value in self.parameterAsFileList(parameters, self.LABELS, context) or []
                  for part in str(value).replace("\n", ";").split(";") if part.strip()]
        folders = []
        for value in values:
            path = Path(str(value).strip())
            folder = path.parent if path.is_file() else path
            if not (folder / "tiles" / "images").is_dir():
                raise self.user_error(InputError("is not a Write training labels folder with tiles (tiles/images)",
                                                 source=str(folder), field=self.LABELS))
            folders.append(folder)
        if not folders:
            raise self.user_error(InputError("no labels folder given", field=self.LABELS))
        return folders

    def _sources(self, parameters, context, folders) -> list[Source]:
        """A folder written on a raster carries its GSD and has no frames (:class:`Source`): it takes no frame layer
        and needs no GSD_CM."""
        layers = self.parameterAsLayerList(parameters, self.FRAMES, context) or []
        gsd = self._optional_double(parameters, self.GSD_CM, context)
        on_raster = [self.run_core(raster_record, f) is not None for f in folders]
        if not layers:
            if gsd is None and not all(on_raster):
                raise self.user_error(InputError("give the frame layers the labels were written from, or one ground "
                                                 "sample distance (GSD_CM)", field=self.FRAMES))
            return [Source(str(f), gsd_default=gsd) for f in folders]
        if len(layers) not in (1, len(folders)):
            raise self.user_error(InputError(f"{len(layers)} frame layers for {len(folders)} labels folders: give one "
                                             "per folder, in the same order, or one for all", field=self.FRAMES))
        records = [self._frame_records(layer) for layer in layers]
        maps = [{str(r["frame_id"]): float(r["gsd_cm"]) for r in recs
                 if r.get("frame_id") is not None and r.get("gsd_cm") is not None} for recs in records]
        return [Source(str(f)) if raster else
                Source(str(f), gsd_cm=maps[0] if len(maps) == 1 else maps[i],
                       frames=records[0] if len(records) == 1 else records[i])
                for i, (f, raster) in enumerate(zip(folders, on_raster))]

    def _optional_double(self, parameters, name, context) -> float | None:
        """An optional number, None when empty: parameterAsDouble alone reads an empty value as 0. Its text
        (parameterAsString) is empty for a value not given, None, or an expression (QgsProperty) that gives NULL."""
        if not self.parameterAsString(parameters, name, context).strip():
            return None
        return self.parameterAsDouble(parameters, name, context)

    def _frame_records(self, layer) -> list[dict]:
        """The frame layer's records (:func:`read_frame_layer`: each frame's GSD, pose and image), read once."""
        names = layer.fields().names()
        if "frame_id" not in names or "gsd_cm" not in names:
            raise self.user_error(InputError("has no fields frame_id and gsd_cm (is it a BirdsEye frame layer?)",
                                             source=layer.name(), field=self.FRAMES))
        return self.run_core(read_frame_layer, layer, layer.name())

    def _python(self, parameters, context, feedback):
        configured = self.parameterAsFile(parameters, self.PYTHON, context) or None
        profile = QgsApplication.qgisSettingsDirPath()
        found, tried = dependencies.find_training_python(configured, profile)
        if found is None:
            group = dependencies.torch_group()
            folder = dependencies.torch_folder(profile)
            try:
                python = dependencies.find_python()
            except dependencies.InstallError:
                python = "python"
            raise QgsProcessingException(self.tr(
                "Train detector needs PyTorch, which it runs in a separate Python process; no Python with torch, "
                "onnx and OpenCV was found ({tried}). In QGIS, choose {menu} and install the group '{group}' "
                "({build} build); or install it yourself: {command}; or name a Python that has them (parameter "
                "{parameter}, or the environment variable {variable}) — for a virtual environment: "
                "<venv>/bin/python -m pip install \"torch=={torch}\" \"torchvision=={torchvision}\" onnx "
                "opencv-python-headless matplotlib onnxruntime scipy").format(
                    tried="; ".join(tried) or self.tr("none set up"), menu=dependencies.MENU_PATH, group=group.title,
                    build=group.build.upper(), command=group.pip_command(python, folder), parameter=self.PYTHON,
                    variable=dependencies.TRAINING_PYTHON_VARIABLE, torch=dependencies.TORCH_VERSION,
                    torchvision=dependencies.TORCHVISION_VERSION))
        feedback.pushInfo(self.tr("Training in {python} ({origin}): torch {torch}.").format(
            python=found.executable, origin=found.origin, torch=found.versions.get("torch")))
        return found

    # ------------------------------------------------------------------ run
    def processAlgorithm(self, parameters, context, feedback):
        folders = self._label_folders(parameters, context)
        sources = self._sources(parameters, context, folders)
        out = self.parameterAsFileOutput(parameters, self.OUTPUT_MODEL, context)
        if not out.lower().endswith(".onnx"):
            out += ".onnx"
        job = TrainJob(
            sources=sources, out=out, backbone=BACKBONES[self.parameterAsEnum(parameters, self.BACKBONE, context)],
            weights=self.parameterAsFile(parameters, self.WEIGHTS, context) or None,
            init=self.parameterAsFile(parameters, self.INIT, context) or None,
            minutes=self.parameterAsDouble(parameters, self.MINUTES, context),
            resolution_cm=self._optional_double(parameters, self.RESOLUTION_CM, context),
            val_fraction=self.parameterAsDouble(parameters, self.VALIDATION_FRACTION, context),
            validation=SPLITS[self.parameterAsEnum(parameters, self.VALIDATION, context)],
            seed=self.parameterAsInt(parameters, self.SEED, context),
            threads=self.parameterAsInt(parameters, self.THREADS, context),
            threshold=self._optional_double(parameters, self.THRESHOLD, context),
            producer="BirdsEye birdseye:traindetector",
            preset=PRESETS[self.parameterAsEnum(parameters, self.PRESET, context)].name)
        python = self._python(parameters, context, feedback)
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryDirectory(prefix="birdseye-train-") as scratch:
            job_file = Path(scratch) / "job.json"
            job_file.write_text(job.to_json(), encoding="utf-8")
            command = [python.executable, "-m", "birdseye_qgis.core.train.child", str(job_file)]
            started = time.perf_counter()
            relay = _Relay(self, feedback, started)
            try:
                run = run_child(command, relay, feedback.isCanceled, env=python.environment(), cwd=scratch,
                                grace_s=self.GRACE_S, on_start=relay.started)
            except Cancelled:
                kept = job.checkpoint_path if job.checkpoint_path.exists() else None
                raise QgsProcessingException(self.tr("Cancelled by the user; no model was written.") + (
                    " " + self.tr("The last checkpoint is kept: {path}").format(path=kept) if kept else "")) from None
            except InputError as exc:
                raise self.user_error(exc) from exc
            except TrainingFailed as exc:
                tail = "\n".join(exc.tail[-12:])
                if tail:
                    feedback.reportError(tail)
                kept = job.checkpoint_path if job.checkpoint_path.exists() else None
                raise QgsProcessingException(str(exc) + (
                    " " + self.tr("The last checkpoint is kept: {path}").format(path=kept) if kept else "")) from exc
        result = run.result
        seconds = time.perf_counter() - started
        overhead = seconds - float(result["seconds"]["train"])
        feedback.pushInfo(self.tr(
            "Wrote {model} (default threshold {threshold:g}), its model card and loss plot; training "
            "{train:.1f} s on {device}, {tiles_per_s:.1f} tiles/s; {overhead:.1f} s outside training (process "
            "start, loading tiles, validation, export; the first line came after {first:.1f} s).").format(
                model=result["model"], threshold=result["threshold"], train=result["seconds"]["train"],
                device=result["device"], tiles_per_s=result["history"]["tiles_per_s"], overhead=overhead,
                first=run.first_event_s or 0.0))
        feedback.pushInfo(self.tr("Default threshold: {rule}.").format(rule=result["threshold_rule"]))
        at_default = self._ground_row(result)
        feedback.setProgress(100)
        return {self.OUTPUT_MODEL: result["model"], self.MODEL_CARD: result["card"], self.PLOT: result.get("plot"),
                self.CHECKPOINT: result["weights"], "TILES": result["data"]["training_tiles"],
                "THRESHOLD_USED": result["threshold"], "TRAIN_SECONDS": result["seconds"]["train"],
                "TILES_PER_SECOND": result["history"]["tiles_per_s"], "VALIDATION_RECALL": at_default.get("recall"),
                "VALIDATION_GMCF": at_default.get("gmcf")}

    @staticmethod
    def _ground_row(result: dict) -> dict:
        """The ground figures (recall, GMCF) at the model's default threshold, empty when not measured there."""
        ground = result.get("ground_validation") or {}
        return (ground.get("by_threshold") or {}).get(f"{result['threshold']:g}") or {}


class _Relay:
    """Passes the child's events to Processing's progress bar and log as they arrive."""

    def __init__(self, algorithm: TrainDetector, feedback, started: float):
        self.alg, self.feedback, self.started_at = algorithm, feedback, started
        self.pid = None
        self.stage = None

    def started(self, process) -> None:
        self.pid = process.pid

    def __call__(self, event: dict) -> None:
        tr, feedback, kind = self.alg.tr, self.feedback, event.get("type")
        if kind == "progress":
            if event.get("fraction") is not None:
                feedback.setProgress(100.0 * float(event["fraction"]))
            if event.get("stage") != self.stage:
                self.stage = event.get("stage")
                feedback.setProgressText(tr("Training: {stage}").format(stage=self.stage))
        elif kind == "start":
            feedback.pushInfo(tr("Training process {pid} started: torch {torch} on {device} ({threads} threads), "
                                 "backbone {backbone}.").format(**{k: event.get(k) for k in (
                                     "pid", "torch", "device", "threads", "backbone")}))
        elif kind == "point":
            val = event.get("val_loss")
            feedback.pushInfo(tr("{stage} step {step}: loss {loss:.4f}, validation {val} ({seconds:.0f} s)").format(
                stage=event["stage"], step=event["step"], loss=event["loss"],
                val="–" if val is None else f"{val:.4f}", seconds=event["seconds"]))
        elif kind == "checkpoint":
            feedback.pushDebugInfo(tr("Checkpoint written: {path} ({stage}, step {step})").format(
                path=event.get("path"), stage=event.get("stage"), step=event.get("step")))
        elif kind == "message" and event.get("level") == "warning":
            feedback.pushWarning(event.get("text", ""))
        elif kind == "message":
            feedback.pushInfo(event.get("text", ""))
        elif kind == "error" and event.get("kind") != "input":
            feedback.reportError(event.get("text", ""))
