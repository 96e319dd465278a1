"""The DEM parameter on importflightlog: footprints drape on the terrain, slope measured and flagged."""
from __future__ import annotations

import json

import pytest
from qgis.core import QgsProcessingException, QgsRasterLayer
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


def test_footprints_drape_on_a_sloped_dem_and_steep_frames_are_flagged(birdseye_provider, tmp_path):
    """A flight over a 20° slope (simulated, noise off; the altimeter measures the slope under each frame), imported
    with the slope's DEM: every footprint follows the slope and is flagged steep; the level import claims none."""
    from registry import simulated_terrain_campaign

    sloped = simulated_terrain_campaign(tmp_path / "slope", {
        "SEED": 5, "N_TARGETS": 3, "FIELD_WIDTH_M": 6.0, "FIELD_LENGTH_M": 5.0, "IMAGE_WIDTH": 320,
        "IMAGE_HEIGHT": 200, "NOISE_OFF": True, "TERRAIN": 1, "SLOPE_DEG": 20.0, "SLOPE_ASPECT_DEG": 90.0})
    level = {f["frame_id"]: f for f in import_frames(tmp_path / "slope").getFeatures()}
    draped = {f["frame_id"]: f for f in sloped["frames"].getFeatures()}
    assert level.keys() == draped.keys()
    for fid, f in draped.items():
        assert f["terrain_slope_deg"] == pytest.approx(20.0, abs=0.3)
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
    same place; on a DEM 0.25 m higher (within the tolerance at 10 m above ground) they move up with it. A DEM
    1 m off at 10 m is refused, naming the offset."""
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
    def dem_at(name, offset):
        dem = synthetic_terrain(site["lat"], site["lon"], kind="plane", slope_deg=0.0,
                                base_height_m=site["ground_height_m"] + offset, size_m=60.0, cell_m=0.5,
                                vertical_datum="ellipsoidal")
        return QgsRasterLayer(write_geotiff(dem, tmp_path / f"{name}.tif"), name)

    with pytest.raises(QgsProcessingException, match=r"\+1\.00 m off the ground measured.*±0\.30 m tolerance"):
        detections(DEM=dem_at("metre", 1.0), DEM_VERTICAL_DATUM=0)
    for name, offset in (("same", 0.0), ("raised", 0.25)):
        on_dem = detections(DEM=dem_at(name, offset), DEM_VERTICAL_DATUM=0)
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


def unit_dem(tmp_path, name, unit, factor=1.0, crs="EPSG:32633"):
    """A 40 × 30 GeoTIFF of 2 m cells with band unit type ``unit`` holding the heights (m) ``z`` / ``factor``,
    one cell no-data; returns the layer and ``z`` (NaN there)."""
    import numpy as np
    from osgeo import gdal, osr

    z = np.add.outer(np.arange(30) * 0.5, np.arange(40) * 0.25) + 100.0
    z[3, 4] = np.nan
    ds = gdal.GetDriverByName("GTiff").Create(str(tmp_path / f"{name}.tif"), 40, 30, 1, gdal.GDT_Float64)
    ds.SetGeoTransform((500000.0, 2.0, 0.0, 6000060.0, 0.0, -2.0))
    srs = osr.SpatialReference()
    srs.SetFromUserInput(crs)
    ds.SetProjection(srs.ExportToWkt())
    band = ds.GetRasterBand(1)
    band.WriteArray(np.where(np.isnan(z), -9999.0, z / factor))
    band.SetNoDataValue(-9999.0)
    band.SetUnitType(unit)
    ds = None
    return QgsRasterLayer(str(tmp_path / f"{name}.tif"), name), z


class Notes:
    def __init__(self):
        self.info = []

    def pushInfo(self, message):
        self.info.append(message)


@pytest.mark.parametrize(("unit", "crs", "factor", "said"), [
    ("ft", "EPSG:32633", 0.3048, "ft"),
    ("US survey foot", "EPSG:32633", 1200 / 3937, "US survey foot"),
    ("", "EPSG:32633+8228", 0.3048, "foot"),  # no band unit: the vertical CRS's (NAVD88 height in feet)
    ("m", "EPSG:32633", 1.0, None),
    ("", "EPSG:32633", 1.0, None)])
def test_dem_heights_in_feet_are_converted_to_metres(birdseye_provider, tmp_path, unit, crs, factor, said):
    import numpy as np

    from birdseye.birdseye_qgis.qgis_io.layers import read_dem

    layer, z = unit_dem(tmp_path, "feet", unit, factor, crs)
    notes = Notes()
    dem = read_dem(layer, "ellipsoidal", feedback=notes)
    # No-data is masked before the scaling: -9999 ft does not become a height of -3047.7 m.
    np.testing.assert_allclose(dem.heights, z, rtol=1e-12, equal_nan=True)
    converted = [m for m in notes.info if "converted to metres" in m]
    assert len(converted) == (said is not None)
    assert all(f"heights in {said}," in m for m in converted)


def test_a_dem_in_an_unknown_height_unit_or_a_feet_crs_is_refused(birdseye_provider, tmp_path):
    from birdseye.birdseye_qgis.core.errors import InputError
    from birdseye.birdseye_qgis.qgis_io.layers import read_dem

    layer, _ = unit_dem(tmp_path, "fathoms", "fathom")
    with pytest.raises(InputError, match=r"fathoms.*'fathom', a unit BirdsEye does not know; convert them to metres"):
        read_dem(layer, "ellipsoidal")
    # Cells in US feet (California zone 3): positions and cell sizes would be read as metres.
    layer, _ = unit_dem(tmp_path, "stateplane", "m", crs="EPSG:2227")
    with pytest.raises(InputError, match=r"stateplane.*EPSG:2227, whose cells are not metres; warp it"):
        read_dem(layer, "ellipsoidal")


def test_a_windowed_read_gives_the_full_read_heights_inside_the_window(birdseye_provider, tmp_path):
    import numpy as np

    from birdseye.birdseye_qgis.qgis_io.layers import read_dem

    layer, _ = unit_dem(tmp_path, "window", "m")
    full = read_dem(layer, "ellipsoidal")
    extent = (500020.3, 6000010.0, 500041.0, 6000030.7)
    window = read_dem(layer, "ellipsoidal", extent=extent)
    assert window.heights.size < full.heights.size / 3
    # The window covers the extent with cells to spare, and samples the same heights inside it.
    x0, dx, y0, dy = window.geotransform
    rows, cols = window.heights.shape
    assert x0 <= extent[0] - dx and x0 + cols * dx >= extent[2] + dx
    assert y0 >= extent[3] - dy and y0 + rows * dy <= extent[1] + dy
    x, y = np.meshgrid(np.linspace(extent[0], extent[2], 23), np.linspace(extent[1], extent[3], 17))
    np.testing.assert_array_equal(window.sample(x, y), full.sample(x, y))
    assert np.all(np.isfinite(window.sample(x, y)))
    # An extent off the raster reads it whole, so the DEM's coverage check still speaks.
    assert read_dem(layer, "ellipsoidal", extent=(0.0, 0.0, 10.0, 10.0)).heights.shape == full.heights.shape
