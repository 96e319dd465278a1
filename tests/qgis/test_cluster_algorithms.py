"""The clustering and scoring algorithms through the registry, on small synthetic layers.

One nadir frame 10 m above level ground (undistorted 1920 × 1200 px camera, fx = fy = 1000 px):
its footprint spans ±9.6 m east and ±6 m north of the frame, so in-view follows from the numbers.
Layers are in UTM zone 56 S (the site is near Dalby, Queensland); the field is described in metres
east/north of the site and converted through the core's exact local frame.
"""
from __future__ import annotations

import csv
import hashlib
import json

import numpy as np
import pytest
from qgis.core import QgsFeature, QgsField, QgsGeometry, QgsPoint, QgsPointXY, QgsProcessingException, QgsVectorLayer
from qgis.PyQt.QtCore import QVariant
from registry import run

from birdseye.birdseye_qgis.core.field.frame_records import FRAME_FIELDS
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame, ProjectedCRS
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat

SITE = LocalFrame(-27.55, 151.95, 400.0)
UTM = ProjectedCRS(32756)
DIGEST = hashlib.sha256(b"demo model").hexdigest()


def grid9(cx, cy, step=0.04):
    return np.array([(cx + i * step, cy + j * step) for i in (-1, 0, 1) for j in (-1, 0, 1)])


CLUSTER_A, CLUSTER_B = grid9(-3.0, 0.0), grid9(3.0, 1.0)
NOISE = np.array([[0.0, -4.0]])
GEOTAGS = {1: (-2.9, 0.0), 2: (5.0, -5.0), 3: (15.0, 0.0)}   # 1 hits A; 2 in view, missed; 3 out of view


def utm_of(en):
    en = np.atleast_2d(np.asarray(en, dtype=float))
    lat, lon, h = SITE.to_geodetic(np.column_stack([en, np.zeros(len(en))]))
    x, y = UTM.from_geodetic(lat, lon)
    return x, y, h


def point_layer(name, fields, rows, en):
    layer = QgsVectorLayer("PointZ?crs=EPSG:32756", name, "memory")
    layer.dataProvider().addAttributes(fields)
    layer.updateFields()
    x, y, h = utm_of(en)
    feats = []
    for row, xi, yi, hi in zip(rows, x, y, h):
        f = QgsFeature(layer.fields())
        f.setAttributes(row)
        f.setGeometry(QgsGeometry(QgsPoint(float(xi), float(yi), float(hi))))
        feats.append(f)
    layer.dataProvider().addFeatures(feats)
    return layer


def detection_layer(en, threshold=0.3, digest=DIGEST, name="detections"):
    fields = [QgsField("frame_id", QVariant.Int), QgsField("u", QVariant.Double), QgsField("v", QVariant.Double),
              QgsField("score", QVariant.Double), QgsField("model", QVariant.String),
              QgsField("model_digest", QVariant.String), QgsField("threshold", QVariant.Double)]
    n = len(en)
    rows = [[k % 3, 100.0, 100.0, 0.4 + 0.5 * k / n, "demo.onnx", digest, threshold] for k in range(n)]
    return point_layer(name, fields, rows, en)


def geotag_layer():
    fields = [QgsField("id", QVariant.Int), QgsField("label", QVariant.String)]
    return point_layer("geotags", fields, [[k, "burrow"] for k in GEOTAGS], list(GEOTAGS.values()))


def nadir_camera(width=1920, height=1200):
    t = np.eye(4)
    t[:3, :3] = [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]
    return CameraModel(width, height, 1000.0, 1000.0, (width - 1) / 2, (height - 1) / 2, (0, 0, 0, 0, 0), t)


def frame_layer(east=0.0, north=0.0, camera=None, images=None):
    """Level nadir frames 10 m above the ground at the given offsets (m east/north of the site)."""
    east, north = np.atleast_1d(east).astype(float), np.atleast_1d(north).astype(float)
    north = np.broadcast_to(north, east.shape)
    cam = camera or nadir_camera()
    lat, lon, h = SITE.to_geodetic(np.column_stack([east, north, np.full(len(east), 10.0)]))
    q = rotmat_to_quat(euler_zyx_to_rotmat(0.0, 0.0, 0.0))
    layer = QgsVectorLayer("None", "frames", "memory")
    kinds = {"int": QVariant.Int, "double": QVariant.Double, "string": QVariant.String}
    layer.dataProvider().addAttributes([QgsField(n, kinds[k]) for n, k, _ in FRAME_FIELDS])
    layer.updateFields()
    feats = []
    for k in range(len(east)):
        values = {"frame_id": k, "image": images[k] if images else "", "time_s": float(k), "lat": float(lat[k]),
                  "lon": float(lon[k]), "height_m": float(h[k]), "qw": float(q[0]), "qx": float(q[1]),
                  "qy": float(q[2]), "qz": float(q[3]), "roll_deg": 0.0, "pitch_deg": 0.0, "yaw_deg": 0.0,
                  "ground_h_m": SITE.h0, "depth_m": 10.0, "rtk_status": 3, "sync_offset_s": 0.0, "gsd_cm": 1.0,
                  "height_ref": "ellipsoidal", "ground_src": "altimeter", "camera": cam.to_json(), "flags": ""}
        f = QgsFeature(layer.fields())
        f.setAttributes([values[n] for n, _, _ in FRAME_FIELDS])
        feats.append(f)
    layer.dataProvider().addFeatures(feats)
    return layer


def verdict_layer(rows):
    layer = QgsVectorLayer("None", "verdicts", "memory")
    names = ["unit_key", "verdict", "provenance", "time", "reviewer"]
    layer.dataProvider().addAttributes([QgsField(n, QVariant.String) for n in names] +
                                       [QgsField("lat", QVariant.Double), QgsField("lon", QVariant.Double)])
    layer.updateFields()
    feats = []
    for unit, verdict, provenance, where in rows:
        lat, lon, _ = SITE.to_geodetic(np.array([[where[0], where[1], 0.0]]))
        f = QgsFeature(layer.fields())
        f.setAttributes([unit, verdict, provenance, "2024-05-01T10:00:00Z", "ana", float(lat[0]), float(lon[0])])
        feats.append(f)
    layer.dataProvider().addFeatures(feats)
    return layer


DETECTIONS = np.concatenate([CLUSTER_A, CLUSTER_B, NOISE])


def test_clusterdetections_writes_hulls_points_and_hit_flags(birdseye_provider):
    det = detection_layer(DETECTIONS)
    result = run("clusterdetections", {"DETECTIONS": det, "GEOTAGS": geotag_layer(), "FRAMES": frame_layer(),
                                       "OUTPUT": "TEMPORARY_OUTPUT", "OUTPUT_POINTS": "TEMPORARY_OUTPUT"})
    assert (result["CLUSTER_COUNT"], result["HIT_COUNT"], result["NOISE_POINTS"]) == (2, 1, 1)
    clusters = {f["hit"]: f for f in result["OUTPUT"].getFeatures()}
    assert result["OUTPUT"].crs().authid() == "EPSG:32756"
    hit, miss = clusters[1], clusters[0]
    assert hit["matched_geotag_ids"] == "1" and miss["matched_geotag_ids"] == ""
    assert (hit["n_detections"], hit["n_frames"]) == (9, 3)
    # centroid = the grid centre; median distance of a 3×3 grid (4 cm step) from its centre is 4 cm
    ax, ay, _ = utm_of([-3.0, 0.0])
    assert hit["centroid_x"] == pytest.approx(ax[0], abs=1e-4) and hit["centroid_y"] == pytest.approx(ay[0], abs=1e-4)
    assert hit["median_extent_m"] == pytest.approx(0.08, abs=1e-6)
    x, y, _ = utm_of(CLUSTER_A)
    for xi, yi in zip(x, y):
        assert hit.geometry().contains(QgsGeometry.fromPointXY(QgsPointXY(xi, yi)))
    assert hit.geometry().area() == pytest.approx(0.08 * 0.08 + 4 * 0.08 * 0.03 + np.pi * 0.03 ** 2, rel=0.05)
    points = list(result["OUTPUT_POINTS"].getFeatures())
    assert len(points) == len(DETECTIONS)
    assert sorted(p["cluster_id"] for p in points).count(-1) == 1
    assert sum(p["core"] for p in points) == 18


def test_clusterdetections_counts_detections_unless_told_to_count_cells(birdseye_provider):
    """Six frames place a spot at the same position (refined poses): six detections in one 3 cm cell. One
    cluster when the minimum points count detections (the default), none when each cell is one point
    (CORE_COUNT 1, the method's)."""
    det = detection_layer(np.repeat([[-2.9, 0.0]], 6, axis=0))
    counted = run("clusterdetections", {"DETECTIONS": det, "GEOTAGS": geotag_layer(), "FRAMES": frame_layer(),
                                        "OUTPUT": "TEMPORARY_OUTPUT", "OUTPUT_POINTS": "TEMPORARY_OUTPUT"})
    assert (counted["CLUSTER_COUNT"], counted["HIT_COUNT"], counted["NOISE_POINTS"]) == (1, 1, 0)
    (point,) = counted["OUTPUT_POINTS"].getFeatures()
    assert point["n_detections"] == 6 and point["core"] == 1
    cells = run("clusterdetections", {"DETECTIONS": det, "GEOTAGS": geotag_layer(), "FRAMES": frame_layer(),
                                      "CORE_COUNT": 1, "OUTPUT": "TEMPORARY_OUTPUT"})
    assert (cells["CLUSTER_COUNT"], cells["NOISE_POINTS"]) == (0, 1)


def test_every_algorithm_that_clusters_offers_what_the_minimum_points_count(birdseye_provider):
    """CORE_COUNT next to every MIN_SAMPLES: an advanced choice, detections (0) by default, cells (1)."""
    from qgis.core import QgsApplication

    from birdseye.birdseye_qgis.qgis_enums import PARAMETER_ADVANCED

    clustering = []
    for alg in QgsApplication.processingRegistry().providerById("birdseye").algorithms():
        if alg.parameterDefinition("MIN_SAMPLES") is None:
            continue
        clustering.append(alg.name())
        choice = alg.parameterDefinition("CORE_COUNT")
        assert choice is not None, alg.name()
        assert len(choice.options()) == 2 and choice.defaultValue() == 0, alg.name()
        assert "the method's" in choice.options()[1] and choice.flags() & PARAMETER_ADVANCED, alg.name()
    assert set(clustering) >= {"clusterdetections", "evaluatedetections", "comparedetectors", "sweepoperatingpoints",
                               "screencheckpoints", "sealpreregistration", "writelabels", "planflight"}


def test_cluster_and_detection_styles_load_on_the_outputs(birdseye_provider):
    from qgis.core import QgsExpression, QgsExpressionContext, QgsExpressionContextUtils

    from birdseye.birdseye_qgis.qgis_io.layers import STYLE_DIR

    result = run("clusterdetections", {"DETECTIONS": detection_layer(DETECTIONS), "OUTPUT": "TEMPORARY_OUTPUT",
                                       "OUTPUT_POINTS": "TEMPORARY_OUTPUT"})
    clusters, points = result["OUTPUT"], result["OUTPUT_POINTS"]
    assert clusters.loadNamedStyle(str(STYLE_DIR / "clusters.qml"))[1]
    renderer = clusters.renderer()
    assert renderer.type() == "categorizedSymbol" and renderer.classAttribute() == "hit"
    assert sorted(str(c.value()) for c in renderer.categories()) == ["0", "1"]
    def legend_keys(layer, feature):
        """The legend keys (rule labels) a feature falls in; an ELSE rule takes what no other rule does."""
        context = QgsExpressionContext(QgsExpressionContextUtils.globalProjectLayerScopes(layer))
        context.setFeature(feature)
        rules = layer.renderer().rootRule().children()
        hits = [r.label() for r in rules if not r.isElse()
                and bool(QgsExpression(r.filterExpression()).evaluate(context))]
        return hits or [r.label() for r in rules if r.isElse()]

    # De-duplicated points: in a cluster or noise, by their cluster id; Detect's output: one score class each.
    assert points.loadNamedStyle(str(STYLE_DIR / "cluster_points.qml"))[1]
    for feature in points.getFeatures():
        expected = "Noise: in no cluster" if feature["cluster_id"] == -1 else "In a cluster"
        assert legend_keys(points, feature) == [expected]
    detections = detection_layer(DETECTIONS)
    assert detections.loadNamedStyle(str(STYLE_DIR / "detections.qml"))[1]
    for feature in detections.getFeatures():
        assert len(legend_keys(detections, feature)) == 1, "every score falls in exactly one class"


def test_clusterdetections_refuses_a_layer_that_is_not_detections(birdseye_provider):
    with pytest.raises(QgsProcessingException, match="not a BirdsEye detection layer"):
        run("clusterdetections", {"DETECTIONS": geotag_layer(), "OUTPUT": "TEMPORARY_OUTPUT"})


def test_a_layer_merged_from_runs_at_two_thresholds_is_refused(birdseye_provider):
    """Filtering a 0.3 run is not a 0.5 run (blobs split): a layer holding both cannot be scored as either."""
    layer = detection_layer(grid9(0.0, 0.0), threshold=0.3)
    layer.startEditing()
    feature = next(layer.getFeatures())
    layer.changeAttributeValue(feature.id(), layer.fields().indexOf("threshold"), 0.5)
    layer.commitChanges()
    with pytest.raises(QgsProcessingException, match="field 'threshold'.*mixes detections of 2 thresholds"):
        run("clusterdetections", {"DETECTIONS": layer, "OUTPUT": "TEMPORARY_OUTPUT"})


def test_evaluatedetections_pre_and_post_by_hand(birdseye_provider, tmp_path):
    verdicts = verdict_layer([
        ("u_b", "confirmed_real", "direct", (3.0, 1.0)),
        ("u_b", "hard_negative", "propagated:dbscan_0.20m", (3.0, 1.0)),
        ("t1", "added", "direct", (1.0, -5.0)),          # in view
    ])
    out_json, out_html = tmp_path / "scores.json", tmp_path / "report.html"
    result = run("evaluatedetections", {
        "DETECTIONS": [detection_layer(DETECTIONS)], "GEOTAGS": geotag_layer(), "FRAMES": [frame_layer()],
        "REVIEW": verdicts, "OUTPUT_JSON": str(out_json), "OUTPUT_REPORT": str(out_html)})
    assert (result["N_IN_VIEW"], result["N_RECOVERED"], result["N_CLUSTERS"], result["N_HIT_CLUSTERS"]) == (2, 1, 2, 1)
    assert result["RECALL_PRE"] == pytest.approx(0.5) and result["GMCF_PRE"] == pytest.approx(0.5)
    scores = json.loads(out_json.read_text())
    assert scores["recall_pre"] == pytest.approx(0.5)
    post = scores["post"]
    assert (post["positive_wins"]["c"], post["positive_wins"]["a"]) == (1, 1)
    assert post["positive_wins"]["gmcf_post"] == pytest.approx(1.0)
    assert post["positive_wins"]["recall_post"] == "0.500"            # (1 + 1) / (2 + 1 + 1); a > 0: a point value
    assert post["majority_wins"]["c"] == 0 and post["hard_negative_wins"]["c"] == 0
    assert post["majority_wins"]["recall_post_value"] == pytest.approx(1 / 3)
    html = out_html.read_text()
    assert "data:image/png;base64," in html and "lower bound on precision" in html and "≥" in html
    # the frame sees geotags 1 and 2 (3 is 15 m east, outside its ±9.6 m footprint): 2 per frame
    assert scores["survey_density"]["mean"] == 2.0 and scores["flights"][0]["survey_density"]["n_frames"] == 1
    assert scores["parameters"]["core_count"] == "detections" and "Survey density" in html


def test_evaluatedetections_pools_two_flights_by_micro_averaging(birdseye_provider, tmp_path):
    # flight 2: 100 m east, a copy of cluster A with its geotag (recovered) and nothing else
    a2 = CLUSTER_A + [103.0, 0.0]
    geo = geotag_layer()
    geo.dataProvider().addFeatures([_geotag_feature(geo, 4, (100.1, 0.0))])
    out = tmp_path / "pooled.json"
    run("evaluatedetections", {"DETECTIONS": [detection_layer(DETECTIONS), detection_layer(a2, name="second")],
                               "GEOTAGS": geo, "FRAMES": [frame_layer(), frame_layer(100.0, 0.0)],
                               "OUTPUT_JSON": str(out), "OUTPUT_REPORT": None})
    scores = json.loads(out.read_text())
    assert [f["recall_pre"] for f in scores["flights"]] == [0.5, 1.0]
    assert scores["recall_pre"] == pytest.approx(2 / 3)            # not (0.5 + 1) / 2
    assert scores["gmcf_pre"] == pytest.approx(2 / 3)
    # survey density: flight 1's frame sees geotags 1 and 2, flight 2's geotag 4: 1.5 per frame over both
    assert [f["survey_density"]["mean"] for f in scores["flights"]] == [2.0, 1.0]
    assert scores["survey_density"]["mean"] == 1.5 and scores["survey_density"]["median"] == 1.5


def _geotag_feature(layer, gid, en):
    x, y, h = utm_of(en)
    f = QgsFeature(layer.fields())
    f.setAttributes([gid, "burrow"])
    f.setGeometry(QgsGeometry(QgsPoint(float(x[0]), float(y[0]), float(h[0]))))
    return f


def test_evaluatedetections_needs_one_frame_layer_per_flight(birdseye_provider, tmp_path):
    with pytest.raises(QgsProcessingException, match="one frame layer per detection layer"):
        run("evaluatedetections", {"DETECTIONS": [detection_layer(DETECTIONS)] * 2, "GEOTAGS": geotag_layer(),
                                   "FRAMES": [frame_layer()], "OUTPUT_JSON": str(tmp_path / "x.json")})


# -------------------------------------------------------------------------------- sweep
def test_sweep_agrees_with_evaluate_and_keeps_a_credible_front(birdseye_provider, tmp_path):
    det, geo, frames = detection_layer(DETECTIONS), geotag_layer(), frame_layer()
    table, doc, plot = tmp_path / "sweep.csv", tmp_path / "sweep.json", tmp_path / "sweep.png"
    result = run("sweepoperatingpoints", {
        "DETECTIONS": [det], "GEOTAGS": geo, "FRAMES": [frames],
        "EPS_M": "0.05,0.10,6", "MIN_SAMPLES": "2,3", "EPS_PRED_M": "0.05,0.20",
        "OUTPUT_TABLE": str(table), "OUTPUT_JSON": str(doc), "OUTPUT_PLOT": str(plot)})
    with open(table, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    # the layer is used at the threshold it was detected at (0.3), never filtered to another
    assert result["N_CONFIGURATIONS"] == len(rows) == 1 * 3 * 2 * 2
    assert {(r["checkpoint"], r["model_digest"], float(r["threshold"])) for r in rows} == {("demo.onnx", DIGEST, 0.3)}
    row = next(r for r in rows if (float(r["threshold"]), float(r["eps_m"]), int(r["min_samples"]),
                                   float(r["eps_pred_m"])) == (0.3, 0.1, 3, 0.2))
    assert (int(row["n_in_view"]), int(row["n_recovered"]), int(row["n_clusters"]), int(row["n_hit_clusters"])) \
        == (2, 1, 2, 1)
    # eps 6 m chains A, B and the noise point into one cluster several metres across: not credible
    chained = [r for r in rows if float(r["eps_m"]) == 6.0 and float(r["threshold"]) == 0.3]
    assert chained and all(r["credible"] == "False" for r in chained)
    assert 0 < result["N_PARETO"] <= result["N_CREDIBLE"] < len(rows)
    front = json.loads(doc.read_text())["pareto"]
    assert len(front) == result["N_PARETO"] and all(r["credible"] for r in front)
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # what the minimum points counted is recorded with the grid and in every row, for the arms chosen from it
    assert json.loads(doc.read_text())["grid"]["core_count"] == "detections"
    assert {r["core_count"] for r in rows} == {"detections"}


def test_the_sweeps_default_grid_is_the_methods(birdseye_provider):
    """The dialog's default lists: 12 thresholds (0.035 among them) × 10 EPS × 12 MIN_SAMPLES × 10 EPS_PRED."""
    from qgis.core import QgsApplication

    alg = QgsApplication.processingRegistry().algorithmById("birdseye:sweepoperatingpoints")
    lists = {name: [float(v) for v in alg.parameterDefinition(name).defaultValue().split(",")]
             for name in ("THRESHOLDS", "EPS_M", "MIN_SAMPLES", "EPS_PRED_M")}
    assert [len(v) for v in lists.values()] == [12, 10, 12, 10]
    assert 0.035 in lists["THRESHOLDS"] and min(lists["THRESHOLDS"]) == 0.03 and max(lists["THRESHOLDS"]) == 0.12


def test_sweep_refuses_layers_that_miss_a_threshold_or_both_kinds_of_input(birdseye_provider, tmp_path):
    other = hashlib.sha256(b"other model").hexdigest()
    frames = frame_layer()
    layers = [detection_layer(DETECTIONS, threshold=0.3), detection_layer(DETECTIONS, threshold=0.5),
              detection_layer(DETECTIONS, threshold=0.3, digest=other)]
    with pytest.raises(QgsProcessingException, match="has no layer detected at threshold\\(s\\) 0.5"):
        run("sweepoperatingpoints", {"DETECTIONS": layers, "GEOTAGS": geotag_layer(), "FRAMES": [frames] * 3,
                                     "OUTPUT_TABLE": str(tmp_path / "t.csv")})
    checkpoint = tmp_path / "demo.onnx"
    checkpoint.write_bytes(b"demo model")
    with pytest.raises(QgsProcessingException, match="not both"):
        run("sweepoperatingpoints", {"DETECTIONS": layers[:1], "CHECKPOINTS": [str(checkpoint)],
                                     "GEOTAGS": geotag_layer(), "FRAMES": [frames],
                                     "OUTPUT_TABLE": str(tmp_path / "t.csv")})
    with pytest.raises(QgsProcessingException, match="EPS_M.*not a number"):
        run("sweepoperatingpoints", {"DETECTIONS": [detection_layer(DETECTIONS)], "GEOTAGS": geotag_layer(),
                                     "FRAMES": [frame_layer()], "EPS_M": "0.1;x",
                                     "OUTPUT_TABLE": str(tmp_path / "t.csv")})


# -------------------------------------------------------------------------------- preregistration
def test_sealed_rule_is_verified_before_scoring_and_refused_when_tampered(birdseye_provider, tmp_path):
    checkpoint = tmp_path / "demo.onnx"
    checkpoint.write_bytes(b"demo model")                      # its SHA-256 is the detections' model_digest
    rule = tmp_path / "rule.json"
    sealed = run("sealpreregistration", {"CHECKPOINTS": [str(checkpoint)], "THRESHOLD": 0.5, "EPS_M": 0.1,
                                         "MIN_SAMPLES": 3, "EPS_PRED_M": 0.2, "NOTE": "flight 2 is held out",
                                         "OUTPUT": str(rule)})
    doc = json.loads(rule.read_text(encoding="utf-8"))
    assert sealed["SEAL"] == doc["seal"] and doc["model_digests"] == [DIGEST]
    assert doc["rule"]["arms"][0]["operating_point"]["threshold"] == 0.5
    out = tmp_path / "scores.json"
    params = {"DETECTIONS": [detection_layer(DETECTIONS, threshold=0.5)], "GEOTAGS": geotag_layer(),
              "FRAMES": [frame_layer()], "PREREGISTRATION": str(rule), "OUTPUT_JSON": str(out), "OUTPUT_REPORT": None,
              "MIN_SAMPLES": 1, "EPS_PRED_M": 5.0}           # the dialog's values are replaced by the rule's
    run("evaluatedetections", params)
    scores = json.loads(out.read_text())
    assert scores["preregistration"]["seal"] == doc["seal"]
    assert scores["parameters"] == doc["rule"]["arms"][0]["operating_point"]
    # scores rise along the layer (0.4 → 0.9): threshold 0.5 leaves cluster A's first detections out
    assert scores["flights"][0]["n_detections"] < len(DETECTIONS)
    tampered = rule.read_text(encoding="utf-8").replace('"threshold": 0.5', '"threshold": 0.4')
    rule.write_text(tampered, encoding="utf-8")
    with pytest.raises(QgsProcessingException, match="seal does not match"):
        run("evaluatedetections", params)
    other = tmp_path / "other.onnx"
    other.write_bytes(b"another model")
    run("sealpreregistration", {"CHECKPOINTS": [str(other)], "THRESHOLD": 0.5, "OUTPUT": str(rule)})
    with pytest.raises(QgsProcessingException, match="does not name"):
        run("evaluatedetections", params)


# -------------------------------------------------------------------------------- checkpoint screening
def onnx_model(path, bias=None):
    """A heatmap model: the channel mean of the image (/255), or a constant ``bias`` everywhere."""
    import onnx
    from onnx import TensorProto, helper

    from birdseye.birdseye_qgis.core.detect.model_metadata import ModelMetadata, embed_metadata

    x = helper.make_tensor_value_info("image", TensorProto.FLOAT, ["n", 3, "h", "w"])
    y = helper.make_tensor_value_info("heat", TensorProto.FLOAT, ["n", 1, "h", "w"])
    w = np.full(3, 0.0 if bias is not None else 1.0 / 3.0)
    inits = [helper.make_tensor("k", TensorProto.FLOAT, [1, 3, 1, 1], w)]
    inputs = ["image", "k"]
    if bias is not None:
        inits.append(helper.make_tensor("b", TensorProto.FLOAT, [1], [bias]))
        inputs.append("b")
    node = helper.make_node("Conv", inputs, ["heat"])
    # IR 8 is opset 17's: a newer onnx stamps its own, which older onnxruntime releases refuse.
    model = helper.make_model(helper.make_graph([node], "m", [x], [y], inits),
                              opset_imports=[helper.make_opsetid("", 17)], ir_version=8)
    embed_metadata(model, ModelMetadata(resolution_cm=1.0, tile_size=32, tiles_overlap_pct=25.0,
                                        output_kind="probability", default_threshold=0.3))
    onnx.save(model, str(path))
    return path


def three_frame_scene(tmp_path):
    """Three nadir frames 0.3 m apart at 10 m (200 × 150 px, 1 cm/px) rendered with a 3 px Gaussian blob at
    each of three targets, as a frame layer with its images, and the targets as a geotag layer."""
    import cv2

    from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
    from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
    from birdseye.birdseye_qgis.core.geometry.projection import project_pairs

    cam = nadir_camera(200, 150)                         # 1 cm/px at 10 m: a 2 m × 1.5 m footprint
    east = np.array([0.0, 0.3, 0.6])
    targets = np.array([[0.1, 0.2], [-0.25, -0.1], [0.45, 0.05]])
    lat, lon, h = SITE.to_geodetic(np.column_stack([east, np.zeros(3), np.full(3, 10.0)]))
    q = rotmat_to_quat(euler_zyx_to_rotmat(0.0, 0.0, 0.0))
    poses = FramePoses(np.arange(3), lat, lon, h, np.tile(q, (3, 1)), np.full(3, SITE.h0), cam)
    geom = FrameGeometry(poses, SITE)
    images = []
    yy, xx = np.mgrid[0:150, 0:200]
    for k in range(3):
        uv = project_pairs(geom, np.full(3, k), np.column_stack([targets, np.zeros(3)]), LevelPlaneGround(geom)).uv
        img = np.zeros((150, 200))
        for u, v in uv:
            img = np.maximum(img, 0.9 * np.exp(-((xx - u) ** 2 + (yy - v) ** 2) / (2 * 3.0 ** 2)))
        path = tmp_path / f"frame_{k}.png"
        cv2.imwrite(str(path), np.repeat(np.rint(255 * img).astype(np.uint8)[:, :, None], 3, axis=2))
        images.append(str(path))
    frames = frame_layer(east, 0.0, cam, images)
    geo = point_layer("geotags", [QgsField("id", QVariant.Int)], [[1], [2], [3]], targets)
    return frames, geo


def test_screencheckpoints_flags_a_collapsed_sparse_model_and_keeps_the_good_one(birdseye_provider, tmp_path):

    frames, geo = three_frame_scene(tmp_path)
    good, flat = onnx_model(tmp_path / "good.onnx"), onnx_model(tmp_path / "flat.onnx", bias=0.8)
    table = tmp_path / "screen.csv"
    result = run("screencheckpoints", {"CHECKPOINTS": [str(good), str(flat)], "FRAMES": [frames], "GEOTAGS": geo,
                                       "PRESET": 1, "MIN_SAMPLES": 1, "COLLAPSED_BELOW": 0.5,
                                       "OUTPUT_TABLE": str(table),
                                       "OUTPUT_JSON": str(tmp_path / "screen.json"),
                                       "OUTPUT_PLOT": str(tmp_path / "screen.png")})
    with open(table, newline="", encoding="utf-8") as f:
        rows = {r["checkpoint"]: r for r in csv.DictReader(f)}
    assert result["N_HEALTHY"] == 1
    g, c = rows["good.onnx"], rows["flat.onnx"]
    assert g["healthy"] == "True" and float(g["recall_pre"]) == 1.0 and float(g["gmcf_pre"]) == 1.0
    assert float(g["f1_pixel"]) == 1.0 and int(g["pixel_tp"]) == 9 and g["frontier"] == "True"
    assert float(g["f1_pixel_radius_px"]) == 10.0 and float(g["f1_geo"]) == 1.0
    # the BirdsEye preset: whole flights at each checkpoint's own threshold (0.3 in its metadata)
    assert float(g["threshold"]) == 0.3 and g["worst_block"] == "frames"
    # 3 detections per frame; the flat model's 1 per frame is measured against it (it is not healthy)
    assert float(g["detections_per_frame"]) == 3.0 and float(g["review_load"]) == 1.0
    assert float(c["review_load"]) == pytest.approx(1 / 3)
    # the flat model fires once per frame, at the same (centre) pixel: collapsed (1/3 < 0.5) and sparse (1 < 1.7)
    assert c["collapsed"] == "True" and c["too_sparse"] == "True" and c["frontier"] == "False"
    assert float(c["distinct_position_fraction"]) == pytest.approx(1 / 3)
    assert float(c["worst_detections_per_frame"]) == 1.0
