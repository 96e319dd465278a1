"""Real DJI frames on a DEM: the six Brighton Beach frames (Phantom 3; AbsoluteAltitude above mean sea level
over a take-off point, no altimeter) with a flat DEM exactly at their take-off ground.

Given above mean sea level (with or without N) or as ellipsoidal heights (with N, or with PROJ's EGM96 grid
standing in), the DEM is accepted, and every label is where the level plane at the take-off ground puts it
(within 0.5 px), none missing: the DEM is that plane. A DEM 3 m below the take-off ground (40 m above it) is
refused with the offset named. (Detect, Cluster and Evaluate on DJI frames with a DEM: test_dji_dem_heights.)
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsFeature,
    QgsGeometry,
    QgsPointXY,
    QgsProject,
    QgsRasterLayer,
    QgsVectorLayer,
)
from registry import rows, run
from test_writelabels import write_geotiff

from birdseye.birdseye_qgis.core.geometry.heights import geoid_undulation
from birdseye.birdseye_qgis.core.sim.terrain import synthetic_terrain
from birdseye.birdseye_qgis.qgis_io.layers import qgs_field

BRIGHTON = Path(__file__).resolve().parents[1] / "data" / "brighton_beach"


@pytest.fixture(scope="module")
def brighton(birdseye_provider, tmp_path_factory):
    base = tmp_path_factory.mktemp("real_dji_dem")
    frames = run("importdjiimages", {"IMAGES": str(BRIGHTON), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    records = list(frames.getFeatures())
    takeoff = float(np.median([f["ground_h_m"] for f in records]))
    lat, lon = float(np.mean([f["lat"] for f in records])), float(np.mean([f["lon"] for f in records]))
    # Geotags on a 4 m grid over every footprint (no heights: labels put them on the ground each frame sees).
    to_wgs84 = QgsCoordinateTransform(frames.crs(), QgsCoordinateReferenceSystem("EPSG:4326"), QgsProject.instance())
    union = QgsGeometry.unaryUnion([f.geometry() for f in records])
    box = union.boundingBox()
    geotags = QgsVectorLayer("Point?crs=EPSG:4326", "grid geotags", "memory")
    geotags.dataProvider().addAttributes([qgs_field("id", "int")])
    geotags.updateFields()
    features, k = [], 0
    for x in np.arange(box.xMinimum(), box.xMaximum(), 4.0):
        for y in np.arange(box.yMinimum(), box.yMaximum(), 4.0):
            if union.contains(QgsGeometry.fromPointXY(QgsPointXY(x, y))):
                k += 1
                feature = QgsFeature(geotags.fields())
                feature.setGeometry(QgsGeometry.fromPointXY(to_wgs84.transform(QgsPointXY(x, y))))
                feature.setAttributes([k])
                features.append(feature)
    geotags.dataProvider().addFeatures(features)

    def flat(name, height, datum):
        dem = synthetic_terrain(lat, lon, "plane", base_height_m=height, size_m=600.0, cell_m=2.0,
                                vertical_datum=datum)
        return QgsRasterLayer(write_geotiff(dem, base / f"{name}.tif"), name)

    n_site = float(geoid_undulation(lat, lon))
    return {"base": base, "frames": frames, "geotags": geotags, "takeoff": takeoff, "n_site": n_site, "flat": flat}


def labels(brighton, name, **params):
    out = brighton["base"] / name
    run("writelabels", {"GEOTAGS": brighton["geotags"], "FRAMES": brighton["frames"], "SIGMA_PX": 2.0,
                        "WRITE_RASTERS": False, "OUTPUT_FOLDER": str(out), "OUTPUT_FRAMES": None,
                        "OUTPUT_GEOTAGS": None, **params})
    return {(int(r["frame_id"]), int(r["geotag_id"])): np.array([float(r["u"]), float(r["v"])])
            for r in rows(out / "labels.csv")}


def test_a_flat_dem_at_the_take_off_ground_gives_the_level_plane_labels_whatever_its_reference(brighton):
    takeoff, n_site, flat = brighton["takeoff"], brighton["n_site"], brighton["flat"]
    assert {f["height_ref"] for f in brighton["frames"].getFeatures()} == {"EGM96"}
    level = labels(brighton, "level")
    assert len(level) > 100
    variants = {
        "msl": dict(DEM=flat("msl", takeoff, "msl"), DEM_VERTICAL_DATUM=1),
        "msl, N given": dict(DEM=flat("msl_n", takeoff, "msl"), DEM_VERTICAL_DATUM=1, GEOID_UNDULATION_M=-28.7),
        "ellipsoidal, N given": dict(DEM=flat("ell_n", takeoff - 28.7, "ellipsoidal"), DEM_VERTICAL_DATUM=0,
                                     GEOID_UNDULATION_M=-28.7),
        "ellipsoidal, EGM96 grid": dict(DEM=flat("ell_grid", takeoff + n_site, "ellipsoidal"), DEM_VERTICAL_DATUM=0),
    }
    for name, params in variants.items():
        on_dem = labels(brighton, name.replace(", ", "_").replace(" ", "_"), **params)
        assert on_dem.keys() == level.keys(), name
        worst = max(np.hypot(*(on_dem[k] - level[k])) for k in level)
        print(f"Brighton, flat DEM ({name}): {len(level)} labels, worst {worst:.4f} px from the level plane's")
        assert worst < 0.5, name


def test_a_dem_off_by_more_than_the_depth_allows_is_refused_naming_the_offset(brighton):
    from qgis.core import QgsProcessingException

    off = brighton["flat"]("off", brighton["takeoff"] + 3.0, "msl")
    with pytest.raises(QgsProcessingException, match=r"take-off height.*3\.00 m below the lowest.*tolerance"):
        labels(brighton, "off", DEM=off, DEM_VERTICAL_DATUM=1)


DSM = BRIGHTON / "dsm_odm_50cm.tif"


def test_opendronemaps_dsm_of_the_flight_is_accepted_and_gives_the_same_labels_both_ways(brighton):
    """OpenDroneMap's surface model of the same flight (in the frames' own heights above sea level, ODM aligned
    it to them; tests/data/brighton_beach/README.md): accepted — the take-off height, 158.51 m, is one the beach
    has (156.2 … 168.6 m) — and the labels on it are the same whether the DSM is given above sea level or as
    ellipsoidal heights (+ N, given or from PROJ's EGM96 grid). Geotags beyond the DSM get no label."""
    from osgeo import gdal

    base, n_site = brighton["base"], brighton["n_site"]
    source = gdal.Open(str(DSM))
    heights = source.GetRasterBand(1).ReadAsArray().astype(float)
    nodata = heights == -9999.0
    for name, n in (("dsm_n", -28.7), ("dsm_grid", n_site)):
        ds = gdal.GetDriverByName("GTiff").CreateCopy(str(base / f"{name}.tif"), source)
        ds.GetRasterBand(1).WriteArray(np.where(nodata, -9999.0, heights + n))
        ds = None
    log = []
    as_msl = labels(brighton, "dsm_msl", DEM=QgsRasterLayer(str(DSM), "ODM DSM"), DEM_VERTICAL_DATUM=1)
    given = labels(brighton, "dsm_ell_n", DEM=QgsRasterLayer(str(base / "dsm_n.tif"), "ODM DSM + N"),
                   DEM_VERTICAL_DATUM=0, GEOID_UNDULATION_M=-28.7)
    grid = labels(brighton, "dsm_ell_grid", DEM=QgsRasterLayer(str(base / "dsm_grid.tif"), "ODM DSM + N(EGM96)"),
                  DEM_VERTICAL_DATUM=0)
    level = labels(brighton, "level_for_dsm")
    assert 30 <= len(as_msl) < len(level)
    for other in (given, grid):
        assert other.keys() == as_msl.keys()
        # float32 heights: 0.03 mm at 160 m, a thousandth of a pixel here.
        assert max(np.hypot(*(other[k] - as_msl[k])) for k in as_msl) < 0.01
    moved = np.array([np.hypot(*(as_msl[k] - level[k])) for k in as_msl if k in level])
    log.append(f"ODM DSM: {len(as_msl)} labels (level plane {len(level)}); moved from the level plane's by median "
               f"{np.median(moved):.2f} px, max {moved.max():.2f} px (the beach's relief around the take-off height)")
    print("\n".join(log))
