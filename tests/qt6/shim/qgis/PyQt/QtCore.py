"""``qgis.PyQt.QtCore`` of QGIS 4."""
from PyQt6.QtCore import *  # noqa: F403
