"""`make demo`, reduced: scripts/demo.py --size small runs the whole chain (simulate → import → labels →
detect with the bundled model → cluster → evaluate → plan → sensor bound) in seconds, and what it
leaves must be what a user opens: a project whose layers are valid, styled, grouped and found again
after the folder is moved, drawn over a farm map of the three fields side by side, the reports beside
it, and a summary whose figures agree with the files.

The demo runs once for the module (a subprocess, as `make demo` runs it); the failure tests start it
again with a broken input and check that it stops loudly.
"""
from __future__ import annotations

import importlib.util
import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
DEMO = REPO_ROOT / "scripts" / "demo.py"
PYTHON = sys.executable  # the test venv's Python: the host's .venv, or a QGIS chroot's (scripts/qgis_chroot.sh)
STYLES = REPO_ROOT / "resources" / "styles"
GROUPS = ["survey", "flight", "labels", "detections", "clusters", "plan", "farm map"]
FLIGHT_KEYS = {"train1": "training flight 1", "train2": "training flight 2", "heldout": "held-out flight"}
FLIGHT_TAGS = {"train1": "training 1", "train2": "training 2", "heldout": "held-out"}
# Each output file of the demo and the style its algorithm gives it.
EXPECTED_STYLE = {
    "geotags_train1": "geotags.qml", "geotags_train2": "geotags.qml", "geotags_heldout": "geotags.qml",
    "frames_train1": "frames.qml", "frames_train2": "frames.qml", "frames_heldout": "frames.qml",
    "track_train1": "track.qml", "track_train2": "track.qml", "track_heldout": "track.qml",
    "frames_labelled_train1": "frames.qml", "frames_labelled_train2": "frames.qml",
    "geotags_seen_train1": "geotags.qml", "geotags_seen_train2": "geotags.qml",
    "detections": "detections.qml", "clusters": "clusters.qml", "cluster_points": "cluster_points.qml",
    "detections_mosaic": "detections.qml", "mosaic_changes": "changes.qml",
    "waypoints": "waypoints.qml", "route": "route.qml", "partitions": "partitions.qml",
}
EXPECTED_GROUP = {name: group for group, names in {
    "survey": ["geotags_train1", "geotags_train2", "geotags_heldout", "partitions"],
    "flight": ["frames_train1", "frames_train2", "frames_heldout", "track_train1", "track_train2", "track_heldout"],
    "labels": ["frames_labelled_train1", "frames_labelled_train2", "geotags_seen_train1", "geotags_seen_train2"],
    "detections": ["detections", "detections_mosaic", "mosaic_changes"],
    "clusters": ["clusters", "cluster_points"], "plan": ["waypoints", "route"],
}.items() for name in names}

pytestmark = pytest.mark.slow


def run_demo(out: Path, *extra: str, timeout: float = 240) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k not in {"QGIS_CUSTOM_CONFIG_PATH", "PYTHONPATH"}}
    env["QT_QPA_PLATFORM"] = "offscreen"
    return subprocess.run([str(PYTHON), str(DEMO), "--out", str(out), "--size", "small", *extra], cwd=REPO_ROOT,
                          env=env, capture_output=True, text=True, timeout=timeout, check=False)


@pytest.fixture(scope="module")
def demo(tmp_path_factory) -> dict:
    out = tmp_path_factory.mktemp("demo") / "birdseye-demo"
    result = run_demo(out)
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-4000:]
    return {"out": out, "stdout": result.stdout,
            "summary": json.loads((out / "demo_summary.json").read_text(encoding="utf-8"))}


def source_stem(layer) -> str:
    return Path(layer.source().split("|")[0]).stem


def is_vector(layer) -> bool:
    from birdseye.birdseye_qgis.qgis_enums import LAYER_VECTOR

    return layer.type() == LAYER_VECTOR


def is_web_basemap(layer) -> bool:
    return layer.providerType() == "wms" and "type=xyz" in layer.source()


def orthomosaics(project) -> dict:
    """Flight key → its field's orthomosaic layer (read from campaigns/<key>/orthomosaic.tif)."""
    return {Path(layer.source()).parent.name: layer for layer in project.mapLayers().values()
            if not is_vector(layer) and Path(layer.source()).name == "orthomosaic.tif"}


def load_demo_script():
    spec = importlib.util.spec_from_file_location("birdseye_demo_script", DEMO)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


def open_project(path: Path):
    from qgis.core import QgsProject

    project = QgsProject()
    assert project.read(str(path)), project.error()
    return project


def renderer_signature(element) -> tuple:
    """Renderer type, its classification field and the colour of each symbol's first layer (r, g, b, a).

    QGIS 3.22 writes a colour as ``r,g,b,a``; 3.40 appends the same colour at full precision
    (``r,g,b,a,rgb:…``), so only the leading 8-bit components are compared.
    """
    colours = [tuple(int(c) for c in opt.get("value").split(",")[:4]) for sym in element.iter("symbol")
               for layer in sym.findall("layer")[:1]
               for opt in layer.iter("Option") if opt.get("name") == "color"]
    return element.get("type"), element.get("attr"), tuple(colours)


def test_summary_screen(demo):
    stdout = demo["stdout"]
    assert "BirdsEye demo finished" in stdout
    for figure in ("frames", "Farm map", "labels in", "Detections", "Clusters", "recall_pre", "gmcf_pre", "route",
                   "Sensor bound at 10 m", "birdseye_demo.qgz"):
        assert figure in stdout, figure
    screen = stdout[stdout.rindex("=" * 78, 0, stdout.rindex("=" * 78)):]
    assert len(screen.splitlines()) <= 24, "the summary must fit one screen"
    as_for_a_user = screen.replace(str(demo["out"]), "birdseye-demo")  # make demo's folder, not pytest's
    assert max(len(line) for line in as_for_a_user.splitlines()) <= 100, "and a terminal's width"
    for step in range(1, 21):
        assert f"[{step}/20]" in stdout  # progress names every step


def test_project_layers_valid_grouped_and_styled(qgis_app, demo):
    project = open_project(demo["out"] / "birdseye_demo.qgz")
    root = project.layerTreeRoot()
    assert [g.name() for g in root.children()] == GROUPS
    layers = [layer for layer in project.mapLayers().values() if is_vector(layer)]
    assert sorted(source_stem(layer) for layer in layers) == sorted(EXPECTED_STYLE)
    for layer in layers:
        stem = source_stem(layer)
        assert layer.isValid(), layer.name()
        assert root.findLayer(layer.id()).parent().name() == EXPECTED_GROUP[stem], stem
        style = ET.parse(STYLES / EXPECTED_STYLE[stem]).getroot().find("renderer-v2")
        from qgis.PyQt.QtXml import QDomDocument

        doc = QDomDocument()
        layer.exportNamedStyle(doc)
        applied = ET.fromstring(doc.toString()).find("renderer-v2")
        assert renderer_signature(applied) == renderer_signature(style), f"{stem} is not styled by {style}"
    # Points are drawn over lines over polygons, whatever their group; the maps under them all.
    drawn = root.customLayerOrder()
    vectors_first = [is_vector(layer) for layer in drawn]
    assert root.hasCustomLayerOrder() and vectors_first == sorted(vectors_first, reverse=True)
    order = [layer.geometryType() for layer in drawn if is_vector(layer)]
    assert order == sorted(order)


def test_layer_names_are_short_unique_and_name_their_flight(qgis_app, demo):
    """"<kind> · <flight>": unique, short enough for the Layers panel, telling the flights apart early."""
    project = open_project(demo["out"] / "birdseye_demo.qgz")
    names = {source_stem(layer): layer.name() for layer in project.mapLayers().values() if is_vector(layer)}
    assert len(set(names.values())) == len(names), sorted(names.values())
    assert max(len(name) for name in names.values()) <= 24, names
    for key, tag in FLIGHT_TAGS.items():
        assert names[f"geotags_{key}"] == f"Geotags · {tag}"
        assert names[f"frames_{key}"] == f"Frames · {tag}"
        assert names[f"track_{key}"] == f"Flight line · {tag}"
    assert names["detections"] == "Detections · held-out" and names["clusters"] == "Clusters · held-out"


def test_the_map_opens_readable(qgis_app, demo):
    """The survey drawn over the waypoints and detections on its geotags; the legends of what the map shows
    open, groups of hidden layers closed."""
    project = open_project(demo["out"] / "birdseye_demo.qgz")
    root = project.layerTreeRoot()
    drawn = [source_stem(layer) for layer in root.customLayerOrder() if is_vector(layer)]
    assert drawn.index("geotags_heldout") < drawn.index("waypoints") < drawn.index("detections") \
        < drawn.index("clusters") < drawn.index("frames_heldout"), drawn
    by_stem = {source_stem(layer): root.findLayer(layer.id()) for layer in project.mapLayers().values()}
    opened = sorted(stem for stem, node in by_stem.items() if node.isExpanded() and is_vector(node.layer()))
    assert opened == ["clusters", "detections", "geotags_heldout"]
    assert not root.findGroup("labels").isExpanded() and root.findGroup("survey").isExpanded()


def test_expected_simulation_warnings_are_notes(demo):
    """The RTK-float episode and altimeter dropouts the simulator makes on purpose read as notes saying why;
    no other warning appears in a normal run."""
    lines = demo["stdout"].splitlines()
    assert any("note:" in line and "no RTK fixed solution" in line and "(expected: " in line for line in lines)
    assert not [line for line in lines if line.strip().startswith("warning:")], "a normal run warns"
    assert "Axes3D" not in demo["stdout"]


def test_an_unexpected_warning_stays_a_warning(qgis_app, capsys):
    script = load_demo_script()
    feedback = script.TerminalFeedback.create(script.FLIGHT_LOG_EXPECTED)
    feedback.pushWarning("18 frame(s) have no RTK fixed solution; kept and flagged rtk_float / rtk_none")
    feedback.pushWarning("the DEM does not cover 3 frame(s)")
    printed = capsys.readouterr().out.splitlines()
    assert printed[0].startswith("    note: 18 frame(s) have no RTK fixed solution") and "(expected: " in printed[0]
    assert printed[1] == "    warning: the DEM does not cover 3 frame(s)"


def test_the_orthomosaics_are_the_farm_map_under_the_survey(qgis_app, demo):
    """Each field's orthomosaic, shown, in the farm map group at the bottom of the legend and drawn below
    every vector layer; the online basemap below them, hidden, so the project draws offline."""
    project = open_project(demo["out"] / "birdseye_demo.qgz")
    root = project.layerTreeRoot()
    maps = orthomosaics(project)
    assert sorted(maps) == sorted(FLIGHT_KEYS)
    farm = root.findGroup("farm map")
    assert root.children()[-1] == farm, "the farm map is the legend's last group: drawn first"
    for key, layer in maps.items():
        node = root.findLayer(layer.id())
        assert layer.isValid() and layer.bandCount() == 4, key
        assert node.parent() == farm and node.isVisible(), key
        assert layer.name() == f"Mosaic · {FLIGHT_TAGS[key]}"
        assert layer.crs() == project.crs()
    basemaps = [layer for layer in project.mapLayers().values() if is_web_basemap(layer)]
    assert len(basemaps) == 1 and "openstreetmap.org" in basemaps[0].source()
    assert root.findLayer(basemaps[0].id()).parent() == farm
    assert not root.findLayer(basemaps[0].id()).isVisible(), "online tiles must not be needed to draw"
    drawn = root.customLayerOrder()
    assert drawn[-1] == basemaps[0]
    survey = [layer for layer in drawn if root.findLayer(layer.id()).parent().name() == "survey"]
    assert max(drawn.index(layer) for layer in survey) < min(drawn.index(layer) for layer in maps.values())
    # The project opens on the whole farm.
    view = project.viewSettings().defaultViewExtent()
    for layer in maps.values():
        assert view.contains(layer.extent()), layer.name()


def test_the_three_flights_have_their_own_fields_side_by_side(qgis_app, demo):
    """The fields' maps do not overlap, lie west to east in the flights' order, and each flight's frames
    and flight line stay over its own field."""
    project = open_project(demo["out"] / "birdseye_demo.qgz")
    maps = orthomosaics(project)
    by_stem = {source_stem(layer): layer for layer in project.mapLayers().values() if is_vector(layer)}
    keys = list(FLIGHT_KEYS)
    for i, a in enumerate(keys):
        for b in keys[i + 1:]:
            assert not maps[a].extent().intersects(maps[b].extent()), f"the fields of {a} and {b} overlap"
    assert [maps[k].extent().xMinimum() for k in keys] == sorted(maps[k].extent().xMinimum() for k in keys)
    for key in keys:
        for stem in (f"frames_{key}", f"track_{key}"):
            assert maps[key].extent().contains(by_stem[stem].extent()), f"{stem} leaves its field"


@pytest.mark.parametrize("size", ["full", "small"])
def test_the_demo_fields_are_apart_at_every_size(size, tmp_path):
    """The layout itself, for the full demo too (its flights simulated without frames): each field's
    simulated ground — everything its frames see, which its map covers — clear of its neighbours'."""
    from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame, ProjectedCRS
    from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, parse_sigmas, simulate_campaign

    script = load_demo_script()
    boxes = []
    for step in script.build_steps(script.SIZES[size], None)[:len(FLIGHT_KEYS)]:
        params = {k.lower(): v for k, v in step.params.items() if k != "OUTPUT_FOLDER"}
        params["sigmas"] = parse_sigmas(params["sigmas"])
        folder = tmp_path / step.name
        simulate_campaign(CampaignConfig(**params, render=False), folder)
        record = json.loads((folder / "truth" / "campaign.json").read_text(encoding="utf-8"))
        e0, e1, n0, n1 = record["field"]["domain_m"]
        local = LocalFrame(*(record["local_frame"][k] for k in ("lat0", "lon0", "h0")))
        lat, lon, _ = local.to_geodetic([[e0, n0, 0.0], [e1, n0, 0.0], [e1, n1, 0.0], [e0, n1, 0.0]])
        x, _ = ProjectedCRS(record["crs"]).from_geodetic(lat, lon)
        boxes.append((x.min(), x.max()))
    for (_, west_end), (east_start, _) in zip(boxes, boxes[1:]):
        assert east_start - west_end > 1.0, f"less than a metre of track between two {size} demo fields"


def test_project_opens_after_the_folder_is_moved(qgis_app, demo, tmp_path):
    moved = tmp_path / "somewhere" / "else"
    shutil.copytree(demo["out"], moved)
    project = open_project(moved / "birdseye_demo.qgz")
    assert project.mapLayers()
    for layer in project.mapLayers().values():
        assert layer.isValid(), layer.name()
        if not is_web_basemap(layer):
            assert Path(layer.source().split("|")[0]).resolve().is_relative_to(moved.resolve()), layer.source()


def test_reports_and_files_beside_the_project(demo):
    out = demo["out"]
    for name in ("evaluation.html", "evaluation.json", "sensor_bound.html", "sensor_bound.json"):
        assert (out / name).stat().st_size > 0, name
    assert "<html" in (out / "evaluation.html").read_text(encoding="utf-8").lower()
    for name in ("mission.kmz", "mission.plan", "mission_litchi.csv", "mission.kml"):
        assert (out / "plan" / name).stat().st_size > 0, name
    for key in ("train1", "train2"):
        labels = out / "labels" / key
        assert (labels / "labels.csv").is_file()
        assert any(labels.rglob("*.png")), f"no label rasters or tiles for {key}"


def test_summary_figures_agree_with_the_outputs(qgis_app, demo):
    """Counted again from the layers and reports the demo wrote, independently of its own bookkeeping."""
    out, figures = demo["out"], demo["summary"]
    project = open_project(out / "birdseye_demo.qgz")
    by_stem = {source_stem(layer): layer for layer in project.mapLayers().values()}
    for key, count in figures["frames"].items():
        assert by_stem[f"frames_{key}"].featureCount() == count > 0
    for key, layer in orthomosaics(project).items():
        assert [layer.width(), layer.height()] == figures["orthomosaics"][key]["size_px"]
    for key, count in figures["geotags"].items():
        assert by_stem[f"geotags_{key}"].featureCount() == count > 0
    for key, count in figures["labels"].items():
        rows = (out / "labels" / key / "labels.csv").read_text(encoding="utf-8").splitlines()
        assert len(rows) - 1 == count
    assert by_stem["detections"].featureCount() == figures["detections"]
    assert by_stem["clusters"].featureCount() == figures["clusters"]
    evaluation = json.loads((out / "evaluation.json").read_text(encoding="utf-8"))
    assert figures["n_in_view"] == evaluation["n_in_view"] and figures["n_recovered"] == evaluation["n_recovered"]
    assert figures["n_in_view"] > 0, "no geotag in view of the held-out flight: the recall below was not checked"
    assert figures["recall_pre"] == pytest.approx(figures["n_recovered"] / figures["n_in_view"])
    route = next(by_stem["route"].getFeatures()).geometry().length()
    assert figures["route_length_m"] == pytest.approx(route, rel=0.02)
    bound = json.loads((out / "sensor_bound.json").read_text(encoding="utf-8"))
    assert [a["verdict_exact"] for a in figures["sensor_bound"]] == [a["verdict_exact"] for a in bound["altitudes"]]
    # Frames against the held-out field's orthomosaic: the comparison's own JSON, over one set of geotags.
    assert by_stem["detections_mosaic"].featureCount() == figures["mosaic_detections"] > 0
    comparison = json.loads((out / "frames_vs_mosaic.json").read_text(encoding="utf-8"))
    frames, mosaic = comparison["before"], comparison["after"]
    assert frames["n_in_view"] == mosaic["n_in_view"] > 0
    assert figures["frames_vs_mosaic"]["recall_pre"] == [pytest.approx(frames["recall_pre"]),
                                                         pytest.approx(mosaic["recall_pre"])]
    assert mosaic["recall_pre"] >= MIN_RECALL_SMALL, "the bundled model finds the targets on the mosaic too"


# The small demo's floor on recall. Its held-out field holds 6 geotags (4 m × 3 m = 12 m²); a cluster
# recovers a geotag within EPS_PRED_M = 0.20 m, a disc of π·0.2² = 0.126 m². The run makes 8 clusters,
# which placed at random would cover 8 × 0.126 / 12 ≈ 8 % of the field: chance recovers each geotag with
# p ≈ 0.08, and 3 or more of 6 with probability C(6,3)·0.08³·0.92³ + … ≈ 1 %. The bundled model recovers
# 3 of 6 (0.5, also before this session's changes); 2 of 6 (what a detector firing at random might reach)
# fails.
MIN_RECALL_SMALL = 0.5


def test_the_detector_finds_the_targets_in_view(demo):
    """The chain must actually detect: frames processed, detections, clusters, geotags in view, and a
    recall a detector firing at random would not reach. Zero of any of them fails, saying which."""
    figures = demo["summary"]
    held_out = next(key for key, title in FLIGHT_KEYS.items() if title == figures["held_out"])
    assert figures["frames_detected"] == figures["frames"][held_out] > 0, (
        f"Detect processed {figures['frames_detected']} of the {figures['frames'][held_out]} held-out frames")
    assert figures["detections"] > 0, "the bundled model detected nothing on the held-out flight"
    assert figures["clusters"] > 0, f"{figures['detections']} detections formed no cluster"
    # The held-out flight covers its whole field, so every geotag of it is in view of some frame.
    assert figures["n_in_view"] == figures["geotags"][held_out] > 0, (
        f"{figures['n_in_view']} of the {figures['geotags'][held_out]} held-out geotags in view")
    assert figures["n_recovered"] / figures["n_in_view"] >= MIN_RECALL_SMALL, (
        f"recall {figures['n_recovered']}/{figures['n_in_view']} is below the floor {MIN_RECALL_SMALL} "
        f"({figures['detections']} detections, {figures['clusters']} clusters, {figures['hit_clusters']} on a geotag)")
    assert 0 < figures["hit_clusters"] <= figures["clusters"]


def test_missing_model_stops_before_anything_runs(tmp_path):
    missing = tmp_path / "no_such_model.onnx"
    result = run_demo(tmp_path / "out", "--model", str(missing), timeout=120)
    assert result.returncode != 0
    assert str(missing) in result.stderr and "FAILED" in result.stderr
    assert not (tmp_path / "out").exists(), "nothing may be simulated before the check"


def test_failing_step_stops_the_demo_with_a_clear_message(tmp_path):
    broken = tmp_path / "broken.onnx"
    broken.write_bytes(b"this is not an ONNX model")
    result = run_demo(tmp_path / "out", "--model", str(broken))
    assert result.returncode != 0
    assert "FAILED" in result.stderr and "birdseye:detect" in result.stderr
    assert "[13/16]" not in result.stdout, "steps after the failed one must not run"
    assert not (tmp_path / "out" / "birdseye_demo.qgz").exists()


def test_refuses_to_wipe_a_folder_that_is_not_a_demo(tmp_path):
    precious = tmp_path / "thesis"
    precious.mkdir()
    (precious / "chapter1.tex").write_text("…")
    result = run_demo(precious, timeout=120)
    assert result.returncode != 0 and "not a BirdsEye demo folder" in result.stderr
    assert (precious / "chapter1.tex").is_file()
