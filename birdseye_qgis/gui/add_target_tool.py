"""A map tool to add a target the detector missed: one click places it (the review's ``a`` term).

The tool only reports where the user clicked; the review dock records the ``added`` verdict (in the
verdict log, committed before the map tool lets go) and restores the previous map tool.
"""
from __future__ import annotations

from qgis.core import QgsCoordinateReferenceSystem, QgsPointXY
from qgis.gui import QgsMapToolEmitPoint, QgsVertexMarker
from qgis.PyQt.QtCore import Qt, pyqtSignal
from qgis.PyQt.QtGui import QColor, QCursor


class AddTargetTool(QgsMapToolEmitPoint):
    """Left click: ``target_added(point, crs)`` in the canvas CRS. Right click or Esc: ``cancelled``."""

    target_added = pyqtSignal(QgsPointXY, QgsCoordinateReferenceSystem)
    cancelled = pyqtSignal()

    def __init__(self, canvas):
        super().__init__(canvas)
        self.setCursor(QCursor(Qt.CursorShape.CrossCursor))
        self._marker: QgsVertexMarker | None = None
        self._previous_tool = None

    def take_over(self) -> None:
        """Become the canvas's map tool, remembering the one the user had."""
        if self.canvas().mapTool() is not self:
            self._previous_tool = self.canvas().mapTool()
            self.canvas().setMapTool(self)

    def hand_back(self) -> None:
        """Give the canvas back the map tool the user had before (or none)."""
        if self.canvas().mapTool() is self:
            if self._previous_tool is not None:
                self.canvas().setMapTool(self._previous_tool)
            else:
                self.canvas().unsetMapTool(self)
        self._previous_tool = None

    def canvasMoveEvent(self, event):
        """A cross follows the pointer, so the user sees where the target will go."""
        if self._marker is None:
            self._marker = QgsVertexMarker(self.canvas())
            self._marker.setIconType(QgsVertexMarker.IconType.ICON_CROSS)
            self._marker.setColor(QColor(40, 200, 90))
            self._marker.setIconSize(16)
            self._marker.setPenWidth(2)
        self._marker.setCenter(event.mapPoint())

    def canvasReleaseEvent(self, event):
        if event.button() == Qt.MouseButton.LeftButton:
            self.target_added.emit(QgsPointXY(event.mapPoint()), self.canvas().mapSettings().destinationCrs())
        elif event.button() == Qt.MouseButton.RightButton:
            self.cancelled.emit()

    def keyPressEvent(self, event):
        if event.key() == Qt.Key.Key_Escape:
            event.accept()
            self.cancelled.emit()

    def deactivate(self):
        if self._marker is not None:
            self.canvas().scene().removeItem(self._marker)
            self._marker = None
        super().deactivate()
