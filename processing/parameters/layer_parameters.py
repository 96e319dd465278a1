"""Layer parameters that know which kind of layer they take — frame layers, geotags, detections, review verdict
tables, surveyed areas, label checks — so the Processing dialog offers only layers of that kind and starts on the
most recent one.

Kinds and "most recent" are ``qgis_io.layer_kinds``'s, the one rule the docks follow too: a kind is recognised
by its schema (geotags: any point layer of no other kind), the most recent layer is the one added last.

The parameters stay plain ``QgsProcessingParameterFeatureSource`` / ``QgsProcessingParameterVectorLayer`` with
no default: ``processing.run``, ``qgis_process`` and the Graphical Modeler take whatever layer or file they are
given, and a result depends only on the values given. Only the widget of the standard Processing dialog knows
kinds, through the parameter's ``widget_wrapper`` metadata (read by QGIS's ``WidgetWrapperFactory`` from
QGIS 3.22 to 4): it lists only layers of the kind and starts a required parameter on the most recent one; an
optional parameter starts empty, since using it is the user's choice. A file, or a layer of another kind
dropped on the box or picked with its "…" button, is still accepted, as QGIS's own box accepts it. The batch
and Modeler dialogs get QGIS's own widget: there a value is one per row, a model input or another
algorithm's output.
"""
from __future__ import annotations

from qgis.core import (
    Qgis,
    QgsMapLayer,
    QgsProcessingContext,
    QgsProcessingParameterFeatureSource,
    QgsProcessingParameterVectorLayer,
    QgsProject,
)
from qgis.gui import (
    QgsAbstractProcessingParameterWidgetWrapper,
    QgsGui,
    QgsMapLayerComboBox,
    QgsProcessingGui,
    QgsProcessingMapLayerComboBox,
)
from qgis.PyQt import sip
from qgis.PyQt.QtWidgets import QComboBox

from ...birdseye_qgis.qgis_io import layer_kinds

if Qgis.QGIS_VERSION_INT >= 33600:
    PARAMETER_OPTIONAL = Qgis.ProcessingParameterFlag.Optional
else:
    from qgis.core import QgsProcessingParameterDefinition

    PARAMETER_OPTIONAL = QgsProcessingParameterDefinition.FlagOptional

#: The kinds a BirdsEye layer parameter takes.
KINDS = (layer_kinds.FRAMES, layer_kinds.GEOTAGS, layer_kinds.DETECTIONS, layer_kinds.VERDICTS, layer_kinds.AREAS,
         layer_kinds.LABEL_CHECKS)
#: QGIS's Processing dialogs by class name, as its ``processing.gui.wrappers.dialogTypes`` names them.
MODELER_DIALOG = "ModelerParametersDialog"
BATCH_DIALOG = "BatchAlgorithmDialog"


def layer_parameter(parameter, kind: str, start: int = 0, near: str = ""):
    """``parameter`` (a feature-source or vector-layer parameter) with the dialog widget of ``kind``
    (:class:`LayerKindWrapper`), which starts a required parameter on the most recent layer of its kind — among
    those over the same ground as the layer of parameter ``near``, when that parameter has one (the frames and
    geotags of the flight the detections come from) — or, with ``start`` 1, on the one before it, and so on."""
    if kind not in KINDS:
        raise ValueError(f"not a kind of layer parameter: {kind!r}")
    parameter.setMetadata({**parameter.metadata(), "widget_wrapper": {
        "class": f"{__name__}.{LayerKindWidget.__name__}", "kind": kind, "start": start, "near": near}})
    return parameter


def source_parameter(name: str, description: str, kind: str, types, optional: bool = False, start: int = 0,
                     near: str = ""):
    """A ``QgsProcessingParameterFeatureSource`` whose dialog offers the layers of ``kind``
    (:func:`layer_parameter`)."""
    return layer_parameter(QgsProcessingParameterFeatureSource(name, description, list(types), optional=optional),
                           kind, start, near)


def vector_parameter(name: str, description: str, kind: str, types, optional: bool = False):
    """A ``QgsProcessingParameterVectorLayer`` (for an algorithm that needs the layer itself, e.g. its selection)
    whose dialog offers the layers of ``kind``."""
    return layer_parameter(QgsProcessingParameterVectorLayer(name, description, list(types), optional=optional),
                           kind)


class LayerKindWidget:
    """The class QGIS's ``WidgetWrapperFactory`` calls for a parameter of :func:`layer_parameter`, with the dialog
    and the metadata's ``kind``, ``start`` and ``near``. It returns the widget wrapper for that dialog: a
    :class:`LayerKindWrapper` in the standard dialog, the one QGIS's registry makes in the batch and Modeler
    dialogs (exactly what QGIS makes for a parameter without ``widget_wrapper``)."""

    def __new__(cls, parameter, dialog, row=0, col=0, kind="", start=0, near=""):
        dialog_type = type(dialog).__name__
        registry = QgsGui.processingGuiRegistry()
        if dialog_type == MODELER_DIALOG:
            wrapper = registry.createModelerParameterWidget(dialog.model, dialog.childId, parameter, dialog.context)
        elif dialog_type == BATCH_DIALOG:
            wrapper = registry.createParameterWidgetWrapper(parameter, QgsProcessingGui.WidgetType.Batch)
        else:
            wrapper = LayerKindWrapper(parameter, kind, start, near)
        wrapper.setDialog(dialog)
        return wrapper


class LayerKindWrapper(QgsAbstractProcessingParameterWidgetWrapper):
    """QGIS's layer box (``QgsProcessingMapLayerComboBox``: drag and drop, files, selected features only) listing
    only the project's layers of ``kind``. An empty value starts a required parameter on the most recent of them
    (see :func:`layer_parameter`); while the choice is still this one's own, it follows the layer of ``near``.
    A layer the user picks, or a value given, stays."""

    def __init__(self, parameter, kind: str, start: int = 0, near: str = ""):
        super().__init__(parameter, QgsProcessingGui.WidgetType.Standard)
        self.kind = kind
        self.start = start
        self.near = near
        self.near_wrapper = None
        #: The box shows this wrapper's own choice, not the user's or a value given.
        self.chose_itself = False
        self._choosing = False

    def createWidget(self):  # noqa: N802 — QGIS's name
        box = QgsProcessingMapLayerComboBox(self.parameterDefinition(), QgsProcessingGui.WidgetType.Standard)
        box.setToolTip(self.parameterDefinition().toolTip())
        box.setWidgetContext(self.widgetContext())
        box.valueChanged.connect(self._value_changed)
        self._offer_only_the_kind(box)
        return box

    def combo(self) -> QgsProcessingMapLayerComboBox | None:
        """QGIS's box, once made. The wrapper owns it from then on: PyQt hands it back only as the QWidget the
        wrapper keeps, so it is cast back."""
        widget = self.wrappedWidget()
        return None if widget is None else sip.cast(widget, QgsProcessingMapLayerComboBox)

    def setWidgetContext(self, context):  # noqa: N802 — QGIS's name
        super().setWidgetContext(context)
        if self.combo() is not None:
            self.combo().setWidgetContext(context)

    def setWidgetValue(self, value, context):  # noqa: N802 — QGIS's name
        """``value`` as given; empty, or a project layer of another kind, starts a required parameter on its own
        choice (an optional one stays empty)."""
        layer = value if isinstance(value, QgsMapLayer) else \
            self.project().mapLayer(value) if isinstance(value, str) and value else None
        if value in (None, "") or (layer is not None and layer_kinds.layer_kind(layer) != self.kind):
            self.choose(context)
        else:
            self._set(value, context, chose_itself=False)

    def widgetValue(self):  # noqa: N802 — QGIS's name
        return self.combo().value()

    def postInitialize(self, wrappers):  # noqa: N802 — QGIS's name
        """Once every box exists: follow the box of ``near`` (its value now, and whenever it changes)."""
        super().postInitialize(wrappers)
        self.near_wrapper = next((w for w in wrappers if self.near
                                  and w.parameterDefinition().name() == self.near), None)
        if self.near_wrapper is not None:
            self.near_wrapper.widgetValueHasChanged.connect(self._near_changed)
            self._near_changed()

    def choose(self, context=None) -> None:
        """Start on this box's own choice: for a required parameter the layer of its kind :func:`layer_parameter`
        describes; none for an optional one."""
        chosen = None
        if not self.parameterDefinition().flags() & PARAMETER_OPTIONAL:
            candidates = layer_kinds.layers_of_kind(self.project(), self.kind)
            near = self._near_layer()
            if near is not None:  # those over the same ground first, each group the most recent first
                candidates.sort(key=lambda layer: not layer_kinds.overlaps(layer, near, self.project()))
            if candidates:
                chosen = candidates[min(self.start, len(candidates) - 1)]
        self._set(chosen, context, chose_itself=True)

    def refresh(self) -> None:
        """List only the layers of the kind (the dialog calls this when layers are added or removed)."""
        if self.combo() is not None:
            self._offer_only_the_kind(self.combo())

    def layer_box(self, box=None) -> QgsMapLayerComboBox:
        """The layer list inside QGIS's box (PyQt knows it only as a QComboBox: it is private to the box)."""
        inner = next(child for child in (box or self.combo()).findChildren(QComboBox)
                     if child.metaObject().className() == "QgsMapLayerComboBox")
        return sip.cast(inner, QgsMapLayerComboBox)

    def project(self):
        return self.widgetContext().project() or QgsProject.instance()

    def _offer_only_the_kind(self, box) -> None:
        self.layer_box(box).setExceptedLayerList(layer_kinds.other_layers(self.project(), self.kind))

    def _near_layer(self):
        """The layer in the box of ``near`` (a :class:`LayerKindWrapper`), if any."""
        box = self.near_wrapper.combo() if isinstance(self.near_wrapper, LayerKindWrapper) else None
        return box.currentLayer() if box is not None else None

    def _near_changed(self, *_) -> None:
        if self.chose_itself:
            self.choose()

    def _set(self, value, context, chose_itself: bool) -> None:
        if context is None:
            context = QgsProcessingContext()
            context.setProject(self.project())
        self._choosing = True
        try:
            self.combo().setValue(value, context)
        finally:
            self._choosing = False
        self.chose_itself = chose_itself

    def _value_changed(self) -> None:
        if not self._choosing:
            self.chose_itself = False  # the user's choice from now on
        self.widgetValueHasChanged.emit(self)
