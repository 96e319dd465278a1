"""Run inside the QGIS desktop by tests/gui/test_map_demo.py (``qgis --code map_probe.py``).

Looks at the demo project as a user does: opens it (``BIRDSEYE_MAP_PROJECT``) in a main window filling the
screen, zooms to a training flight and to the held-out flight and saves a screenshot of each view, Layers
panel and all, to ``BIRDSEYE_MAP_SCREENSHOTS`` (``<prefix>_<view>.png``, prefix ``BIRDSEYE_MAP_PREFIX``).
It records what the test checks in the JSON report ``BIRDSEYE_PROBE_RESULT``: each layer's name (and whether the
Layers panel has room for it), source file, group, visibility, renderer, legend labels and the fill opacity of its
polygon symbols, and the drawing order.
The steps are a generator played by ``probe_session.play``; every exception is recorded, never shown in a dialog,
and QGIS quits at the end.
"""
import os
import sys

from qgis.core import QgsApplication, QgsProject
from qgis.PyQt.QtCore import Qt
from qgis.PyQt.QtGui import QFontMetrics
from qgis.PyQt.QtWidgets import QDockWidget
from qgis.utils import iface

from birdseye.birdseye_qgis.qgis_enums import LAYER_VECTOR

sys.path.insert(0, os.environ["BIRDSEYE_PROBE_DIR"])
from probe_session import canvas_idle, file_stem, play  # noqa: E402

PROJECT = os.environ["BIRDSEYE_MAP_PROJECT"]
SCREENSHOTS = os.environ["BIRDSEYE_MAP_SCREENSHOTS"]
PREFIX = os.environ["BIRDSEYE_MAP_PREFIX"]
RESULT_PATH = os.environ["BIRDSEYE_PROBE_RESULT"]
# The views a user looks at: the layer whose extent is zoomed to, with a margin (fraction of its size).
VIEWS = {"training": ("frames_train1", 0.08), "heldout": ("frames_heldout", 0.08)}
SETTLE_MS = 1500  # after the canvas is drawn, before its screenshot
result = {"errors": [], "screenshots": {}, "timeouts": []}


def fill_opacities(symbol) -> list:
    """Opacity (0..1) of every fill a polygon symbol paints: symbol opacity × colour alpha of each layer that
    fills (a simple fill with a brush), 0 for a layer that only draws lines or markers."""
    out = []
    for k in range(symbol.symbolLayerCount()):
        sub = symbol.symbolLayer(k)
        if sub.layerType() == "SimpleFill":
            solid = sub.brushStyle() != Qt.BrushStyle.NoBrush
            out.append(round(symbol.opacity() * sub.color().alphaF(), 3) if solid else 0.0)
        elif sub.layerType() in ("GradientFill", "ShapeburstFill", "RasterFill", "SVGFill", "LinePatternFill",
                                 "PointPatternFill"):
            out.append(round(symbol.opacity(), 3))
    return out


def name_room(tree, node) -> dict:
    """Where the node's name ends in the Layers panel and how much room it has, in pixels: the text starts
    after the check box and the layer icon and must end before the indicator icons at the right edge."""
    index = tree.node2index(node)
    rect = tree.visualRect(index)
    font = tree.model().data(index, Qt.ItemDataRole.FontRole)
    metrics = QFontMetrics(font) if font is not None else tree.fontMetrics()
    icon = tree.iconSize().width() if tree.iconSize().width() > 0 else 16
    text_end = rect.left() + 2 * (icon + 6) + metrics.horizontalAdvance(node.name())
    return {"text_end": text_end, "room": tree.viewport().width() - (icon + 4)}


def describe(layer, root, tree) -> dict:
    node = root.findLayer(layer.id())
    entry = {"name": layer.name(), "stem": file_stem(layer), "valid": layer.isValid(),
             "group": node.parent().name() if node is not None and node.parent() is not None else None,
             "visible": bool(node is not None and node.isVisible()), "vector": False, **name_room(tree, node)}
    if layer.type() != LAYER_VECTOR:
        return entry
    renderer = layer.renderer()
    items = renderer.legendSymbolItems() if renderer is not None else []
    entry.update(vector=True, renderer=renderer.type() if renderer is not None else None,
                 legend=[item.label() for item in items],
                 fill_opacity=sorted({o for item in items if item.symbol() is not None
                                      for o in fill_opacities(item.symbol())}))
    return entry


def shoot(name: str) -> None:
    path = os.path.join(SCREENSHOTS, f"{PREFIX}_{name}.png")
    result["screenshots"][name] = path if iface.mainWindow().grab().save(path) else None


def session():
    main_window = iface.mainWindow()
    screen = QgsApplication.instance().primaryScreen().geometry()
    main_window.setGeometry(screen)
    main_window.showMaximized()
    result["screen"] = [screen.width(), screen.height()]
    # The reader's Layers panel: the Browser above it closed, so the legend has the window's height.
    for dock in main_window.findChildren(QDockWidget):
        if dock.objectName() == "Browser":
            dock.hide()
    result["project_opened"] = iface.addProject(PROJECT)
    yield canvas_idle(SETTLE_MS)
    project = QgsProject.instance()
    root = project.layerTreeRoot()
    result["groups"] = [node.name() for node in root.children()]
    tree = iface.layerTreeView()
    result["layers"] = [describe(layer, root, tree) for layer in project.mapLayers().values()]
    result["drawing_order"] = [file_stem(layer) for layer in root.layerOrder()]
    shoot("project")
    by_stem = {file_stem(layer): layer for layer in project.mapLayers().values()}
    canvas = iface.mapCanvas()
    for view, (stem, margin) in VIEWS.items():
        extent = by_stem[stem].extent()
        extent = extent.buffered(margin * max(extent.width(), extent.height()))
        canvas.setExtent(canvas.mapSettings().layerToMapCoordinates(by_stem[stem], extent))
        canvas.refresh()
        yield canvas_idle(SETTLE_MS)
        shoot(view)


play(session(), result, RESULT_PATH)
