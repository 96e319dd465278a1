"""Names of ``qgis.gui`` for the PyQt6 probe (see core.py)."""
from .core import NeedsQgis


def __getattr__(name: str) -> NeedsQgis:
    return NeedsQgis(name)
