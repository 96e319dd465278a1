"""``qgis.PyQt`` of QGIS 4: PyQt6."""
from PyQt6 import sip  # noqa: F401
