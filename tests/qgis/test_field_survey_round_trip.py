"""The field survey's loop end to end, through the registry (issue 32): a review's unresolved clusters go out in
a field package; a worker "collects" in it as QField does — geotags created under a simulated RTK position, one of
them FLOAT, decisions saved at the points to visit, the form's expressions evaluated in QField's position context;
the package comes back through Import geotags with fixes, accuracies and times intact and the decisions in the
review's own verdict log, which Write labels then takes as it takes the dock's verdicts.

The review is ``test_review_loop``'s scene (one nadir frame over six clusters; geotag 1 matches A; B confirmed,
C hard negative; D uncertain, E conflicting, F never judged), its verdicts in a real GeoPackage log.
"""
from __future__ import annotations

import csv
import json

import cv2
import numpy as np
import pytest
from qgis.core import (
    QgsExpression,
    QgsExpressionContext,
    QgsExpressionContextScope,
    QgsFeatureRequest,
    QgsFieldConstraints,
    QgsGeometry,
    QgsPoint,
    QgsProject,
    QgsVectorLayer,
    QgsVectorLayerUtils,
)
from qgis.PyQt.QtCore import QDateTime, Qt
from test_cluster_algorithms import SITE, frame_layer, geotag_layer, run
from test_review_loop import SPOTS, scene

from birdseye.birdseye_qgis.core.field import field_survey as fs
from birdseye.birdseye_qgis.core.review.actions import PlannedRow
from birdseye.birdseye_qgis.core.scoring.verdicts import CONFIRMED, HARD_NEGATIVE
from birdseye.birdseye_qgis.qgis_io.review_store import RowMeta, VerdictStore

#: The review of test_review_loop.scene(), as the dock would have logged it.
REVIEW_ROWS = [("uA", "hard_negative", "direct", "A"), ("uB", "confirmed_real", "direct", "B"),
               ("uC", "hard_negative", "direct", "C"), ("uD", "uncertain", "direct", "D"),
               ("uE", "confirmed_real", "direct", "E"), ("uE", "hard_negative", "propagated:dbscan_0.20m/uE", "E")]
#: What the worker finds at the points to visit: D and F are burrows, E is not.
DECIDED = {"D": CONFIRMED, "E": HARD_NEGATIVE, "F": CONFIRMED}
#: The simulated receiver: two geotags, one RTK fixed and one RTK float, each with its own time.
RECORDS = [("Fixed RTK", 0.011, 0.019, "2026-11-28T08:30:15.250Z", (1.0, 2.0)),
           ("Float RTK", 0.094, 0.161, "2026-11-28T08:41:02.500Z", (-2.0, -1.0))]
ORTHOMETRIC_M = 371.5        # the receiver's altitude (orthometric, QField's default setting)
N_M = 41.25                  # the geoid undulation given to Import geotags


def geodetic(east, north):
    lat, lon, _ = SITE.to_geodetic(np.array([[east, north, 0.0]]))
    return float(lat[0]), float(lon[0])


def review_log(path):
    store = VerdictStore(path)
    try:
        meta = RowMeta("ana", json.dumps({}), json.dumps({}), json.dumps({}))
        for key, verdict, provenance, spot in REVIEW_ROWS:   # one action each, as the dock appends them
            store.append([PlannedRow(key, verdict, provenance, *geodetic(*SPOTS[spot]), ("detections",))],
                         "verdict", meta)
        return store.layer_uri
    finally:
        store.close()


def position_scope(fix, h_acc, v_acc, time, lat, lon):
    """QField's position variables for a receiver at (lat, lon) with this fix."""
    scope = QgsExpressionContextScope("position")
    for name, value in {"position_quality_description": fix, "position_horizontal_accuracy": h_acc,
                        "position_vertical_accuracy": v_acc, "position_pdop": 1.3, "position_hdop": 0.7,
                        "position_vdop": 1.1, "position_number_of_used_satellites": 21,
                        "position_averaged_count": 0, "position_source_name": "Bluetooth: Reach RS4",
                        "position_timestamp": QDateTime.fromString(time, Qt.DateFormat.ISODateWithMs),
                        "position_coordinate": QgsGeometry(QgsPoint(lon, lat, ORTHOMETRIC_M)),
                        "user_full_name": "Ann Field"}.items():
        scope.setVariable(name, value)
    return scope


def in_position(layer, scope, feature=None):
    """The layer's expression context with ``scope`` appended (the context takes ownership of it)."""
    context = QgsExpressionContext(layer.createExpressionContext())
    context.appendScope(scope)
    if feature is not None:
        context.setFeature(feature)
    return context


def collect(project_path):
    """The worker's day in the package: a geotag per RECORDS, and the decisions DECIDED at the points to visit
    (QField saves the visit with its update defaults evaluated in the position context). Returns whether each
    geotag met the accuracy requirement, in RECORDS order."""
    project = QgsProject()
    assert project.read(str(project_path))
    (geotags,) = project.mapLayersByName("Geotags")
    (visits,) = project.mapLayersByName("Points to visit")
    met = []
    assert geotags.startEditing()
    for fix, h_acc, v_acc, time, (east, north) in RECORDS:
        lat, lon = geodetic(east, north)
        scope = position_scope(fix, h_acc, v_acc, time, lat, lon)
        feature = QgsVectorLayerUtils.createFeature(geotags, QgsGeometry(QgsPoint(lon, lat, ORTHOMETRIC_M)), {},
                                                    in_position(geotags, scope))
        index = geotags.fields().indexOf("h_acc_m")
        met.append(QgsVectorLayerUtils.validateAttribute(geotags, feature, index,
                                                         QgsFieldConstraints.ConstraintStrengthSoft)[0])
        assert geotags.addFeature(feature)
    assert geotags.commitChanges(), geotags.commitErrors()

    # QField saves a decided visit with its update defaults evaluated in its position context; QGIS's own editing
    # would evaluate them again without it, so the values go to the provider as QField stores them.
    changes = {}
    for visit in visits.getFeatures(QgsFeatureRequest()):
        point = visit.geometry().asPoint()
        east, north, _ = SITE.from_geodetic(point.y(), point.x(), SITE.h0).reshape(3)
        spot = next(k for k, xy in SPOTS.items() if abs(xy[0] - east) < 0.05 and abs(xy[1] - north) < 0.05)
        visit["decision"] = DECIDED[spot]
        context = in_position(visits, position_scope("Fixed RTK", 0.01, 0.02, "2026-11-28T09:05:00.000Z",
                                                     point.y(), point.x()), visit)
        values = {visits.fields().indexOf("decision"): DECIDED[spot]}
        for k in range(visits.fields().count()):
            definition = visits.defaultValueDefinition(k)
            if definition.isValid() and definition.applyOnUpdate():
                values[k] = QgsExpression(definition.expression()).evaluate(context)
        changes[visit.id()] = values
    assert visits.dataProvider().changeAttributeValues(changes)
    decided = list(visits.dataProvider().getFeatures())
    assert {f["worker"] for f in decided} == {"Ann Field"} and {f["fix"] for f in decided} == {"Fixed RTK"}
    assert all(f["h_acc_m"] == 0.01 and f["time_utc"].isValid() for f in decided)
    return met


def test_unresolved_clusters_go_out_to_the_field_and_come_back_as_verdicts_write_labels_takes(
        birdseye_provider, tmp_path):
    frame_image = str(tmp_path / "frame0.png")      # the scene's one frame, grey: Write labels cuts tiles from it
    assert cv2.imwrite(frame_image, np.full((1200, 1920, 3), 80, np.uint8))
    det, _ = scene()
    log_uri = review_log(tmp_path / "review.gpkg")
    verdicts = QgsVectorLayer(log_uri, "verdicts", "ogr")
    assert verdicts.isValid()
    package = run("preparefieldsurvey", {
        "OUTPUT_FOLDER": str(tmp_path / "walk"), "CLASSES": "burrow", "GEOTAGS": geotag_layer(),
        "REVIEW": verdicts, "REVIEW_DETECTIONS": [det], "REVIEW_FRAMES": [frame_layer()]})
    assert package["VISIT_COUNT"] == 3                               # D, E, F: what the review left open
    meta = QgsVectorLayer(f"{tmp_path / 'walk' / fs.PACKAGE_GPKG}|layername={fs.META_TABLE}", "meta", "ogr")
    assert {f["key"]: f["value"] for f in meta.getFeatures()}[fs.META_REVIEW_LOG] == str(tmp_path / "review.gpkg")

    met = collect(package["PROJECT"])
    assert met == [True, False], "the FLOAT point is flagged by the accuracy requirement, the fixed one passes"

    imported = run("importgeotags", {"INPUT": str(tmp_path / "walk" / fs.PACKAGE_GPKG),
                                     "GEOID_UNDULATION_M": N_M, "OUTPUT": "TEMPORARY_OUTPUT"})
    assert (imported["GEOTAG_COUNT"], imported["DECISIONS_IMPORTED"], imported["VISITS_UNDECIDED"]) == (2, 3, 0)
    rows = sorted(imported["OUTPUT"].getFeatures(), key=lambda f: f["time_utc"])
    assert [(f["fix_quality"], f["h_acc_m"], f["v_acc_m"], f["worker"], f["label"]) for f in rows] == [
        (4, 0.011, 0.019, "Ann Field", "burrow"), (5, 0.094, 0.161, "Ann Field", "burrow")]
    # QGIS 3.22's GeoPackage writer keeps whole seconds of a DateTime field; later releases keep milliseconds.
    assert [f["time_utc"][:19] for f in rows] == [t[:19] for _, _, _, t, _ in RECORDS]
    assert ["rtk_float" in (f["flags"] or "") for f in rows] == [False, True]
    assert [f["h_ellipsoid"] for f in rows] == pytest.approx([ORTHOMETRIC_M + N_M] * 2)
    assert [f["h_msl"] for f in rows] == pytest.approx([ORTHOMETRIC_M] * 2)

    # The review now holds the field's verdicts: Write labels labels D and F (confirmed, no geotag) beside the
    # dock's B, and E (its direct vote now the field's rejection, agreeing with the propagated one) joins C as a
    # hard negative: nothing is left unresolved.
    review = QgsVectorLayer(log_uri, "verdicts", "ogr")
    reviewers = {f["unit_key"]: f["reviewer"] for f in review.getFeatures()}
    assert reviewers["uD"] == "field:Ann Field" and any(r == "field:Ann Field" and k.startswith("u-")
                                                          for k, r in reviewers.items())
    out = tmp_path / "labels"
    labels = run("writelabels", {
        "GEOTAGS": geotag_layer(), "FRAMES": frame_layer(images=[frame_image]), "SIGMA_PX": 5.0,
        "WRITE_RASTERS": False, "WRITE_TILES": True, "TILE_SIZE": 224, "SURVEY_MARGIN_M": 20.0,
        "NEGATIVE_RATIO": 1.0, "REVIEW": review, "REVIEW_DETECTIONS": [det], "OUTPUT_FOLDER": str(out),
        "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None})
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["n_unresolved_in_view"] == 0
    assert (labels["REVIEW_TARGETS"], labels["HARD_NEGATIVES"]) == (3, 2)
    targets = [r for r in csv.DictReader(open(out / "labels.csv", encoding="utf-8")) if r["provenance"] == "review"]
    assert len(targets) == 3
