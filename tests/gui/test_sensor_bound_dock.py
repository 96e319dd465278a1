"""The sensor-bound calculator dock, headless (pytest-qgis iface, qtbot).

What the user does — type a value, pick a platform, load a calibration, press a button — and what must
follow: the numbers shown are the core's for the inputs shown (preview grid while typing, every pixel
on demand, identical to ``birdseye:sensorbound``), σ_label reaches the project for ``writelabels``,
and "Run in Processing…" opens the algorithm with the dock's values.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from qgis.core import QgsApplication, QgsExpressionContextUtils, QgsProject
from qgis.PyQt.QtCore import Qt
from qgis.PyQt.QtGui import QColor

from birdseye.birdseye_qgis.core.design import sensor_bound as sb
from birdseye.birdseye_qgis.core.design.bound_report import ACCEPT_COLOUR, REJECT_COLOUR, stride_for
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel, write_kalibr_yaml
from birdseye.birdseye_qgis.gui import sensor_bound_dock as dock_module

REPO_ROOT = Path(__file__).resolve().parents[2]
SCREENSHOT = REPO_ROOT / "build" / "screenshots" / "sensor_bound_dock.png"
DEPLOYED = sb.Intrinsics(fx=4264.4945, fy=4262.8927, cx=958.4594, cy=592.5033, width=1920, height=1200)
DEPLOYED_SIGMAS = [0.010, 0.010, 0.060, 0.04, 0.04, 0.13]
PREVIEW_STRIDE = stride_for(DEPLOYED, dock_module.PREVIEW_MAX_POINTS)


@pytest.fixture(scope="module")
def shown_dock(qgis_iface):
    """One dock for the module (building the plot is the slow part), shown as a floating window."""
    widget = dock_module.SensorBoundDock(qgis_iface)
    widget.setFloating(True)
    widget.resize(430, 1320)
    widget.show()
    yield widget
    widget.close()
    widget.deleteLater()


@pytest.fixture
def dock(shown_dock, qtbot):
    """The dock back on the deployed platform, as the user gets it by picking that preset."""
    shown_dock.calibration_widget.setFilePath("")
    shown_dock.apply_preset(dock_module.PRESET_DEPLOYED)
    shown_dock.altitude_combo.setCurrentIndex(0)
    assert shown_dock.recompute()
    qtbot.waitExposed(shown_dock)
    return shown_dock


def table_texts(dock):
    table = dock.results_table
    return [[table.item(r, c).text() for c in range(table.columnCount())] for r in range(table.rowCount())]


def type_into(qtbot, spin, text):
    """Replace a spin box's text by typing, as a user would."""
    spin.setFocus()
    spin.lineEdit().selectAll()
    qtbot.keyClicks(spin.lineEdit(), text)


def wait_for_update(qtbot, dock, before):
    qtbot.waitUntil(lambda: dock.result is not before, timeout=5000)


def test_opens_on_the_deployed_platform_with_its_verdicts(dock):
    assert dock.preset_combo.currentText() == dock_module.PRESET_DEPLOYED
    assert dock.camera() == DEPLOYED and dock.sigmas() == pytest.approx(DEPLOYED_SIGMAS)
    expected = sb.evaluate_bounds(DEPLOYED, [10.0, 20.0], DEPLOYED_SIGMAS, 30.0, PREVIEW_STRIDE)
    assert dock.result == expected
    rows = table_texts(dock)
    assert [r[0] for r in rows] == ["10 m", "20 m"]
    assert rows[0][1] == f"{expected['altitudes'][0]['sup_trace_px2']:.3g}"
    assert rows[0][3].endswith("✗") and rows[0][4].endswith("✓")  # trace rejects, exact accepts at 10 m
    assert rows[0][4].startswith(f"{expected['altitudes'][0]['kappa_exact']:.3g}")
    colours = [dock.results_table.item(0, c).background().color() for c in (3, 4)]
    assert colours == [QColor(REJECT_COLOUR), QColor(ACCEPT_COLOUR)]
    assert f"every {PREVIEW_STRIDE} px" in dock.status_label.text() and PREVIEW_STRIDE == 4


def test_typing_a_sigma_updates_the_table_after_a_pause(dock, qtbot):
    before = dock.result
    yaw = dock.sigma_spins[5]
    type_into(qtbot, yaw, "0.8")
    assert dock._timer.isActive() and dock.result is before  # debounced: nothing computed while typing
    wait_for_update(qtbot, dock, before)
    sigmas = DEPLOYED_SIGMAS[:5] + [0.8]
    assert dock.sigmas() == pytest.approx(sigmas)
    expected = sb.evaluate_bounds(DEPLOYED, [10.0, 20.0], sigmas, 30.0, PREVIEW_STRIDE)
    assert dock.result == expected
    assert table_texts(dock)[0][4].startswith(f"{expected['altitudes'][0]['kappa_exact']:.3g}")
    assert expected["altitudes"][0]["verdict_exact"] == "reject"  # a 0.8° heading error is too much at 10 m
    assert table_texts(dock)[0][4].endswith("✗")
    assert dock.preset_combo.currentText() == dock_module.PRESET_CUSTOM
    # the budget table shows the typed sigma and the share moves to yaw
    assert dock.budget_table.item(5, 0).text() == "0.800°"
    shares = expected["altitudes"][0]["budget_share"]
    assert dock.budget_table.item(5, 3).text() == f"{100 * shares[5]:.1f} %" and np.argmax(shares) == 5


def test_altitudes_tolerance_and_invalid_input(dock, qtbot):
    before = dock.result
    dock.altitudes_edit.selectAll()
    qtbot.keyClicks(dock.altitudes_edit, "12, 25, 40")
    type_into(qtbot, dock.tolerance_spin, "21")
    wait_for_update(qtbot, dock, before)
    assert [r[0] for r in table_texts(dock)] == ["12 m", "25 m", "40 m"]
    assert dock.result == sb.evaluate_bounds(DEPLOYED, [12.0, 25.0, 40.0], DEPLOYED_SIGMAS, 21.0, PREVIEW_STRIDE)
    assert dock.sigma_label.text() == "Label sigma σ_label = r/3 = 7.00 px"

    valid = dock.result
    qtbot.keyClicks(dock.altitudes_edit, ", x")
    qtbot.waitUntil(lambda: not dock.results_table.isEnabled(), timeout=5000)
    assert "Altitudes" in dock.status_label.text() and "'x'" in dock.status_label.text()
    assert dock.result is valid and not dock.processing_button.isEnabled()
    dock.altitudes_edit.selectAll()
    qtbot.keyClicks(dock.altitudes_edit, "0")
    qtbot.waitUntil(lambda: "not above the ground" in dock.status_label.text(), timeout=5000)


def test_platform_preset_restores_every_value(dock, qtbot):
    type_into(qtbot, dock.fx_spin, "3000")
    dock.altitudes_edit.setText("50")
    type_into(qtbot, dock.sigma_spins[2], "0.2")
    assert dock.preset_combo.currentText() == dock_module.PRESET_CUSTOM
    deployed_index = dock.preset_combo.findText(dock_module.PRESET_DEPLOYED)
    dock.preset_combo.setCurrentIndex(deployed_index)
    dock.preset_combo.activated.emit(deployed_index)
    assert dock.camera() == DEPLOYED and dock.sigmas() == pytest.approx(DEPLOYED_SIGMAS)
    assert dock.tolerance_px() == 30.0 and dock.altitudes() == [10.0, 20.0]
    assert dock.preset_combo.currentText() == dock_module.PRESET_DEPLOYED
    before = dock.result
    wait_for_update(qtbot, dock, before)
    assert dock.result == sb.evaluate_bounds(DEPLOYED, [10.0, 20.0], DEPLOYED_SIGMAS, 30.0, PREVIEW_STRIDE)


def enter_platform(qtbot, dock, camera, sigmas, tolerance_px, altitudes):
    """Type a whole platform into the dock, as a user would, and wait for the numbers of exactly it."""
    for spin, value in ((dock.fx_spin, camera.fx), (dock.fy_spin, camera.fy), (dock.cx_spin, camera.cx),
                        (dock.cy_spin, camera.cy), (dock.width_spin, camera.width), (dock.height_spin, camera.height),
                        *zip(dock.sigma_spins, sigmas), (dock.tolerance_spin, tolerance_px)):
        type_into(qtbot, spin, f"{value:g}")
    dock.altitudes_edit.selectAll()
    qtbot.keyClicks(dock.altitudes_edit, ", ".join(f"{a:g}" for a in altitudes))
    qtbot.waitUntil(lambda: dock.result["inputs"]["intrinsics"]["fx"] == camera.fx
                    and dock.result["inputs"]["sigmas"] == pytest.approx(sigmas)
                    and dock.result["inputs"]["tolerance_px"] == tolerance_px
                    and [a["altitude_m"] for a in dock.result["altitudes"]] == list(altitudes), timeout=5000)


# A camera and budget whose bound is worked out by hand (sensor_bound's module docstring: J(u), Σ_u = J S Jᵀ).
# fx = fy = f = 1000 px, principal point (400, 300) in a 1001 × 801 frame; σx = σy = 0.03 m, σz = 0.1 m, no
# roll or pitch, σ_yaw = 0.5°. With x = (u − cx)/f, y = (v − cy)/f, a = (x, y), b = (−y, x) (a ⊥ b,
# |a|² = |b|² = r²), the x, y columns give (f/Z)²σ²·I, the z column −(f/Z)·a and the yaw column f·b, so
#   Σ_u = (f/Z)²·σxy²·I + (f/Z)²·σz²·a aᵀ + f²·σyaw²·b bᵀ,
#   λ_max = (f/Z)²σxy² + r²·max((f/Z)²σz², f²σyaw²),   tr = 2(f/Z)²σxy² + r²((f/Z)²σz² + f²σyaw²),
# both growing with r, so worst at the pixel farthest from the principal point, (1000, 800), the frame's last:
# r² = 0.6² + 0.5² = 0.61. f²σyaw² = 10⁶·(0.5·π/180)² = 76.154 px² (altitude-free).
#   10 m (f/Z = 100): 9 px² + 0.61·max(100, 76.154) = 9 + 61 = 70 px²;  tr = 18 + 61 + 46.454 = 125.454 px²
#   20 m (f/Z = 50):  2.25 + 0.61·max(25, 76.154) = 2.25 + 46.454 = 48.704;  tr = 4.5 + 15.25 + 46.454 = 66.204
# Tolerance 27 px → λ_target = (27/3)² = 81 px²: κ* = 81/sup. At 10 m exact 81/70 = 1.157 accept, trace
# 81/125.454 = 0.646 reject; at 20 m exact 81/48.704 = 1.663, trace 81/66.204 = 1.224, both accept.
HAND_CAMERA = sb.Intrinsics(fx=1000.0, fy=1000.0, cx=400.0, cy=300.0, width=1001, height=801)
HAND_SIGMAS = [0.03, 0.03, 0.1, 0.0, 0.0, 0.5]
YAW_PX2 = 1e6 * math.radians(0.5) ** 2 * 0.61


def test_the_numbers_are_the_hand_worked_bound(dock, qtbot):
    enter_platform(qtbot, dock, HAND_CAMERA, HAND_SIGMAS, 27.0, [10.0, 20.0])
    ten, twenty = dock.result["altitudes"]
    assert ten["sup_lmax_px2"] == pytest.approx(70.0) and ten["sup_trace_px2"] == pytest.approx(79.0 + YAW_PX2)
    assert twenty["sup_lmax_px2"] == pytest.approx(2.25 + YAW_PX2)
    assert twenty["sup_trace_px2"] == pytest.approx(19.75 + YAW_PX2)
    assert (ten["kappa_exact"], ten["kappa_trace"]) == pytest.approx((81 / 70, 81 / (79.0 + YAW_PX2)))
    assert (ten["verdict_exact"], ten["verdict_trace"]) == ("accept", "reject")
    assert (twenty["verdict_exact"], twenty["verdict_trace"]) == ("accept", "accept")
    assert ten["worst_pixel"] == twenty["worst_pixel"] == [1000.0, 800.0]
    # At 10 m the worst pixel's variance splits 9 : 9 : 61 : 0 : 0 : 46.454 over x, y, z, roll, pitch, yaw.
    assert ten["budget_share"] == pytest.approx(np.array([9, 9, 61, 0, 0, YAW_PX2]) / (79.0 + YAW_PX2))
    rows = table_texts(dock)
    assert [r[0] for r in rows] == ["10 m", "20 m"] and rows[0][1] == f"{79.0 + YAW_PX2:.3g}" == "125"
    assert rows[0][3].endswith("✗") and rows[0][4].endswith("✓") and rows[0][4].startswith("1.16")


def test_the_mount_turns_roll_as_worked_out_by_hand(dock, qtbot):
    """Roll alone (σ 0.5°, s = (0.5·π/180)² rad²) on the camera above; Σ_u has rank 1, so λ_max = tr = s·|j|².
    Method mount, roll → φx: j = f·(−x·y, −(1 + y²)); nadir mount, roll → φy: j = f·(1 + x², x·y). Both
    grow with |x| and |y|: worst at (1000, 800), x = 0.6, y = 0.5, where
    method |j|²/f² = 0.3² + 1.25² = 1.6525 and nadir |j|²/f² = 1.36² + 0.3² = 1.9396."""
    s = math.radians(0.5) ** 2
    enter_platform(qtbot, dock, HAND_CAMERA, [0.0, 0.0, 0.0, 0.5, 0.0, 0.0], 27.0, [10.0])
    assert dock.result["inputs"]["mount"] == "method"
    assert dock.result["altitudes"][0]["sup_lmax_px2"] == pytest.approx(1e6 * s * 1.6525)
    before = dock.result
    dock.mount_combo.setCurrentIndex(sb.MOUNTS.index(sb.NADIR_MOUNT))
    wait_for_update(qtbot, dock, before)
    nadir = dock.result["altitudes"][0]
    assert (nadir["sup_lmax_px2"], nadir["sup_trace_px2"]) == pytest.approx((1e6 * s * 1.9396, 1e6 * s * 1.9396))
    assert nadir["worst_pixel"] == [1000.0, 800.0]
    dock.mount_combo.setCurrentIndex(sb.MOUNTS.index(sb.METHOD_MOUNT))


def test_every_platform_preset_is_offered():
    from birdseye.birdseye_qgis.core.design.platforms import PLATFORMS

    assert dock_module.PRESETS == tuple(p.name for p in PLATFORMS) + (dock_module.PRESET_CUSTOM,)
    assert {"deployed", "dji_metadata"} <= {p.key for p in PLATFORMS}


def test_every_preset_in_the_combo_box(dock):
    """Each platform under its name, or a shorter one where its name would not fit the dock; the item's tooltip
    gives the full name."""
    from birdseye.birdseye_qgis.core.design.platforms import PLATFORMS

    shown = [dock.preset_combo.itemText(i) for i in range(dock.preset_combo.count())]
    assert shown == ["Deployed platform (BirdsEye method)", "DJI RTK drone, poses from photos", "Custom"]
    tips = [dock.preset_combo.itemData(i, Qt.ItemDataRole.ToolTipRole) for i in range(len(PLATFORMS))]
    assert tips == [p.name for p in PLATFORMS]


def test_the_mount_changes_the_numbers_and_travels_with_the_preset(dock, qtbot):
    assert dock.mount() is sb.METHOD_MOUNT and dock.result["inputs"]["mount"] == "method"
    sigmas = DEPLOYED_SIGMAS[:3] + [0.3] + DEPLOYED_SIGMAS[4:]    # roll ≠ pitch: the mount matters
    type_into(qtbot, dock.sigma_spins[3], "0.3")
    before = dock.result
    dock.mount_combo.setCurrentIndex(sb.MOUNTS.index(sb.NADIR_MOUNT))
    wait_for_update(qtbot, dock, before)
    expected = sb.evaluate_bounds(DEPLOYED, [10.0, 20.0], sigmas, 30.0, PREVIEW_STRIDE, mount=sb.NADIR_MOUNT)
    assert dock.result == expected
    method = sb.evaluate_bounds(DEPLOYED, [10.0, 20.0], sigmas, 30.0, PREVIEW_STRIDE)
    assert expected["altitudes"][0]["kappa_exact"] != pytest.approx(method["altitudes"][0]["kappa_exact"], rel=0.01)
    image = dock.figure.axes[0].images[0]
    np.testing.assert_allclose(np.asarray(image.get_array()),
                               sb.lmax_field(DEPLOYED, 10.0, sigmas, stride_for(DEPLOYED), mount=sb.NADIR_MOUNT))
    assert dock.processing_parameters()["MOUNT"] == sb.MOUNTS.index(sb.NADIR_MOUNT)
    assert dock.preset_combo.currentText() == dock_module.PRESET_CUSTOM
    # the deployed sigmas on the nadir mount are not the deployed platform either
    dock._set_values(DEPLOYED, DEPLOYED_SIGMAS)
    dock._sync_preset()
    assert dock.preset_combo.currentText() == dock_module.PRESET_CUSTOM
    dock.apply_preset(dock_module.PRESET_DEPLOYED)
    assert dock.mount() is sb.METHOD_MOUNT and dock.preset_combo.currentText() == dock_module.PRESET_DEPLOYED


def test_calibration_file_sets_the_intrinsics(dock, qtbot, tmp_path):
    camera = CameraModel(width=1600, height=1300, fx=1500.0, fy=1480.0, cx=790.0, cy=660.0)
    path = tmp_path / "camchain.yaml"
    write_kalibr_yaml(camera, path)
    before = dock.result
    dock.calibration_widget.setFilePath(str(path))
    assert (dock.fx_spin.value(), dock.fy_spin.value(), dock.cx_spin.value(), dock.cy_spin.value(),
            dock.width_spin.value(), dock.height_spin.value()) == (1500.0, 1480.0, 790.0, 660.0, 1600, 1300)
    assert dock.preset_combo.currentText() == dock_module.PRESET_CUSTOM
    assert dock.processing_parameters()["CALIBRATION"] == str(path)
    wait_for_update(qtbot, dock, before)
    assert dock.result["inputs"]["intrinsics"] == {"fx": 1500.0, "fy": 1480.0, "cx": 790.0, "cy": 660.0,
                                                   "width": 1600, "height": 1300}
    # A file with more digits than the fields show stays named, and the bound uses its every digit.
    precise = CameraModel(width=480, height=300, fx=1066.123456789, fy=1065.72321, cx=239.23984, cy=147.75081)
    precise_path = tmp_path / "precise.yaml"
    write_kalibr_yaml(precise, precise_path)
    before = dock.result
    dock.calibration_widget.setFilePath(str(precise_path))
    wait_for_update(qtbot, dock, before)
    assert dock.calibration_widget.filePath() == str(precise_path) and dock.fx_spin.text() == "1066.1235 px"
    assert dock.result["inputs"]["intrinsics"]["fx"] == 1066.123456789
    assert dock.processing_parameters()["CALIBRATION"] == str(precise_path)
    assert dock.processing_parameters()["FX"] == 1066.123456789
    # once an intrinsic is edited the file no longer describes the camera: it is not passed on
    type_into(qtbot, dock.fx_spin, "1510")
    assert "CALIBRATION" not in dock.processing_parameters() and dock.calibration_widget.filePath() == ""

    broken = tmp_path / "broken.yaml"
    broken.write_text("cam0:\n  intrinsics: [1, 2]\n", encoding="utf-8")
    dock.calibration_widget.setFilePath(str(broken))
    assert "broken.yaml" in dock.status_label.text() and dock.fx_spin.value() == 1510.0


def test_full_resolution_equals_the_processing_algorithm(dock, birdseye_provider, qtbot, tmp_path):
    import processing

    qtbot.mouseClick(dock.full_button, Qt.LeftButton)
    assert dock.full_resolution and dock.result["inputs"]["stride_px"] == 1
    assert "every pixel" in dock.status_label.text()
    parameters = dict(dock.processing_parameters(), OUTPUT_JSON=str(tmp_path / "bound.json"))
    processing.run("birdseye:sensorbound", parameters)
    written = json.loads((tmp_path / "bound.json").read_text(encoding="utf-8"))
    assert written["altitudes"] == json.loads(json.dumps(dock.result["altitudes"]))


def test_run_in_processing_opens_the_algorithm_with_the_dock_values(dock, birdseye_provider, qtbot, monkeypatch):
    import processing
    from qgis.core import QgsProcessingContext

    opened = []
    monkeypatch.setattr(processing, "execAlgorithmDialog", lambda alg_id, params: opened.append((alg_id, params)))
    type_into(qtbot, dock.sigma_spins[0], "0.025")
    qtbot.mouseClick(dock.processing_button, Qt.LeftButton)
    assert len(opened) == 1
    alg_id, parameters = opened[0]
    assert alg_id == "birdseye:sensorbound"
    assert parameters["SIGMAS"] == "0.025,0.01,0.06,0.04,0.04,0.13" and parameters["ALTITUDES"] == "10, 20"
    assert parameters["FX"] == DEPLOYED.fx and parameters["WIDTH"] == 1920 and parameters["TOLERANCE_PX"] == 30.0
    alg = QgsApplication.processingRegistry().algorithmById(alg_id)
    names = {p.name() for p in alg.parameterDefinitions()}
    assert set(parameters) <= names
    ok, message = alg.checkParameterValues(dict(parameters, OUTPUT_JSON="/tmp/x.json"), QgsProcessingContext())
    assert ok, message


def test_sigma_label_is_handed_to_write_labels_as_a_parameter(dock, qtbot, monkeypatch):
    """σ_label = r/3 reaches Write labels as the SIGMA_PX value of its dialog, which the user sees; nothing is
    kept in the project that would change a result out of sight."""
    import processing
    from qgis.core import QgsApplication, QgsProcessingContext

    opened = []
    monkeypatch.setattr(processing, "execAlgorithmDialog", lambda alg_id, params: opened.append((alg_id, params)))
    type_into(qtbot, dock.tolerance_spin, "24")
    qtbot.mouseClick(dock.sigma_button, Qt.LeftButton)
    assert opened == [("birdseye:writelabels", {"SIGMA_PX": 8.0})]
    assert QgsExpressionContextUtils.projectScope(QgsProject.instance()).variable("birdseye_sigma_label_px") is None
    alg = QgsApplication.processingRegistry().algorithmById("birdseye:writelabels")
    assert alg.parameterDefinition("SIGMA_PX").checkValueIsAcceptable(8.0, QgsProcessingContext())


def test_plot_shows_the_chosen_altitude_field(dock, qtbot):
    from birdseye.birdseye_qgis.core.design.bound_report import stride_for as plot_stride

    dock.altitude_combo.setCurrentIndex(1)
    image = dock.figure.axes[0].images[0]
    expected = sb.lmax_field(DEPLOYED, 20.0, DEPLOYED_SIGMAS, plot_stride(DEPLOYED))
    np.testing.assert_allclose(np.asarray(image.get_array()), expected)
    assert "20 m" in dock.figure.axes[0].get_title()
    assert dock.worst_label.text() == "Worst pixel (1919, 1199): the bottom-right corner."


def test_screenshot(qgis_iface, qtbot):
    """A picture of the dock for the README, in QGIS's usual 9 pt interface font."""
    from docks_layout import qgis_interface_font

    with qgis_interface_font():
        widget = dock_module.SensorBoundDock(qgis_iface)
        qtbot.addWidget(widget)
        widget.setFloating(True)
        widget.resize(400, 1240)
        widget.show()
        qtbot.waitExposed(widget)
        qtbot.wait(100)
        body = widget.widget().widget()
        assert body.width() <= widget.widget().viewport().width(), "the dock needs a horizontal scroll bar"
        SCREENSHOT.parent.mkdir(parents=True, exist_ok=True)
        assert widget.grab().save(str(SCREENSHOT))
    assert SCREENSHOT.stat().st_size > 20_000


@pytest.mark.parametrize("preset", ["deployed", "dji_metadata"])
def test_nothing_is_cut_off_at_the_narrowest_width(qgis_iface, qtbot, preset):
    """At its minimum width, in QGIS's 9 pt interface font, every label, field, header and cell shows whole
    (tests/gui/docks_layout.py), for an accepting and a rejecting platform; and the answer leads, in words."""
    from docks_layout import layout_problems, qgis_interface_font

    from birdseye.birdseye_qgis.core.design.platforms import platform

    with qgis_interface_font():
        widget = dock_module.SensorBoundDock(qgis_iface)
        qtbot.addWidget(widget)
        widget.apply_preset(platform(preset).name)
        assert widget.recompute()
        widget.setFloating(True)
        widget.resize(dock_module.MINIMUM_WIDTH, 900)
        widget.show()
        qtbot.waitExposed(widget)
        qtbot.wait(100)
        assert widget.width() == dock_module.MINIMUM_WIDTH
        assert layout_problems(widget) == []
        ten = widget.result["altitudes"][0]
        verdict = "labels stay within their tolerance" if ten["verdict_exact"] == "accept" \
            else "labels leave their tolerance"
        assert widget.summary_label.text().startswith("<b>10 m</b>") and verdict in widget.summary_label.text()


def test_the_dji_metadata_preset_is_offered_and_rejected_at_10_m(dock, qtbot):
    from birdseye.birdseye_qgis.core.design.platforms import DJI_METADATA

    index = dock_module.PRESETS.index(DJI_METADATA.name)
    before = dock.result
    dock.preset_combo.setCurrentIndex(index)
    dock.preset_combo.activated.emit(index)
    assert dock.camera() == DJI_METADATA.camera and dock.sigmas() == pytest.approx(list(DJI_METADATA.sigmas))
    assert dock.mount() is DJI_METADATA.mount
    assert dock.preset() == DJI_METADATA.name   # recognised after the spins rounded it
    wait_for_update(qtbot, dock, before)
    assert dock.result["altitudes"][0]["verdict_exact"] == "reject"


def test_numbers_are_written_to_fit_a_narrow_dock():
    assert [dock_module.kappa_text(k) for k in (None, 0.004, 0.0129, 0.922, 1.3368, 21.36, 998.0, 1234.5)] == \
        ["∞", "< 0.01", "0.0129", "0.922", "1.34", "21.4", "998", "> 999"]
    assert [dock_module.spread_text(v) for v in (4.664, 74.803, 108.48, 8534.7, 1.25e6)] == \
        ["4.66", "74.8", "108", "8\u2009535", "1\u2009250\u2009000"]
    assert [dock_module.sigma_text(v, "m") for v in (0.0136, 0.144, 1.234)] == \
        ["13.6\u2009mm", "144\u2009mm", "1.23\u2009m"]
    assert dock_module.sigma_text(0.3016, "deg") == "0.302°"
    assert [dock_module.where_in_frame(u, v, 1920, 1200) for u, v in ((1919, 1199), (0, 0), (0, 600), (960, 600))] \
        == ["the bottom-right corner", "the top-left corner", "the left edge", "inside the frame"]
