"""One geotag layer, one set of ids: every algorithm that names geotags names each the same way.

The rule (docs/design.md#geotags): the ``id`` field when the layer has one, else the row (1.., feature
order), never the provider's feature id — a Shapefile counts features from 0, a GeoPackage from 1. The
same points are read as a memory layer, a GeoPackage and a Shapefile, with and without an ``id``
field, through Write labels (labels.csv), Cluster detections (matched_geotag_ids), Compare detectors
(geotag_id), Plan the survey flight (geotag_ids) and the review dock's reader; each output's id at each
geotag's position must be the one the rule gives. The scene is ``test_cluster_algorithms``' nadir frame.
"""
from __future__ import annotations

import csv

import numpy as np
import pytest
from qgis.core import (
    QgsCoordinateTransformContext,
    QgsFeature,
    QgsField,
    QgsProcessingException,
    QgsProject,
    QgsVectorFileWriter,
    QgsVectorLayer,
)
from qgis.PyQt.QtCore import QVariant
from test_cluster_algorithms import SITE, UTM, detection_layer, frame_layer, grid9, point_layer, run

from birdseye.birdseye_qgis.qgis_io.review_store import read_review_inputs

#: Positions (m east, north of the site, all in view of the frame) in feature order, and their ids.
POSITIONS = [(-3.0, 0.0), (3.0, 1.0), (-6.0, 3.0), (5.0, -4.0)]
FIELD_IDS = [17, 3, 42, 8]
ROW_IDS = [1, 2, 3, 4]


def geotags(with_id: bool, ids=FIELD_IDS, positions=POSITIONS):
    fields = ([QgsField("id", QVariant.Int)] if with_id else []) + [QgsField("label", QVariant.String)]
    rows = [([i] if with_id else []) + ["burrow"] for i in ids[:len(positions)]]
    return point_layer("geotags", fields, rows, positions)


def saved_copy(layer, tmp_path, driver: str):
    """``layer`` written to a GeoPackage or a Shapefile and opened again."""
    suffix = {"GPKG": "gpkg", "ESRI Shapefile": "shp"}[driver]
    path = str(tmp_path / f"geotags_{len(list(tmp_path.iterdir()))}.{suffix}")
    options = QgsVectorFileWriter.SaveVectorOptions()
    options.driverName = driver
    error = QgsVectorFileWriter.writeAsVectorFormatV3(layer, path, QgsCoordinateTransformContext(), options)[0]
    assert error == QgsVectorFileWriter.WriterError.NoError
    copy = QgsVectorLayer(path, "geotags", "ogr")
    assert copy.isValid() and copy.featureCount() == layer.featureCount()
    return copy


def spot(lat, lon):
    """The POSITIONS entry nearest (lat, lon), within 0.3 m."""
    east, north, _ = SITE.from_geodetic(lat, lon, SITE.h0).reshape(3)
    return nearest(east, north)


def nearest(east, north):
    d = [np.hypot(east - e, north - n) for e, n in POSITIONS]
    assert min(d) < 0.3
    return POSITIONS[int(np.argmin(d))]


def ids_by_path(layer, tmp_path):
    """{path: {position: id as text}} of every algorithm output that names geotags."""
    spots = np.concatenate([grid9(*p) for p in POSITIONS])
    det = detection_layer(spots)
    out = {}
    folder = tmp_path / f"labels_{len(list(tmp_path.iterdir()))}"
    run("writelabels", {"GEOTAGS": layer, "FRAMES": frame_layer(), "WRITE_RASTERS": False, "OUTPUT_FOLDER": str(folder),
                        "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None})
    rows = list(csv.DictReader(open(folder / "labels.csv", encoding="utf-8")))
    # 1 m east = +100 px in u, 1 m north = −100 px in v from the centre (959.5, 599.5).
    out["writelabels"] = {nearest((float(r["u"]) - 959.5) / 100, (599.5 - float(r["v"])) / 100): r["geotag_id"]
                          for r in rows}

    clusters = run("clusterdetections", {"DETECTIONS": det, "GEOTAGS": layer, "FRAMES": frame_layer(),
                                         "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    out["clusterdetections"] = {spot(*UTM.to_geodetic(f["centroid_x"], f["centroid_y"])): f["matched_geotag_ids"]
                                for f in clusters.getFeatures()}

    changes = run("comparedetectors", {"DETECTIONS_OLD": detection_layer(spots, digest="a" * 64, name="old"),
                                       "DETECTIONS_NEW": detection_layer(spots, digest="b" * 64, name="new"),
                                       "GEOTAGS": layer, "FRAMES": frame_layer(), "OUTPUT": "TEMPORARY_OUTPUT",
                                       "OUTPUT_JSON": str(folder) + ".json", "OUTPUT_REPORT": None})["OUTPUT"]
    out["comparedetectors"] = {}
    for f in changes.getFeatures():
        if f["geotag_id"]:
            p = f.geometry().asPoint()
            out["comparedetectors"][spot(*UTM.to_geodetic(p.x(), p.y()))] = f["geotag_id"]

    waypoints = run("planflight", {"GEOTAGS": layer, "MERGE_RADIUS_M": 0.5, "OUTPUT_WAYPOINTS": "TEMPORARY_OUTPUT",
                                   "OUTPUT_ROUTE": "TEMPORARY_OUTPUT"})["OUTPUT_WAYPOINTS"]
    out["planflight"] = {spot(f["lat"], f["lon"]): f["geotag_ids"] for f in waypoints.getFeatures()}

    review = read_review_inputs([det], frame_layer(), layer).geotags
    out["review"] = {spot(la, lo): str(i) for i, la, lo in zip(review.ids, review.lat, review.lon)}
    return out


@pytest.mark.parametrize("with_id", [True, False], ids=["id field", "no id field"])
def test_every_algorithm_names_each_geotag_by_the_same_id_in_every_format(birdseye_provider, tmp_path, with_id):
    memory = geotags(with_id)
    expected = {p: str(i) for p, i in zip(POSITIONS, FIELD_IDS if with_id else ROW_IDS)}
    copies = {"memory": memory, "GeoPackage": saved_copy(memory, tmp_path, "GPKG"),
              "Shapefile": saved_copy(memory, tmp_path, "ESRI Shapefile")}
    for fmt, layer in copies.items():
        for path, ids in ids_by_path(layer, tmp_path).items():
            assert ids == expected, (fmt, path)


def test_the_selection_keeps_the_ids_of_the_whole_layer(birdseye_provider):
    layer = geotags(with_id=False)
    QgsProject.instance().addMapLayer(layer)
    try:
        layer.selectByIds([f.id() for f in layer.getFeatures()][2:])
        waypoints = run("planflight", {"GEOTAGS": layer, "SELECTED_ONLY": True, "MERGE_RADIUS_M": 0.5,
                                       "OUTPUT_WAYPOINTS": "TEMPORARY_OUTPUT",
                                       "OUTPUT_ROUTE": "TEMPORARY_OUTPUT"})["OUTPUT_WAYPOINTS"]
        assert {spot(f["lat"], f["lon"]): f["geotag_ids"] for f in waypoints.getFeatures()} == {
            POSITIONS[2]: "3", POSITIONS[3]: "4"}
    finally:
        QgsProject.instance().removeMapLayer(layer.id())


@pytest.mark.parametrize("ids,message", [
    ([17, 3, 17, 8], "geotags, row 1, field 'id': gives id 17 to 2 geotags (rows 1, 3)"),
    ([17, None, 42, None], "geotags, row 2, field 'id': has 2 geotag(s) without an id (row(s) 2, 4)"),
])
def test_shared_or_empty_ids_are_refused_naming_the_rows(birdseye_provider, tmp_path, ids, message):
    layer = geotags(True, ids)
    for alg, params in (("writelabels", {"FRAMES": frame_layer(), "OUTPUT_FOLDER": str(tmp_path / "l"),
                                         "WRITE_RASTERS": False, "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None}),
                        ("evaluatedetections", {"DETECTIONS": [detection_layer(grid9(-3.0, 0.0))],
                                                "FRAMES": [frame_layer()], "OUTPUT_JSON": str(tmp_path / "e.json"),
                                                "OUTPUT_REPORT": None}),
                        ("planflight", {"OUTPUT_WAYPOINTS": "TEMPORARY_OUTPUT", "OUTPUT_ROUTE": "TEMPORARY_OUTPUT"})):
        with pytest.raises(QgsProcessingException) as info:
            run(alg, {"GEOTAGS": layer, **params})
        assert message in str(info.value), alg


def test_a_geotag_without_a_position_leaves_the_others_their_ids(birdseye_provider, tmp_path):
    layer = geotags(True)
    empty = QgsFeature(layer.fields())
    empty.setAttributes([99, "burrow"])
    layer.dataProvider().addFeatures([empty])                                   # row 5, no geometry
    layer.dataProvider().addFeatures([next(geotags(True, [5], POSITIONS[:1]).getFeatures())])   # row 6
    result = run("writelabels", {"GEOTAGS": layer, "FRAMES": frame_layer(), "WRITE_RASTERS": False,
                                 "OUTPUT_FOLDER": str(tmp_path / "l"), "OUTPUT_FRAMES": None,
                                 "OUTPUT_GEOTAGS": "TEMPORARY_OUTPUT"})
    seen = {f["id"]: f["frames_seen"] for f in result["OUTPUT_GEOTAGS"].getFeatures()}
    assert seen == {17: 1, 3: 1, 42: 1, 8: 1, 99: 0, 5: 1}
    with pytest.raises(QgsProcessingException, match="row 5, field 'geometry': has no position"):
        run("planflight", {"GEOTAGS": layer, "OUTPUT_WAYPOINTS": "TEMPORARY_OUTPUT",
                           "OUTPUT_ROUTE": "TEMPORARY_OUTPUT"})
