"""A stand-in ``qgis`` package for the PyQt6 probe (tests/qt6/probe_pure_qt.py): ``qgis.PyQt`` is PyQt6,
as in QGIS 4; ``qgis.core`` and ``qgis.gui`` only let modules import (see core.py)."""
