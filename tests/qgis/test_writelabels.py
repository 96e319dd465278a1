"""birdseye:writelabels through the registry, on a simulated campaign imported by the importers."""
from __future__ import annotations

import csv
import json

import numpy as np
import pytest
from qgis.core import QgsExpressionContextUtils, QgsProcessingException, QgsProject
from registry import run

from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign


def simulate_and_import(folder, **config):
    cfg = CampaignConfig(seed=3, n_targets=6, field_width_m=8.0, field_length_m=6.0, image_width=480,
                         image_height=300, n_missed=1, n_spurious=1, **config)
    simulate_campaign(cfg, folder)
    geotags = run("importgeotags", {"INPUT": str(folder / "geotags.csv"), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    frames = run("importflightlog", {"POSE_LOG": str(folder / "poses.csv"), "IMAGES": str(folder / "frames"),
                                     "CALIBRATION": str(folder / "calibration.yaml"),
                                     "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    return folder, geotags, frames


@pytest.fixture(scope="module")
def imported(birdseye_provider, tmp_path_factory):
    return simulate_and_import(tmp_path_factory.mktemp("campaign"))


def test_writelabels_writes_the_training_set_and_counts(imported, tmp_path):
    folder, geotags, frames = imported
    out = tmp_path / "labels"
    result = run("writelabels", {"GEOTAGS": geotags, "FRAMES": frames, "SIGMA_PX": 4.0, "EDGE_BUFFER_PX": 5,
                                 "WRITE_TILES": True, "TILE_SIZE": 96, "WRITE_COCO": True,
                                 "OUTPUT_FOLDER": str(out), "OUTPUT_FRAMES": "TEMPORARY_OUTPUT",
                                 "OUTPUT_GEOTAGS": "TEMPORARY_OUTPUT"})
    rows = list(csv.DictReader(open(out / "labels.csv")))
    summary = json.loads((out / "summary.json").read_text())
    assert result["LABEL_COUNT"] == len(rows) == summary["n_labels"] > 10
    assert result["SIGMA_USED_PX"] == 4.0 and {r["sigma_px"] for r in rows} == {"4"}
    assert all(float(r["margin_px"]) >= 5.0 for r in rows)
    # Label counts on a copy of the frame layer agree with the CSV; the input layer is untouched.
    counted = {f["frame_id"]: f["n_labels"] for f in result["OUTPUT_FRAMES"].getFeatures()}
    per_frame = {}
    for r in rows:
        per_frame[int(r["frame_id"])] = per_frame.get(int(r["frame_id"]), 0) + 1
    assert {k: v for k, v in counted.items() if v} == per_frame
    assert "n_labels" not in frames.fields().names()
    seen = {f["id"]: f["frames_seen"] for f in result["OUTPUT_GEOTAGS"].getFeatures()}
    per_geotag = {}
    for r in rows:
        per_geotag[int(r["geotag_id"])] = per_geotag.get(int(r["geotag_id"]), 0) + 1
    assert {k: v for k, v in seen.items() if v} == per_geotag
    assert sorted(k for k, v in seen.items() if v == 0) == sorted(
        summary["geotags_never_in_view"] + summary["geotags_only_at_edge"])
    # One raster per frame, the image's size; tiles side by side.
    n_frames = frames.featureCount()
    assert len(list((out / "rasters").glob("*.png"))) == n_frames
    images = sorted(p.name for p in (out / "tiles" / "images").iterdir())
    assert images and images == sorted(p.name for p in (out / "tiles" / "labels").iterdir())
    coco = json.loads((out / "coco_keypoints.json").read_text())
    assert len(coco["annotations"]) == len(rows)


def test_sigma_comes_from_the_parameters_alone(imported, tmp_path):
    """SIGMA_PX (10 px unless given) or r / 3 of a sensorbound JSON; the sensor-bound dock's project value
    (@birdseye_sigma_label_px) changes nothing: a result depends only on the parameters given."""
    folder, geotags, frames = imported
    base = {"GEOTAGS": geotags, "FRAMES": frames, "WRITE_RASTERS": False, "OUTPUT_FRAMES": None,
            "OUTPUT_GEOTAGS": None}
    QgsExpressionContextUtils.setProjectVariable(QgsProject.instance(), "birdseye_sigma_label_px", 7.5)
    try:
        assert run("writelabels", {**base, "OUTPUT_FOLDER": str(tmp_path / "a")})["SIGMA_USED_PX"] == 10.0
        assert run("writelabels", {**base, "SIGMA_PX": 6.0,
                                   "OUTPUT_FOLDER": str(tmp_path / "b")})["SIGMA_USED_PX"] == 6.0
    finally:
        QgsExpressionContextUtils.removeProjectVariable(QgsProject.instance(), "birdseye_sigma_label_px")
    bound = tmp_path / "bound.json"
    bound.write_text(json.dumps({"inputs": {"tolerance_px": 24.0},
                                 "altitudes": [{"altitude_m": 10.0, "verdict_exact": "accept"}]}))
    result = run("writelabels", {**base, "SIGMA_PX": 6.0, "SENSOR_BOUND_JSON": str(bound),
                                 "OUTPUT_FOLDER": str(tmp_path / "c")})
    assert result["SIGMA_USED_PX"] == 8.0
    bound.write_text(json.dumps({"inputs": {"tolerance_px": 24.0},
                                 "altitudes": [{"altitude_m": 10.0, "verdict_exact": "reject"}]}))
    with pytest.raises(QgsProcessingException, match="rejected at 10 m"):
        run("writelabels", {**base, "SENSOR_BOUND_JSON": str(bound), "OUTPUT_FOLDER": str(tmp_path / "d")})


def test_a_layer_that_is_not_a_frame_layer_is_refused(imported, tmp_path):
    folder, geotags, frames = imported
    from qgis.core import QgsVectorLayer

    polygons = QgsVectorLayer("Polygon?crs=EPSG:32756&field=name:string", "fields", "memory")
    from qgis.core import QgsFeature, QgsGeometry
    f = QgsFeature(polygons.fields())
    f.setGeometry(QgsGeometry.fromWkt("POLYGON((0 0, 1 0, 1 1, 0 0))"))
    f["name"] = "paddock"
    polygons.dataProvider().addFeature(f)
    with pytest.raises(QgsProcessingException, match="not a BirdsEye frame layer"):
        run("writelabels", {"GEOTAGS": geotags, "FRAMES": polygons, "OUTPUT_FOLDER": str(tmp_path)})


def write_geotiff(dem, path):
    from osgeo import gdal, osr

    rows, cols = dem.heights.shape
    ds = gdal.GetDriverByName("GTiff").Create(str(path), cols, rows, 1, gdal.GDT_Float32)
    x0, dx, y0, dy = dem.geotransform
    ds.SetGeoTransform((x0, dx, 0.0, y0, 0.0, dy))
    srs = osr.SpatialReference()
    srs.SetFromUserInput(str(dem.crs))
    ds.SetProjection(srs.ExportToWkt())
    ds.GetRasterBand(1).WriteArray(dem.heights)
    ds.GetRasterBand(1).SetNoDataValue(-9999.0)
    ds = None
    return str(path)


def test_a_flat_dem_gives_the_level_plane_labels_and_a_wrong_datum_is_refused(birdseye_provider, tmp_path):
    from qgis.core import QgsRasterLayer

    from birdseye.birdseye_qgis.core.sim.terrain import synthetic_terrain

    # Noise off: the altimeter's level plane and a flat DEM at the true ground must agree exactly
    # (with noise, the DEM path takes its depth from the INS height, the level plane from the altimeter).
    folder, geotags, frames = simulate_and_import(tmp_path / "campaign", noise_off=True)
    campaign = json.loads((folder / "truth" / "campaign.json").read_text())
    lat, lon = campaign["site"]["lat"], campaign["site"]["lon"]
    ground = campaign["site"]["ground_height_m"]
    dem = synthetic_terrain(lat, lon, kind="plane", slope_deg=0.0, base_height_m=ground, size_m=80.0, cell_m=1.0,
                            vertical_datum="ellipsoidal")
    layer = QgsRasterLayer(write_geotiff(dem, tmp_path / "dem.tif"), "dem")
    assert layer.isValid()
    base = {"GEOTAGS": geotags, "FRAMES": frames, "SIGMA_PX": 4.0, "WRITE_RASTERS": False,
            "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None}
    run("writelabels", {**base, "OUTPUT_FOLDER": str(tmp_path / "plane")})
    run("writelabels", {**base, "DEM": layer, "DEM_VERTICAL_DATUM": 0, "OUTPUT_FOLDER": str(tmp_path / "dem")})
    read = lambda name: {(r["frame_id"], r["geotag_id"]): (float(r["u"]), float(r["v"]))
                         for r in csv.DictReader(open(tmp_path / name / "labels.csv"))}
    plane, with_dem = read("plane"), read("dem")
    common = set(plane) & set(with_dem)
    assert set(plane) == set(with_dem) and len(plane) > 5
    assert max(np.hypot(plane[k][0] - with_dem[k][0], plane[k][1] - with_dem[k][1]) for k in common) < 0.01
    with pytest.raises(QgsProcessingException, match="MSL|undulation|vertical"):
        run("writelabels", {**base, "DEM": layer, "DEM_VERTICAL_DATUM": 1, "OUTPUT_FOLDER": str(tmp_path / "x")})


def tiles_of(folder):
    return sorted(p.name for p in (folder / "tiles" / "images").iterdir())


def polygon_far_away(frames):
    """A drawn surveyed area 1 km east of every frame: no frame sees any of it."""
    from qgis.core import QgsFeature, QgsGeometry, QgsRectangle, QgsVectorLayer

    extent = frames.extent()
    far = QgsRectangle(extent.xMaximum() + 1000.0, extent.yMinimum(), extent.xMaximum() + 1100.0, extent.yMaximum())
    layer = QgsVectorLayer(f"Polygon?crs={frames.crs().authid()}", "surveyed", "memory")
    f = QgsFeature()
    f.setGeometry(QgsGeometry.fromRect(far))
    layer.dataProvider().addFeatures([f])
    return layer


def test_no_negative_tiles_outside_the_surveyed_area_and_targets_csv(imported, tmp_path):
    """Drawn far from the flight, the surveyed area holds no tile: every positive tile is still written, no negative
    is. targets.csv lists each geotag written to labels.csv once, with its position and ellipsoidal height."""
    folder, geotags, frames = imported
    base = {"GEOTAGS": geotags, "FRAMES": frames, "SIGMA_PX": 4.0, "WRITE_RASTERS": False, "WRITE_TILES": True,
            "TILE_SIZE": 96, "NEGATIVE_RATIO": 3.0, "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None}
    run("writelabels", {**base, "OUTPUT_FOLDER": str(tmp_path / "hull")})
    run("writelabels", {**base, "SURVEYED_AREA": polygon_far_away(frames), "OUTPUT_FOLDER": str(tmp_path / "far")})
    hull = json.loads((tmp_path / "hull" / "summary.json").read_text())
    far = json.loads((tmp_path / "far" / "summary.json").read_text())
    assert hull["surveyed_area"] == {"source": "geotag_hull", "margin_m": 1.0, "geotags": 6}
    assert far["surveyed_area"] == {"source": "drawn", "rings": 1}
    assert far["tiles"]["positive"] == hull["tiles"]["positive"] > 0
    assert far["tiles"]["negative"] == 0 < hull["tiles"]["negative"]
    assert far["tiles"]["skipped"]["outside_surveyed_area"] > hull["tiles"]["skipped"]["outside_surveyed_area"]
    labels = list(csv.DictReader(open(tmp_path / "far" / "labels.csv")))
    assert len(tiles_of(tmp_path / "far")) == far["tiles"]["positive"]
    targets = list(csv.DictReader(open(tmp_path / "far" / "targets.csv")))
    assert [t["geotag_id"] for t in targets] == sorted({r["geotag_id"] for r in labels}, key=int)
    by_id = {f["id"]: f for f in geotags.getFeatures()}
    for t in targets:
        f = by_id[int(t["geotag_id"])]
        assert float(t["lat"]) == pytest.approx(f["lat"], abs=1e-9)
        assert float(t["lon"]) == pytest.approx(f["lon"], abs=1e-9)
        assert float(t["height_m"]) == pytest.approx(f["h_ellipsoid"], abs=1e-3) and t["height_ref"] == "ellipsoidal"
        assert (t["label"], t["provenance"]) == (f["label"], "survey")


def mark_check_layer(residuals):
    """A label check as Import camera solution writes it (fields of MARK_CHECK_FIELDS), one check-point mark per
    residual (Δu, Δv) px, saved nowhere: a memory layer."""
    from qgis.core import QgsFeature, QgsVectorLayer

    from birdseye.birdseye_qgis.core.labels.mark_check import MARK_CHECK_FIELDS
    from birdseye.birdseye_qgis.qgis_io import layers

    layer = QgsVectorLayer("PointZ?crs=EPSG:4326", "label check", "memory")
    layer.dataProvider().addAttributes(layers.qgs_fields(MARK_CHECK_FIELDS).toList())
    layer.updateFields()
    for k, (du, dv) in enumerate(residuals):
        f = QgsFeature(layer.fields())
        f["point_id"], f["kind"], f["frame_id"] = k + 1, "check_point", 1
        f["u_mark"], f["v_mark"], f["u_label"], f["v_label"] = 100.0, 200.0, 100.0 + du, 200.0 + dv
        layer.dataProvider().addFeatures([f])
    return layer


def test_sigma_measured_on_a_label_check(imported, tmp_path):
    """σ = per-axis RMS of label − mark: residuals (6, 8), (0, 0), (−3, 4), (0, −5): Σ = 100 + 0 + 25 + 25 = 150
    over 4 marks, σ = √(150/8) = 4.330 px, in labels.csv, summary.json and the log. Without a check it is refused."""
    from registry import Recorder

    folder, geotags, frames = imported
    base = {"GEOTAGS": geotags, "FRAMES": frames, "WRITE_RASTERS": False, "OUTPUT_FRAMES": None,
            "OUTPUT_GEOTAGS": None, "SIGMA_SOURCE": 1}
    feedback = Recorder()
    result = run("writelabels", {**base, "MARK_CHECK": mark_check_layer([(6, 8), (0, 0), (-3, 4), (0, -5)]),
                                 "OUTPUT_FOLDER": str(tmp_path / "m")}, feedback)
    sigma = np.sqrt(150 / 8)
    assert result["SIGMA_USED_PX"] == pytest.approx(sigma)
    summary = json.loads((tmp_path / "m" / "summary.json").read_text())
    assert summary["sigma_px"] == pytest.approx(sigma) and summary["label_radius_px"] == pytest.approx(3 * sigma)
    assert summary["sigma_source"]["source"] == "mark_check" and summary["sigma_source"]["n_marks"] == 4
    assert {r["sigma_px"] for r in csv.DictReader(open(tmp_path / "m" / "labels.csv"))} == {f"{sigma:g}"}
    assert any("σ = 4.33 px measured on" in i and "4 check_point mark(s)" in i for i in feedback.infos)
    assert any("uncertain by about ±25 %" in w for w in feedback.warnings)
    with pytest.raises(QgsProcessingException, match="give MARK_CHECK"):
        run("writelabels", {**base, "OUTPUT_FOLDER": str(tmp_path / "x")})
    given = run("writelabels", {**base, "SIGMA_SOURCE": 0, "SIGMA_PX": 6.0, "MARK_CHECK": mark_check_layer([(1, 1)]),
                                "OUTPUT_FOLDER": str(tmp_path / "g")})
    assert given["SIGMA_USED_PX"] == 6.0
    assert json.loads((tmp_path / "g" / "summary.json").read_text())["sigma_source"] == {
        "source": "given", "parameter": "SIGMA_PX"}


def test_relief_check_reports_the_frames_whose_displacement_exceeds_the_label_radius(imported, tmp_path):
    """Each frame listed has a label whose h·r/d, in px, exceeds 3σ; a larger relief lists at least those frames,
    no relief none."""
    folder, geotags, frames = imported
    base = {"GEOTAGS": geotags, "FRAMES": frames, "SIGMA_PX": 3.0, "WRITE_RASTERS": False, "OUTPUT_FRAMES": None,
            "OUTPUT_GEOTAGS": None}
    over = {}
    for h in (0.0, 0.5, 1.0):
        result = run("writelabels", {**base, "RELIEF_M": h, "OUTPUT_FOLDER": str(tmp_path / f"h{h}")})
        relief = json.loads((tmp_path / f"h{h}" / "summary.json").read_text())["relief"]
        assert relief["source"] == f"RELIEF_M = {h:g} m" and result["RELIEF_FRAMES_OVER"] == relief["n_frames_over"]
        for f in relief["frames_over"]:
            assert f["displacement_px"] > 9.0
            assert f["displacement_cm"] == pytest.approx(100 * h * f["nadir_distance_m"] / f["height_m"], abs=0.02)
        over[h] = {f["frame_id"] for f in relief["frames_over"]}
    assert over[0.0] == set() and over[0.5] <= over[1.0] and over[1.0]
    result = run("writelabels", {**base, "OUTPUT_FOLDER": str(tmp_path / "none")})
    assert json.loads((tmp_path / "none" / "summary.json").read_text())["relief"] is None
    assert result["RELIEF_FRAMES_OVER"] == 0


def test_a_geotag_without_a_position_stops_the_tiles(imported, tmp_path):
    """It may lie in any tile: writing tiles is refused naming the row; without tiles it is left out, warned."""
    from qgis.core import QgsFeature, QgsVectorLayer
    from registry import Recorder

    folder, geotags, frames = imported
    copy = QgsVectorLayer(f"PointZ?crs={geotags.crs().authid()}", "geotags", "memory")
    copy.dataProvider().addAttributes(geotags.fields().toList())
    copy.updateFields()
    copy.dataProvider().addFeatures(list(geotags.getFeatures()) + [QgsFeature(copy.fields())])
    last = copy.featureCount()
    base = {"GEOTAGS": copy, "FRAMES": frames, "WRITE_RASTERS": False, "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None}
    with pytest.raises(QgsProcessingException, match=f"row {last}.*may lie in any negative tile"):
        run("writelabels", {**base, "WRITE_TILES": True, "OUTPUT_FOLDER": str(tmp_path / "t")})
    feedback = Recorder()
    run("writelabels", {**base, "OUTPUT_FOLDER": str(tmp_path / "n")}, feedback)
    assert any("1 geotag(s) without a position are left out" in w for w in feedback.warnings)
