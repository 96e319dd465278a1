"""Run inside the QGIS desktop by tests/gui/test_dialogs_desktop.py (``qgis --code dialogs_probe.py``).

Opens the demo project (``BIRDSEYE_DIALOGS_PROJECT``) in a maximised main window, adds a review verdict table (the
review dock's GeoPackage), then opens every BirdsEye algorithm's Processing dialog as the toolbox does
(``processing.createAlgorithmDialog``, shown), lets it paint, saves a screenshot to
``BIRDSEYE_DIALOGS_SCREENSHOTS/<alg_id>.png`` and records what the test checks:

* the dialog's frame on the screen; the parameter panel's horizontal scroll bar;
* every visible widget of the parameter panel that does not fit the panel's visible width (with its advanced
  parameters shown too), by its class and text;
* every layer box: its parameter, the kind it takes (BirdsEye's layer parameters), the layer it starts on and
  that layer's kind, the kinds it lists, and whether it starts over the same ground as the box it follows.

The JSON report goes to ``BIRDSEYE_PROBE_RESULT``. The steps are a generator played by ``probe_session.play``;
every exception is recorded, never shown in a dialog, so the desktop never waits for a click. QGIS quits at the end.
"""
import os
import sys
import traceback

from qgis.core import QgsApplication, QgsProject, QgsVectorLayer
from qgis.gui import QgsCollapsibleGroupBoxBasic, QgsMapLayerComboBox
from qgis.PyQt import sip
from qgis.PyQt.QtCore import QPoint
from qgis.PyQt.QtWidgets import (
    QAbstractButton,
    QAbstractSpinBox,
    QComboBox,
    QLabel,
    QLineEdit,
    QPlainTextEdit,
    QScrollArea,
    QWidget,
)
from qgis.utils import iface, plugins

sys.path.insert(0, os.environ["BIRDSEYE_PROBE_DIR"])
from probe_session import play, settle  # noqa: E402

PROJECT = os.environ["BIRDSEYE_DIALOGS_PROJECT"]
SCREENSHOTS = os.environ["BIRDSEYE_DIALOGS_SCREENSHOTS"]
RESULT_PATH = os.environ["BIRDSEYE_PROBE_RESULT"]
VERDICTS = os.environ["BIRDSEYE_DIALOGS_VERDICTS"]
SETTLE_MS = 400
#: What a person reads or operates in a parameter panel; containers and a box's inner parts are left out.
CONTROLS = (QLabel, QComboBox, QLineEdit, QPlainTextEdit, QAbstractButton, QAbstractSpinBox)
result = {"errors": [], "deleted_wrappers": [], "dialogs": {}}
#: Parameter types that show a layer box.
LAYER_TYPES = ("source", "vector", "raster", "layer", "mesh", "pointcloud")


def parameter_scroll_area(dialog) -> QScrollArea:
    """The scroll area of the dialog's parameter panel (QGIS's QgsProcessingParametersWidgetBase)."""
    return next(area for area in dialog.findChildren(QScrollArea)
                if area.parentWidget() is not None
                and area.parentWidget().objectName() == "QgsProcessingParametersWidgetBase")


def text_of(widget) -> str:
    for getter in ("text", "currentText", "toolTip"):
        value = getattr(widget, getter, None)
        if callable(value) and value():
            return value()[:90]
    return ""


def clipped_widgets(area: QScrollArea) -> list:
    """Visible controls whose right edge lies beyond the visible width of the scroll area."""
    viewport = area.viewport()
    found = []
    for widget in area.widget().findChildren(QWidget):
        if not isinstance(widget, CONTROLS) or not widget.isVisibleTo(area.widget()) or widget.width() <= 0:
            continue
        left = widget.mapTo(viewport, QPoint(0, 0)).x()
        if left < 0 or left + widget.width() > viewport.width():
            found.append({"class": widget.metaObject().className(), "text": text_of(widget),
                          "right": left + widget.width(), "visible_width": viewport.width()})
    return found


def widest_controls(area: QScrollArea, count: int = 4) -> list:
    """The visible controls that need the most width (their minimum size), the widest first: what makes a panel
    scroll sideways."""
    controls = [widget for widget in area.widget().findChildren(QWidget)
                if isinstance(widget, CONTROLS) and widget.isVisibleTo(area.widget())]
    controls.sort(key=lambda widget: -widget.minimumSizeHint().width())
    return [{"class": widget.metaObject().className(), "text": text_of(widget),
             "min_width": widget.minimumSizeHint().width()} for widget in controls[:count]]


def layer_boxes(dialog) -> list:
    """Every layer box of the dialog: the parameter, the kind it takes, where it starts and what it lists."""
    from birdseye.birdseye_qgis.qgis_io.layer_kinds import layer_kind, overlaps
    from birdseye.processing.parameters.layer_parameters import PARAMETER_OPTIONAL

    boxes, current_of = [], {}
    for name, wrapper in dialog.mainWidget().wrappers.items():
        if sip.isdeleted(wrapper):
            # QGIS's panel has been seen holding a wrapper it made whose C++ object is gone (3.22 and 3.40, now
            # and then, never one of BirdsEye's layer boxes): recorded, and an error if it is a layer box's.
            definition = dialog.algorithm().parameterDefinition(name)
            if definition is not None and definition.type() in LAYER_TYPES:
                raise RuntimeError(f"the layer box of {name} is deleted")
            result["deleted_wrappers"].append(f"{dialog.algorithm().name()}:{name}")
            continue
        kind = getattr(wrapper, "kind", None)
        widget = wrapper.wrappedWidget() if hasattr(wrapper, "wrappedWidget") else None
        if widget is None:
            continue
        inner = [sip.cast(child, QgsMapLayerComboBox) for child in widget.findChildren(QComboBox)
                 if child.metaObject().className() == "QgsMapLayerComboBox"]
        if not inner:
            continue
        box = inner[0]
        current = box.currentLayer()
        listed = [box.layer(i) for i in range(box.count())]
        definition = wrapper.parameterDefinition()
        current_of[name] = current
        boxes.append({"parameter": name, "type": definition.type(), "kind": kind, "near": getattr(wrapper, "near", ""),
                      "optional": bool(definition.flags() & PARAMETER_OPTIONAL),
                      "current": current.name() if current else None,
                      "current_kind": layer_kind(current) if current else None,
                      "listed_kinds": sorted({layer_kind(layer) for layer in listed if layer is not None})})
    for box in boxes:  # a box that starts near another's layer: is its layer over the same ground?
        if box["near"]:
            box["over_near"] = overlaps(current_of[box["parameter"]], current_of.get(box["near"]),
                                        QgsProject.instance())
    return boxes


def inspect_dialog(alg_id: str, dialog) -> dict:
    screen = dialog.screen().availableGeometry() if hasattr(dialog, "screen") else \
        QgsApplication.instance().primaryScreen().availableGeometry()
    frame = dialog.frameGeometry()
    area = parameter_scroll_area(dialog)
    report = {"title": dialog.windowTitle(),
              "screen": [screen.x(), screen.y(), screen.width(), screen.height()],
              "frame": [frame.x(), frame.y(), frame.width(), frame.height()],
              "fits_screen": screen.contains(frame),
              "horizontal_scrollbar": area.horizontalScrollBar().isVisible(),
              "content_min_width": area.widget().minimumSizeHint().width(),
              "visible_width": area.viewport().width(),
              "clipped": clipped_widgets(area),
              "widest": widest_controls(area),
              "layer_boxes": layer_boxes(dialog)}
    path = os.path.join(SCREENSHOTS, f"{alg_id}.png")
    report["screenshot"] = path if dialog.grab().save(path) else None
    # The advanced parameters too: opened, they must fit as well.
    for group in dialog.findChildren(QgsCollapsibleGroupBoxBasic):
        group.setCollapsed(False)
    return report


def add_verdict_table() -> None:
    """A review's verdict table, as the review dock writes it, so the REVIEW boxes have their kind to offer."""
    from birdseye.birdseye_qgis.qgis_io.review_store import VerdictStore

    store = VerdictStore(VERDICTS)
    layer = QgsVectorLayer(store.layer_uri, "birdseye_verdicts", "ogr")
    store.close()
    if not layer.isValid():
        raise RuntimeError(f"the verdict table {VERDICTS} does not open")
    QgsProject.instance().addMapLayer(layer)


def steps():
    """The session, one step per event-loop turn: each step lets QGIS paint for ``SETTLE_MS``."""
    import processing

    main_window = iface.mainWindow()
    main_window.showMaximized()
    result["plugin_loaded"] = plugins.get("birdseye") is not None
    result["project_opened"] = iface.addProject(PROJECT)
    add_verdict_table()
    result["layers"] = sorted(layer.name() for layer in QgsProject.instance().mapLayers().values())
    yield settle(SETTLE_MS)
    provider = QgsApplication.processingRegistry().providerById("birdseye")
    for algorithm in sorted(provider.algorithms(), key=lambda a: a.id()):
        alg_id = algorithm.name()
        try:
            dialog = processing.createAlgorithmDialog(algorithm.id(), {})
            dialog.show()
            yield settle(SETTLE_MS, f"{alg_id} dialog painted")
            result["dialogs"][alg_id] = inspect_dialog(alg_id, dialog)
            yield settle(SETTLE_MS, f"{alg_id} advanced parameters painted")
            area = parameter_scroll_area(dialog)
            result["dialogs"][alg_id]["advanced_horizontal_scrollbar"] = area.horizontalScrollBar().isVisible()
            result["dialogs"][alg_id]["advanced_clipped"] = clipped_widgets(area)
            result["dialogs"][alg_id]["advanced_widest"] = widest_controls(area)
            dialog.close()
            dialog.deleteLater()
        except Exception:  # noqa: BLE001 — reported to the test
            result["errors"].append(f"{alg_id}: {traceback.format_exc()}")


play(steps(), result, RESULT_PATH)
