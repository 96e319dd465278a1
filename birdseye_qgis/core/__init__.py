"""Pure geometry and data code of BirdsEye.

Nothing in this package imports ``qgis`` or ``PyQt``; heavy optional packages (cv2, onnxruntime,
scipy) are imported inside the functions that need them.
"""
