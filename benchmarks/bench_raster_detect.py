"""Benchmark: birdseye:detectraster's core on a 20,000 × 20,000 px orthomosaic, read through QGIS's raster provider.

What it states:

* **Peak memory** of the whole process (QGIS, ONNX Runtime and the run; /proc's ``VmHWM``), in a child process
  that does nothing else. Goal: below 1.5 GB — the raster itself is 1.2 GB of pixels, so it must never be in memory.
* **Throughput** as a ratio to bare ONNX Runtime on the same tiles: the time inside ``InferenceSession.run``
  during the run is the baseline (the model alone on exactly the tiles the run feeds it); everything else —
  reading windows through the provider, resampling, normalising, tiling, stitching, peaks, seams — is the
  plugin's overhead. Goal: overhead under 15 % of the baseline.

* **Side by side with Deepness** (PUTvision's QGIS plugin, which runs ONNX models on raster layers), when a
  checkout of it is given (``--deepness`` or ``DEEPNESS_SRC``; it is not a package, so nothing installs it): its own
  ``MapProcessorRegression`` — how its dock runs a model whose metadata says ``Regressor``, as BirdsEye's models
  do — over the same raster with the same model, at the tile size, overlap and resolution the model's metadata
  gives and BirdsEye's batch of :data:`TILE_BATCH` tiles, headless (a mock canvas, as Deepness's own tests run
  it), in a child process of its own: its time, the time inside its ``InferenceSession.run``, its tiles and
  its peak memory. Deepness writes the heatmap as a raster (its result held whole in memory as 8-bit);
  BirdsEye's run also finds the peaks and stitches them.

The raster (RGB, 8-bit, tiled and DEFLATE-compressed GeoTIFF at 1 cm/px, the bundled model's resolution; a
textured field with a dark hump every 2 m) is written once with GDAL into build/bench_raster_detect.

    .venv/bin/python benchmarks/bench_raster_detect.py [--size 20000] [--model file.onnx] [--deepness CHECKOUT]
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import _path
import numpy as np

from birdseye.birdseye_qgis.core.detect.raster_detect import TILE_BATCH

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
    inside, tiles = [0.0, 0], [0]
    timed_session(model.session, inside)
    run = model.run

    def counted_run(batch):
        tiles[0] += len(batch)
        return run(batch)

    model.run = counted_run
    before_kb = peak_kb()
    t0 = time.perf_counter()
    with bounded_block_cache():  # as detectraster runs it
        found = detect_raster(model, grid, ProviderWindows(layer, grid, [1, 2, 3]))
    total = time.perf_counter() - t0
    print(json.dumps({"total_s": total, "inside_s": inside[0], "tiles": tiles[0], "windows": found.windows,
                      "detections": len(found), "merged": found.merged, "before_run_kb": before_kb,
                      "peak_kb": peak_kb(),
                      "width": grid.width, "height": grid.height}), flush=True)
    os._exit(0)  # QGIS's exit can crash a standalone script; the figures are out


def timed_session(session, timer: list):
    """``session`` with its ``run`` timed into ``timer`` ([seconds, calls])."""
    run = session.run

    def timed(*args, **kwargs):
        t = time.perf_counter()
        out = run(*args, **kwargs)
        timer[0] += time.perf_counter() - t
        timer[1] += 1
        return out

    session.run = timed
    return session


def deepness_child(path: str, model_path: str, checkout: str) -> None:
    """Run Deepness's own MapProcessorRegression over the raster with the model; print the figures as JSON."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from unittest.mock import MagicMock

    from qgis.core import QgsApplication, QgsProject, QgsRasterLayer

    app = QgsApplication([], False)
    app.initQgis()
    assert app
    sys.path.insert(0, str(Path(checkout) / "src"))
    from deepness.common.channels_mapping import ChannelsMapping, ImageChannelStandaloneBand
    from deepness.common.processing_overlap import ProcessingOverlap, ProcessingOverlapOptions
    from deepness.common.processing_parameters.map_processing_parameters import ProcessedAreaType
    from deepness.common.processing_parameters.regression_parameters import RegressionParameters
    from deepness.processing.map_processor.map_processing_result import MapProcessingResultSuccess
    from deepness.processing.map_processor.map_processor_regression import MapProcessorRegression
    from deepness.processing.models.regressor import Regressor

    layer = QgsRasterLayer(path, "bench")
    QgsProject.instance().addMapLayer(layer)
    model = Regressor(model_path)
    inside = [0.0, 0]
    timed_session(model.sess, inside)
    channels = ChannelsMapping()   # as Deepness's dock maps a three-band raster onto a three-input model
    channels.set_image_channels([ImageChannelStandaloneBand(band_number=b, name=n)
                                 for b, n in ((1, "red"), (2, "green"), (3, "blue"))])
    channels.set_number_of_model_inputs_same_as_image_channels()
    tile = int(model.get_metadata_tile_size() or model.get_input_size_in_pixels()[0])
    params = RegressionParameters(
        resolution_cm_per_px=model.get_metadata_resolution(), tile_size_px=tile, batch_size=TILE_BATCH,
        local_cache=False, processed_area_type=ProcessedAreaType.ENTIRE_LAYER, mask_layer_id=None,
        input_layer_id=layer.id(), input_channels_mapping=channels, output_scaling=1.0,
        processing_overlap=ProcessingOverlap(ProcessingOverlapOptions.OVERLAP_IN_PERCENT,
                                             percentage=model.get_metadata_tiles_overlap()),
        model=model)
    before_kb = peak_kb()
    t0 = time.perf_counter()
    processor = MapProcessorRegression(rlayer=layer, vlayer_mask=None, map_canvas=MagicMock(), params=params)
    with contextlib.redirect_stdout(sys.stderr):  # Deepness prints a line per tile
        processor.run()
    total = time.perf_counter() - t0
    result = processor._processing_result
    if not isinstance(result, MapProcessingResultSuccess):
        raise SystemExit(f"Deepness's run failed: {result.message} {getattr(result, 'exception', '')}")
    print(json.dumps({"total_s": total, "inside_s": inside[0], "calls": inside[1],
                      "tiles": processor.x_bins_number * processor.y_bins_number, "tile_px": tile,
                      "overlap_pct": model.get_metadata_tiles_overlap(), "before_run_kb": before_kb,
                      "peak_kb": peak_kb()}), flush=True)
    os._exit(0)


def figures_of(command: list, cwd: Path | None = None) -> dict:
    """Run a child of this script (in ``cwd``); its figures (the JSON on its last line of output)."""
    done = subprocess.run([sys.executable, str(Path(__file__).resolve()), *command], capture_output=True, text=True,
                          cwd=cwd)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command[:1])} failed:\n{done.stderr[-3000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--size", type=int, default=20000, help="raster side, px (default 20000)")
    parser.add_argument("--model", default=str(MODEL))
    parser.add_argument("--deepness", default=os.environ.get("DEEPNESS_SRC"),
                        help="a checkout of https://github.com/PUTvision/qgis-plugin-deepness to run side by side "
                             "(default: $DEEPNESS_SRC)")
    parser.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    parser.add_argument("--deepness-child", nargs=3, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child(*args.child)
        return
    if args.deepness_child:
        deepness_child(*args.deepness_child)
        return
    if args.deepness and not (Path(args.deepness) / "src" / "deepness" / "processing" / "map_processor").is_dir():
        parser.error(f"--deepness: {args.deepness} is not a checkout of Deepness (no src/deepness/processing/"
                     "map_processor)")
    FOLDER.mkdir(parents=True, exist_ok=True)
    raster = FOLDER / f"field_{args.size}.tif"
    if not raster.is_file():
        print(f"writing a {args.size} × {args.size} px GeoTIFF once ({raster}) …", flush=True)
        t0 = time.perf_counter()
        write_raster(raster.with_suffix(".part.tif"), args.size)
        raster.with_suffix(".part.tif").rename(raster)
        print(f"  written in {time.perf_counter() - t0:.0f} s ({raster.stat().st_size / 1e6:.0f} MB on disk)")
    r = figures_of(["--child", str(raster), args.model])
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
    if not args.deepness:
        print("Deepness side by side: not run (give --deepness or DEEPNESS_SRC: a checkout of "
              "https://github.com/PUTvision/qgis-plugin-deepness)")
        return
    # Deepness writes its heatmap raster through a GeoTIFF named grid_data in the current folder: keep it in ours.
    scratch = FOLDER / "deepness_run"
    scratch.mkdir(exist_ok=True)
    d = figures_of(["--deepness-child", str(raster), str(Path(args.model).resolve()),
                    str(Path(args.deepness).resolve())], cwd=scratch)
    print(f"Deepness  MapProcessorRegression, same raster and model: {d['tiles']} tiles of {d['tile_px']} px "
          f"overlapping {d['overlap_pct']:g} %, batches of {TILE_BATCH}")
    print(f"  its InferenceSession.run:                        {d['inside_s']:7.1f} s")
    print(f"  its total:                                       {d['total_s']:7.1f} s  ({mpx / d['total_s']:.2f} Mpx/s; "
          f"overhead / its baseline {(d['total_s'] - d['inside_s']) / d['inside_s']:.1%})")
    print(f"  its peak memory: {d['peak_kb'] / 1024:.0f} MB (QGIS and the model loaded: "
          f"{d['before_run_kb'] / 1024:.0f} MB)")
    print(f"ratio BirdsEye total / Deepness total: {r['total_s'] / d['total_s']:.2f} (BirdsEye also finds the peaks; "
          f"time per tile {r['total_s'] / r['tiles'] * 1e3:.0f} ms against {d['total_s'] / d['tiles'] * 1e3:.0f} ms)")


if __name__ == "__main__":
    main()
