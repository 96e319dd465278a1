"""Number boxes in BirdsEye's Processing dialogs show the decimals their unit needs ("10.0" px, "0.200" m), not
QGIS's six ("10.000000"), without rounding a default or the smallest value allowed (base.number_decimals)."""
from __future__ import annotations

import pytest
from qgis.core import QgsApplication
from qgis.PyQt.QtWidgets import QAbstractSpinBox

from birdseye.birdseye_qgis.qgis_enums import NUMBER_DOUBLE


def decimal_numbers():
    for algorithm in QgsApplication.processingRegistry().providerById("birdseye").algorithms():
        for parameter in algorithm.parameterDefinitions():
            if parameter.type() == "number" and parameter.dataType() == NUMBER_DOUBLE:
                yield algorithm.id(), parameter


def test_every_decimal_number_names_decimals_that_keep_its_values(birdseye_provider):
    checked = 0
    for alg_id, parameter in decimal_numbers():
        decimals = parameter.metadata()["widget_wrapper"]["decimals"]
        assert 0 <= decimals <= 6, (alg_id, parameter.name())
        for value in (parameter.defaultValue(), parameter.minimum()):
            if value is not None and abs(value) < 1e300:
                assert round(value, decimals) == pytest.approx(value, abs=1e-12), (alg_id, parameter.name(), value)
        checked += 1
    assert checked > 50


def test_the_dialog_shows_them(qgis_iface, birdseye_provider, monkeypatch):
    import processing

    monkeypatch.setattr(qgis_iface, "browserModel", lambda: None, raising=False)
    monkeypatch.setattr(qgis_iface, "activeLayer", lambda: None, raising=False)
    dialog = processing.createAlgorithmDialog("birdseye:writelabels", {})
    try:
        wrappers = dialog.mainWidget().wrappers

        def shown(name):
            return wrappers[name].wrappedWidget().findChild(QAbstractSpinBox) or wrappers[name].wrappedWidget()

        assert shown("SIGMA_PX").text() == "10.0"          # px: 0.1
        assert shown("EPS_M").text() == "0.200"             # m, down to 0.001 m
        assert shown("NEGATIVE_RATIO").text() == "1.000"    # no unit: 3
    finally:
        dialog.close()
