"""BirdsEye library: the science in ``core`` (no QGIS), the QGIS glue and the GUI."""
