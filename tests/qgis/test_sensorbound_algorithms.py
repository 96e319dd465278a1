"""``birdseye:sensorbound``, ``montecarlobound`` and ``terrainslope`` through the Processing registry.

Each run is compared with a direct call of the core function it wraps (same inputs, so the numbers must
be identical), plus properties the outputs must have on their own: the raster's georeferencing and its
maximum against the JSON supremum, the deployed platform's verdicts, the terrain limit as a round trip
through the error formula, and a message naming the parameter for every kind of bad input.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from qgis.core import QgsProcessingException, QgsProcessingFeedback
from registry import run

from birdseye.birdseye_qgis.core.design import monte_carlo_bound as mc
from birdseye.birdseye_qgis.core.design import sensor_bound as sb
from birdseye.birdseye_qgis.core.design import terrain_slope as ts
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel, write_kalibr_yaml

DEPLOYED = sb.Intrinsics(fx=4264.4945, fy=4262.8927, cx=958.4594, cy=592.5033, width=1920, height=1200)
DEPLOYED_SIGMAS = [0.010, 0.010, 0.060, 0.04, 0.04, 0.13]
JSON_KEYS = {"altitude_m", "sup_trace_px2", "sup_lmax_px2", "kappa_trace", "kappa_exact", "verdict_trace",
             "verdict_exact", "worst_pixel", "balanced_trace_sigma", "balanced_exact_sigma", "budget_share"}


class RecordingFeedback(QgsProcessingFeedback):
    """Keeps what an algorithm logs and the progress it reports."""

    def __init__(self):
        super().__init__()
        self.infos, self.warnings, self.progress = [], [], []
        self.progressChanged.connect(self.progress.append)

    def pushInfo(self, info):
        self.infos.append(info)
        super().pushInfo(info)

    def pushWarning(self, warning):
        self.warnings.append(warning)
        super().pushWarning(warning)


def read_json(path):
    with open(path, encoding="utf-8") as handle:
        return json.load(handle)


# ------------------------------------------------------------------------------------------ sensorbound
@pytest.fixture(scope="module")
def deployed_run(birdseye_provider, tmp_path_factory):
    """The algorithm with its defaults (the deployed platform, every pixel) and every output."""
    out = tmp_path_factory.mktemp("sensorbound")
    feedback = RecordingFeedback()
    result = run("sensorbound", {"OUTPUT_JSON": str(out / "bound.json"), "OUTPUT_REPORT": str(out / "bound.html"),
                                 "OUTPUT_RASTER": str(out / "lmax.tif")}, feedback)
    return result, feedback


def test_defaults_are_the_deployed_platform_and_match_the_core(deployed_run):
    result, _ = deployed_run
    written = read_json(result["OUTPUT_JSON"])
    direct = sb.evaluate_bounds(DEPLOYED, [10.0, 20.0], DEPLOYED_SIGMAS, 30.0, 1)
    assert [e["altitude_m"] for e in written["altitudes"]] == [10.0, 20.0]
    for entry, expected in zip(written["altitudes"], direct["altitudes"]):
        assert JSON_KEYS <= set(entry)
        assert entry == pytest.approx(expected, rel=1e-12)
    assert written["inputs"]["intrinsics"] == direct["inputs"]["intrinsics"]
    assert written["inputs"]["sigmas"] == pytest.approx(DEPLOYED_SIGMAS)
    assert written["inputs"]["calibration"] is None
    assert written["inputs"]["mount"] == "method" and written["inputs"]["axis_convention"] == sb.METHOD_MOUNT.convention


def test_deployed_platform_at_10_m_fails_the_trace_bound_but_passes_the_exact_one(deployed_run):
    at_10 = read_json(deployed_run[0]["OUTPUT_JSON"])["altitudes"][0]
    assert at_10["verdict_trace"] == "reject" and at_10["kappa_trace"] < 1
    assert at_10["verdict_exact"] == "accept" and at_10["kappa_exact"] > 1
    # the exact supremum never exceeds the trace one, so κ* exact ≥ κ* trace
    assert at_10["sup_lmax_px2"] <= at_10["sup_trace_px2"]


def test_log_has_a_readable_summary_per_altitude_and_progress_reaches_100(deployed_run):
    _, feedback = deployed_run
    summaries = [line for line in feedback.infos if "κ*" in line]
    assert len(summaries) == 2
    assert summaries[0].startswith("10 m:") and "trace κ* = 0.922 REJECT" in summaries[0]
    assert "exact κ* = 1.34 ACCEPT" in summaries[0]
    assert summaries[1].startswith("20 m:") and "REJECT" not in summaries[1]
    assert feedback.progress and feedback.progress[-1] == pytest.approx(100.0)
    assert feedback.progress == sorted(feedback.progress)


def test_report_shows_every_altitude_its_verdicts_and_a_plot(deployed_run):
    text = open(deployed_run[0]["OUTPUT_REPORT"], encoding="utf-8").read()
    assert text.count('src="data:image/png;base64,') == 2
    assert "10 m above the ground" in text and "20 m above the ground" in text
    # trace: reject at 10 m, accept at 20 m; exact: accept at both
    assert text.count('<td class="reject">') == 1 and text.count('<td class="accept">') == 3


def test_raster_is_the_lmax_field_in_pixel_coordinates(deployed_run):
    from osgeo import gdal

    written = read_json(deployed_run[0]["OUTPUT_JSON"])
    dataset = gdal.Open(deployed_run[0]["OUTPUT_RASTER"])
    assert (dataset.RasterXSize, dataset.RasterYSize, dataset.RasterCount) == (1920, 1200, 2)
    assert dataset.GetProjection() == ""
    # stride 1: cell (j, i) covers x ∈ [j, j+1], y ∈ [−i−1, −i], i.e. the image pixel (u, v) = (j, i)
    assert dataset.GetGeoTransform() == (0.0, 1.0, 0.0, 0.0, 0.0, -1.0)
    for band_index, entry in enumerate(written["altitudes"], start=1):
        band = dataset.GetRasterBand(band_index)
        assert f"{entry['altitude_m']:g} m" in band.GetDescription()
        values = band.ReadAsArray()
        assert values.max() == pytest.approx(entry["sup_lmax_px2"], rel=1e-6)
        u, v = (int(c) for c in entry["worst_pixel"])
        assert values[v, u] == pytest.approx(entry["sup_lmax_px2"], rel=1e-6)
        # one interior pixel against an independent per-pixel covariance
        cov = sb.pixel_covariance(DEPLOYED, 300.0, 900.0, entry["altitude_m"],
                                  sb.sigmas_to_variances(DEPLOYED_SIGMAS))[0]
        assert values[900, 300] == pytest.approx(np.linalg.eigvalsh(cov)[-1], rel=1e-6)


def test_raster_with_a_stride_that_does_not_divide_the_frame_warns_and_stops_short(birdseye_provider, tmp_path):
    from osgeo import gdal

    feedback = RecordingFeedback()
    result = run("sensorbound", {"ALTITUDES": "15", "STRIDE_PX": 7, "OUTPUT_JSON": str(tmp_path / "b.json"),
                                 "OUTPUT_RASTER": str(tmp_path / "f.tif")}, feedback)
    dataset = gdal.Open(result["OUTPUT_RASTER"])
    columns, rows = (1920 - 1) // 7 + 1, (1200 - 1) // 7 + 1  # pixel centres 0, 7, … up to the last one, W − 1
    assert (dataset.RasterXSize, dataset.RasterYSize, dataset.RasterCount) == (columns, rows, 1)
    x0, dx, _, y0, _, dy = dataset.GetGeoTransform()
    assert (dx, dy) == (7.0, -7.0) and x0 + dx / 2 == 0.5 and y0 + dy / 2 == -0.5  # cell (0, 0) centred on u=v=0
    assert any("OUTPUT_RASTER" in w and "stride 7" in w for w in feedback.warnings)
    expected = sb.lmax_field(DEPLOYED, 15.0, DEPLOYED_SIGMAS, 7)[:(1200 - 1) // 7 + 1, :(1920 - 1) // 7 + 1]
    np.testing.assert_allclose(dataset.GetRasterBand(1).ReadAsArray(), expected, rtol=1e-6)
    assert result["OUTPUT_REPORT"] is None


def test_the_chosen_mount_reaches_the_json_and_the_raster(birdseye_provider, tmp_path):
    """Roll six times pitch: the nadir mount (roll and pitch swapped against the method's) must show."""
    from osgeo import gdal

    sigmas = [0.01, 0.01, 0.06, 0.3, 0.05, 0.13]
    result = run("sensorbound", {"MOUNT": sb.MOUNTS.index(sb.NADIR_MOUNT), "SIGMAS": "0.01,0.01,0.06,0.3,0.05,0.13",
                                 "ALTITUDES": "10", "STRIDE_PX": 8, "OUTPUT_JSON": str(tmp_path / "b.json"),
                                 "OUTPUT_REPORT": None, "OUTPUT_RASTER": str(tmp_path / "f.tif")})
    written = read_json(result["OUTPUT_JSON"])
    nadir = sb.evaluate_bounds(DEPLOYED, [10.0], sigmas, 30.0, 8, mount=sb.NADIR_MOUNT)
    method = sb.evaluate_bounds(DEPLOYED, [10.0], sigmas, 30.0, 8)
    assert written["inputs"]["mount"] == "nadir_top_forward"
    assert written["altitudes"][0] == pytest.approx(nadir["altitudes"][0], rel=1e-12)
    assert written["altitudes"][0]["sup_lmax_px2"] != pytest.approx(method["altitudes"][0]["sup_lmax_px2"], rel=0.01)
    dataset = gdal.Open(result["OUTPUT_RASTER"])
    assert dataset.GetMetadata()["MOUNT"] == "nadir_top_forward"
    regular = ((1200 - 1) // 8 + 1, (1920 - 1) // 8 + 1)  # the raster: the stride's regular grid
    np.testing.assert_allclose(dataset.GetRasterBand(1).ReadAsArray(),
                               sb.lmax_field(DEPLOYED, 10.0, sigmas, 8, mount=sb.NADIR_MOUNT)[:regular[0], :regular[1]],
                               rtol=1e-6)


def test_calibration_file_overrides_the_typed_intrinsics(birdseye_provider, tmp_path):
    camera = CameraModel(width=1600, height=1300, fx=1500.0, fy=1480.0, cx=790.0, cy=660.0)
    path = tmp_path / "camchain.yaml"
    write_kalibr_yaml(camera, path)
    feedback = RecordingFeedback()
    result = run("sensorbound", {"CALIBRATION": str(path), "FX": 1.0, "FY": 2.0, "CX": 3.0, "CY": 4.0,
                                 "WIDTH": 5, "HEIGHT": 6, "ALTITUDES": "12", "SIGMAS": "0.02,0.02,0.05,0.1,0.1,0.2",
                                 "TOLERANCE_PX": 24, "STRIDE_PX": 2, "OUTPUT_JSON": str(tmp_path / "b.json")},
                 feedback)
    written = read_json(result["OUTPUT_JSON"])
    expected = sb.evaluate_bounds(camera, [12.0], [0.02, 0.02, 0.05, 0.1, 0.1, 0.2], 24.0, 2)
    assert written["inputs"]["intrinsics"] == expected["inputs"]["intrinsics"]
    assert written["altitudes"][0] == pytest.approx(expected["altitudes"][0], rel=1e-12)
    assert written["inputs"]["calibration"] == str(path)
    assert any("camchain.yaml" in line and "ignored" in line for line in feedback.infos)


@pytest.mark.parametrize("bad, name, says", [
    ({"ALTITUDES": "10, ten"}, "ALTITUDES", "'ten' is not a number"),
    ({"ALTITUDES": "10,-5"}, "ALTITUDES", "-5 m is not above the ground"),
    ({"ALTITUDES": "0"}, "ALTITUDES", "0 m is not above the ground"),
    ({"ALTITUDES": " , "}, "ALTITUDES", "no values"),
    ({"SIGMAS": "0.01,0.01,0.06"}, "SIGMAS", "expected 6 sigmas"),
    ({"SIGMAS": "0.01,0.01,0.06,0.04,0.04,0.13,0.1"}, "SIGMAS", "got 7"),
    ({"SIGMAS": "0.01,0.01,0.06,-0.04,0.04,0.13"}, "SIGMAS", "roll sigma is negative"),
    ({"SIGMAS": "0.01;0.01;x;0.04;0.04;0.13"}, "SIGMAS", "item 3 'x'"),
    ({"TOLERANCE_PX": 0}, "TOLERANCE_PX", "greater than 0 px"),
    ({"TOLERANCE_PX": -30}, "TOLERANCE_PX", "greater than 0 px"),
    ({"FX": 0}, "FX", "focal length"),
    ({"FY": -4000}, "FY", "focal length"),
    ({"STRIDE_PX": 0}, "STRIDE_PX", ""),
    ({"WIDTH": 0}, "WIDTH", ""),
])
def test_bad_input_names_the_parameter(birdseye_provider, tmp_path, bad, name, says):
    with pytest.raises(QgsProcessingException) as error:
        run("sensorbound", dict(bad, OUTPUT_JSON=str(tmp_path / "b.json")))
    message = str(error.value)
    assert name in message and says in message, message
    assert not (tmp_path / "b.json").exists()


def test_bad_calibration_file_is_named(birdseye_provider, tmp_path):
    broken = tmp_path / "broken.yaml"
    broken.write_text("cam0:\n  intrinsics: [1500, 1500, 800]\n  resolution: [1600, 1300]\n", encoding="utf-8")
    for path, says in ((tmp_path / "missing.yaml", "not found"), (broken, "intrinsics")):
        with pytest.raises(QgsProcessingException) as error:
            run("sensorbound", {"CALIBRATION": str(path), "OUTPUT_JSON": str(tmp_path / "b.json")})
        message = str(error.value)
        assert "CALIBRATION" in message and path.name in message and says in message, message


def test_cancel_stops_before_any_output(birdseye_provider, tmp_path):
    feedback = RecordingFeedback()
    feedback.cancel()
    with pytest.raises(QgsProcessingException, match="Cancelled"):
        run("sensorbound", {"OUTPUT_JSON": str(tmp_path / "b.json")}, feedback)
    assert not (tmp_path / "b.json").exists()


# ------------------------------------------------------------------------------------- montecarlobound
def test_montecarlobound_matches_the_core_and_the_linearisation_holds(birdseye_provider, tmp_path):
    from matplotlib import image

    parameters = {"ALTITUDES": "10,20", "N_SAMPLES": 4000, "SEED": 7, "SCALE_MIN": 0.5, "SCALE_MAX": 50,
                  "SCALE_STEPS": 4, "PER_AXIS": True, "OUTPUT_JSON": str(tmp_path / "mc.json"),
                  "OUTPUT_PNG": str(tmp_path / "mc.png")}
    feedback = RecordingFeedback()
    result = run("montecarlobound", parameters, feedback)
    written = read_json(result["OUTPUT_JSON"])
    scales = np.logspace(math.log10(0.5), math.log10(50), 4)
    assert written["inputs"]["scales"] == pytest.approx(scales.tolist())
    for entry, altitude in zip(written["altitudes"], (10.0, 20.0)):
        check = mc.monte_carlo_check(DEPLOYED, altitude, DEPLOYED_SIGMAS, 4000, seed=7)
        study = mc.scaling_study(DEPLOYED, altitude, DEPLOYED_SIGMAS, scales, True, 4000, seed=7)
        # same seed, same draws: identical numbers
        assert entry["check"] == json.loads(json.dumps(check.to_json_dict()))
        assert entry["scaling"] == json.loads(json.dumps(study.to_json_dict()))
        assert entry["kappa_exact"] == pytest.approx(sb.evaluate_bound(DEPLOYED, altitude, DEPLOYED_SIGMAS).kappa_exact)
        # acceptance: sKLD < 1e-2 at scale 1 for the deployed platform at 10 and 20 m
        assert entry["max_skld"] < mc.SKLD_THRESHOLD and entry["linearisation_holds"] is True
        assert set(entry["scaling"]["per_axis"]) == set(sb.AXES)
    assert sum("the linearised bound holds" in line for line in feedback.infos) == 2
    # The method's grid: 35 ground points every 0.67 m at 10 m, their ellipses summarised in the log.
    assert written["inputs"]["ground_spacing_m"] == mc.GROUND_SPACING_M == 0.67
    assert written["altitudes"][0]["check"]["summary"]["n_points"] == 35
    assert any(line.startswith("10 m: 35 ground points every 0.67 m (5 × 7)") and "semi-major axis max" in line
               for line in feedback.infos)
    # one panel per altitude, stacked: twice the height of the core's single plot
    single = image.imread(mc.plot_scaling_study(study, tmp_path / "single.png"))
    stacked = image.imread(result["OUTPUT_PNG"])
    assert stacked.shape[0] == 2 * single.shape[0] and stacked.shape[1] == single.shape[1]


def test_montecarlobound_grid_spacing_and_cutoffs_reach_the_core(birdseye_provider, tmp_path):
    feedback = RecordingFeedback()
    result = run("montecarlobound", {"ALTITUDES": "10", "GROUND_SPACING_M": 1.5, "SKLD_CUTOFFS": "0.01, 0.1",
                                     "SIGMAS": "0.01,0.01,0.06,0.04,0.04,0.13", "N_SAMPLES": 1000, "SEED": 2,
                                     "SCALE_STEPS": 2, "OUTPUT_JSON": str(tmp_path / "mc.json"), "OUTPUT_PNG": None},
                 feedback)
    written = read_json(result["OUTPUT_JSON"])
    check = mc.monte_carlo_check(DEPLOYED, 10.0, DEPLOYED_SIGMAS, 1000, 1.5, seed=2, skld_cutoffs=(0.01, 0.1))
    entry = written["altitudes"][0]
    assert entry["check"] == json.loads(json.dumps(check.to_json_dict()))
    # 4.502 m × 2.815 m: ±2.251 / 1.5 → 1 node each side across, ±1.408 / 1.5 → none down.
    assert entry["check"]["grid_shape"] == [1, 3] and len(entry["check"]["points"]) == 3
    assert set(entry["check"]["summary"]["fraction_over_skld"]) == {"0.01", "0.1"}
    assert written["inputs"]["skld_cutoffs"] == [0.01, 0.1] and written["inputs"]["ellipse_sigmas"] == 3.0
    assert any("0.0% over 0.01, 0.0% over 0.1" in line for line in feedback.infos)


@pytest.mark.parametrize("bad, name", [({"SCALE_MIN": 0}, "SCALE_MIN"), ({"SCALE_MAX": 0.05}, "SCALE_MAX"),
                                       ({"SIGMAS": "1,2,3"}, "SIGMAS"), ({"ALTITUDES": "-1"}, "ALTITUDES"),
                                       ({"GROUND_SPACING_M": 0}, "GROUND_SPACING_M"),
                                       ({"SKLD_CUTOFFS": "0.01,0"}, "SKLD_CUTOFFS"),
                                       ({"SKLD_CUTOFFS": "small"}, "SKLD_CUTOFFS")])
def test_montecarlobound_bad_input_names_the_parameter(birdseye_provider, tmp_path, bad, name):
    with pytest.raises(QgsProcessingException, match=name):
        run("montecarlobound", dict(bad, N_SAMPLES=100, OUTPUT_JSON=str(tmp_path / "mc.json")))


def test_montecarlobound_draws_through_the_chosen_mount(birdseye_provider, tmp_path):
    sigmas = [0.01, 0.01, 0.06, 0.3, 0.05, 0.13]
    result = run("montecarlobound", {"MOUNT": sb.MOUNTS.index(sb.NADIR_MOUNT), "SIGMAS": "0.01,0.01,0.06,0.3,0.05,0.13",
                                     "ALTITUDES": "10", "N_SAMPLES": 2000, "SEED": 4, "SCALE_STEPS": 2,
                                     "OUTPUT_JSON": str(tmp_path / "mc.json"), "OUTPUT_PNG": None})
    written = read_json(result["OUTPUT_JSON"])
    check = mc.monte_carlo_check(DEPLOYED, 10.0, sigmas, 2000, seed=4, mount=sb.NADIR_MOUNT)
    assert written["inputs"]["mount"] == "nadir_top_forward"
    assert written["altitudes"][0]["check"] == json.loads(json.dumps(check.to_json_dict()))
    bound = sb.evaluate_bound(DEPLOYED, 10.0, sigmas, mount=sb.NADIR_MOUNT)
    assert written["altitudes"][0]["kappa_exact"] == pytest.approx(bound.kappa_exact)


# ---------------------------------------------------------------------------------------- terrainslope
def test_terrainslope_grid_and_frame_limits(birdseye_provider, tmp_path):
    feedback = RecordingFeedback()
    result = run("terrainslope", {"ALTITUDE_M": 15, "TOLERANCE_PX": 20, "MAX_SLOPE_DEG": 30,
                                  "OUTPUT_JSON": str(tmp_path / "t.json"), "OUTPUT_PNG": str(tmp_path / "t.png")},
                 feedback)
    written = read_json(result["OUTPUT_JSON"])
    slopes, ratios = np.array(written["slopes_deg"]), np.array(written["distance_ratios"])
    assert slopes[0] == 0 and slopes[-1] == 30 and np.allclose(np.diff(slopes), 0.5)
    errors = np.array([[np.nan if e is None else e for e in row] for row in written["error_px"]])
    np.testing.assert_allclose(errors, ts.slope_error_grid(DEPLOYED, 15.0, slopes, ratios), rtol=1e-12)
    frame = ts.frame_distance_ratios(DEPLOYED)
    assert set(written["frame_points"]) == set(frame)
    for name, point in written["frame_points"].items():
        assert point["distance_ratio"] == pytest.approx(frame[name])
        assert point["distance_m"] == pytest.approx(15.0 * frame[name])
        # round trip: at the reported limit the level-plane error is exactly the tolerance
        assert ts.slope_error_px(DEPLOYED, 15.0, point["max_slope_deg"], frame[name]) == pytest.approx(20.0)
    # the corner is farthest from the nadir point, so it tolerates the least slope
    assert written["frame_points"]["corner"]["max_slope_deg"] < written["frame_points"]["edge_u"]["max_slope_deg"]
    assert sum("uphill slope" in line for line in feedback.infos) == 3
    with open(result["OUTPUT_PNG"], "rb") as handle:
        assert handle.read(8) == b"\x89PNG\r\n\x1a\n"


def test_terrainslope_marks_targets_level_with_the_camera_as_null(birdseye_provider, tmp_path):
    """A wide lens reaches ρ·tan α ≥ 1 inside the study: those cells are null, not infinite."""
    result = run("terrainslope", {"FX": 400, "FY": 400, "CX": 960, "CY": 600, "MAX_SLOPE_DEG": 60,
                                  "OUTPUT_JSON": str(tmp_path / "t.json")})
    written = read_json(result["OUTPUT_JSON"])
    flat = [e for row in written["error_px"] for e in row]
    assert None in flat and all(e is None or math.isfinite(e) for e in flat)


@pytest.mark.parametrize("bad, name", [({"ALTITUDE_M": 0}, "ALTITUDE_M"), ({"MAX_SLOPE_DEG": 90}, "MAX_SLOPE_DEG"),
                                       ({"MAX_SLOPE_DEG": 0}, "MAX_SLOPE_DEG"), ({"TOLERANCE_PX": 0}, "TOLERANCE_PX")])
def test_terrainslope_bad_input_names_the_parameter(birdseye_provider, tmp_path, bad, name):
    with pytest.raises(QgsProcessingException, match=name):
        run("terrainslope", dict(bad, OUTPUT_JSON=str(tmp_path / "t.json")))


def test_the_dji_metadata_preset_sets_camera_and_sigmas_and_fails_at_10_m(birdseye_provider, tmp_path):
    """PLATFORM picks a preset: its camera and sigmas replace the typed ones (which are left at odd
    values here to show it), and the DJI metadata budget is rejected at 10 m, the heading dominating."""
    from birdseye.birdseye_qgis.core.design.platforms import DJI_METADATA, PLATFORMS

    feedback = RecordingFeedback()
    index = 1 + PLATFORMS.index(DJI_METADATA)
    out = run("sensorbound", {"PLATFORM": index, "FX": 100.0, "SIGMAS": "9,9,9,9,9,9", "MOUNT": 0, "ALTITUDES": "10",
                              "STRIDE_PX": 8, "OUTPUT_JSON": str(tmp_path / "dji.json"), "OUTPUT_REPORT": None},
              feedback)
    result = read_json(out["OUTPUT_JSON"])
    assert result["inputs"]["platform"] == "dji_metadata"
    assert result["inputs"]["mount"] == DJI_METADATA.mount.key == "nadir_top_forward"
    assert result["inputs"]["sigmas"] == pytest.approx(list(DJI_METADATA.sigmas))
    assert result["inputs"]["intrinsics"]["fx"] == pytest.approx(DJI_METADATA.camera.fx)
    direct = sb.evaluate_bound(DJI_METADATA.camera, 10.0, DJI_METADATA.sigmas, 30.0, 8).to_json_dict()
    (entry,) = result["altitudes"]
    assert entry["kappa_exact"] == pytest.approx(direct["kappa_exact"]) and entry["verdict_exact"] == "reject"
    assert int(np.argmax(entry["budget_share"])) == 5          # yaw
    assert any("DJI RTK drone" in line and "DJI specifications" in line for line in feedback.infos)
