"""What the review shows on the map: the unit under review (centred and marked), the survey, the verdicts."""
from __future__ import annotations

from qgis.core import (
    Qgis,
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsMessageLog,
    QgsPointXY,
    QgsProject,
    QgsRectangle,
    QgsVectorLayer,
)
from qgis.gui import QgsVertexMarker
from qgis.PyQt import sip
from qgis.PyQt.QtCore import QTimer
from qgis.PyQt.QtGui import QColor

from ...__about__ import LOG_TAG, tr
from ...qgis_io.review_project import verdict_layer
from .model import VERDICT_COLOURS, VERDICT_TEXT


class ReviewMap:
    """The map canvas side of a review (``canvas`` may be None: headless, nothing is drawn)."""

    def __init__(self, canvas, parent):
        self.canvas = canvas
        self.marker: QgsVertexMarker | None = None
        self.verdict_layer: QgsVectorLayer | None = None
        self._verdict_layer_id = ""
        self._refresh = QTimer(parent)
        self._refresh.setSingleShot(True)
        self._refresh.timeout.connect(self._reload_verdicts)

    def centre_on(self, lat: float, lon: float, scale: float, colour: str) -> None:
        """Centre the canvas on the unit at ``scale`` (1:scale) and mark it in its verdict's colour."""
        if self.canvas is None:
            return
        to_canvas = QgsCoordinateTransform(QgsCoordinateReferenceSystem("EPSG:4326"),
                                           self.canvas.mapSettings().destinationCrs(), QgsProject.instance())
        try:
            point = to_canvas.transform(QgsPointXY(lon, lat))
        except Exception:  # noqa: BLE001 — a canvas CRS that cannot hold the site: leave the map alone
            return
        if self.canvas.extent().isEmpty():   # a canvas that never showed a layer: give it the site
            self.canvas.setExtent(QgsRectangle(point.x() - 10, point.y() - 10, point.x() + 10, point.y() + 10))
        self.canvas.setCenter(point)
        if abs(self.canvas.scale() - scale) > 0.5:
            self.canvas.zoomScale(scale)
        if self.marker is None:
            self.marker = QgsVertexMarker(self.canvas)
            self.marker.setIconType(QgsVertexMarker.IconType.ICON_CIRCLE)
            self.marker.setIconSize(22)
            self.marker.setPenWidth(3)
        self.marker.setColor(QColor(colour))
        self.marker.setCenter(point)
        self.canvas.refresh()

    def remove_marker(self) -> None:
        if self.marker is not None and self.canvas is not None:
            self.canvas.scene().removeItem(self.marker)
        self.marker = None

    @staticmethod
    def show_survey(geotag_layer) -> None:
        node = QgsProject.instance().layerTreeRoot().findLayer(geotag_layer.id())
        if node is not None:
            node.setItemVisibilityChecked(True)

    def show_verdicts(self, store, name: str) -> None:
        """The current direct verdicts (and added targets) as a layer read from the log itself."""
        project = QgsProject.instance()
        for layer in project.mapLayers().values():
            if isinstance(layer, QgsVectorLayer) and layer.source().split("|")[0] == str(store.path) \
                    and "birdseye_verdicts" in layer.source():
                self.verdict_layer, self._verdict_layer_id = layer, layer.id()
                return
        layer = verdict_layer(store, name, VERDICT_COLOURS, VERDICT_TEXT)
        if not layer.isValid():
            QgsMessageLog.logMessage(tr("Verdict layer {uri} could not be loaded").format(uri=store.layer_uri),
                                     LOG_TAG, Qgis.MessageLevel.Warning)
            return
        project.addMapLayer(layer)
        self.verdict_layer, self._verdict_layer_id = layer, layer.id()

    def forget_layers(self, layer_ids) -> None:
        """Layers were removed from the project (the objects are already deleted)."""
        if self._verdict_layer_id in layer_ids:
            self.verdict_layer, self._verdict_layer_id = None, ""

    def refresh_verdicts_soon(self) -> None:
        """Redraw the verdict layer once a burst of verdicts has settled."""
        self._refresh.start(300)

    def _reload_verdicts(self) -> None:
        if self.verdict_layer is not None and not sip.isdeleted(self.verdict_layer):
            self.verdict_layer.dataProvider().reloadData()
            self.verdict_layer.triggerRepaint()
