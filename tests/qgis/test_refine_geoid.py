"""birdseye:refineposes on the six real Brighton Beach DJI frames at full size (../shared/data beside the clone, as
in CI: missing data is a failure; no DewarpData, so the camera is only nominal and its focal length is fixed by the
flying height) with geotags whose ellipsoidal heights are the take-off ground's, AbsoluteAltitude − RelativeAltitude
+ N.

The frames' heights are above mean sea level (EGM96), the geotags' ellipsoidal: with the N the user gives
(GEOID_UNDULATION_M) or PROJ's EGM96 grid they meet again at the take-off ground, and the focal length lands on
the FC300S lens's ≈ 2,333 px (3.61 mm on a 6.19 mm-wide 4000 px sensor) whatever N. Compared bare, as the
refinement once did, N / depth would have scaled it (−28.5 m at 40 m: 70 %). With the drone's absolute heights 25 m
off (a barometric offset), its own take-off ground is used and the report says how far the surveyed ground lies from
it."""
from __future__ import annotations

import json
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest
from registry import run

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from strip_xmp import strip_xmp  # noqa: E402  (tests/data, put on the path above)

ORIGINALS = Path(__file__).resolve().parents[3] / "shared" / "data" / "brighton_beach"
LENS_PX = 3.61 / 6.19 * 4000


def imported(tmp_path, **shift):
    """The six frames through importdjiimages; ``shift`` sets (``rtk_status``) or moves (``height_m``,
    ``ground_h_m``, m) those fields of every frame, as another drone or a barometric offset would have logged
    them."""
    assert ORIGINALS.is_dir(), f"{ORIGINALS} is missing: the shared data must lie beside the repository"
    images = tmp_path / "images"
    shutil.copytree(ORIGINALS, images, ignore=shutil.ignore_patterns("*.md", "LICENSE", "*.laz"))
    frames = run("importdjiimages", {"IMAGES": str(images), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    fields = frames.fields()
    changes = {}
    for feature in frames.getFeatures():
        changes[feature.id()] = {fields.indexOf(name): value if name == "rtk_status" else feature[name] + value
                                 for name, value in shift.items()}
    assert frames.dataProvider().changeAttributeValues(changes)
    return frames


def geotags_at(frames, height):
    """A point layer of surveyed targets under the frames, at ``height`` (ellipsoidal, m) as their Z."""
    from qgis.core import QgsFeature, QgsGeometry, QgsPoint, QgsVectorLayer

    layer = QgsVectorLayer("PointZ?crs=EPSG:4326", "geotags", "memory")
    features = []
    for frame in frames.getFeatures():
        feature = QgsFeature(layer.fields())
        feature.setGeometry(QgsGeometry(QgsPoint(frame["lon"], frame["lat"], height)))
        features.append(feature)
    layer.dataProvider().addFeatures(features)
    return layer


def refined(frames, geotags, tmp_path, undulation=None):
    """refineposes with ``geotags`` and GEOID_UNDULATION_M ``undulation`` (None: left empty); the rows, the focal
    length (px) and the report."""
    params = {"FRAMES": frames, "GEOTAGS": geotags, "OUTPUT": "TEMPORARY_OUTPUT",
              "OUTPUT_REPORT": str(tmp_path / "report.html")}
    if undulation is not None:
        params["GEOID_UNDULATION_M"] = undulation
    result = run("refineposes", params)
    rows = list(result["OUTPUT"].getFeatures())
    assert result["REGISTERED_COUNT"] == len(rows) == 6
    assert np.mean([f["reprojection_rms_px"] for f in rows]) <= 1.0
    return rows, json.loads(rows[0]["camera"])["fx"], (tmp_path / "report.html").read_text(encoding="utf-8")


@pytest.mark.slow
@pytest.mark.timeout(900)
@pytest.mark.parametrize("undulation", [None, -10.0, 20.0], ids=["egm96-grid", "N-10", "N+20"])
def test_geotags_at_the_takeoff_grounds_ellipsoidal_height_fix_the_lens_whatever_n(birdseye_provider, tmp_path,
                                                                                    undulation):
    """Frames with an RTK fix (set here) take the geotags' ground: converted, it is the take-off ground again, and
    the focal length is the lens's within 2 %."""
    from birdseye.birdseye_qgis.core.geometry import heights

    frames = imported(tmp_path, rtk_status=3)
    first = next(frames.getFeatures())
    n = undulation
    if n is None:
        assert heights.geoid_grid_installed("EGM96"), "PROJ's EGM96 grid is missing (make setup installs proj-data)"
        n = float(heights.geoid_undulation(first["lat"], first["lon"]))
    rows, focal, report = refined(frames, geotags_at(frames, first["ground_h_m"] + n), tmp_path, undulation)
    print(f"Brighton, N = {n:+.2f} m ({'EGM96 grid' if undulation is None else 'given'}): focal {focal:.1f} px, "
          f"lens {LENS_PX:.1f} px")
    assert focal == pytest.approx(LENS_PX, rel=0.02)
    assert "surveyed (geotags)" in report and "most frames have an RTK fix" in report
    assert all(f["ground_src"] == "tie_points" and f["height_ref"] == "EGM96" for f in rows)


@pytest.mark.slow
@pytest.mark.timeout(900)
def test_a_barometric_offset_keeps_the_drones_own_ground_and_the_report_says_by_how_much(birdseye_provider,
                                                                                         tmp_path):
    """AbsoluteAltitude 25 m high moves camera and take-off heights alike; geotags stay at the true take-off
    ground (N = −28.57 m, EGM96 at the site). Without RTK the drone's own ground is used: the focal length is
    still the lens's, and the report and log give the surveyed ground 25 m below it."""
    frames = imported(tmp_path, height_m=25.0, ground_h_m=25.0)
    first = next(frames.getFeatures())
    true_ground = first["ground_h_m"] - 25.0
    rows, focal, report = refined(frames, geotags_at(frames, true_ground - 28.57), tmp_path, -28.57)
    print(f"Brighton, heights 25 m off: focal {focal:.1f} px, lens {LENS_PX:.1f} px")
    assert focal == pytest.approx(LENS_PX, rel=0.02)
    assert "the frames have no RTK fix" in report and "<td>own</td>" in report
    assert "<td>-25.000</td>" in report  # surveyed − own
    assert "the take-off point" in report  # the warning: the ground is one height for the site


@pytest.mark.slow
@pytest.mark.timeout(900)
def test_exif_only_frames_without_a_ground_are_refined_and_take_the_geotags_ground(birdseye_provider, tmp_path):
    """The frames with their XMP stripped and no flight height given have no ground (ground_src empty). Refined
    without geotags, every frame is registered and gets the tie points' ground while the report says the focal
    length could not be determined; with geotags at the take-off ground (ellipsoidal, N given) it is the lens's."""
    from qgis.core import NULL

    assert ORIGINALS.is_dir(), f"{ORIGINALS} is missing: the shared data must lie beside the repository"
    images = tmp_path / "images"
    images.mkdir()
    for path in sorted(ORIGINALS.glob("*.JPG")):
        strip_xmp(path, images / path.name)
    frames = run("importdjiimages", {"IMAGES": str(images), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    before = list(frames.getFeatures())
    assert all(f["ground_h_m"] == NULL and f["ground_src"] in ("", NULL) and "no_ground_height" in f["flags"]
               for f in before)
    nominal = json.loads(before[0]["camera"])["fx"]
    result = run("refineposes", {"FRAMES": frames, "OUTPUT": "TEMPORARY_OUTPUT",
                                 "OUTPUT_REPORT": str(tmp_path / "report.html")})
    rows = list(result["OUTPUT"].getFeatures())
    assert result["REGISTERED_COUNT"] == 6
    assert all(f["ground_src"] == "tie_points" and f["ground_h_m"] != NULL and "no_ground_height" not in f["flags"]
               for f in rows)
    assert json.loads(rows[0]["camera"])["fx"] == pytest.approx(nominal, rel=0.002)
    report = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "cannot determine its focal length" in report and "no ground height" in report

    # DJI_0018's AbsoluteAltitude − RelativeAltitude (198.31 − 39.80 m): the take-off ground above sea level.
    rows, focal, report = refined(frames, geotags_at(frames, 158.51 - 28.57), tmp_path, -28.57)
    print(f"Brighton, EXIF only, geotags' ground: focal {focal:.1f} px, lens {LENS_PX:.1f} px")
    assert focal == pytest.approx(LENS_PX, rel=0.02)
    assert "most frames have no ground of their own" in report
