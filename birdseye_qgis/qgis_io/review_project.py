"""A review kept in the QGIS project (its layers, log, parameters), and its verdicts shown as a layer."""
from __future__ import annotations

import json
from dataclasses import dataclass

from qgis.core import QgsCategorizedSymbolRenderer, QgsMarkerSymbol, QgsRendererCategory, QgsVectorLayer

PROJECT_SCOPE = "BirdsEye"


@dataclass
class SavedReview:
    detection_layers: list
    frame_layer: object
    geotag_layer: object
    store_path: str
    parameters: dict
    propagate: bool


def save_review(project, detection_layers, frame_layer, geotag_layer, store_path: str, parameters: dict,
                propagate: bool) -> None:
    """Keep the review in ``project``; ``frame_layer`` None for detections found on a raster (they need none)."""
    project.writeEntry(PROJECT_SCOPE, "review/detections", [layer.id() for layer in detection_layers])
    project.writeEntry(PROJECT_SCOPE, "review/frames", frame_layer.id() if frame_layer is not None else "")
    project.writeEntry(PROJECT_SCOPE, "review/geotags", geotag_layer.id())
    project.writeEntry(PROJECT_SCOPE, "review/store", store_path)
    project.writeEntry(PROJECT_SCOPE, "review/parameters", json.dumps(parameters))
    save_propagate(project, propagate)


def save_propagate(project, propagate: bool) -> None:
    project.writeEntry(PROJECT_SCOPE, "review/propagate", bool(propagate))


def saved_review(project) -> SavedReview | None:
    """The review ``project`` was saved with, or None when it has none or one of its layers is gone (a review of
    detections found on a raster was saved without a frame layer: ``frame_layer`` None)."""
    ids, ok = project.readListEntry(PROJECT_SCOPE, "review/detections")
    if not ok or not ids:
        return None
    layers = [project.mapLayer(i) for i in ids]
    frame_id = project.readEntry(PROJECT_SCOPE, "review/frames")[0]
    frame_layer = project.mapLayer(frame_id) if frame_id else None
    geotag_layer = project.mapLayer(project.readEntry(PROJECT_SCOPE, "review/geotags")[0])
    store = project.readEntry(PROJECT_SCOPE, "review/store")[0]
    if None in layers or (frame_id and frame_layer is None) or geotag_layer is None or not store:
        return None
    parameters = json.loads(project.readEntry(PROJECT_SCOPE, "review/parameters", "{}")[0] or "{}")
    propagate = project.readBoolEntry(PROJECT_SCOPE, "review/propagate", False)[0]
    return SavedReview(layers, frame_layer, geotag_layer, store, parameters, propagate)


def verdict_layer(store, name: str, colours: dict, labels: dict) -> QgsVectorLayer:
    """The latest direct verdict of every unit (and the added targets) from the log, styled by verdict."""
    layer = QgsVectorLayer(store.layer_uri, name, "ogr")
    if not layer.isValid():
        return layer
    layer.setSubsetString("fid IN (SELECT MAX(fid) FROM birdseye_verdicts WHERE provenance = 'direct' "
                          "GROUP BY unit_key) AND verdict <> 'unreviewed'")
    categories = []
    for verdict in ("confirmed_real", "hard_negative", "uncertain", "added"):
        colour = colours[verdict]
        symbol = QgsMarkerSymbol.createSimple(
            {"name": "cross2", "color": colour, "size": "4", "outline_color": colour, "outline_width": "0.8"}
            if verdict == "added" else
            {"name": "circle", "color": colour, "size": "3.2", "outline_color": "white", "outline_width": "0.4"})
        categories.append(QgsRendererCategory(verdict, symbol, labels[verdict]))
    layer.setRenderer(QgsCategorizedSymbolRenderer("verdict", categories))
    return layer
