"""QGIS-side readers and writers: layers to core inputs and back, styles, the review store, project settings.

Everything here may import ``qgis``; nothing imports ``processing/`` (the algorithms and the docks both
call it). See docs/design.md, "Architecture".
"""
