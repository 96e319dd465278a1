"""The BirdsEye Processing provider (id ``birdseye``) and its algorithms.

Import this package only relatively from inside the plugin: as a top-level name it would shadow
QGIS's own ``processing`` module.
"""
