"""The ``birdseye`` Processing provider."""
from __future__ import annotations

import importlib
import inspect
import pkgutil
import warnings

from qgis.core import Qgis, QgsMessageLog, QgsProcessingProvider
from qgis.PyQt.QtGui import QIcon

from ..birdseye_qgis.__about__ import ICON_PATH, LOG_TAG, NAME
from .algorithms import base
from .algorithms.base import BirdsEyeAlgorithm

# A matplotlib installed with pip beside the system's (Debian's python3-matplotlib, whose mpl_toolkits is found
# first) warns "Unable to import Axes3D" when it is first imported, by an algorithm or a dock: its 3D projection
# comes from the other installation. BirdsEye draws no 3D plot, so that one warning is dropped, for the whole
# plugin, from the moment QGIS loads it.
warnings.filterwarnings("ignore", message="Unable to import Axes3D", category=UserWarning)


def algorithm_classes() -> list[type[BirdsEyeAlgorithm]]:
    """Every algorithm class in ``processing/algorithms`` (one per module), sorted by id.

    A module that fails to import (for instance a missing optional package) is logged and skipped,
    so one broken algorithm never hides the others.
    """
    from . import algorithms

    found = {}
    for info in pkgutil.iter_modules(algorithms.__path__):
        if info.name == "base":
            continue
        try:
            module = importlib.import_module(f"{algorithms.__name__}.{info.name}")
        except Exception as exc:  # noqa: BLE001 — reported, never fatal for QGIS
            QgsMessageLog.logMessage(f"{NAME}: algorithm module '{info.name}' failed to load: {exc}",
                                     LOG_TAG, Qgis.MessageLevel.Critical)
            continue
        for _, cls in inspect.getmembers(module, inspect.isclass):
            if issubclass(cls, base.BirdsEyeAlgorithm) and cls.ALG_ID and cls.__module__ == module.__name__:
                found[cls.ALG_ID] = cls
    return [found[k] for k in sorted(found)]


class BirdsEyeProvider(QgsProcessingProvider):
    def id(self) -> str:
        return "birdseye"

    def name(self) -> str:
        return NAME

    def longName(self) -> str:
        return "BirdsEye — survey-driven aerial labels and detection"

    def icon(self) -> QIcon:
        return QIcon(str(ICON_PATH))

    def loadAlgorithms(self) -> None:
        for cls in algorithm_classes():
            self.addAlgorithm(cls())
