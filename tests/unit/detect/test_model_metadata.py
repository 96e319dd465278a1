"""The ONNX metadata schema: one writer, one reader, and every problem listed at once."""
import json

import numpy as np
import onnx
import pytest
from onnx import TensorProto, helper

from birdseye.birdseye_qgis.core.detect.model_metadata import (
    DEEPNESS_SCHEMA,
    ModelMetadata,
    ModelMetadataError,
    embed_metadata,
    read_onnx_metadata,
    validate,
)
from birdseye.birdseye_qgis.core.errors import InputError


def demo_metadata(**changes) -> ModelMetadata:
    values = dict(resolution_cm=0.5, tile_size=64, tiles_overlap_pct=12.5, output_kind="logits",
                  default_threshold=0.4, standardization_mean=(0.4, 0.45, 0.5),
                  standardization_std=(0.2, 0.21, 0.22), class_names=("burrow",), training_gsd_cm=0.23,
                  label_sigma_px=4.5, description="unit test")
    values.update(changes)
    return ModelMetadata(**values)


def identity_model(h=64, w=64, out_channels=1):
    """A 1×1 convolution 3 → out_channels, input N×3×h×w (None = dynamic)."""
    x = helper.make_tensor_value_info("x", TensorProto.FLOAT, ["n", 3, h or "h", w or "w"])
    y = helper.make_tensor_value_info("y", TensorProto.FLOAT, ["n", out_channels, h or "h", w or "w"])
    weight = helper.make_tensor("w", TensorProto.FLOAT, [out_channels, 3, 1, 1], [1.0 / 3] * (3 * out_channels))
    graph = helper.make_graph([helper.make_node("Conv", ["x", "w"], ["y"])], "g", [x], [y], [weight])
    return helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])


def test_props_are_json_and_round_trip():
    meta = demo_metadata(extra={"author": json.dumps("lab")})
    props = meta.to_props()
    assert all(isinstance(v, str) for v in props.values())
    # Deepness's own readers: json.loads per key, class names as {"0": name}, overlap in percent.
    assert json.loads(props["model_type"]) == "Regressor"
    assert json.loads(props["resolution"]) == 0.5 and json.loads(props["tile_size"]) == 64
    assert json.loads(props["class_names"]) == {"0": "burrow"}
    assert json.loads(props["standardization_std"]) == [0.2, 0.21, 0.22]
    back = ModelMetadata.from_props(props)
    assert back == meta
    assert back.overlap_px == 8  # 12.5 % of 64 px


def test_embedded_metadata_reads_back_from_the_file(tmp_path):
    model = identity_model()
    model.metadata_props.add(key="author", value=json.dumps("lab"))
    model.metadata_props.add(key="tile_size", value="999")  # stale value: replaced, not duplicated
    embed_metadata(model, demo_metadata())
    keys = [p.key for p in model.metadata_props]
    assert len(keys) == len(set(keys))
    path = tmp_path / "m.onnx"
    onnx.save(model, str(path))
    meta = read_onnx_metadata(path)
    assert meta.tile_size == 64 and meta.extra == {"author": json.dumps("lab")}
    assert meta == demo_metadata(extra={"author": json.dumps("lab")})


def test_every_problem_is_listed_at_once():
    props = demo_metadata().to_props()
    del props["output_kind"]
    del props["resolution"]
    props["tile_size"] = "32"                      # contradicts the fixed 64×64 input
    props["default_threshold"] = "1.5"
    props["standardization_std"] = "[0.2, 0.0, 0.2]"
    props["input_channel_order"] = "RGB"          # not JSON: a string needs quotes
    props["class_names"] = json.dumps({"0": "a", "2": "b"})
    problems = validate(props, input_shape=["n", 3, 64, 64], output_shape=["n", 2, 64, 64])
    text = "\n".join(problems)
    for expected in ("missing key(s): resolution, output_kind", "'tile_size' is 32 but the model input is 64×64",
                     "'default_threshold' must be < 1", "'standardization_std' values must be > 0",
                     "'input_channel_order' is not JSON-encoded", "'class_names' must map consecutive",
                     "output has 2 channels"):
        assert expected in text, expected
    assert len(problems) == 7
    with pytest.raises(ModelMetadataError) as err:
        ModelMetadata.from_props(props, ["n", 3, 64, 64], ["n", 2, 64, 64], source="bad.onnx")
    assert err.value.problems == problems
    assert isinstance(err.value, InputError) and str(err.value).startswith("bad.onnx: ")
    assert all(p in str(err.value) for p in problems)


DEEPNESS_PROPS = {"model_type": json.dumps("Segmentor"), "resolution": "3.0", "tile_size": "512",
                  "tiles_overlap": "10", "class_names": json.dumps({"0": "field"})}


def test_a_deepness_segmentor_is_read_by_deepness_conventions():
    """Deepness's keys only: the defaults of Deepness's dock and segmentor, stated in the module docstring."""
    meta = ModelMetadata.from_props(DEEPNESS_PROPS, ["n", 3, 512, 512], ["n", 1, 512, 512])
    assert meta.schema_version == DEEPNESS_SCHEMA == 0
    assert meta.model_type == "Segmentor" and meta.class_names == ("field",) and meta.output_channel == 0
    assert (meta.resolution_cm, meta.tile_size, meta.tiles_overlap_pct) == (3.0, 512, 10.0)
    assert meta.output_kind == "probability" and meta.default_threshold == 0.5
    assert meta.input_channel_order == "RGB"
    assert meta.standardization_mean == (0.0, 0.0, 0.0) and meta.standardization_std == (1.0, 1.0, 1.0)
    # Deepness's own threshold key; its tiles_overlap default; tile_size from a fixed input; lower-case type;
    # class names as a Python literal with integer keys (Deepness's ast fallback).
    props = {"model_type": '"segmentor"', "resolution": "2", "seg_thresh": "0.7", "class_names": "{0: 'nest'}",
             "standardization_mean": "[0.5, 0.5, 0.5]", "standardization_std": "[0.25, 0.25, 0.25]"}
    meta = ModelMetadata.from_props(props, ["n", 3, 256, 256], ["n", 256, 256])
    assert (meta.tile_size, meta.tiles_overlap_pct, meta.default_threshold) == (256, 15, 0.7)
    assert meta.class_names == ("nest",) and meta.standardization_std == (0.25, 0.25, 0.25)
    # seg_thresh 0 switches Deepness's threshold off: Deepness's default stands.
    assert ModelMetadata.from_props(dict(props, seg_thresh="0"), ["n", 3, 256, 256]).default_threshold == 0.5
    assert any("'seg_thresh' must be a probability" in p for p in validate(dict(props, seg_thresh="1.5")))
    # A BirdsEye key on a Deepness model is honoured.
    assert ModelMetadata.from_props(dict(DEEPNESS_PROPS, output_kind='"logits"')).output_kind == "logits"


def test_a_deepness_segmentor_writes_back_as_one():
    """to_props of a Deepness-read model states its defaults and stays a Deepness model (no schema key)."""
    meta = ModelMetadata.from_props(dict(DEEPNESS_PROPS, seg_thresh="0.6", author='"lab"'))
    props = meta.to_props()
    assert "birdseye_schema_version" not in props and json.loads(props["default_threshold"]) == 0.6
    assert props["seg_thresh"] == "0.6" and props["author"] == '"lab"'
    assert ModelMetadata.from_props(props) == meta


def test_a_background_target_segmentor_gives_its_target_channel():
    two = ["n", 2, 512, 512]
    meta = ModelMetadata.from_props(DEEPNESS_PROPS | {"class_names": json.dumps({"0": "background", "1": "nest"})},
                                    ["n", 3, 512, 512], two)
    assert meta.output_channel == 1 and meta.class_names == ("background", "nest")
    unnamed = {k: v for k, v in DEEPNESS_PROPS.items() if k != "class_names"}
    assert ModelMetadata.from_props(unnamed, None, two).class_names == ("background", "target")
    # Without a shape, Deepness's one name per output channel tells.
    assert ModelMetadata.from_props(DEEPNESS_PROPS | {"class_names": json.dumps(["bg", "nest"])}).output_channel == 1
    assert any("names 1 classes for 2 output channel(s)" in p for p in validate(DEEPNESS_PROPS, None, two))
    # A BirdsEye model stays one channel.
    assert any("has 2 channels" in p for p in validate(demo_metadata(tile_size=512).to_props(), None, two))


def test_what_cannot_cross_from_deepness_is_refused_clearly():
    four = {"0": "water", "1": "forest", "2": "field", "3": "road"}
    problems = validate(DEEPNESS_PROPS | {"class_names": json.dumps(four)}, ["n", 3, 512, 512], ["n", 4, 512, 512])
    assert problems == ["the model segments 4 classes (water, forest, field, road); BirdsEye detects one target: "
                        "it reads a Deepness segmentor with one output channel (the target) or two (background, "
                        "target)"]
    problems = validate(DEEPNESS_PROPS | {"model_type": '"Detector"', "det_conf": "0.3"})
    assert len(problems) == 1 and "YOLO-style boxes" in problems[0] and "gives no heatmap" in problems[0]
    problems = validate(DEEPNESS_PROPS | {"model_type": '"Regressor"'})
    assert len(problems) == 1 and "measured quantity, not a probability" in problems[0]
    assert "missing key(s): birdseye_schema_version, output_kind, default_threshold" in problems[0]
    problems = validate({k: v for k, v in DEEPNESS_PROPS.items() if k not in ("resolution", "tile_size")},
                        ["n", 3, "h", "w"])
    assert problems == ["missing key(s): resolution, tile_size (a Deepness model without it needs an input of "
                        "fixed height and width)"]
    assert any("4 channels" in p for p in validate(DEEPNESS_PROPS, ["n", 4, 512, 512]))


@pytest.mark.parametrize("key, value, message", [
    ("model_type", '"Superresolution"', "a heatmap model is"),
    ("tiles_overlap", "100", "'tiles_overlap' must be < 100"),
    ("tiles_overlap", "96", "leaves no tile core"),
    ("birdseye_schema_version", "7", "update the plugin"),
    ("output_kind", '"softmax"', "'output_kind' must be one of probability, logits"),
    ("tile_size", "64.5", "'tile_size' must be an integer"),
    ("resolution", "true", "'resolution' must be a number"),
    ("standardization_mean", "[0.5, 0.5]", "has 2 values but 'standardization_std' has 3"),
])
def test_single_problems_name_the_key(key, value, message):
    props = demo_metadata(tile_size=8).to_props()
    props[key] = value
    problems = validate(props, ["n", 3, 8, 8], ["n", 1, 8, 8])
    assert any(message in p for p in problems), problems


def test_shape_contradictions():
    props = demo_metadata().to_props()
    assert validate(props, ["n", 3, None, None], ["n", 1, None, None]) == []
    assert validate(props, ["n", 3, 64, 64], ["n", 64, 64]) == []
    assert any("4 input channels" in p or "has 4 channels" in p for p in validate(props, ["n", 4, 64, 64]))
    assert any("must have the input's size" in p for p in validate(props, ["n", 3, 64, 64], ["n", 1, 32, 32]))


def test_unreadable_file_is_an_input_error(tmp_path):
    path = tmp_path / "broken.onnx"
    path.write_bytes(np.arange(100, dtype=np.uint8).tobytes())
    with pytest.raises(InputError, match="broken.onnx"):
        read_onnx_metadata(path)


def test_the_bundled_model_carries_valid_metadata_and_its_card_figures():
    import hashlib
    from pathlib import Path

    models = Path(__file__).resolve().parents[3] / "models"
    path = models / "birdseye_demo_heatmap.onnx"
    meta = read_onnx_metadata(path)
    assert meta.output_kind == "probability" and meta.class_names == ("burrow",)
    assert "SIMULATED" in meta.description and path.stat().st_size < 5_000_000
    # The recorded figures belong to this very file, and meet the goal of recalling 80 % of in-view targets.
    report = json.loads((models / "birdseye_demo_heatmap.training.json").read_text())
    assert report["model"]["sha256"] == hashlib.sha256(path.read_bytes()).hexdigest()
    assert {k: json.loads(v) for k, v in meta.to_props().items()} == report["model"]["metadata"]
    assert report["validation"]["threshold"] == meta.default_threshold
    assert report["validation"]["at_default_threshold"]["truth_recall"] >= 0.8
