"""DJI frames (heights above mean sea level, over a take-off point) on a DEM, through the product path.

A DJI campaign is simulated over a plane tilted by 20°, with the geoid undulation N = −30 m (the drone writes
``AbsoluteAltitude = h − N``), exact metadata. ``importdjiimages`` reads the frames as EGM96 heights over
their take-off point; the simulator's DEM (``truth/dem.tif``) is ellipsoidal.

* Write labels with that DEM, N given: every label within 1 px of where the simulator's true pose puts the
  target's true position (no ground model: the target's own height), none missing among the targets the true
  geometry sees; the same DEM expressed above sea level gives the same labels.
* Detect with that DEM: every detection's ground point is where its pixel's ray, cast from the true pose onto
  the true (ellipsoidal) terrain, meets it, within 2 cm.
* Without N, the EGM96 grid stands in for it: at this site it differs from −30 m by metres, so the DEM check
  (or the labels) says so rather than placing labels silently off.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from qgis.core import QgsProcessingException, QgsRasterLayer
from registry import Recorder, rows, run
from test_writelabels import write_geotiff

from birdseye.birdseye_qgis.core.geometry.dem import DemGround, DemRaster
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.heights import geoid_undulation
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import pixel_to_ground
from birdseye.birdseye_qgis.core.sim.dji_images import dji_camera_model

N = -30.0
DJI_SLOPE = {"PLATFORM": 1, "SEED": 11, "N_TARGETS": 12, "FIELD_WIDTH_M": 8.0, "FIELD_LENGTH_M": 6.0,
             "ALTITUDE_M": 10.0, "IMAGE_WIDTH": 960, "IMAGE_HEIGHT": 720, "RTK_SIGMA_M": 0.0, "N_MISSED": 0,
             "N_SPURIOUS": 0, "NOISE_OFF": True, "TERRAIN": 1, "SLOPE_DEG": 20.0, "SLOPE_ASPECT_DEG": 250.0,
             "GEOID_UNDULATION_M": N}


def read_geotiff(path, datum) -> DemRaster:
    from osgeo import gdal

    ds = gdal.Open(str(path))
    x0, dx, _, y0, _, dy = ds.GetGeoTransform()
    band = ds.GetRasterBand(1)
    return DemRaster(band.ReadAsArray().astype(float), (x0, dx, y0, dy), ds.GetProjection(), datum,
                     nodata=band.GetNoDataValue(), source=str(path))

@pytest.fixture(scope="module")
def flight(birdseye_provider, tmp_path_factory):
    base = tmp_path_factory.mktemp("dji_dem")
    folder = base / "campaign"
    sim = run("simulatecampaign", {**DJI_SLOPE, "OUTPUT_FOLDER": str(folder)})
    frames = run("importdjiimages", {"IMAGES": sim["FRAMES_FOLDER"], "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    geotags = run("importgeotags", {"INPUT": sim["GEOTAGS"], "FIX_FILTER": 1, "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    dem = QgsRasterLayer(sim["DEM"], "terrain (ellipsoidal)")
    assert dem.isValid()
    truth_dem = read_geotiff(sim["DEM"], "ellipsoidal")
    # The same terrain above mean sea level, as the drone measures heights.
    msl_path = write_geotiff(DemRaster(truth_dem.heights - N, truth_dem.geotransform, truth_dem.crs, "msl"),
                             base / "msl.tif")
    return {"base": base, "folder": folder, "frames": frames, "geotags": geotags, "dem": dem,
            "dem_msl": QgsRasterLayer(msl_path, "terrain (MSL)"), "truth_dem": truth_dem}


def true_geometry(folder, images):
    """The simulator's true poses of the frames ``images`` (ellipsoidal heights) and its camera."""
    truth = {Path(r["image"]).name: r for r in rows(folder / "truth" / "frames_true.csv")}
    t = [truth[Path(i).name] for i in images]
    num = lambda key: np.array([float(r[key]) for r in t])
    width, height = DJI_SLOPE["IMAGE_WIDTH"], DJI_SLOPE["IMAGE_HEIGHT"]
    poses = FramePoses(np.arange(len(t)), num("lat_deg"), num("lon_deg"), num("height_m"),
                       np.stack([num(k) for k in ("qw", "qx", "qy", "qz")], axis=1), num("ground_h_m"),
                       dji_camera_model(width, height))
    return FrameGeometry(poses, LocalFrame.around(poses.lat, poses.lon, poses.height))


def labels(flight, name, **params):
    run("writelabels", {"GEOTAGS": flight["geotags"], "FRAMES": flight["frames"], "SIGMA_PX": 5.0,
                        "WRITE_RASTERS": False, "OUTPUT_FOLDER": str(flight["base"] / name), "OUTPUT_FRAMES": None,
                        "OUTPUT_GEOTAGS": None, **params})
    return {(int(r["frame_id"]), int(r["geotag_id"])): r for r in rows(flight["base"] / name / "labels.csv")}


def test_the_imported_frames_say_what_their_heights_are(flight):
    records = list(flight["frames"].getFeatures())
    assert {f["height_ref"] for f in records} == {"EGM96"} and {f["ground_src"] for f in records} == {"takeoff"}
    site = json.loads((flight["folder"] / "truth" / "campaign.json").read_text())["site"]
    # AbsoluteAltitude − RelativeAltitude: the take-off point's ellipsoidal height − N.
    np.testing.assert_allclose([f["ground_h_m"] for f in records], site["ground_height_m"] - N, atol=2e-3)


def test_labels_on_the_dem_sit_where_the_true_pose_puts_the_true_target(flight):
    on_dem = labels(flight, "ellipsoidal_dem", DEM=flight["dem"], DEM_VERTICAL_DATUM=0, GEOID_UNDULATION_M=N)
    as_msl = labels(flight, "msl_dem", DEM=flight["dem_msl"], DEM_VERTICAL_DATUM=1)
    # The same labels (both GeoTIFFs hold float32 heights, rounded to 0.03 mm at 430 m).
    assert on_dem.keys() == as_msl.keys()
    for key, r in on_dem.items():
        assert (float(r["u"]), float(r["v"])) == pytest.approx((float(as_msl[key]["u"]), float(as_msl[key]["v"])),
                                                               abs=0.01)
    # The truth: each target's true position through each frame's true pose, nothing else.
    folder = flight["folder"]
    frames = {f["frame_id"]: f for f in flight["frames"].getFeatures()}
    targets = {int(r["geotag_row"]): r for r in rows(folder / "truth" / "targets.csv") if r["geotag_row"]}
    keys = [(f, g) for f in frames for g in targets]
    geometry = true_geometry(folder, [frames[f]["image"] for f, _ in keys])
    xyz = geometry.local.from_geodetic(*(np.array([float(targets[g][c]) for _, g in keys])
                                         for c in ("lat", "lon", "h_ground")))
    cam = geometry.to_camera(np.arange(len(keys)), xyz)
    uv = geometry.camera.project(cam)
    edge = 10.0  # writelabels' default edge buffer (px), and a margin for the rounding at the border
    seen = (cam[:, 2] > 0) & geometry.camera.in_frame(uv, edge + 1.0)
    expected = {k: uv[i] for i, k in enumerate(keys) if seen[i]}
    assert len(expected) >= 20 and set(expected) <= set(on_dem)
    errors = np.array([np.hypot(float(on_dem[k]["u"]) - p[0], float(on_dem[k]["v"]) - p[1])
                       for k, p in expected.items()])
    print(f"DJI labels on the DEM vs the truth ({len(errors)}): median {np.median(errors):.3f}, "
          f"max {errors.max():.3f} px")
    assert errors.max() < 1.0


def test_without_n_the_egm96_grid_stands_in_and_a_wrong_n_is_not_used_silently(flight):
    site = json.loads((flight["folder"] / "truth" / "campaign.json").read_text())["site"]
    n_egm96 = float(geoid_undulation(site["lat"], site["lon"]))
    assert abs(n_egm96 - N) > 5.0  # this site's EGM96 is far from the simulator's N, so a mix-up shows
    with pytest.raises(QgsProcessingException, match=r"take-off height.*EGM96 grid|EGM96.*take-off height"):
        labels(flight, "no_n", DEM=flight["dem"], DEM_VERTICAL_DATUM=0)


def test_detections_on_the_dem_lie_where_their_rays_meet_the_true_terrain(flight):
    log = Recorder()
    detected = run("detect", {"FRAMES": flight["frames"], "THRESHOLD": 0.05, "DEM": flight["dem"],
                              "DEM_VERTICAL_DATUM": 0, "GEOID_UNDULATION_M": N, "OUTPUT": "TEMPORARY_OUTPUT"}, log)
    assert any("DEM against the frames" in line and "N = -30.00 m as given" in line for line in log.infos)
    layer = detected["OUTPUT"]
    dets = list(layer.getFeatures())
    assert len(dets) >= 10
    frames = {f["frame_id"]: f for f in flight["frames"].getFeatures()}
    geometry = true_geometry(flight["folder"], [frames[d["frame_id"]]["image"] for d in dets])
    ground = DemGround.from_dem(geometry, flight["truth_dem"], vertical_offset_m=0.0)  # ellipsoidal truth
    uv = np.array([[d["u"], d["v"]] for d in dets])
    true_xyz, valid = pixel_to_ground(geometry, ground, np.arange(len(dets)), uv)
    assert valid.all()
    from qgis.core import QgsCoordinateReferenceSystem, QgsCoordinateTransform, QgsProject

    to_wgs84 = QgsCoordinateTransform(layer.crs(), QgsCoordinateReferenceSystem("EPSG:4326"), QgsProject.instance())
    points = [to_wgs84.transform(d.geometry().constGet().x(), d.geometry().constGet().y()) for d in dets]
    heights = np.array([d.geometry().constGet().z() for d in dets]) + N  # the frames' EGM96 heights → ellipsoidal
    found = geometry.local.from_geodetic(np.array([p.y() for p in points]), np.array([p.x() for p in points]), heights)
    error = np.linalg.norm(found - true_xyz, axis=1)
    print(f"detections on the DEM vs their rays on the true terrain ({len(error)}): max {error.max() * 100:.2f} cm")
    assert error.max() < 0.02


def test_cluster_evaluate_and_the_review_stand_on_the_dem_with_the_frames_reference(flight):
    """The scoring steps take the recorded DEM again and convert it into the DJI frames' heights as Detect did:
    every target the true geometry sees is in view, and detections form hit clusters. (Recall is not compared
    with the level plane's: on the DEM one target's detections fall within millimetres, into one 3 cm
    de-duplication cell, which DBSCAN's core test then counts as one point — the clustering issue of "the
    science" — while the level plane's scatter over decimetres passes it.)"""
    from birdseye.birdseye_qgis.qgis_io.review_store import read_review_inputs

    def scored(name, **dem):
        detected = run("detect", {"FRAMES": flight["frames"], "THRESHOLD": 0.05, "OUTPUT": "TEMPORARY_OUTPUT", **dem})
        clusters = run("clusterdetections", {"DETECTIONS": detected["OUTPUT"], "GEOTAGS": flight["geotags"],
                                             "FRAMES": flight["frames"], "OUTPUT": "TEMPORARY_OUTPUT", **dem})
        out = flight["base"] / f"{name}.json"
        run("evaluatedetections", {"DETECTIONS": [detected["OUTPUT"]], "GEOTAGS": flight["geotags"],
                                   "FRAMES": [flight["frames"]], "OUTPUT_JSON": str(out), "OUTPUT_REPORT": None,
                                   **dem})
        return detected["OUTPUT"], clusters, json.loads(out.read_text())

    layer, clusters, on_dem = scored("dem", DEM=flight["dem"], DEM_VERTICAL_DATUM=0, GEOID_UNDULATION_M=N)
    _, _, level = scored("level")
    print(f"DJI over a 20° slope: on the DEM {on_dem['n_in_view']} in view, recall {on_dem['recall_pre']:.3f}, "
          f"{clusters['HIT_COUNT']} hit clusters; level plane {level['n_in_view']} in view, recall "
          f"{level['recall_pre']:.3f}")
    assert on_dem["n_in_view"] == DJI_SLOPE["N_TARGETS"]  # all of the field is flown over
    assert on_dem["n_recovered"] >= 1 and clusters["HIT_COUNT"] >= 1 and level["n_in_view"] == on_dem["n_in_view"]
    # The review reopens the recorded DEM (and the N recorded with the detections).
    inputs = read_review_inputs([layer], flight["frames"], flight["geotags"])
    assert inputs.ground_fallback == ""


def test_the_sweep_and_screening_place_their_detections_on_the_dem_in_the_frames_reference(flight, tmp_path):
    """The sweep and checkpoint screening detect again: with the DEM (ellipsoidal, N given) they convert it into
    the DJI frames' heights as Detect does, and count every flown-over target in view."""
    from birdseye.processing.algorithms.detect import DEFAULT_MODEL

    dem = {"DEM": flight["dem"], "DEM_VERTICAL_DATUM": 0, "GEOID_UNDULATION_M": N}
    swept = run("sweepoperatingpoints", {"CHECKPOINTS": [str(DEFAULT_MODEL)], "FRAMES": [flight["frames"]],
                                         "GEOTAGS": flight["geotags"], "THRESHOLDS": "0.05", "EPS_M": "0.2",
                                         "MIN_SAMPLES": "1", "EPS_PRED_M": "0.2",
                                         "OUTPUT_TABLE": str(tmp_path / "s.csv"), "OUTPUT_JSON": None,
                                         "OUTPUT_PLOT": None, **dem})
    (row,) = rows(swept["OUTPUT_TABLE"])
    assert int(row["n_in_view"]) == DJI_SLOPE["N_TARGETS"] and int(row["n_recovered"]) >= 1
    out = tmp_path / "screen.json"
    run("screencheckpoints", {"CHECKPOINTS": [str(DEFAULT_MODEL)], "FRAMES": [flight["frames"]],
                              "GEOTAGS": flight["geotags"], "BLOCK_FRAMES": 0, "MIN_SAMPLES": 1,
                              "OUTPUT_TABLE": str(tmp_path / "screen.csv"), "OUTPUT_JSON": str(out),
                              "OUTPUT_PLOT": None, **dem})
    (screened,) = json.loads(out.read_text(encoding="utf-8"))["checkpoints"]
    assert screened["n_in_view"] == DJI_SLOPE["N_TARGETS"]
