"""The layer styles of resources/styles, loaded as Processing loads them onto each output's schema: each loads,
its legend says in words what each colour means and fits the Layers panel, each feature is drawn by the one
class meant for it, frame footprints are outlines, and label-check distances never overprint."""
from __future__ import annotations

import re
from pathlib import Path

import pytest
from qgis.core import (
    QgsFeature,
    QgsGeometry,
    QgsMapRendererSequentialJob,
    QgsMapSettings,
    QgsPointXY,
    QgsRectangle,
    QgsRenderContext,
    QgsVectorLayer,
)
from qgis.PyQt.QtCore import QSize, Qt

from birdseye.birdseye_qgis.core.field.flight_track import TRACK_FIELDS
from birdseye.birdseye_qgis.core.field.frames import FRAME_LAYER_FIELDS
from birdseye.birdseye_qgis.core.field.geotags import GEOTAG_FIELDS
from birdseye.birdseye_qgis.core.field.survey_report import PARTITION_FIELDS
from birdseye.birdseye_qgis.core.labels.mark_check import MARK_CHECK_FIELDS
from birdseye.birdseye_qgis.core.plan.flight_plan import ROUTE_FIELDS, WAYPOINT_FIELDS
from birdseye.birdseye_qgis.core.scoring.compare import CHANGE_FIELDS, CHANGES
from birdseye.birdseye_qgis.qgis_io.detections import CLUSTER_FIELDS, DETECTION_FIELDS, POINT_FIELDS
from birdseye.birdseye_qgis.qgis_io.layers import qgs_fields

STYLES = Path(__file__).resolve().parents[2] / "resources" / "styles"
# Each style, the geometry and schema of the outputs it styles, and its renderer.
SCHEMAS = {
    "geotags.qml": ("PointZ", GEOTAG_FIELDS, "categorizedSymbol"),
    "frames.qml": ("PolygonZ", FRAME_LAYER_FIELDS, "categorizedSymbol"),
    "track.qml": ("LineStringZ", TRACK_FIELDS, "RuleRenderer"),
    "detections.qml": ("PointZ", DETECTION_FIELDS, "RuleRenderer"),
    "clusters.qml": ("Polygon", CLUSTER_FIELDS, "categorizedSymbol"),
    "cluster_points.qml": ("Point", POINT_FIELDS, "RuleRenderer"),
    "waypoints.qml": ("PointZ", WAYPOINT_FIELDS, "RuleRenderer"),
    "route.qml": ("LineString", ROUTE_FIELDS, "RuleRenderer"),
    "mark_check.qml": ("PointZ", MARK_CHECK_FIELDS, "RuleRenderer"),
    "changes.qml": ("Point", CHANGE_FIELDS, "categorizedSymbol"),
    "partitions.qml": ("MultiPolygon", PARTITION_FIELDS, "RuleRenderer"),
}
# A legend entry the Layers panel shows whole at its default width (one group deep, DejaVu Sans 9 pt).
MAX_LEGEND_CHARS = 24
# A footprint may tint the map this much at most: 75 overlapping frames must not add up to a solid colour.
MAX_FILL_OPACITY = 0.05


def styled(style: str, name: str = "layer") -> QgsVectorLayer:
    geometry, schema, _ = SCHEMAS[style]
    layer = QgsVectorLayer(f"{geometry}?crs=EPSG:32756", name, "memory")
    layer.dataProvider().addAttributes(qgs_fields(schema).toList())
    layer.updateFields()
    message, ok = layer.loadNamedStyle(str(STYLES / style))
    assert ok, f"{style}: {message}"
    return layer


def drawn_as(layer, values: dict) -> list:
    """The legend entries a feature with these attribute values is drawn with."""
    renderer = layer.renderer().clone()
    feature = QgsFeature(layer.fields())
    for name, value in values.items():
        feature[name] = value
    context = QgsRenderContext()
    expressions = layer.createExpressionContext()
    expressions.setFeature(feature)
    context.setExpressionContext(expressions)
    renderer.startRender(context, layer.fields())
    try:
        keys = renderer.legendKeysForFeature(feature, context)
    finally:
        renderer.stopRender(context)
    labels = {item.ruleKey(): item.label() for item in renderer.legendSymbolItems()}
    return sorted(labels[key] for key in keys if key in labels)  # not the rule-based renderer's root rule


def symbol_of(layer, label: str):
    items = layer.renderer().legendSymbolItems()  # they own their symbols
    return next(item.symbol().clone() for item in items if item.label() == label)


def test_every_style_has_a_style_file():
    assert sorted(p.name for p in STYLES.glob("*.qml")) == sorted(SCHEMAS)


@pytest.mark.parametrize("style", sorted(SCHEMAS))
def test_the_legend_says_in_words_what_each_colour_means(qgis_app, style):
    layer = styled(style)
    assert layer.renderer().type() == SCHEMAS[style][2]
    legend = [item.label() for item in layer.renderer().legendSymbolItems()]
    assert legend and len(set(legend)) == len(legend), legend
    for label in legend:
        assert len(re.findall(r"[A-Za-z]{2,}", label)) >= 2, f"{style}: {label!r} is not words"
        assert len(label) <= MAX_LEGEND_CHARS, f"{style}: {label!r} is cut off in the Layers panel"


def test_frame_footprints_are_outlines(qgis_app):
    layer = styled("frames.qml")
    for item in layer.renderer().legendSymbolItems():
        symbol = item.symbol()
        for k in range(symbol.symbolLayerCount()):
            fill = symbol.symbolLayer(k)
            filled = fill.brushStyle() != Qt.BrushStyle.NoBrush
            opacity = symbol.opacity() * fill.fillColor().alphaF() if filled else 0.0
            assert opacity <= MAX_FILL_OPACITY, f"{item.label()}: fill opacity {opacity:.2f}"


@pytest.mark.parametrize("values, label", [
    ({"rtk_status": 3, "flags": ""}, "RTK fixed, cm accurate"),
    ({"rtk_status": 2, "flags": "rtk_float"}, "RTK float, dm accurate"),
    ({"rtk_status": 1, "flags": "rtk_none"}, "No RTK, m accurate"),
    ({"rtk_status": None, "flags": None}, "RTK status unknown"),
    # A camera solution's frames are bundle adjusted, whatever RTK status their images carry.
    ({"rtk_status": None, "flags": "camera_solution,geotag_heights"}, "From a camera solution"),
    ({"rtk_status": 1, "flags": "camera_solution"}, "From a camera solution"),
    ({"rtk_status": 3, "flags": "yaw_from_flight,refined"}, "Refined from the images"),
    ({"rtk_status": 3, "flags": "not_refined"}, "Not refined: metadata"),
    ({"rtk_status": 2, "flags": "rtk_float,not_refined"}, "Not refined: metadata"),
])
def test_each_frame_is_drawn_by_the_one_class_meant_for_it(qgis_app, values, label):
    assert drawn_as(styled("frames.qml"), values) == [label]


def test_refined_and_metadata_frames_look_different(qgis_app):
    layer = styled("frames.qml")
    refined, metadata = symbol_of(layer, "Refined from the images"), symbol_of(layer, "Not refined: metadata")
    colours = [s.symbolLayer(0).strokeColor().name() for s in (refined, metadata)]
    dashes = [s.symbolLayer(0).strokeStyle() for s in (refined, metadata)]
    assert colours[0] != colours[1] and dashes == [Qt.PenStyle.SolidLine, Qt.PenStyle.DashLine], (colours, dashes)


@pytest.mark.parametrize("values, label", [
    ({"fix_quality": 4, "flags": ""}, "RTK fixed, cm accurate"),
    ({"fix_quality": 5, "flags": "rtk_float"}, "RTK float, dm accurate"),
    ({"fix_quality": 1, "flags": "no_rtk"}, "No RTK fix, m accurate"),
    ({"fix_quality": None, "flags": None}, "No RTK fix, m accurate"),
    ({"fix_quality": 0, "flags": "control_point"}, "Control point"),
    ({"fix_quality": 0, "flags": "check_point"}, "Check point (not fitted)"),
])
def test_each_geotag_is_drawn_by_its_class(qgis_app, values, label):
    assert drawn_as(styled("geotags.qml"), values) == [label]


@pytest.mark.parametrize("style, values, label", [
    ("clusters.qml", {"hit": 1}, "On a surveyed target"),
    ("clusters.qml", {"hit": 0}, "Not on a target: review"),
    ("detections.qml", {"score": 0.93}, "Strong, score 0.8 to 1"),
    ("detections.qml", {"score": 0.6}, "Medium, score 0.5 to 0.8"),
    ("detections.qml", {"score": 0.12}, "Weak, score below 0.5"),
    ("cluster_points.qml", {"cluster_id": 4}, "In a cluster"),
    ("cluster_points.qml", {"cluster_id": -1}, "Noise: in no cluster"),
    ("mark_check.qml", {"error_px": 1.9}, "Within 3 px of the mark"),
    ("mark_check.qml", {"error_px": 7.3}, "3 to 10 px from the mark"),
    ("mark_check.qml", {"error_px": 12.0}, "Over 10 px from the mark"),
    ("mark_check.qml", {"error_px": None}, "No label in that image"),
    ("partitions.qml", {"worker": 2}, "Worker 2's pieces"),
    ("partitions.qml", {"worker": 9}, "Other workers' pieces"),
])
def test_each_feature_is_drawn_by_one_class(qgis_app, style, values, label):
    assert drawn_as(styled(style), values) == [label]


def test_every_change_has_its_own_class(qgis_app):
    layer = styled("changes.qml")
    assert sorted(c.value() for c in layer.renderer().categories()) == sorted(CHANGES)


def test_flight_lines_are_labelled_with_their_flight(qgis_app):
    """Two flights' lines read differently, each numbered within its own flight when it has parts."""
    from qgis.core import QgsExpression

    def labels(name: str, segments: int) -> list:
        layer = styled("track.qml", name)
        features = []
        for k in range(1, segments + 1):
            feature = QgsFeature(layer.fields())
            feature.setAttributes([k, f"Flight line {k}: 75 frames, 0.2 min, 31 m", 0.0, 14.8, 14.8, 75, 31.0])
            feature.setGeometry(QgsGeometry.fromPolylineXY([QgsPointXY(0, k), QgsPointXY(30, k)]))
            features.append(feature)
        layer.dataProvider().addFeatures(features)
        settings = layer.labeling().settings()
        assert layer.labelsEnabled() and settings.isExpression
        expression = QgsExpression(settings.fieldName)
        context = layer.createExpressionContext()
        out = []
        for feature in layer.getFeatures():
            context.setFeature(feature)
            out.append(expression.evaluate(context))
        assert not expression.hasEvalError(), expression.evalErrorString()
        return out

    first, second = labels("Flight line · training 1", 1), labels("Flight line · training 2", 1)
    assert first == ["Flight line · training 1: 75 frames, 0.2 min, 31 m"]
    assert first != second
    assert labels("Flight line · held-out", 2) == ["Flight line · held-out, part 1: 75 frames, 0.2 min, 31 m",
                                                   "Flight line · held-out, part 2: 75 frames, 0.2 min, 31 m"]


def test_label_check_distances_never_overprint(qgis_app):
    """Four marks of each control point, closer together than their labels are long: one label per point, on its
    worst mark and only when that is over 3 px, giving the range of its marks' distances; no two labels overlap."""
    layer = styled("mark_check.qml")
    errors = {1: [1.9, 7.3, 2.4, 11.8], 2: [4.2, 0.8, 9.6, 5.5], 3: [3.1, 2.0, 2.2, 1.0], 4: [1.0, 2.5, 0.4, 2.9]}
    features = []
    for point_id, point_errors in errors.items():
        for k, error in enumerate(point_errors):
            feature = QgsFeature(layer.fields())
            feature["point_id"], feature["error_px"] = point_id, error
            x, y = 500000.0 + 0.12 * (point_id % 2) + 0.02 * k, 6950000.0 + 0.1 * (point_id // 2) + 0.015 * k
            feature.setGeometry(QgsGeometry.fromPointXY(QgsPointXY(x, y)))
            features.append(feature)
    layer.dataProvider().addFeatures(features)
    layer.updateExtents()
    settings = QgsMapSettings()
    settings.setLayers([layer])
    settings.setDestinationCrs(layer.crs())
    settings.setOutputSize(QSize(400, 300))
    settings.setExtent(QgsRectangle(499999.7, 6949999.8, 500000.5, 6950000.4))
    job = QgsMapRendererSequentialJob(settings)
    job.start()
    job.waitForFinished()
    placed = [label for label in job.takeLabelingResults().allLabels() if not getattr(label, "isUnplaced", False)]
    assert sorted(label.labelText for label in placed) == ["0.8–9.6 px", "1.0–3.1 px", "1.9–11.8 px"]
    boxes = [label.labelRect for label in placed]
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            assert not a.intersects(b), "two label-check distances overprint"
