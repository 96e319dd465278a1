"""Derive tests/data/brighton_beach/dsm_odm_50cm.tif from OpenDroneMap's point cloud of the Brighton Beach flight.

The point cloud (``../shared/data/brighton_beach/model.laz``: 940,393 points, WGS 84 / UTM zone 15N, heights in
the reference of the frames' GPS altitudes — DJI's ``AbsoluteAltitude``) is a surface model of the same flight
made by a tool that is not ours. This script rasterises it once into a small GeoTIFF: 0.5 m cells over the
cloud's extent, each the median height of the points in it (a DSM; cells without points are no-data, -9999),
float32, DEFLATE. Nothing at run time reads the laz file, so laspy stays out of the project's requirements.

Run (reproducible: the same input gives the same file, byte for byte, with these versions):

    python3 -m venv /tmp/lasvenv && /tmp/lasvenv/bin/pip install "laspy[lazrs]==2.7.0" "lazrs==0.8.2" "numpy==2.4.6"
    /tmp/lasvenv/bin/python scripts/derive_brighton_dsm.py ../shared/data/brighton_beach/model.laz \\
        tests/data/brighton_beach/dsm_odm_50cm.tif

GDAL writes the GeoTIFF (Debian's python3-gdal, run with PYTHONPATH=/usr/lib/python3/dist-packages, or any GDAL).
"""
from __future__ import annotations

import argparse

import numpy as np

CELL_M = 0.5
NODATA = -9999.0
EPSG = 32615  # WGS 84 / UTM zone 15N, as the point cloud's GeoKeys and GeoAsciiParams state


def rasterise(x, y, z, cell_m: float = CELL_M):
    """Median height per cell of a north-up grid snapped to whole cells; (heights, (x0, dx, y0, dy))."""
    x0, y1 = np.floor(x.min() / cell_m) * cell_m, np.ceil(y.max() / cell_m) * cell_m
    cols = int(np.ceil((x.max() - x0) / cell_m)) + 1
    rows = int(np.ceil((y1 - y.min()) / cell_m)) + 1
    col = np.floor((x - x0) / cell_m).astype(np.int64)
    row = np.floor((y1 - y) / cell_m).astype(np.int64)
    cell = row * cols + col
    order = np.lexsort((z, cell))
    cell, z = cell[order], z[order]
    starts = np.flatnonzero(np.r_[True, cell[1:] != cell[:-1]])
    ends = np.r_[starts[1:], len(cell)]
    heights = np.full(rows * cols, NODATA)
    # Median of each run of one cell's sorted heights.
    heights[cell[starts]] = 0.5 * (z[starts + (ends - starts - 1) // 2] + z[starts + (ends - starts) // 2])
    return heights.reshape(rows, cols).astype(np.float32), (x0, cell_m, y1, -cell_m)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("laz")
    parser.add_argument("tif")
    args = parser.parse_args()
    import laspy
    from osgeo import gdal, osr

    cloud = laspy.read(args.laz)
    heights, (x0, dx, y0, dy) = rasterise(np.asarray(cloud.x), np.asarray(cloud.y), np.asarray(cloud.z))
    rows, cols = heights.shape
    ds = gdal.GetDriverByName("GTiff").Create(args.tif, cols, rows, 1, gdal.GDT_Float32,
                                               ["COMPRESS=DEFLATE", "PREDICTOR=3"])
    ds.SetGeoTransform((x0, dx, 0.0, y0, 0.0, dy))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(EPSG)
    ds.SetProjection(srs.ExportToWkt())
    band = ds.GetRasterBand(1)
    band.SetNoDataValue(NODATA)
    band.SetUnitType("m")
    band.WriteArray(heights)
    ds = None
    valid = heights[heights != NODATA]
    print(f"{args.tif}: {cols} × {rows} cells of {dx} m, {valid.size} with points, heights "
          f"{valid.min():.2f} … {valid.max():.2f} m")


if __name__ == "__main__":
    main()
