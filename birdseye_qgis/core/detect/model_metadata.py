"""The metadata schema of BirdsEye heatmap models: the one module that reads and writes it.

A model carries its own processing defaults in the ONNX file's ``metadata_props``, every value
JSON-encoded (a string is ``"\\"Regressor\\""``, a number ``"0.5"``). Writer and reader live here, so
the keys can never drift apart.

Keys shared with the Deepness QGIS plugin (same names, same meaning, so one file serves both):

==========================  ========================================================================
``model_type``              ``"Regressor"`` (written; Deepness then shows the heatmap as a raster);
                            ``"Segmentor"`` is read as well (a one-channel segmentation output)
``resolution``              the ground sample distance the model works at, cm/px: every frame is
                            resampled to it before tiling
``tile_size``               tile edge, px at ``resolution`` (equals the input's height and width
                            when the ONNX input has fixed spatial dimensions)
``tiles_overlap``           overlap of neighbouring tiles, **percent** of ``tile_size`` (Deepness's
                            unit); only each tile's core is kept
``standardization_mean``    per input channel, subtracted after scaling pixel values to [0, 1]
``standardization_std``     per input channel, divided after that (all > 0)
``class_names``             ``{"0": "burrow"}``: one name per output channel (Deepness format)
==========================  ========================================================================

BirdsEye's own keys:

==========================  ========================================================================
``birdseye_schema_version`` integer, :data:`SCHEMA_VERSION`
``output_kind``             ``"probability"`` (values in [0, 1]) or ``"logits"`` (a sigmoid is applied)
``default_threshold``       probability in (0, 1) a peak must exceed, used when the user sets none
``input_channel_order``     ``"RGB"`` or ``"BGR"``: channel order of the input tensor (NCHW, uint8/255)
``training_gsd_cm``         optional: native ground sample distance of the training frames, cm/px
``peak_blur_sigma_px``      optional, default 1.0: Gaussian blur (px at ``resolution``) before peaks
``label_sigma_px``          optional: σ of the soft labels trained on, px at ``resolution``
``description``             optional free text (training data, recipe, version)
==========================  ========================================================================

**Models made for Deepness.** A model without ``birdseye_schema_version`` whose ``model_type`` is
``"Segmentor"`` is read by Deepness's own conventions (its ``ModelBase``/``Segmentor`` and the defaults of
its dock, ``deepness/common/config_entry_key.py``), and its metadata carries
``schema_version`` :data:`DEEPNESS_SCHEMA` (0):

* ``output_kind`` ``"probability"``: Deepness thresholds a segmentor's output as probabilities, so the
  sigmoid or softmax is inside the model;
* ``default_threshold`` from Deepness's ``seg_thresh`` when it lies in (0, 1), else Deepness's default
  0.5 (``seg_thresh`` 0 switches Deepness's threshold off; on two channels that is an argmax, p > 0.5);
* ``tiles_overlap`` 15 % (Deepness's default) when absent; ``tile_size`` the input's fixed size when
  absent; ``input_channel_order`` ``"RGB"`` (Deepness feeds the raster's bands in order);
* the output: one channel (N×1×H×W or N×H×W, Deepness's sigmoid case) is the target's probability; two
  channels (background, target: Deepness's softmax case) give channel 1 (:attr:`ModelMetadata.output_channel`).
  More classes, where the target is ambiguous, are refused; so are Deepness's other model types
  (``"Detector"``: boxes, no heatmap; a ``"Regressor"`` without BirdsEye's keys: a measured quantity, no
  probability).

``resolution`` stays required: a model's scale cannot be guessed, and a wrong one finds nothing. A key a
Deepness model also carries from BirdsEye's table (``output_kind``, ``default_threshold``, …) is honoured.

A model with missing or contradictory metadata is refused with one message that lists everything
wrong (:class:`ModelMetadataError`).
"""
from __future__ import annotations

import ast
import json
from dataclasses import dataclass, field

from ..errors import InputError

SCHEMA_VERSION = 1
MODEL_TYPES_READ = ("Regressor", "Segmentor")
OUTPUT_KINDS = ("probability", "logits")
CHANNEL_ORDERS = ("RGB", "BGR")

REQUIRED_KEYS = ("model_type", "resolution", "tile_size", "tiles_overlap", "birdseye_schema_version",
                 "output_kind", "default_threshold")
OPTIONAL_DEFAULTS = {
    "standardization_mean": [0.0, 0.0, 0.0],
    "standardization_std": [1.0, 1.0, 1.0],
    "class_names": {"0": "target"},
    "input_channel_order": "RGB",
    "training_gsd_cm": None,
    "peak_blur_sigma_px": 1.0,
    "label_sigma_px": None,
    "description": "",
}
KNOWN_KEYS = REQUIRED_KEYS + tuple(OPTIONAL_DEFAULTS)

#: ``schema_version`` of a model read by Deepness's conventions (no ``birdseye_schema_version`` key).
DEEPNESS_SCHEMA = 0
#: Deepness's threshold key for a segmentor (``ModelBase.get_metadata_segmentation_threshold``).
DEEPNESS_THRESHOLD_KEY = "seg_thresh"
#: Deepness's dock defaults (``ConfigEntryKey``) for what a Deepness model may leave out.
DEEPNESS_DEFAULTS = {"tiles_overlap": 15, "output_kind": "probability", "default_threshold": 0.5}


class ModelMetadataError(InputError):
    """A model whose metadata cannot be used; ``problems`` lists every reason."""

    def __init__(self, problems: list[str], source: str | None = None):
        self.problems = list(problems)
        text = "the model's metadata is not usable by BirdsEye:\n" + "\n".join(f"  - {p}" for p in problems)
        text += ("\n(see models/README.md, 'Metadata schema', for the keys a BirdsEye heatmap model "
                 "carries)")
        super().__init__(text, source=source)


@dataclass(frozen=True)
class ModelMetadata:
    """The processing settings a heatmap model carries (units in the field names).

    ``schema_version`` is :data:`DEEPNESS_SCHEMA` for a model read by Deepness's conventions;
    ``output_channel`` is the output channel holding the target's probability (1 for Deepness's two-channel
    background/target models, derived from the output's shape, never a key).
    """

    resolution_cm: float
    tile_size: int
    tiles_overlap_pct: float
    output_kind: str
    default_threshold: float
    standardization_mean: tuple = (0.0, 0.0, 0.0)
    standardization_std: tuple = (1.0, 1.0, 1.0)
    class_names: tuple = ("target",)
    input_channel_order: str = "RGB"
    training_gsd_cm: float | None = None
    peak_blur_sigma_px: float = 1.0
    label_sigma_px: float | None = None
    description: str = ""
    model_type: str = "Regressor"
    schema_version: int = SCHEMA_VERSION
    output_channel: int = 0
    extra: dict = field(default_factory=dict)

    @property
    def overlap_px(self) -> int:
        """Tile overlap in px at the model's resolution."""
        return int(round(self.tile_size * self.tiles_overlap_pct / 100.0))

    def to_props(self) -> dict[str, str]:
        """``metadata_props`` entries: key → JSON-encoded value (unknown extra keys kept)."""
        values = {
            "model_type": self.model_type,
            "resolution": self.resolution_cm,
            "tile_size": self.tile_size,
            "tiles_overlap": self.tiles_overlap_pct,
            "standardization_mean": list(self.standardization_mean),
            "standardization_std": list(self.standardization_std),
            "class_names": {str(i): name for i, name in enumerate(self.class_names)},
            "birdseye_schema_version": self.schema_version,
            "output_kind": self.output_kind,
            "default_threshold": self.default_threshold,
            "input_channel_order": self.input_channel_order,
            "training_gsd_cm": self.training_gsd_cm,
            "peak_blur_sigma_px": self.peak_blur_sigma_px,
            "label_sigma_px": self.label_sigma_px,
            "description": self.description,
        }
        if self.schema_version == DEEPNESS_SCHEMA:  # stays a Deepness model: its defaults written out
            del values["birdseye_schema_version"]
        props = {k: json.dumps(v) for k, v in values.items() if v is not None}
        props.update(self.extra)
        return props

    @classmethod
    def from_props(cls, props: dict[str, str], input_shape=None, output_shape=None,
                   source: str | None = None) -> "ModelMetadata":
        """Parse and validate; raises :class:`ModelMetadataError` listing every problem."""
        values, problems = _parse(props, input_shape, output_shape)
        if problems:
            raise ModelMetadataError(problems, source)
        return cls(
            resolution_cm=float(values["resolution"]), tile_size=int(values["tile_size"]),
            tiles_overlap_pct=float(values["tiles_overlap"]), output_kind=values["output_kind"],
            default_threshold=float(values["default_threshold"]),
            standardization_mean=tuple(float(x) for x in values["standardization_mean"]),
            standardization_std=tuple(float(x) for x in values["standardization_std"]),
            class_names=tuple(str(n) for n in _class_list(values["class_names"])),
            input_channel_order=values["input_channel_order"],
            training_gsd_cm=None if values["training_gsd_cm"] is None else float(values["training_gsd_cm"]),
            peak_blur_sigma_px=float(values["peak_blur_sigma_px"]),
            label_sigma_px=None if values["label_sigma_px"] is None else float(values["label_sigma_px"]),
            description=str(values["description"]), model_type=str(values["model_type"]).capitalize(),
            schema_version=int(values["birdseye_schema_version"]), output_channel=values["output_channel"],
            extra={k: v for k, v in props.items() if k not in KNOWN_KEYS})


def validate(props: dict[str, str], input_shape=None, output_shape=None) -> list[str]:
    """Everything wrong with a model's metadata (and its input/output shapes); empty when usable.

    ``input_shape``/``output_shape`` are the ONNX tensor shapes (NCHW; a dimension may be a name or
    None when dynamic).
    """
    return _parse(props, input_shape, output_shape)[1]


def read_onnx_metadata(path) -> ModelMetadata:
    """Metadata of an ONNX file, validated against its input and output shapes."""
    import onnx

    try:
        model = onnx.load(str(path), load_external_data=False)
    except Exception as exc:
        raise InputError(f"is not a readable ONNX model ({exc})", source=str(path)) from exc
    props = {p.key: p.value for p in model.metadata_props}
    graph_inputs = [i for i in model.graph.input if i.name not in {t.name for t in model.graph.initializer}]
    return ModelMetadata.from_props(props, _value_info_shape(graph_inputs[0]) if graph_inputs else None,
                                    _value_info_shape(model.graph.output[0]) if model.graph.output else None,
                                    source=str(path))


def embed_metadata(model, metadata: ModelMetadata) -> None:
    """Write ``metadata`` into an ``onnx.ModelProto``'s ``metadata_props`` (replacing those keys)."""
    props = metadata.to_props()
    keep = [(p.key, p.value) for p in model.metadata_props if p.key not in props and p.key not in KNOWN_KEYS]
    del model.metadata_props[:]
    for key, value in keep + sorted(props.items()):
        entry = model.metadata_props.add()
        entry.key, entry.value = key, value


# ---------------------------------------------------------------------- parsing and checks
def _value_info_shape(value_info) -> list:
    dims = value_info.type.tensor_type.shape.dim
    return [d.dim_value if d.HasField("dim_value") else (d.dim_param or None) for d in dims]


def _parse(props: dict[str, str], input_shape, output_shape) -> tuple[dict, list[str]]:
    problems: list[str] = []
    values: dict = {}
    for key, raw in props.items():
        if key not in KNOWN_KEYS and key != DEEPNESS_THRESHOLD_KEY:
            continue
        try:
            values[key] = json.loads(raw)
        except (TypeError, json.JSONDecodeError):
            if key == "class_names":  # Deepness also reads a Python literal (integer keys: {0: "field"})
                try:
                    values[key] = ast.literal_eval(raw)
                    continue
                except (ValueError, SyntaxError):
                    pass
            problems.append(f"'{key}' is not JSON-encoded (got {raw!r}; a string value needs quotes, "
                            f"e.g. {json.dumps(str(raw))})")
    model_type = str(values.get("model_type", "")).capitalize()
    type_ok = "model_type" not in values or model_type in MODEL_TYPES_READ
    deepness = "birdseye_schema_version" not in props and model_type == "Segmentor"
    if deepness:
        _deepness_defaults(values, input_shape, problems)
        required = ("model_type", "resolution", "tile_size")
    else:
        required = REQUIRED_KEYS
    missing = [k for k in required if k not in values and k not in props]
    if missing and type_ok:  # a model type that cannot cross says so below, without a list of keys
        hint = ""
        if "birdseye_schema_version" in missing:
            hint = (" — a 'Regressor' without BirdsEye's keys is a Deepness regression model, whose output is a "
                    "measured quantity, not a probability" if model_type == "Regressor" else
                    " — this looks like a model made for another tool; BirdsEye needs its own keys too")
            hint += " (a Deepness 'Segmentor' is read by Deepness's conventions)"
        elif deepness and "tile_size" in missing:
            hint = " (a Deepness model without it needs an input of fixed height and width)"
        problems.append(f"missing key(s): {', '.join(missing)}{hint}")
    for key, default in OPTIONAL_DEFAULTS.items():
        values.setdefault(key, default)

    def number(key, kind=float, low=None, high=None, low_open=False, high_open=False):
        if key not in values:
            return None
        v = values[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or (kind is int and v != int(v)):
            problems.append(f"'{key}' must be {'an integer' if kind is int else 'a number'} (got {v!r})")
            return None
        if low is not None and (v <= low if low_open else v < low):
            problems.append(f"'{key}' must be {'>' if low_open else '≥'} {low} (got {v})")
            return None
        if high is not None and (v >= high if high_open else v > high):
            problems.append(f"'{key}' must be {'<' if high_open else '≤'} {high} (got {v})")
            return None
        return v

    if model_type == "Detector":
        problems.append("'model_type' is 'Detector': a Deepness object detector (YOLO-style boxes) gives no "
                        "heatmap; BirdsEye runs heatmap models ('Regressor' with BirdsEye's keys, or a "
                        "one-target 'Segmentor')")
    elif not type_ok:
        problems.append(f"'model_type' is {values['model_type']!r}; a heatmap model is "
                        f"{' or '.join(repr(t) for t in MODEL_TYPES_READ)} (one output channel of scores)")
    number("resolution", low=0, low_open=True)
    tile = number("tile_size", int, low=8)
    overlap = number("tiles_overlap", low=0, high=100, high_open=True)
    version = number("birdseye_schema_version", int, low=DEEPNESS_SCHEMA if deepness else 1)
    if version is not None and version > SCHEMA_VERSION:
        problems.append(f"'birdseye_schema_version' is {version}; this plugin reads up to {SCHEMA_VERSION} "
                        "(update the plugin)")
    if "output_kind" in values and values["output_kind"] not in OUTPUT_KINDS:
        problems.append(f"'output_kind' must be one of {', '.join(OUTPUT_KINDS)} (got {values['output_kind']!r})")
    number("default_threshold", low=0, high=1, low_open=True, high_open=True)
    if values["input_channel_order"] not in CHANNEL_ORDERS:
        problems.append(f"'input_channel_order' must be one of {', '.join(CHANNEL_ORDERS)} "
                        f"(got {values['input_channel_order']!r})")
    if values["training_gsd_cm"] is not None:
        number("training_gsd_cm", low=0, low_open=True)
    number("peak_blur_sigma_px", low=0)
    if values["label_sigma_px"] is not None:
        number("label_sigma_px", low=0, low_open=True)
    if tile is not None and overlap is not None and round(tile * overlap / 100.0) >= tile:
        problems.append(f"'tiles_overlap' of {overlap}% leaves no tile core at tile_size {tile}")

    mean, std = values["standardization_mean"], values["standardization_std"]
    for key, vec in (("standardization_mean", mean), ("standardization_std", std)):
        if not isinstance(vec, list) or not vec or not all(
                isinstance(x, (int, float)) and not isinstance(x, bool) for x in vec):
            problems.append(f"'{key}' must be a list of numbers, one per input channel (got {vec!r})")
    if isinstance(std, list) and any(isinstance(x, (int, float)) and x <= 0 for x in std):
        problems.append(f"'standardization_std' values must be > 0 (got {std})")
    if isinstance(mean, list) and isinstance(std, list) and len(mean) != len(std):
        problems.append(f"'standardization_mean' has {len(mean)} values but 'standardization_std' has {len(std)}")

    if deepness and "class_names" not in props:  # Deepness names unnamed channels itself; so do we
        n_out = _output_channels(output_shape)
        values["class_names"] = {"0": "background", "1": "target"} if n_out == 2 else {"0": "target"}
    classes = _class_list(values["class_names"])
    if classes is None:
        problems.append("'class_names' must map consecutive indices from \"0\" to names, "
                        f"e.g. {{\"0\": \"burrow\"}} (got {values['class_names']!r})")

    shape_problems, values["output_channel"] = _shape_problems(input_shape, output_shape, tile, mean, classes,
                                                               deepness)
    problems += shape_problems
    return values, problems


def _deepness_defaults(values: dict, input_shape, problems: list[str]) -> None:
    """Fill in what a Deepness segmentor leaves out, by Deepness's conventions (module docstring)."""
    values["birdseye_schema_version"] = DEEPNESS_SCHEMA
    if "tile_size" not in values and input_shape is not None and len(input_shape) == 4:
        h, w = input_shape[2:]
        if isinstance(h, int) and h > 0 and h == w:
            values["tile_size"] = h
    for key in ("tiles_overlap", "output_kind"):
        values.setdefault(key, DEEPNESS_DEFAULTS[key])
    if "default_threshold" in values:
        return
    t = values.get(DEEPNESS_THRESHOLD_KEY)
    if t is None or t == 0:
        values["default_threshold"] = DEEPNESS_DEFAULTS["default_threshold"]
    elif isinstance(t, (int, float)) and not isinstance(t, bool) and 0 < t < 1:
        values["default_threshold"] = float(t)
    else:
        problems.append(f"'{DEEPNESS_THRESHOLD_KEY}' must be a probability from 0 to below 1 (got {t!r})")


def _output_channels(output_shape):
    """Channels of an N×C×H×W output (1 for N×H×W); None when unknown or dynamic."""
    if output_shape is None:
        return None
    if len(output_shape) == 3:
        return 1
    if len(output_shape) == 4 and isinstance(output_shape[1], int):
        return output_shape[1]
    return None


def _shape_problems(input_shape, output_shape, tile, mean, classes, deepness=False) -> tuple[list[str], int]:
    """Problems of the input/output shapes against the metadata, and the output channel of the target."""
    problems = []
    channel = 0
    if input_shape is not None:
        if len(input_shape) != 4:
            problems.append(f"the model input must be NCHW (4 dimensions); it has shape {input_shape}")
        else:
            channels, h, w = input_shape[1:]
            if isinstance(channels, int) and channels != 3:
                problems.append(f"the model input has {channels} channels; BirdsEye feeds 3 (colour frames)")
            if isinstance(mean, list) and isinstance(channels, int) and len(mean) != channels:
                problems.append(f"'standardization_mean' has {len(mean)} values for {channels} input channels")
            if tile is not None:
                fixed = [d for d in (h, w) if isinstance(d, int) and d > 0]
                if any(d != tile for d in fixed):
                    problems.append(f"'tile_size' is {tile} but the model input is {h}×{w} px")
    n_out = _output_channels(output_shape)
    if deepness and n_out is None and classes is not None:
        n_out = len(classes)  # Deepness names each output channel
    if output_shape is not None and len(output_shape) not in (3, 4):
        problems.append(f"the model output must be N×1×H×W or N×H×W; it has shape {output_shape}")
    elif deepness and n_out is not None and n_out > 2:
        names = f" ({', '.join(classes)})" if classes is not None and len(classes) == n_out else ""
        problems.append(f"the model segments {n_out} classes{names}; BirdsEye detects one target: it reads a "
                        "Deepness segmentor with one output channel (the target) or two (background, target)")
    elif n_out is not None:
        if n_out == 2 and deepness:
            channel = 1
        elif n_out != 1:
            problems.append(f"the model output has {n_out} channels; a BirdsEye heatmap model has one")
        if channel == 1 or n_out == 1:
            if classes is not None and len(classes) != n_out:
                problems.append(f"'class_names' names {len(classes)} classes for {n_out} output channel(s)")
    if output_shape is not None and input_shape is not None and len(input_shape) == 4 \
            and len(output_shape) in (3, 4):
        hin, win = input_shape[2:]
        hout, wout = output_shape[-2:]
        if all(isinstance(d, int) for d in (hin, win, hout, wout)) and (hin, win) != (hout, wout):
            problems.append(f"the heatmap ({hout}×{wout}) must have the input's size ({hin}×{win})")
    return problems, channel


def _class_list(class_names):
    """Class names in index order from Deepness's ``{"0": name, ...}`` (or a list); None if invalid."""
    if isinstance(class_names, list) and class_names and all(isinstance(n, str) for n in class_names):
        return list(class_names)
    if not isinstance(class_names, dict) or not class_names:
        return None
    try:
        items = sorted((int(k), v) for k, v in class_names.items())
    except (TypeError, ValueError):
        return None
    if [k for k, _ in items] != list(range(len(items))) or not all(isinstance(v, str) for _, v in items):
        return None
    return [v for _, v in items]
