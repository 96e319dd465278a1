"""The detector a run uses, shared by detect and detectraster: ``MODEL`` (an ONNX heatmap model; empty: the
bundled demo model) and ``THRESHOLD`` (a probability; empty: the model's own default)."""
from __future__ import annotations

from qgis.core import QgsProcessingParameterFile, QgsProcessingParameterNumber

from ...birdseye_qgis.__about__ import BUNDLED_MODEL
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE


class ModelParametersMixin:
    """``add_model_parameters`` in ``initAlgorithm``, ``model_choice`` in ``processAlgorithm``."""

    MODEL = "MODEL"
    THRESHOLD = "THRESHOLD"

    def add_model_parameters(self) -> None:
        self.addParameter(QgsProcessingParameterFile(
            self.MODEL, self.tr("ONNX model (empty: the bundled one)"),
            fileFilter="ONNX models (*.onnx)", defaultValue=str(BUNDLED_MODEL), optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.THRESHOLD, self.tr("Threshold (empty: the model's own)"),
            NUMBER_DOUBLE, optional=True, minValue=0.0, maxValue=1.0))

    def model_choice(self, parameters, context) -> tuple[str, float | None]:
        """(the model file, the threshold given or None for the model's own)."""
        path = self.parameterAsFile(parameters, self.MODEL, context) or str(BUNDLED_MODEL)
        if parameters.get(self.THRESHOLD) in (None, ""):
            return path, None
        return path, self.parameterAsDouble(parameters, self.THRESHOLD, context)
