"""Names of ``qgis.core`` for the PyQt6 probe: every name resolves, so a module that imports QGIS
classes can be imported, but calling one fails — the probe exercises only the pure-Qt parts."""
from __future__ import annotations


class NeedsQgis:
    """A QGIS class, enum or value that this test does not have."""

    def __init__(self, name: str):
        self._name = name

    def __getattr__(self, attribute: str) -> NeedsQgis:
        return NeedsQgis(f"{self._name}.{attribute}")

    def __call__(self, *args, **kwargs):
        raise RuntimeError(f"{self._name} needs QGIS; the PyQt6 probe covers only the pure-Qt parts")


class _Qgis(NeedsQgis):
    QGIS_VERSION_INT = 40000  # the QGIS the probe stands for: QGIS 4, Qt 6


Qgis = _Qgis("Qgis")


def __getattr__(name: str) -> NeedsQgis:
    return NeedsQgis(name)
