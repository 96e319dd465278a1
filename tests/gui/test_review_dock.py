"""The review dock, headless (pytest-qgis iface, qtbot), over a small simulated campaign.

The campaign is simulated and imported with the importers; two detection layers ("checkpoints") are
made by projecting the simulator's true targets and look-alikes into the imported frames (so chips show
the real target under the circle) and back-projecting through the logged poses, as Detect would. Then
the dock is driven as a reviewer drives it — by keyboard — and what must follow is checked: every unit
judged, undo, an added target, the log's rows, the scores worked out by hand (the dock's and
``evaluatedetections``' on the same verdict table), resume after reopening the project, changed inputs
reported, chips with prefetch.
"""
from __future__ import annotations

import csv
import json
import shutil
import statistics
import threading
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsFeature,
    QgsField,
    QgsGeometry,
    QgsPoint,
    QgsPointXY,
    QgsProject,
    QgsVectorFileWriter,
    QgsVectorLayer,
)
from qgis.PyQt.QtCore import QPoint, Qt, QVariant

from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame, ProjectedCRS
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry
from birdseye.birdseye_qgis.core.geometry.projection import pixel_to_ground, project_in_view
from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign
from birdseye.birdseye_qgis.gui.review import dock as dock_module
from birdseye.birdseye_qgis.gui.review import jobs as jobs_module
from birdseye.birdseye_qgis.gui.review import widgets as widgets_module
from birdseye.birdseye_qgis.qgis_io.review_store import VERDICT_TABLE, VerdictStore

REPO_ROOT = Path(__file__).resolve().parents[2]
SCREENSHOT = REPO_ROOT / "build" / "screenshots" / "review_dock.png"
UTM = 32756
KEYS = {"confirmed_real": Qt.Key_1, "hard_negative": Qt.Key_2, "uncertain": Qt.Key_3}


def run(alg_id, params):
    import processing

    return processing.run(f"birdseye:{alg_id}", params)


# ---------------------------------------------------------------------------------------------- campaign
def read_truth(folder):
    targets = list(csv.DictReader(open(folder / "truth" / "targets.csv")))
    distractors = list(csv.DictReader(open(folder / "truth" / "distractors.csv")))
    return targets, distractors


def detections_of(points, groups, local, rng, score):
    """(frame_id, u, v, score, x, y, z) of every point in view of every frame: its projection with a
    detector's 2.5 px localisation noise (about 2.4 cm here), back-projected through the logged pose
    onto the frame's level ground."""
    lat = np.array([p[0] for p in points])
    lon = np.array([p[1] for p in points])
    h = np.array([p[2] for p in points])
    rows = []
    for poses in groups:
        geometry = FrameGeometry(poses, local)
        ground = LevelPlaneGround(geometry)
        proj = project_in_view(geometry, local.from_geodetic(lat, lon, h), ground, edge_buffer_px=3)
        uv = proj.uv + rng.normal(0, 2.5, proj.uv.shape)
        pts, ok = pixel_to_ground(geometry, ground, proj.frame_idx, uv)
        plat, plon, ph = local.to_geodetic(pts)
        x, y = ProjectedCRS(UTM).from_geodetic(plat, plon)
        for k in np.flatnonzero(ok):
            rows.append((int(poses.frame_id[proj.frame_idx[k]]), float(uv[k, 0]), float(uv[k, 1]),
                         float(score[proj.point_idx[k]]), float(x[k]), float(y[k]), float(ph[k])))
    return rows


def write_detection_layer(path, name, rows):
    layer = QgsVectorLayer(f"PointZ?crs=EPSG:{UTM}", name, "memory")
    layer.dataProvider().addAttributes([QgsField("frame_id", QVariant.Int), QgsField("u", QVariant.Double),
                                        QgsField("v", QVariant.Double), QgsField("score", QVariant.Double),
                                        QgsField("model", QVariant.String), QgsField("model_digest", QVariant.String),
                                        QgsField("threshold", QVariant.Double)])
    layer.updateFields()
    features = []
    for frame_id, u, v, score, x, y, z in rows:
        f = QgsFeature(layer.fields())
        f.setAttributes([frame_id, u, v, score, f"{name}.onnx", name * 4, 0.3])
        f.setGeometry(QgsGeometry(QgsPoint(x, y, z)))
        features.append(f)
    layer.dataProvider().addFeatures(features)
    options = QgsVectorFileWriter.SaveVectorOptions()
    options.driverName = "GPKG"
    options.layerName = name
    options.actionOnExistingFile = (QgsVectorFileWriter.CreateOrOverwriteLayer if Path(path).exists()
                                    else QgsVectorFileWriter.CreateOrOverwriteFile)
    error = QgsVectorFileWriter.writeAsVectorFormatV3(layer, str(path), QgsProject.instance().transformContext(),
                                                      options)
    assert error[0] == QgsVectorFileWriter.NoError, error


@pytest.fixture(scope="module")
def campaign(birdseye_provider, tmp_path_factory):
    """A simulated flight with geotags, frames and two detection layers, in GeoPackages."""
    from birdseye.birdseye_qgis.qgis_io.detections import read_pose_groups

    folder = tmp_path_factory.mktemp("review_campaign")
    cfg = CampaignConfig(seed=5, n_targets=6, field_width_m=8.0, field_length_m=6.0, image_width=480,
                         image_height=300, n_missed=1, n_spurious=1)
    simulate_campaign(cfg, folder)
    run("importgeotags", {"INPUT": str(folder / "geotags.csv"), "OUTPUT": str(folder / "geotags.gpkg")})
    run("importflightlog", {"POSE_LOG": str(folder / "poses.csv"), "IMAGES": str(folder / "frames"),
                            "CALIBRATION": str(folder / "calibration.yaml"), "OUTPUT": str(folder / "frames.gpkg")})
    frames = QgsVectorLayer(str(folder / "frames.gpkg"), "frames", "ogr")
    groups = read_pose_groups(frames)[0]
    local = LocalFrame.around(np.concatenate([g.lat for g in groups]), np.concatenate([g.lon for g in groups]),
                              np.concatenate([g.ground_height for g in groups]))
    targets, distractors = read_truth(folder)
    in_view = lambda pts: len(detections_of(pts, groups, local, np.random.default_rng(0), np.ones(len(pts))))
    real = [(float(t["lat"]), float(t["lon"]), float(t["h_ground"])) for t in targets]
    real = [p for p in real if in_view([p]) >= 4]
    fakes = [(float(d["lat"]), float(d["lon"]), 400.0) for d in distractors]
    fakes = [p for p in fakes if in_view([p]) >= 4][:3]
    assert len(real) >= 5 and len(fakes) == 3, (len(real), len(fakes))
    missed = real[0]                                   # no layer fires there: the reviewer adds it
    rng = np.random.default_rng(7)
    a_points = real[1:] + fakes[:2]
    b_points = real[2:] + fakes[1:]
    det = folder / "detections.gpkg"
    for name, points, (lo, hi) in (("model_a", a_points, (0.5, 0.95)), ("model_b", b_points, (0.4, 0.9))):
        write_detection_layer(det, name, detections_of(points, groups, local, rng, rng.uniform(lo, hi, len(points))))
    return SimpleNamespace(folder=folder, real=real[1:], fakes=fakes, missed=missed)


def copy_campaign(campaign, tmp_path):
    """The campaign's GeoPackages copied (each test keeps its own verdict log) and loaded."""
    for name in ("geotags.gpkg", "frames.gpkg", "detections.gpkg"):
        shutil.copy(campaign.folder / name, tmp_path / name)
    layers = SimpleNamespace(
        a=QgsVectorLayer(f"{tmp_path / 'detections.gpkg'}|layername=model_a", "model_a", "ogr"),
        b=QgsVectorLayer(f"{tmp_path / 'detections.gpkg'}|layername=model_b", "model_b", "ogr"),
        frames=QgsVectorLayer(str(tmp_path / "frames.gpkg"), "frames", "ogr"),
        geotags=QgsVectorLayer(str(tmp_path / "geotags.gpkg"), "geotags", "ogr"))
    for layer in vars(layers).values():
        assert layer.isValid()
    QgsProject.instance().addMapLayers(list(vars(layers).values()))
    return layers


@pytest.fixture
def clean_project(qgis_iface, qtbot):
    project = QgsProject.instance()
    project.clear()
    canvas = qgis_iface.mapCanvas()
    canvas.setDestinationCrs(QgsCoordinateReferenceSystem(f"EPSG:{UTM}"))
    canvas.resize(800, 600)
    canvas.show()
    qtbot.waitExposed(canvas)
    yield project
    project.clear()


@pytest.fixture
def make_dock(qgis_iface, qtbot):
    docks = []

    def make():
        dock = dock_module.ReviewDock(qgis_iface)
        dock.setFloating(True)
        dock.resize(460, 1340)
        dock.show()
        qtbot.waitExposed(dock)
        docks.append(dock)
        return dock

    yield make
    for dock in docks:
        dock.shutdown()
        dock.close()
        dock.deleteLater()


def start(dock, layers, detection_layers=None, store=None):
    dock.set_inputs(detection_layers or [layers.a, layers.b], layers.frames, layers.geotags, store)
    assert dock.start_review(), dock.banner.text()
    dock.panel.setFocus()


def wait_chips(qtbot, dock, key=None):
    key = key or dock.current_key
    qtbot.waitUntil(lambda: dock.chips_shown_for == key, timeout=10000)


def wait_scores(qtbot, dock):
    qtbot.waitUntil(lambda: not dock._score_timer.isActive() and
                    dock._shown_score_generation == dock._score_generation, timeout=20000)
    assert dock.scores_error is None and dock.scores


def nearest(points, lat, lon):
    d = [np.hypot((p[0] - lat) * 111320, (p[1] - lon) * 98700) for p in points]
    return int(np.argmin(d)), float(min(d))


def truth_verdict(campaign, dock, key):
    i = dock.units.index[key]
    lat, lon = dock.units.lat[i], dock.units.lon[i]
    k_real, d_real = nearest(campaign.real, lat, lon)
    k_fake, d_fake = nearest(campaign.fakes, lat, lon)
    assert min(d_real, d_fake) < 0.1, "every unit lies on a simulated target or look-alike"
    return "confirmed_real" if d_real < d_fake else "hard_negative"


# ---------------------------------------------------------------------------------------------- the review
def test_a_whole_review_by_keyboard(campaign, clean_project, make_dock, qtbot, qgis_iface, tmp_path):
    layers = copy_campaign(campaign, tmp_path)
    dock = make_dock()
    start(dock, layers)
    store_path = tmp_path / "detections.gpkg"          # default: the first detection layer's GeoPackage
    assert Path(dock.session.store.path) == store_path
    assert not dock.propagate_check.isChecked()          # propagation is off by default
    units = dock.units
    assert len(units) == len(campaign.real) + len(campaign.fakes)
    # model_a alone: the first real target and the first look-alike; model_b alone: the last look-alike.
    assert sorted(map(tuple, units.layers_fired)) == sorted(
        [("model_a",)] * 2 + [("model_a", "model_b")] * len(campaign.real) + [("model_b",)])
    # Unmatched units come first.
    matched = [bool(units.matched[units.index[k]]) for k in dock.entries]
    assert matched == sorted(matched) and not matched[0] and matched[-1]
    assert dock.banner.isHidden()
    wait_scores(qtbot, dock)                            # before any verdict: POST = PRE, c = a = 0
    before = json.loads(json.dumps(dock.scores))
    # By hand, from the campaign (seed 5): 6 geotags, all in view (targets 1, 2, 4, 5, 6 surveyed, target 3
    # not, and one spurious geotag with no target); model_a fires at targets 2–6 and look-alikes 0, 1: 7
    # clusters, 4 on a geotag (target 3 has none within 0.2 m) → recall 4/6, GMCF 4/7; model_b at targets
    # 3–6 and look-alikes 1, 2: 6 clusters, 3 hits → recall 3/6, GMCF 3/6.
    assert {name: (d["n_recovered"], d["n_in_view"], d["n_hit_clusters"], d["n_clusters"])
            for name, d in before.items()} == {"model_a": (4, 6, 4, 7), "model_b": (3, 6, 3, 6)}
    assert (before["model_a"]["recall_pre"], before["model_a"]["gmcf_pre"]) == pytest.approx((4 / 6, 4 / 7))
    assert (before["model_b"]["recall_pre"], before["model_b"]["gmcf_pre"]) == pytest.approx((3 / 6, 3 / 6))
    for d in before.values():
        assert {(p["c"], p["a"], p["gmcf_post"]) for p in d["post"].values()} == {(0, 0, d["gmcf_pre"])}

    wait_chips(qtbot, dock)
    decided = {}
    mistake_done = False
    while True:
        key = dock.current_key
        verdict = truth_verdict(campaign, dock, key)
        if key == dock.entries[2]:
            verdict = "uncertain"
        if not mistake_done and verdict == "confirmed_real":
            # A slip of the finger, undone: the log gets the row and its undo, the unit is unreviewed.
            qtbot.keyClick(dock.panel, Qt.Key_2)
            assert dock.session.ledger.direct(key) == "hard_negative" and dock.current_key != key
            qtbot.keyClick(dock.panel, Qt.Key_Z, Qt.ControlModifier)
            assert dock.current_key == key and dock.session.ledger.direct(key) == "unreviewed"
            mistake_done = True
        # A reviewer looks at the chips before deciding; moving on must show the next chips at once.
        nxt = dock._neighbour(key, +1)
        if nxt is not None:
            qtbot.waitUntil(lambda: nxt in dock.chip_loader.chips, timeout=10000)
        qtbot.keyClick(dock.panel, KEYS[verdict])
        decided[key] = verdict
        if nxt is None:
            break
        assert dock.current_key == nxt
        wait_chips(qtbot, dock)
    assert mistake_done
    assert set(decided) == set(units.keys)
    for key, verdict in decided.items():
        assert dock.status(key).direct == verdict
    assert "of {n} units reviewed".format(n=len(units)) in dock.progress_label.text()
    assert f"{len(units)} of {len(units)} units reviewed" in dock.progress_label.text()

    # Every move showed its chips. The latency is printed for benchmarks/bench_review_chips.py, which holds
    # its goal; a test asserts no time.
    latencies = dock.chip_latencies_ms[1:]
    assert len(latencies) >= len(units) - 1
    print(f"\nchip latency with prefetch: median {statistics.median(latencies):.1f} ms, "
          f"max {max(latencies):.1f} ms over {len(latencies)} moves")

    # Add the target no layer detected: A, then a click on the map where it is.
    canvas = qgis_iface.mapCanvas()
    qtbot.keyClick(dock.panel, Qt.Key_A)
    assert canvas.mapTool() is dock._tool
    mlat, mlon, _ = campaign.missed
    x, y = ProjectedCRS(UTM).from_geodetic(np.array([mlat]), np.array([mlon]))
    canvas.setCenter(QgsPointXY(float(x[0]), float(y[0])))
    canvas.zoomScale(100)
    pixel = canvas.getCoordinateTransform().transform(QgsPointXY(float(x[0]), float(y[0])))
    qtbot.mouseClick(canvas.viewport(), Qt.LeftButton, Qt.NoModifier, QPoint(round(pixel.x()), round(pixel.y())))
    added = dock.session.ledger.added_targets()
    assert len(added) == 1 and canvas.mapTool() is not dock._tool
    assert nearest([campaign.missed], added[0].lat, added[0].lon)[1] < 0.05   # 1:100, 1 px ≈ 2.6 cm
    assert dock.entries[-1] == added[0].key

    # The log: append-only rows, complete, one action per verdict, the undo naming its action.
    store = VerdictStore(store_path, create=False)
    rows = store.rows()
    assert len(rows) == len(units) + 2 + 1
    undo = [r for r in rows if r["action"] == "undo"]
    assert len(undo) == 1 and undo[0]["verdict"] == "unreviewed" and undo[0]["undoes"] == undo[0]["action_id"] - 1
    assert all(r["reviewer"] and r["time"].endswith("Z") and json.loads(r["input_digests"]) for r in rows)
    assert [r["time"] for r in rows] == sorted(r["time"] for r in rows)
    with pytest.raises(Exception, match="append-only"):
        store.connection.execute(f"DELETE FROM {VERDICT_TABLE}")
    assert store.integrity_check() == "ok"
    store.close()
    # On the map: the verdict layer shows each unit's current verdict and the added target.
    layer = dock.verdict_layer
    assert layer is not None and QgsProject.instance().mapLayer(layer.id()) is layer
    qtbot.waitUntil(lambda: layer.featureCount() == len(units) + 1, timeout=5000)
    shown = {f["unit_key"]: f["verdict"] for f in layer.getFeatures()}
    assert shown == {**decided, added[0].key: "added"}

    # Scores after the review, by hand: both layers fired at target 3, which nobody surveyed and the
    # reviewer confirmed, so c = 1; the added target 1 has its geotag within 0.2 m, so a = 0 (n_in_view
    # counts it already); the look-alikes are hard negatives or uncertain and change nothing. Under every
    # convention: model_a GMCF (4 + 1)/7 = 5/7, recall ≥ (4 + 1)/(6 + 1 + 0) = 5/7; model_b GMCF
    # (3 + 1)/6 = 4/6, recall ≥ (3 + 1)/(6 + 1) = 4/7. evaluatedetections on the same verdict table must
    # give the same figures.
    wait_scores(qtbot, dock)
    review = QgsVectorLayer(f"{store_path}|layername={VERDICT_TABLE}", "verdicts", "ogr")
    assert review.isValid() and review.featureCount() == len(rows)
    by_hand = {"model_a": (5 / 7, 5 / 7, "≥ 0.714"), "model_b": (4 / 6, 4 / 7, "≥ 0.571")}
    for layer in (layers.a, layers.b):
        out = tmp_path / f"scores_{layer.name()}.json"
        run("evaluatedetections", {"DETECTIONS": [layer], "GEOTAGS": layers.geotags, "FRAMES": [layers.frames],
                                   "REVIEW": review, "OUTPUT_JSON": str(out), "OUTPUT_REPORT": None})
        gmcf, recall, shown = by_hand[layer.name()]
        for scores in (dock.scores[layer.name()], json.loads(out.read_text())):
            for convention, post in scores["post"].items():
                assert (post["c"], post["a"]) == (1, 0), convention
                assert post["gmcf_post"] == pytest.approx(gmcf) and post["recall_post_value"] == pytest.approx(recall)
                assert post["recall_post"] == shown, convention
    # … and they are what the verdicts say: c = confirmed units a layer fired at with no geotag near;
    # a = 0, since the target the reviewer added was surveyed (n_in_view counts it already): a counts
    # only added targets where no cluster fired and no geotag lies within EPS_PRED.
    missed = min(read_truth(campaign.folder)[0],
                 key=lambda t: nearest([campaign.missed], float(t["lat"]), float(t["lon"]))[1])
    assert missed["surveyed"] == "1"
    for name in ("model_a", "model_b"):
        c = sum(1 for k in units.keys if decided[k] == "confirmed_real" and not units.matched[units.index[k]]
                and name in units.layers_fired[units.index[k]])
        for convention in ("positive_wins", "majority_wins", "hard_negative_wins"):
            post = dock.scores[name]["post"][convention]
            assert (post["c"], post["a"]) == (c, 0)
    assert dock.scores_table.item(0, 0).text() == "model_a" and "≥" in dock.scores_table.item(1, 2).text()
    assert dock.scores["model_a"]["post"]["positive_wins"]["gmcf_post"] > before["model_a"]["gmcf_pre"]

    # Screenshot of a matched unit with its chips.
    dock.go_to(dock.entries[len(dock.entries) - 2])
    wait_chips(qtbot, dock)
    qtbot.wait(50)
    SCREENSHOT.parent.mkdir(parents=True, exist_ok=True)
    assert dock.grab().save(str(SCREENSHOT))


def test_a_log_beside_the_detections_shows_on_the_map_and_the_detections_stay_readable(campaign, clean_project,
                                                                                       make_dock, qtbot, tmp_path):
    """The default log goes into the detections' GeoPackage, which QGIS holds open since before the verdict
    table existed; the layers of that file are reopened (review_store.open_store). Without that, the real
    desktop fails to open the verdict layer ("Cannot reopen …: Cannot find layer birdseye_verdicts"), which
    tests/gui/test_docks_desktop.py checks in QGIS's log; here: the verdict layer works and the reopened
    detection layers are intact."""
    from qgis.core import QgsApplication

    messages = []

    def collect(message, tag, level):
        messages.append(f"{tag}: {message}")

    QgsApplication.messageLog().messageReceived.connect(collect)
    try:
        layers = copy_campaign(campaign, tmp_path)
        counts = (layers.a.featureCount(), layers.b.featureCount())
        dock = make_dock()
        start(dock, layers)
        assert Path(dock.session.store.path) == tmp_path / "detections.gpkg"
        dock.run_command("confirmed_real")
        layer = dock.verdict_layer
        qtbot.waitUntil(lambda: layer.featureCount() == 1, timeout=5000)
        assert layer.isValid() and [f["verdict"] for f in layer.getFeatures()] == ["confirmed_real"]
        assert (layers.a.isValid(), layers.b.isValid()) == (True, True)
        assert (layers.a.featureCount(), layers.b.featureCount()) == counts
    finally:
        QgsApplication.messageLog().messageReceived.disconnect(collect)
    assert not [m for m in messages if VERDICT_TABLE in m], messages


def test_the_default_log_follows_the_layers_and_a_chosen_one_stays(campaign, clean_project, make_dock, tmp_path):
    """The log path the dock filled in for one review's layers is a default, not a choice: a review of layers in
    another GeoPackage writes into that one, not into the first review's file. A path the user chose stays."""
    layers = copy_campaign(campaign, tmp_path)
    shutil.copy(tmp_path / "detections.gpkg", tmp_path / "other.gpkg")
    other = QgsVectorLayer(f"{tmp_path / 'other.gpkg'}|layername=model_b", "model_b_other", "ogr")
    assert other.isValid()
    QgsProject.instance().addMapLayer(other)
    dock = make_dock()
    start(dock, layers, [layers.a])
    assert Path(dock.session.store.path) == tmp_path / "detections.gpkg"
    start(dock, layers, [other])
    assert Path(dock.session.store.path) == tmp_path / "other.gpkg"
    start(dock, layers, [other], store=str(tmp_path / "mine.gpkg"))
    start(dock, layers, [layers.a])
    assert Path(dock.session.store.path) == tmp_path / "mine.gpkg"


def test_nothing_is_cut_off_at_the_narrowest_width(campaign, clean_project, make_dock, qtbot, tmp_path):
    """At its minimum width, in QGIS's 9 pt interface font, before and after Start, every label, field, header and
    cell shows whole (tests/gui/docks_layout.py; the real desktop: tests/gui/test_docks_desktop.py)."""
    from docks_layout import layout_problems, qgis_interface_font

    with qgis_interface_font():
        layers = copy_campaign(campaign, tmp_path)
        dock = make_dock()
        dock.resize(dock.minimumWidth(), 900)
        qtbot.waitUntil(lambda: dock.width() == dock.minimumWidth())
        assert layout_problems(dock) == []
        start(dock, layers)
        wait_scores(qtbot, dock)
        wait_chips(qtbot, dock)
        assert layout_problems(dock) == []


def test_chips_show_the_frames_that_detected_the_unit(campaign, clean_project, make_dock, qtbot, tmp_path):
    layers = copy_campaign(campaign, tmp_path)
    dock = make_dock()
    start(dock, layers)
    wait_chips(qtbot, dock)
    key = dock.current_key
    plans, images, n_frames, error = dock.chip_loader.chips[key]
    i = dock.units.index[key]
    assert error is None and n_frames == dock.units.n_frames[i] and len(plans) == min(4, n_frames)
    assert len(dock.chips.pixmaps) == len(plans) and dock.chips.pixmaps[0].width() == widgets_module.CHIP_DISPLAY_PX
    frames_seen = {int(f) for f in dock.units.detection_frame[dock.units.detection_unit == i]}
    assert {int(p.frame_id) for p in plans} <= frames_seen
    # Cold (no prefetch, empty image cache): the chips still come; the time printed is the benchmark's
    # baseline (benchmarks/bench_review_chips.py).
    dock.chip_loader.chips.clear()
    dock.chip_loader.pixels = dock.chip_loader.frame_images = type(dock.chip_loader.frame_images)(24)
    t0 = time.perf_counter()
    dock.go_to(dock._neighbour(key, +1))
    wait_chips(qtbot, dock)
    print(f"\nchip latency without prefetch (cold): {(time.perf_counter() - t0) * 1000:.1f} ms")
    assert dock.chip_loader.chips[dock.current_key][3] is None


def test_filters_by_layer_and_verdict_and_the_map_follows(campaign, clean_project, make_dock, qtbot, qgis_iface,
                                                          tmp_path):
    layers = copy_campaign(campaign, tmp_path)
    dock = make_dock()
    start(dock, layers)
    units = dock.units
    # The map follows the unit: centred on it at the review scale.
    canvas = qgis_iface.mapCanvas()
    i = units.index[dock.current_key]
    x, y = ProjectedCRS(UTM).from_geodetic(units.lat[i:i + 1], units.lon[i:i + 1])
    assert (canvas.center().x(), canvas.center().y()) == pytest.approx((x[0], y[0]), abs=1e-3)
    assert canvas.scale() == pytest.approx(widgets_module.DEFAULT_SCALE, rel=1e-3)
    dock.layer_filter.setCurrentIndex(dock.layer_filter.findData("model_b"))
    assert dock.visible == [k for k in dock.entries if "model_b" in units.layers_fired[units.index[k]]]
    assert dock.current_key in dock.visible
    dock.layer_filter.setCurrentIndex(0)
    dock.verdict_filter.setCurrentIndex(dock.verdict_filter.findData("todo"))
    first = dock.current_key
    qtbot.keyClick(dock.panel, Qt.Key_H)
    assert first not in dock.visible and dock.current_key == dock.visible[0]
    dock.verdict_filter.setCurrentIndex(dock.verdict_filter.findData("hard_negative"))
    assert dock.visible == [first]
    dock.verdict_filter.setCurrentIndex(dock.verdict_filter.findData("unmatched"))
    assert dock.visible == [k for k in dock.entries if not units.matched[units.index[k]]]


def test_reopening_the_project_resumes_exactly_where_the_reviewer_stopped(campaign, clean_project, make_dock,
                                                                         qtbot, tmp_path):
    layers = copy_campaign(campaign, tmp_path)
    dock = make_dock()
    start(dock, layers)
    dock.propagate_check.setChecked(True)
    for key in (Qt.Key_1, Qt.Key_2, Qt.Key_3):
        qtbot.keyClick(dock.panel, key)
    qtbot.keyClick(dock.panel, Qt.Key_N)
    qtbot.keyClick(dock.panel, Qt.Key_P)
    qtbot.keyClick(dock.panel, Qt.Key_P)            # moved back without a verdict: the cursor must still hold
    dock.verdict_filter.setCurrentIndex(dock.verdict_filter.findData("all"))
    stopped_at, decided = dock.current_key, {k: dock.status(k).direct for k in dock.units.keys}
    project_file = tmp_path / "review.qgz"
    assert QgsProject.instance().write(str(project_file))
    QgsProject.instance().clear()
    assert dock.session is None and not dock.panel.isEnabled()
    assert QgsProject.instance().read(str(project_file))
    qtbot.waitUntil(lambda: dock.session is not None, timeout=10000)
    assert dock.current_key == stopped_at and dock.propagate_check.isChecked()
    assert {k: dock.status(k).direct for k in dock.units.keys} == decided
    # A new dock on the reopened project does the same, and undo still knows the last action.
    dock.shutdown()
    second = make_dock()
    qtbot.waitUntil(lambda: second.session is not None, timeout=10000)
    assert second.current_key == stopped_at and second.banner.isHidden()
    qtbot.keyClick(second.panel, Qt.Key_Z, Qt.ControlModifier)
    assert sum(1 for v in (second.status(k).direct for k in second.units.keys) if v != "unreviewed") == 2


def test_changed_input_layers_are_detected_and_reported(campaign, clean_project, make_dock, qtbot, tmp_path):
    layers = copy_campaign(campaign, tmp_path)
    dock = make_dock()
    start(dock, layers)
    qtbot.keyClick(dock.panel, Qt.Key_1)
    qtbot.keyClick(dock.panel, Qt.Key_2)
    start(dock, layers)                                # same inputs: nothing to report
    assert dock.input_check.ok and dock.banner.isHidden()
    feature = next(layers.b.getFeatures())
    assert layers.b.dataProvider().changeAttributeValues({feature.id(): {layers.b.fields().indexOf("score"): 0.123}})
    start(dock, layers)
    assert dock.input_check.changed == {"detections:model_b": 2}
    assert not dock.banner.isHidden() and "model_b" in dock.banner.text() and "changed" in dock.banner.text()
    # Parameters count too: the units were made with another EPS.
    dock.eps_spin.setValue(0.12)
    start(dock, layers)
    assert "eps_m" in dock.input_check.parameters and "eps_m" in dock.banner.text()


def test_a_layer_that_cannot_be_reviewed_is_reported_by_name(campaign, clean_project, make_dock, tmp_path):
    layers = copy_campaign(campaign, tmp_path)
    dock = make_dock()
    # The geotag layer is not offered as the frames: the choice stays empty and the banner says what is missing.
    dock.set_inputs([layers.a], layers.geotags, layers.geotags)
    assert dock.frames_combo.currentLayer() is None
    assert not dock.start_review()
    assert "choose the frame layer" in dock.banner.text()
    # A frame layer whose cameras cannot be read is named.
    camera = layers.frames.fields().indexOf("camera")
    assert layers.frames.dataProvider().changeAttributeValues(
        {feature.id(): {camera: "{not json"} for feature in layers.frames.getFeatures()})
    dock.set_inputs([layers.a], layers.frames, layers.geotags)
    assert dock.frames_combo.currentLayer() is layers.frames
    assert not dock.start_review()
    assert "frames, row 1, field 'camera': camera model is not valid JSON" in dock.banner.text(), dock.banner.text()
    assert dock.session is None and not dock.panel.isEnabled()
    assert not (tmp_path / "detections.gpkg-journal").exists()


def test_the_methods_units_can_be_chosen_and_come_back_with_the_project(campaign, clean_project, make_dock,
                                                                       qtbot, tmp_path):
    layers = copy_campaign(campaign, tmp_path)
    dock = make_dock()
    dock.units_combo.setCurrentIndex(dock.units_combo.findData("method"))
    start(dock, layers)
    units = dock.units
    # Detections near a geotag are set aside; the rest form one unit per frame: the three look-alikes
    # (each seen by at least four frames) give at least twelve units, none matched, each of one frame.
    assert dock.params.units == "method" and not units.matched.any() and set(units.n_frames.tolist()) == {1}
    assert len(units) >= 4 * len(campaign.fakes)
    for k, key in enumerate(units.keys):
        assert key.rsplit("@", 1)[1] == str(units.detection_frame[units.detection_unit == k][0])
    qtbot.keyClick(dock.panel, Qt.Key_1)
    project_file = tmp_path / "review.qgz"
    assert QgsProject.instance().write(str(project_file))
    QgsProject.instance().clear()
    dock.units_combo.setCurrentIndex(dock.units_combo.findData("consensus"))
    assert QgsProject.instance().read(str(project_file))
    qtbot.waitUntil(lambda: dock.session is not None, timeout=10000)
    assert dock.units_combo.currentData() == "method" and dock.units.keys == units.keys
    assert sum(1 for k in dock.units.keys if dock.status(k).direct == "confirmed_real") == 1


def test_what_the_minimum_points_count_is_recorded_and_an_older_review_reopens_counting_cells(
        campaign, clean_project, make_dock, qtbot, tmp_path):
    """The choice reaches the units, the scores and every verdict row; a review saved before it was recorded
    was built counting cells, and reopens that way."""
    import json

    from birdseye.birdseye_qgis.qgis_io.review_project import PROJECT_SCOPE

    layers = copy_campaign(campaign, tmp_path)
    dock = make_dock()
    assert dock.core_count_combo.currentData() == "detections"
    dock.core_count_combo.setCurrentIndex(dock.core_count_combo.findData("cells"))
    start(dock, layers)
    assert dock.params.core_count == "cells" and dock.operating_point().core_count == "cells"
    assert dock.units.clustering.core_count == "cells"
    qtbot.keyClick(dock.panel, Qt.Key_1)
    assert {json.loads(r["postprocessing"])["core_count"] for r in dock.session.ledger.rows} == {"cells"}
    project = QgsProject.instance()
    saved = json.loads(project.readEntry(PROJECT_SCOPE, "review/parameters")[0])
    assert saved["core_count"] == "cells"
    del saved["core_count"]                                    # as a project saved before it was recorded
    project.writeEntry(PROJECT_SCOPE, "review/parameters", json.dumps(saved))
    project_file = tmp_path / "older.qgz"
    assert project.write(str(project_file))
    project.clear()
    dock.core_count_combo.setCurrentIndex(dock.core_count_combo.findData("detections"))
    assert project.read(str(project_file))
    qtbot.waitUntil(lambda: dock.session is not None, timeout=10000)
    assert dock.core_count_combo.currentData() == "cells" and dock.params.core_count == "cells"


def test_the_worker_threads_never_call_pyproj(campaign, clean_project, make_dock, qtbot, tmp_path, monkeypatch):
    """pyproj 3.7 crashes QGIS when it runs on a thread Qt started (pyproj#1509), as the dock's chip and
    score jobs are: whatever the pyproj, nothing they run may call it there. Every pyproj entry point
    records the calls made from threads Python did not start; the jobs then plan a unit's chips, an
    added target's chips and the scores."""
    import pyproj

    foreign, ran_on = [], []

    def on_foreign_thread() -> bool:
        return isinstance(threading.current_thread(), threading._DummyThread)

    for owner, name in ((pyproj.CRS, "__init__"), (pyproj.Transformer, "__init__"), (pyproj.Transformer, "transform"),
                        (pyproj.Proj, "__init__"), (pyproj.Proj, "get_factors")):
        def watched(*args, _original=getattr(owner, name), _label=f"{owner.__name__}.{name}", **kwargs):
            if on_foreign_thread():
                foreign.append(_label)
            return _original(*args, **kwargs)

        monkeypatch.setattr(owner, name, watched)
    for module, name in ((dock_module, "plan_unit_chips"), (dock_module, "plan_point_chips"),
                         (jobs_module, "evaluate_flights")):
        def recorded(*args, _original=getattr(module, name), _label=name, **kwargs):
            ran_on.append((_label, on_foreign_thread()))
            return _original(*args, **kwargs)

        monkeypatch.setattr(module, name, recorded)
    layers = copy_campaign(campaign, tmp_path)
    dock = make_dock()
    start(dock, layers)
    wait_chips(qtbot, dock)
    lat, lon, _ = campaign.missed
    to_map = ProjectedCRS(UTM)
    x, y = (float(c) for c in to_map.from_geodetic(lat, lon))
    dock.add_target_at(QgsPointXY(x, y), QgsCoordinateReferenceSystem(f"EPSG:{UTM}"))
    added = dock.session.ledger.added_targets()[0].key
    dock.go_to(added)
    wait_chips(qtbot, dock, added)
    wait_scores(qtbot, dock)
    assert {label for label, foreign_thread in ran_on if foreign_thread} == {
        "plan_unit_chips", "plan_point_chips", "evaluate_flights"}
    assert all(dock.chip_loader.chips[k][3] is None for k in dock.chip_loader.chips)
    assert dock.chip_loader.chips[added][0], "the added target's chips were planned"
    assert foreign == []


# ---------------------------------------------------------------------------------------------- a raster
@pytest.fixture
def mosaic(birdseye_provider, clean_project, tmp_path):
    """The test orthomosaic (tests/raster_scene.py: a hump on each of six targets, the last one transparent)
    searched by Detect targets on a raster with the identity model: five detections, one per visible target.
    Geotags on the first four targets (hits), on a bare spot of the raster (in view, missed), on the transparent
    target and 40 m east of the raster (neither in view); the fifth target has none (an unmatched unit)."""
    from raster_scene import TARGETS, identity_model, map_of, rgba_orthomosaic

    ortho = rgba_orthomosaic(tmp_path / "ortho.tif")
    found = run("detectraster", {"RASTER": ortho, "MODEL": identity_model(tmp_path / "m.onnx"),
                                 "OUTPUT": str(tmp_path / "on_mosaic.gpkg")})
    assert found["DETECTION_COUNT"] == 5
    xy = [map_of(ortho, u, v) for u, v in TARGETS[:4] + [(600.0, 300.0), TARGETS[5]]]
    x, y = map_of(ortho, 600.0, 300.0)
    xy.append((x + 40.0, y))
    geotags = QgsVectorLayer(f"Point?crs=EPSG:{UTM}", "survey", "memory")
    geotags.dataProvider().addAttributes([QgsField("id", QVariant.Int), QgsField("label", QVariant.String)])
    geotags.updateFields()
    features = []
    for k, (gx, gy) in enumerate(xy):
        feature = QgsFeature(geotags.fields())
        feature.setAttributes([k + 1, "burrow"])
        feature.setGeometry(QgsGeometry.fromPointXY(QgsPointXY(gx, gy)))
        features.append(feature)
    geotags.dataProvider().addFeatures(features)
    options = QgsVectorFileWriter.SaveVectorOptions()
    options.driverName = "GPKG"
    error = QgsVectorFileWriter.writeAsVectorFormatV3(geotags, str(tmp_path / "survey.gpkg"),
                                                      QgsProject.instance().transformContext(), options)
    assert error[0] == QgsVectorFileWriter.NoError, error
    geotags = QgsVectorLayer(str(tmp_path / "survey.gpkg"), "survey", "ogr")
    detections = QgsVectorLayer(found["OUTPUT"], "on_mosaic", "ogr")
    assert detections.isValid() and geotags.featureCount() == 7
    QgsProject.instance().addMapLayers([detections, geotags])
    return SimpleNamespace(ortho=ortho, detections=detections, geotags=geotags, targets=TARGETS)


def gdal_window(path, window):
    """The raster's red, green and blue over ``window`` (x0, y0, x1, y1) as GDAL reads them, in BGR order."""
    from osgeo import gdal

    x0, y0, x1, y1 = window
    ds = gdal.Open(str(path))
    rgb = [ds.GetRasterBand(b).ReadAsArray(x0, y0, x1 - x0, y1 - y0) for b in (1, 2, 3)]
    return np.dstack(rgb[::-1])


def test_detections_found_on_a_raster_are_reviewed_with_chips_cut_from_it(mosaic, clean_project, make_dock, qtbot,
                                                                          tmp_path):
    from raster_scene import map_of

    from birdseye.birdseye_qgis.core.review.chips import render_chip

    dock = make_dock()
    # Offered, and chosen by itself (the most recent detection layer); no frame layer needed, and the dock says so.
    assert dock.detections_combo.itemData(0) == mosaic.detections.id()
    assert dock.detections_combo.checkedItemsData() == [mosaic.detections.id()]
    assert not dock.frames_combo.isEnabled() and "Not needed" in dock.frames_combo.toolTip()
    assert dock.frames_combo.currentLayer() is None
    dock.set_inputs([mosaic.detections], None, mosaic.geotags)
    assert dock.start_review(), dock.banner.text()
    dock.panel.setFocus()
    units = dock.units
    # One unit per detection (one image shows a target once); four on geotags, the fifth target's unmatched first.
    assert len(units) == 5 and int(units.matched.sum()) == 4 and not units.matched[units.index[dock.current_key]]
    assert dock.inputs.view_mask.tolist() == [True] * 5 + [False, False]

    # The scores are Evaluate detections' on the same layers (no frame layer: the raster says what is in view).
    wait_scores(qtbot, dock)
    out = tmp_path / "scores.json"
    evaluated = run("evaluatedetections", {"DETECTIONS": [mosaic.detections], "GEOTAGS": mosaic.geotags,
                                           "OUTPUT_JSON": str(out), "OUTPUT_REPORT": None})
    shown = dock.scores["on_mosaic"]
    assert (evaluated["N_IN_VIEW"], evaluated["N_RECOVERED"], evaluated["N_CLUSTERS"],
            evaluated["N_HIT_CLUSTERS"]) == (5, 4, 5, 4)
    assert (shown["n_in_view"], shown["n_recovered"], shown["n_clusters"], shown["n_hit_clusters"]) == (5, 4, 5, 4)
    assert shown["recall_pre"] == json.loads(out.read_text())["recall_pre"]

    # A unit's chip: one window of the raster around it, its pixels those GDAL reads there, the marks on them.
    wait_chips(qtbot, dock)
    for key in [dock.current_key, next(k for k in units.keys if units.matched[units.index[k]])]:
        dock.go_to(key)
        wait_chips(qtbot, dock, key)
        plans, images, n_frames, error = dock.chip_loader.chips[key]
        assert error is None and n_frames == 1 and len(plans) == 1 and len(dock.chips.pixmaps) == 1
        plan, i = plans[0], units.index[key]
        assert plan.image == mosaic.ortho and plan.frame_id == 0
        (d,) = np.flatnonzero(units.detection_unit == i)
        u, v = units.detection_uv[d]
        x0, y0, x1, y1 = plan.window
        assert (x1 - x0, y1 - y0) == (dock.window_spin.value(),) * 2 and x0 <= u < x1 and y0 <= v < y1
        assert plan.detections == [(pytest.approx(u - x0), pytest.approx(v - y0), 0)]
        expected = gdal_window(mosaic.ortho, plan.window)
        assert np.array_equal(dock.chip_loader.pixels.window(plan), expected)
        assert np.array_equal(images[0], render_chip(expected, plan, widgets_module.CHIP_DISPLAY_PX))
        # The painted hump is under the detection: the brightest pixel of the window.
        assert expected[round(v) - y0, round(u) - x0, 0] == expected.max() > 200
        if units.matched[i]:   # the geotag on the target is drawn where the detection is
            (gu, gv, label), = plan.geotags
            assert (gu, gv) == (pytest.approx(u - x0, abs=0.5), pytest.approx(v - y0, abs=0.5)) and label != ""
            qtbot.wait(50)
            assert dock.grab().save(str(SCREENSHOT.with_name("review_dock_raster.png")))
        else:
            assert plan.geotags == []
    # Near the raster's edge the window moves inside it (the first target is 60 px from the left, 70 from the top).
    first = next(k for k in units.keys if np.allclose(units.detection_uv[units.detection_unit == units.index[k]][0],
                                                      mosaic.targets[0], atol=0.5))
    dock.go_to(first)
    wait_chips(qtbot, dock, first)
    assert dock.chip_loader.chips[first][0][0].window[:2] == (0, 6)

    # An added target's chip: the raster around the point clicked, the point marked where GDAL puts it.
    x, y = map_of(mosaic.ortho, 700.0, 300.0)
    dock.add_target_at(QgsPointXY(x, y), QgsCoordinateReferenceSystem(f"EPSG:{UTM}"))
    added = dock.session.ledger.added_targets()[0].key
    dock.go_to(added)
    wait_chips(qtbot, dock, added)
    (plan,), images, n_frames, error = dock.chip_loader.chips[added]
    assert error is None and n_frames == 1
    (u, v, layer), = plan.detections
    assert layer == -1 and (u + plan.window[0], v + plan.window[1]) == (pytest.approx(700.0, abs=0.05),
                                                                        pytest.approx(300.0, abs=0.05))
    assert np.array_equal(dock.chip_loader.pixels.window(plan), gdal_window(mosaic.ortho, plan.window))
    # It counts in the scores after review (a): the raster covers it — there is no frame to see it — as in
    # Evaluate detections on the same log.
    wait_scores(qtbot, dock)
    assert {conv: post["a"] for conv, post in dock.scores["on_mosaic"]["post"].items()} == \
        dict.fromkeys(dock.scores["on_mosaic"]["post"], 1)
    review = QgsVectorLayer(f"{dock.session.store.path}|layername={VERDICT_TABLE}", "verdicts", "ogr")
    run("evaluatedetections", {"DETECTIONS": [mosaic.detections], "GEOTAGS": mosaic.geotags, "REVIEW": review,
                               "OUTPUT_JSON": str(out), "OUTPUT_REPORT": None})
    assert dock.scores["on_mosaic"]["post"] == json.loads(out.read_text())["flights"][0]["post"]
    # Undo while the added target is on screen: it goes, and the dock shows a unit that is left.
    dock.run_command("undo")
    assert dock.session.ledger.added_targets() == [] and dock.current_key in dock.entries
    assert added not in dock.entries
    dock.go_to(first)

    # A verdict is recorded in the log as for frames, and counts in the scores as in Evaluate detections'.
    key = dock.current_key
    qtbot.keyClick(dock.panel, Qt.Key_1)
    rows = [r for r in dock.session.store.rows() if r["action"] == "verdict"]
    assert [(r["unit_key"], r["verdict"], json.loads(r["layers_fired"])) for r in rows] == \
        [(key, "confirmed_real", ["on_mosaic"])]
    assert "detections:on_mosaic" in json.loads(rows[0]["input_digests"])
    wait_scores(qtbot, dock)
    review = QgsVectorLayer(f"{dock.session.store.path}|layername={VERDICT_TABLE}", "verdicts", "ogr")
    run("evaluatedetections", {"DETECTIONS": [mosaic.detections], "GEOTAGS": mosaic.geotags, "REVIEW": review,
                               "OUTPUT_JSON": str(out), "OUTPUT_REPORT": None})
    assert dock.scores["on_mosaic"]["post"] == json.loads(out.read_text())["flights"][0]["post"]

    # Saved without a frame layer, the review comes back with the project.
    project_file = tmp_path / "mosaic.qgz"
    assert QgsProject.instance().write(str(project_file))
    QgsProject.instance().clear()
    assert QgsProject.instance().read(str(project_file))
    qtbot.waitUntil(lambda: dock.session is not None, timeout=10000)
    assert dock.raster is not None and dock.session.ledger.direct(key) == "confirmed_real"


def test_a_review_of_raster_and_frame_detections_together_is_refused(mosaic, clean_project, make_dock, tmp_path):
    frame_detections = QgsVectorLayer(f"Point?crs=EPSG:{UTM}", "on_frames", "memory")
    frame_detections.dataProvider().addAttributes([QgsField(n, QVariant.Double) for n in ("frame_id", "u", "v",
                                                                                          "score")])
    frame_detections.updateFields()
    feature = QgsFeature(frame_detections.fields())
    feature.setAttributes([1, 10.0, 20.0, 0.9])
    feature.setGeometry(next(mosaic.detections.getFeatures()).geometry())
    frame_detections.dataProvider().addFeatures([feature])
    QgsProject.instance().addMapLayer(frame_detections)
    dock = make_dock()
    dock.set_inputs([mosaic.detections], None, mosaic.geotags, str(tmp_path / "log.gpkg"))
    assert not dock.frames_combo.isEnabled()
    # The user ticks the frame detections too: they need their frames, so the frame choice comes back.
    dock.detections_combo.toggleItemCheckState(dock.detections_combo.findData(frame_detections.id()))   # a click
    assert dock.frames_combo.isEnabled() and "Not needed" not in dock.frames_combo.toolTip()
    assert not dock.start_review()
    assert "not both" in dock.banner.text() and "on_mosaic found on a raster" in dock.banner.text()
    assert dock.session is None
