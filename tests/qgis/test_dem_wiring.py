"""The DEM parameter on importflightlog: footprints drape on the terrain, slope measured and flagged."""
from __future__ import annotations

import json

import pytest
from qgis.core import QgsRasterLayer
from test_writelabels import write_geotiff

from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign
from birdseye.birdseye_qgis.core.sim.terrain import synthetic_terrain


@pytest.fixture(scope="module")
def campaign(birdseye_provider, tmp_path_factory):
    folder = tmp_path_factory.mktemp("campaign")
    simulate_campaign(CampaignConfig(seed=5, n_targets=3, field_width_m=6.0, field_length_m=5.0, image_width=320,
                                     image_height=200, noise_off=True), folder)
    return folder


def import_frames(folder, **extra):
    import processing

    return processing.run("birdseye:importflightlog", {
        "POSE_LOG": str(folder / "poses.csv"), "IMAGES": str(folder / "frames"),
        "CALIBRATION": str(folder / "calibration.yaml"), "OUTPUT": "TEMPORARY_OUTPUT", **extra})["OUTPUT"]


def test_footprints_drape_on_a_sloped_dem_and_steep_frames_are_flagged(campaign, tmp_path):
    site = json.loads((campaign / "truth" / "campaign.json").read_text())["site"]
    dem = synthetic_terrain(site["lat"], site["lon"], kind="plane", slope_deg=20.0, aspect_deg=90.0,
                            base_height_m=site["ground_height_m"], size_m=60.0, cell_m=0.5,
                            vertical_datum="ellipsoidal")
    layer = QgsRasterLayer(write_geotiff(dem, tmp_path / "slope.tif"), "slope")
    level = {f["frame_id"]: f for f in import_frames(campaign).getFeatures()}
    draped = {f["frame_id"]: f for f in import_frames(campaign, DEM=layer, DEM_VERTICAL_DATUM=0).getFeatures()}
    assert level.keys() == draped.keys()
    for fid, f in draped.items():
        assert f["terrain_slope_deg"] == pytest.approx(20.0, abs=0.2)
        assert "steep_terrain" in f["flags"] and "steep_terrain" not in (level[fid]["flags"] or "")
        zs = [v.z() for v in f.geometry().vertices()]
        assert max(zs) - min(zs) > 0.5  # the ring follows the slope; the level ring is flat
        zl = [v.z() for v in level[fid].geometry().vertices()]
        assert max(zl) - min(zl) < 0.05
    # Without a DEM no slope is claimed.
    assert all(v is None or (hasattr(v, "isNull") and v.isNull())
               for v in (f["terrain_slope_deg"] for f in level.values()))


def test_detect_back_projects_onto_the_dem(campaign, tmp_path):
    """On flat terrain a DEM at the true ground and the altimeter's level plane put detections at the
    same place; on a DEM 1 m higher they move towards the nadir by the similar-triangle amount."""
    import processing

    site = json.loads((campaign / "truth" / "campaign.json").read_text())["site"]
    frames = import_frames(campaign)

    def detections(**extra):
        out = processing.run("birdseye:detect", {"FRAMES": frames, "THRESHOLD": 0.05, "OUTPUT": "TEMPORARY_OUTPUT",
                                                 **extra})["OUTPUT"]
        points = {}
        for f in out.getFeatures():
            p = f.geometry().constGet()
            points[(f["frame_id"], round(f["u"], 3), round(f["v"], 3))] = (p.x(), p.y(), p.z())
        return points

    level = detections()
    assert level, "the demo model finds the simulated burrows"
    for name, offset in (("same", 0.0), ("raised", 1.0)):
        dem = synthetic_terrain(site["lat"], site["lon"], kind="plane", slope_deg=0.0,
                                base_height_m=site["ground_height_m"] + offset, size_m=60.0, cell_m=0.5,
                                vertical_datum="ellipsoidal")
        layer = QgsRasterLayer(write_geotiff(dem, tmp_path / f"{name}.tif"), name)
        on_dem = detections(DEM=layer, DEM_VERTICAL_DATUM=0)
        assert on_dem.keys() == level.keys()
        for key, p in on_dem.items():
            q = level[key]
            assert p[2] - q[2] == pytest.approx(offset, abs=0.01)
            if offset == 0.0:
                assert p[0] == pytest.approx(q[0], abs=0.005) and p[1] == pytest.approx(q[1], abs=0.005)


def test_dji_footprints_on_a_dem_at_the_take_off_height_match_the_level_ones(birdseye_provider, tmp_path):
    """Real DJI frames (Brighton Beach): a flat MSL DEM at the take-off height gives the level footprints;
    one 13 m lower (the field below the knoll the drone took off from) gives footprints larger by
    (40 + 13) / 40; a DEM 40 m off every terrain around is refused as another vertical reference."""
    from pathlib import Path

    import numpy as np
    import processing
    from qgis.core import QgsProcessingException

    brighton = Path(__file__).resolve().parents[1] / "data" / "brighton_beach"
    run = lambda **extra: {f["frame_id"]: f for f in processing.run(
        "birdseye:importdjiimages", {"IMAGES": str(brighton), "OUTPUT": "TEMPORARY_OUTPUT", **extra})["OUTPUT"]
        .getFeatures()}
    level = run()
    first = next(iter(level.values()))
    takeoff = first["ground_h_m"]

    def dem_layer(field_height, knoll_height, name):
        dem = synthetic_terrain(first["lat"], first["lon"], kind="plane", base_height_m=field_height,
                                size_m=400.0, cell_m=2.0, vertical_datum="msl")
        x, y = dem.cell_centres()  # the take-off knoll, 150 m east of the first frame
        dem.heights[np.ix_(np.abs(y - y.mean()) < 5.0, np.abs(x - x.mean() - 150.0) < 5.0)] = knoll_height
        return QgsRasterLayer(write_geotiff(dem, tmp_path / f"{name}.tif"), name)

    with pytest.raises(QgsProcessingException, match=r"take-off height \(\d+\.\d+ m, the median over 6 frames"):
        run(DEM=dem_layer(takeoff + 40.0, takeoff + 40.0, "off"), DEM_VERTICAL_DATUM=1)
    for drop in (0.0, 13.0):
        layer = dem_layer(takeoff - drop, takeoff, f"dem{drop:g}")
        draped = run(DEM=layer, DEM_VERTICAL_DATUM=1)
        assert draped.keys() == level.keys()
        for fid, f in draped.items():
            depth = level[fid]["depth_m"]
            ratio = (f.geometry().area() / level[fid].geometry().area()) ** 0.5
            assert ratio == pytest.approx((depth + drop) / depth, rel=0.01)
