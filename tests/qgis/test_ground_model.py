"""GROUND_MODEL: the method's plane (normal to the optical axis at the raw altimeter range) through the
DEM parameter group, on a simulated campaign imported by the importers."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from qgis.core import QgsApplication, QgsProcessingException, QgsRasterLayer
from registry import rows, run

from birdseye.birdseye_qgis.core.geometry.camera import load_calibration
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround, MethodPlaneGround
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import project_pairs
from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign

METHOD_PLANE = 1


@pytest.fixture(scope="module")
def imported(birdseye_provider, tmp_path_factory):
    """Exact metadata (noise off), so the frames' own poses are the truth the expectation is built from."""
    folder = tmp_path_factory.mktemp("campaign")
    simulate_campaign(CampaignConfig(seed=8, n_targets=10, field_width_m=9.0, field_length_m=7.0, image_width=480,
                                     image_height=300, n_missed=0, n_spurious=0, noise_off=True), folder)
    geotags = run("importgeotags", {"INPUT": str(folder / "geotags.csv"), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    frames = run("importflightlog", {"POSE_LOG": str(folder / "poses.csv"), "IMAGES": str(folder / "frames"),
                                     "CALIBRATION": str(folder / "calibration.yaml"),
                                     "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    return folder, geotags, frames


def labels(imported, out, **extra):
    _, geotags, frames = imported
    run("writelabels", {"GEOTAGS": geotags, "FRAMES": frames, "WRITE_RASTERS": False, "OUTPUT_FOLDER": str(out),
                        "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None, **extra})
    return {(Path(r["image"]).name, int(r["geotag_id"])): np.array([float(r["u"]), float(r["v"])])
            for r in rows(out / "labels.csv")}


def expected_labels(folder, keys, ground_model):
    """Each (image, geotag) projected through the frame's true pose onto ``ground_model``, in core alone."""
    camera = load_calibration(folder / "calibration.yaml")
    truth = {Path(r["image"]).name: r for r in rows(folder / "truth" / "frames_true.csv")}
    geotags = [line.split(",") for line in (folder / "geotags.csv").read_text().splitlines()]
    chosen = [truth[image] for image, _ in keys]
    num = lambda key: np.array([float(r[key]) for r in chosen])
    poses = FramePoses(np.arange(len(chosen)), num("lat_deg"), num("lon_deg"), num("height_m"),
                       np.stack([num(k) for k in ("qw", "qx", "qy", "qz")], axis=1), num("ground_h_m"), camera)
    local = LocalFrame.around(poses.lat, poses.lon, poses.height)
    geometry = FrameGeometry(poses, local)
    latlon = np.array([[float(v) for v in geotags[geotag_id - 1][:2]] for _, geotag_id in keys])
    points = local.from_geodetic(latlon[:, 0], latlon[:, 1], num("ground_h_m"))
    return project_pairs(geometry, np.arange(len(chosen)), points, ground_model(geometry)).uv


def test_writelabels_places_geotags_on_the_methods_plane(imported, tmp_path):
    folder = imported[0]
    level = labels(imported, tmp_path / "level")
    method = labels(imported, tmp_path / "method", GROUND_MODEL=METHOD_PLANE)
    common = sorted(set(level) & set(method))
    assert len(common) > 20
    got = np.array([method[k] for k in common])
    np.testing.assert_allclose(got, expected_labels(folder, common, MethodPlaneGround), atol=0.01)
    np.testing.assert_allclose(np.array([level[k] for k in common]), expected_labels(folder, common, LevelPlaneGround),
                               atol=0.01)
    # The simulated multirotor tilts a few degrees: the two grounds disagree off the image centre.
    shift = np.hypot(*(got - np.array([level[k] for k in common])).T)
    print(f"method plane vs level ground: median {np.median(shift):.2f} px, max {shift.max():.2f} px")
    assert shift.max() > 0.5


def test_a_dem_and_the_methods_plane_exclude_each_other(imported, tmp_path):
    from test_writelabels import write_geotiff

    from birdseye.birdseye_qgis.core.sim.terrain import synthetic_terrain

    _, geotags, frames = imported
    first = next(frames.getFeatures())
    dem = synthetic_terrain(first["lat"], first["lon"], kind="plane", base_height_m=first["ground_h_m"], size_m=60.0,
                            cell_m=0.5, vertical_datum="ellipsoidal")
    layer = QgsRasterLayer(write_geotiff(dem, tmp_path / "flat.tif"), "flat")
    with pytest.raises(QgsProcessingException, match="GROUND_MODEL.*DEM"):
        labels(imported, tmp_path / "both", GROUND_MODEL=METHOD_PLANE, DEM=layer, DEM_VERTICAL_DATUM=0)


def test_the_choice_is_offered_where_labels_and_detections_are_placed(birdseye_provider):
    registry = QgsApplication.processingRegistry()
    for alg_id in ("writelabels", "detect"):
        choice = registry.algorithmById(f"birdseye:{alg_id}").parameterDefinition("GROUND_MODEL")
        assert choice is not None and choice.defaultValue() == 0, alg_id
        assert "method" in choice.options()[METHOD_PLANE]
    for importer in ("importflightlog", "importdjiimages"):
        assert registry.algorithmById(f"birdseye:{importer}").parameterDefinition("GROUND_MODEL") is None


def test_detect_places_detections_on_the_methods_plane(imported):
    """Level ground: every detection at its frame's ground height. The method's plane, tilted with the
    camera: the same detections, at heights that follow the tilt, each along its viewing ray."""
    import processing

    _, _, frames = imported
    ground_h = {f["frame_id"]: f["ground_h_m"] for f in frames.getFeatures()}

    def detections(**extra):
        out = processing.run("birdseye:detect", {"FRAMES": frames, "THRESHOLD": 0.05, "OUTPUT": "TEMPORARY_OUTPUT",
                                                 **extra})["OUTPUT"]
        points = {}
        for f in out.getFeatures():
            p = f.geometry().constGet()
            points[(f["frame_id"], round(f["u"], 3), round(f["v"], 3))] = np.array([p.x(), p.y(), p.z()])
        return points

    level, method = detections(), detections(GROUND_MODEL=METHOD_PLANE)
    assert level and method.keys() == level.keys()
    assert all(p[2] == pytest.approx(ground_h[key[0]], abs=1e-3) for key, p in level.items())
    rise = np.array([method[key][2] - ground_h[key[0]] for key in level])
    moved = np.array([np.hypot(*(method[key][:2] - level[key][:2])) for key in level])
    print(f"method plane vs level ground: heights {rise.min():+.3f}…{rise.max():+.3f} m, moved up to "
          f"{moved.max():.3f} m")
    assert np.abs(rise).max() > 0.05
    # Each detection slides along its own viewing ray, which is within 45° of the vertical in these
    # frames: it moves less horizontally than vertically.
    assert np.all(moved <= np.abs(rise) + 1e-6)
