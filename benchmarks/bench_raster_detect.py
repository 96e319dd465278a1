"""Benchmark: birdseye:detectraster's core on a 20,000 × 20,000 px orthomosaic, read through QGIS's raster provider.

What it states:

* **Peak memory** of the whole process (QGIS, ONNX Runtime and the run; /proc's ``VmHWM``), in a child process
  that does nothing else. Goal: below 1.5 GB — the raster itself is 1.2 GB of pixels, so it must never be in memory.
* **Throughput** as a ratio to bare ONNX Runtime on the same tiles: the time inside ``InferenceSession.run``
  during the run is the baseline (the model alone on exactly the tiles the run feeds it); everything else —
  reading windows through the provider, resampling, normalising, tiling, stitching, peaks, seams — is the
  plugin's overhead. Goal: overhead under 15 % of the baseline.

The raster (RGB, 8-bit, tiled and DEFLATE-compressed GeoTIFF at 1 cm/px, the bundled model's resolution; a
textured field with a dark hump every 2 m) is written once with GDAL into build/bench_raster_detect.

    .venv/bin/python benchmarks/bench_raster_detect.py [--size 20000] [--model file.onnx]
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import _path
import numpy as np

MODEL = _path.REPO_ROOT / "models" / "birdseye_demo_heatmap.onnx"
FOLDER = _path.REPO_ROOT / "build" / "bench_raster_detect"
STRIP = 512
HUMP_SPACING_PX = 200


def write_raster(path: Path, size: int) -> None:
    """A ``size``² px field at 1 cm/px (EPSG:32756), written strip by strip: soil texture and a dark 3 cm
    hump every 2 m."""
    from osgeo import gdal, osr

    ds = gdal.GetDriverByName("GTiff").Create(str(path), size, size, 3, gdal.GDT_Byte,
                                              ["TILED=YES", "COMPRESS=DEFLATE", "BIGTIFF=IF_SAFER"])
    ds.SetGeoTransform((500000.0, 0.01, 0.0, 6000000.0, 0.0, -0.01))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32756)
    ds.SetProjection(srs.ExportToWkt())
    rng = np.random.default_rng(1)
    texture = (150 + 25 * rng.standard_normal((STRIP, 1024))).clip(0, 255)
    yy, xx = np.mgrid[0:HUMP_SPACING_PX, 0:HUMP_SPACING_PX] - HUMP_SPACING_PX / 2
    hump = 1.0 - 0.7 * np.exp(-(xx ** 2 + yy ** 2) / (2 * 3.0 ** 2))
    for y0 in range(0, size, STRIP):
        rows = min(STRIP, size - y0)
        tex = np.tile(texture, (1, size // 1024 + 1))[:rows, :size]
        dark = np.tile(hump, (STRIP // HUMP_SPACING_PX + 2, size // HUMP_SPACING_PX + 1))
        dark = dark[y0 % HUMP_SPACING_PX:y0 % HUMP_SPACING_PX + rows, :size]
        for b, gain in enumerate((1.0, 0.85, 0.7)):
            ds.GetRasterBand(b + 1).WriteArray(np.rint(tex * dark * gain).astype(np.uint8), 0, y0)
    ds.FlushCache()
    ds = None


def peak_kb() -> int:
    """The process's peak resident memory (kB): /proc's VmHWM, which exec resets — ``ru_maxrss`` keeps the peak
    of the process that forked this one (the parent that wrote the raster)."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1])
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


def child(path: str, model_path: str) -> None:
    """Run detectraster's core on the raster through QGIS's provider; print the figures as JSON."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from qgis.core import QgsApplication, QgsRasterLayer

    app = QgsApplication([], False)
    app.initQgis()
    assert app
    from birdseye.birdseye_qgis.core.detect.detector import HeatmapModel
    from birdseye.birdseye_qgis.core.detect.raster_detect import detect_raster
    from birdseye.birdseye_qgis.qgis_io.raster_reader import ProviderWindows, bounded_block_cache, raster_grid

    layer = QgsRasterLayer(path, "bench")
    grid = raster_grid(layer)
    model = HeatmapModel(model_path)
    inside = [0.0, 0]
    run = model.run

    def timed_run(tiles):
        t = time.perf_counter()
        out = run(tiles)
        inside[0] += time.perf_counter() - t
        inside[1] += len(tiles)
        return out

    model.run = timed_run
    before_kb = peak_kb()
    t0 = time.perf_counter()
    with bounded_block_cache():  # as detectraster runs it
        found = detect_raster(model, grid, ProviderWindows(layer, grid, [1, 2, 3]))
    total = time.perf_counter() - t0
    print(json.dumps({"total_s": total, "inside_s": inside[0], "tiles": inside[1], "windows": found.windows,
                      "detections": len(found), "merged": found.merged, "before_run_kb": before_kb,
                      "peak_kb": peak_kb(),
                      "width": grid.width, "height": grid.height}), flush=True)
    os._exit(0)  # QGIS's exit can crash a standalone script; the figures are out


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--size", type=int, default=20000, help="raster side, px (default 20000)")
    parser.add_argument("--model", default=str(MODEL))
    parser.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child(*args.child)
        return
    FOLDER.mkdir(parents=True, exist_ok=True)
    raster = FOLDER / f"field_{args.size}.tif"
    if not raster.is_file():
        print(f"writing a {args.size} × {args.size} px GeoTIFF once ({raster}) …", flush=True)
        t0 = time.perf_counter()
        write_raster(raster.with_suffix(".part.tif"), args.size)
        raster.with_suffix(".part.tif").rename(raster)
        print(f"  written in {time.perf_counter() - t0:.0f} s ({raster.stat().st_size / 1e6:.0f} MB on disk)")
    done = subprocess.run([sys.executable, __file__, "--child", str(raster), args.model], capture_output=True,
                          text=True, check=True)
    r = json.loads(done.stdout.strip().splitlines()[-1])
    overhead = r["total_s"] - r["inside_s"]
    mpx = r["width"] * r["height"] / 1e6
    expected = (args.size // HUMP_SPACING_PX) ** 2
    print(f"raster: {r['width']} × {r['height']} px at 1 cm/px ({mpx:.0f} Mpx, {3 * mpx / 1e3:.2f} GB of pixels), "
          f"{r['windows']} windows, {r['tiles']} tiles; {r['detections']} detections of {expected} humps "
          f"({r['merged']} on a window seam kept once)")
    print(f"peak memory of the process: {r['peak_kb'] / 1024:.0f} MB (QGIS and the model loaded: "
          f"{r['before_run_kb'] / 1024:.0f} MB)  (goal < 1536 MB)")
    print(f"baseline  InferenceSession.run on the run's tiles: {r['inside_s']:7.1f} s")
    print(f"detectraster total:                                {r['total_s']:7.1f} s  ({mpx / r['total_s']:.2f} Mpx/s)")
    print(f"ratio overhead / baseline: {overhead / r['inside_s']:.1%}  (goal < 15 %; reading through the provider, "
          "resampling, normalising, tiling, stitching, peaks)")


if __name__ == "__main__":
    main()
