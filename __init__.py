"""BirdsEye for QGIS — survey-driven aerial training sets and detector review."""


def classFactory(iface):
    """QGIS entry point; imports lazily so a missing optional package never stops QGIS starting."""
    from .birdseye_qgis.gui.plugin import BirdsEyePlugin
    from .processing.provider import BirdsEyeProvider

    return BirdsEyePlugin(iface, BirdsEyeProvider)
