"""Values BirdsEye keeps in the QGIS project, so one step can hand them to another.

σ_label goes from the sensor-bound calculator to ``writelabels`` through the project: both an entry and
a project variable are written; a saved project keeps variables as text, so read with
``read_sigma_label_px``.
"""
from __future__ import annotations

import math

from qgis.core import QgsExpressionContextUtils

SIGMA_LABEL_SCOPE = "birdseye"
SIGMA_LABEL_KEY = "sigma_label_px"
SIGMA_LABEL_VARIABLE = "birdseye_sigma_label_px"


def store_sigma_label_px(project, sigma_px: float) -> None:
    """Store σ_label (px) in ``project``: entry ``birdseye/sigma_label_px``, variable ``@birdseye_sigma_label_px``."""
    project.writeEntryDouble(SIGMA_LABEL_SCOPE, SIGMA_LABEL_KEY, float(sigma_px))
    QgsExpressionContextUtils.setProjectVariable(project, SIGMA_LABEL_VARIABLE, float(sigma_px))


def read_sigma_label_px(project):
    """σ_label (px) stored in ``project`` by the calculator, or None: the variable first, then the entry.

    The variable wins because users can edit it (Project ▸ Properties ▸ Variables).
    """
    value = QgsExpressionContextUtils.projectScope(project).variable(SIGMA_LABEL_VARIABLE)
    try:
        if value not in (None, ""):
            sigma = float(value)
            return sigma if sigma > 0 and math.isfinite(sigma) else None
    except (TypeError, ValueError):
        return None
    sigma, found = project.readDoubleEntry(SIGMA_LABEL_SCOPE, SIGMA_LABEL_KEY)
    return sigma if found and sigma > 0 and math.isfinite(sigma) else None
