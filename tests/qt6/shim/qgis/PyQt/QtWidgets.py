"""``qgis.PyQt.QtWidgets`` of QGIS 4."""
from PyQt6.QtWidgets import *  # noqa: F403
