"""The layer boxes of BirdsEye's Processing dialogs (processing/parameters/layer_parameters.py), in the dialog QGIS's
toolbox opens (``processing.createAlgorithmDialog``), headless with pytest-qgis.

Each box lists only the layers of its kind (qgis_io/layer_kinds.py: frames, geotags, detections, verdict tables) and
a required one starts on the most recent of them; an optional one starts empty. Batch and Modeler dialogs get QGIS's
own widgets, and nothing of this reaches a run: a parameter's value is only ever the one given.
"""
from __future__ import annotations

import pytest
from qgis.core import QgsApplication, QgsFeature, QgsGeometry, QgsPointXY, QgsProject, QgsVectorLayer
from qgis.PyQt.QtWidgets import QDialog

from birdseye.birdseye_qgis.core.field.frame_records import FRAME_FIELD_NAMES
from birdseye.birdseye_qgis.core.plan.flight_plan import WAYPOINT_FIELDS
from birdseye.birdseye_qgis.qgis_io import layer_kinds
from birdseye.birdseye_qgis.qgis_io.detections import CLUSTER_FIELDS, DETECTION_FIELDS
from birdseye.birdseye_qgis.qgis_io.review_store import VERDICT_FIELD_NAMES
from birdseye.processing.parameters.layer_parameters import KINDS, LayerKindWidget, LayerKindWrapper

SITE = (151.95, -27.55)
OTHER_FIELD = (151.96, -27.55)  # about 1 km east


def memory_layer(geometry: str, fields, name: str, at=SITE) -> QgsVectorLayer:
    uri = f"{geometry}?crs=EPSG:4326" + "".join(f"&field={n}:string" for n in fields)
    layer = QgsVectorLayer(uri, name, "memory")
    feature = QgsFeature(layer.fields())
    point = QgsGeometry.fromPointXY(QgsPointXY(*at))
    feature.setGeometry(point if geometry == "Point" else point.buffer(0.0005, 4))
    layer.dataProvider().addFeatures([feature])
    layer.updateExtents()
    assert layer.isValid(), name
    return layer


def names(schema) -> list:
    return [field[0] for field in schema]


@pytest.fixture
def project(qgis_iface, birdseye_provider, monkeypatch):
    """A project with layers of every kind, added in this order: a verdict table, a survey, old frames, the
    detections, clusters, waypoints, new frames (the most recent frame layer), a second detection layer.

    The iface stub's browser model and active layer are MagicMocks, which QGIS's dialog hands to C++: none here."""
    monkeypatch.setattr(qgis_iface, "browserModel", lambda: None, raising=False)
    monkeypatch.setattr(qgis_iface, "activeLayer", lambda: None, raising=False)
    project = QgsProject.instance()
    project.clear()
    layer_kinds.track(project)
    added = {}
    # Named so that QGIS's own choice, the first by name, is the wrong one for every box.
    for key, name, geometry, fields in (
            ("verdicts", "verdicts", "Point", VERDICT_FIELD_NAMES[1:]), ("survey", "survey", "Point", ["id", "label"]),
            ("frames old", "Frames 1", "Polygon", FRAME_FIELD_NAMES),
            ("detections old", "Detections 1", "Point", names(DETECTION_FIELDS)),
            ("clusters", "Clusters", "Polygon", names(CLUSTER_FIELDS)),
            ("waypoints", "Waypoints", "Point", names(WAYPOINT_FIELDS)),
            ("frames new", "Frames 2", "Polygon", FRAME_FIELD_NAMES),
            ("detections new", "Detections 2", "Point", names(DETECTION_FIELDS))):
        added[key] = memory_layer(geometry, fields, name)
        project.addMapLayer(added[key])
    yield added
    project.clear()


def dialog_wrappers(alg_id, parameters=None):
    """The parameter widget wrappers of ``birdseye:<alg_id>``'s dialog, as the toolbox opens it."""
    import processing

    dialog = processing.createAlgorithmDialog(f"birdseye:{alg_id}", parameters or {})
    return dialog, dialog.mainWidget().wrappers


def layer_parameters():
    """(algorithm id, parameter) of every parameter of ours that takes one map layer."""
    for algorithm in QgsApplication.processingRegistry().providerById("birdseye").algorithms():
        for parameter in algorithm.parameterDefinitions():
            if parameter.type() in ("source", "vector"):
                yield algorithm.id(), parameter


def test_every_layer_parameter_names_its_kind(birdseye_provider):
    """Every single-layer parameter of ours (Import geotags' INPUT_LAYER aside: it reads any point layer, for
    another engineer to decide) has the dialog widget of a kind."""
    found = {f"{alg}:{p.name()}": p.metadata().get("widget_wrapper", {}).get("kind")
             for alg, p in layer_parameters() if alg != "birdseye:importgeotags"}
    assert found and all(kind in KINDS for kind in found.values()), found
    assert found["birdseye:detect:FRAMES"] == found["birdseye:writelabels:FRAMES"] == layer_kinds.FRAMES
    assert found["birdseye:writelabels:GEOTAGS"] == found["birdseye:planflight:GEOTAGS"] == layer_kinds.GEOTAGS
    assert found["birdseye:writelabels:REVIEW"] == layer_kinds.VERDICTS
    assert found["birdseye:clusterdetections:DETECTIONS"] == layer_kinds.DETECTIONS


def test_boxes_offer_their_kind_and_start_on_the_most_recent(project):
    dialog, wrappers = dialog_wrappers("writelabels")
    try:
        frames, geotags, review = wrappers["FRAMES"], wrappers["GEOTAGS"], wrappers["REVIEW"]
        assert isinstance(frames, LayerKindWrapper)
        assert frames.combo().currentLayer() is project["frames new"]
        assert set(offered(frames)) == {project["frames old"], project["frames new"]}
        # Geotags: any point layer of no other kind; not detections, waypoints or verdicts.
        assert geotags.combo().currentLayer() is project["survey"]
        assert offered(geotags) == [project["survey"]]
        # Optional: only verdict tables offered, and none chosen until the user chooses.
        assert offered(review) == [project["verdicts"]]
        assert review.combo().currentLayer() is None and review.parameterValue() in (None, "")
        assert dialog.mainWidget().createProcessingParameters()["FRAMES"] == project["frames new"].id()
    finally:
        dialog.close()


def test_detect_frames_never_start_on_a_point_layer_of_another_kind(project):
    """Detect takes point or polygon frame layers: its box starts on the frames, not on the survey."""
    dialog, wrappers = dialog_wrappers("detect")
    try:
        assert wrappers["FRAMES"].combo().currentLayer() is project["frames new"]
        assert all(layer_kinds.layer_kind(layer) == layer_kinds.FRAMES for layer in offered(wrappers["FRAMES"]))
    finally:
        dialog.close()


def test_compare_detectors_starts_old_and_new_on_the_two_latest_detection_layers(project):
    dialog, wrappers = dialog_wrappers("comparedetectors")
    try:
        assert wrappers["DETECTIONS_NEW"].combo().currentLayer() is project["detections new"]
        assert wrappers["DETECTIONS_OLD"].combo().currentLayer() is project["detections old"]
    finally:
        dialog.close()


def test_a_value_given_wins_and_a_layer_of_the_wrong_kind_is_not_taken(project):
    dialog, wrappers = dialog_wrappers("writelabels", {"FRAMES": project["frames old"].id(),
                                                       "GEOTAGS": project["detections new"].id()})
    try:
        assert wrappers["FRAMES"].combo().currentLayer() is project["frames old"]
        assert wrappers["GEOTAGS"].combo().currentLayer() is project["survey"]
    finally:
        dialog.close()


def test_a_layer_added_while_the_dialog_is_open_is_offered_by_its_kind(project):
    dialog, wrappers = dialog_wrappers("clusterdetections")
    try:
        later_frames = memory_layer("Polygon", FRAME_FIELD_NAMES, "frames added later")
        QgsProject.instance().addMapLayer(later_frames)
        assert later_frames in offered(wrappers["FRAMES"])
        assert later_frames not in offered(wrappers["DETECTIONS"]) + offered(wrappers["GEOTAGS"])
    finally:
        dialog.close()


@pytest.fixture
def two_fields(project):
    """Two fields' survey, frames and detections, added field A, field B, then field A again: the latest frames
    are B's, the latest detections A's."""
    project = QgsProject.instance()
    project.removeAllMapLayers()
    added = {}
    for key, geometry, fields, at in (
            ("survey A", "Point", ["id", "label"], SITE), ("frames A", "Polygon", FRAME_FIELD_NAMES, SITE),
            ("detections A1", "Point", names(DETECTION_FIELDS), SITE),
            ("survey B", "Point", ["id", "label"], OTHER_FIELD),
            ("frames B", "Polygon", FRAME_FIELD_NAMES, OTHER_FIELD),
            ("detections B", "Point", names(DETECTION_FIELDS), OTHER_FIELD),
            ("detections A2", "Point", names(DETECTION_FIELDS), SITE)):
        added[key] = memory_layer(geometry, fields, key, at)
        project.addMapLayer(added[key])
    return added


def test_a_box_starts_on_the_layer_over_the_same_ground(two_fields):
    dialog, wrappers = dialog_wrappers("comparedetectors")
    try:
        assert wrappers["DETECTIONS_NEW"].combo().currentLayer() is two_fields["detections A2"]
        # The old detector ran on the same flight: A1, though B's detections are more recent.
        assert wrappers["DETECTIONS_OLD"].combo().currentLayer() is two_fields["detections A1"]
        assert wrappers["FRAMES"].combo().currentLayer() is two_fields["frames A"]
        assert wrappers["GEOTAGS"].combo().currentLayer() is two_fields["survey A"]
    finally:
        dialog.close()


def test_its_own_choice_follows_the_flight_and_the_users_stays(two_fields):
    dialog, wrappers = dialog_wrappers("writelabels")
    try:
        frames, geotags = wrappers["FRAMES"].combo(), wrappers["GEOTAGS"].combo()
        assert frames.currentLayer() is two_fields["frames B"] and geotags.currentLayer() is two_fields["survey B"]
        frames.setLayer(two_fields["frames A"])
        assert geotags.currentLayer() is two_fields["survey A"], "follows the frames while it is its own choice"
        geotags.setLayer(two_fields["survey B"])
        frames.setLayer(two_fields["frames B"])
        frames.setLayer(two_fields["frames A"])
        assert geotags.currentLayer() is two_fields["survey B"], "the user's choice stays"
    finally:
        dialog.close()


class ModelerParametersDialog(QDialog):
    """Stands for QGIS's Modeler dialog of a child algorithm (what the widget factory reads of it)."""

    def __init__(self):
        super().__init__()
        from qgis.core import QgsProcessingContext, QgsProcessingModelAlgorithm

        self.model, self.childId, self.context = QgsProcessingModelAlgorithm(), "child", QgsProcessingContext()


def test_batch_and_modeler_dialogs_get_qgis_own_widgets(project):
    """Where a value is one per row, a model input or another step's output, QGIS's widget is the right one."""
    from processing.gui.BatchAlgorithmDialog import BatchAlgorithmDialog
    from qgis.gui import QgsProcessingModelerParameterWidget

    algorithm = QgsApplication.processingRegistry().createAlgorithmById("birdseye:writelabels")
    batch = BatchAlgorithmDialog(algorithm.create())
    try:
        [row] = batch.mainWidget().wrappers
        frames = row[[p.name() for p in algorithm.parameterDefinitions()].index("FRAMES")]
        assert frames.parameterDefinition().name() == "FRAMES" and not isinstance(frames, LayerKindWrapper)
    finally:
        batch.close()
    parameter = algorithm.parameterDefinition("FRAMES")
    modeler = LayerKindWidget(parameter, ModelerParametersDialog(), kind=parameter.metadata()["widget_wrapper"]["kind"])
    assert isinstance(modeler, QgsProcessingModelerParameterWidget)


def test_the_parameters_themselves_carry_no_default_layer(project):
    """qgis_process and processing.run see plain parameters: no layer of the project is a default."""
    for alg, parameter in layer_parameters():
        assert parameter.defaultValue() in (None, ""), f"{alg}:{parameter.name()}"


def offered(wrapper) -> list:
    box = wrapper.layer_box()
    return [layer for layer in (box.layer(i) for i in range(box.count())) if layer is not None]
