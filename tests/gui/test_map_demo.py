"""The demo project's map as a user meets it, in the real QGIS desktop under its own Xvfb.

QGIS opens the session's small demo (conftest.py; the probe only reads it) on a 1366 × 768 and on a
1920 × 1080 screen with ``--code map_probe.py``, which zooms to a training flight and to the held-out flight,
saves screenshots (Layers panel and map) to build/screenshots/map/ and reports every layer's name, renderer,
legend and fill. The tests check what makes the map read at a glance: every BirdsEye layer styled with its
own palette and a legend in words, names short, unique and shown whole in the Layers panel, frame footprints
drawn as outlines (no fill hiding the survey points), the survey drawn over what was detected around it.

Set ``BIRDSEYE_E2E_DEMO`` to a folder made by ``make demo`` to look at the full demo instead.
"""
from __future__ import annotations

import re
from pathlib import Path

import pytest
import test_desktop
from test_desktop import REPO_ROOT, run_probe, screenshot_folder

PROBE = Path(__file__).with_name("map_probe.py")
SCREENSHOTS = REPO_ROOT / "build" / "screenshots" / "map"
SCREENS = {"1366x768": "1366x768x24", "1920x1080": "1920x1080x24"}
DESKTOP_TIMEOUT_S = 120
# No layer name longer, and no two names alike in their first this many characters, whatever the panel's width;
# test_no_layer_name_is_cut_off_in_the_layers_panel measures the width the panel has.
MAX_NAME_CHARS = 30
# A footprint may tint the map this much at most: 75 overlapping frames must not add up to a solid colour.
MAX_FILL_OPACITY = 0.05
# Each BirdsEye output (by the start of its file name in the demo) and the renderer its style uses.
RENDERERS = {"geotags": "categorizedSymbol", "frames": "categorizedSymbol", "track": "RuleRenderer",
             "detections": "RuleRenderer", "clusters": "categorizedSymbol", "cluster_points": "RuleRenderer",
             "waypoints": "RuleRenderer", "route": "RuleRenderer", "mosaic_changes": "categorizedSymbol",
             "partitions": "RuleRenderer"}

pytestmark = test_desktop.pytestmark  # slow, and skipped without Debian's qgis or Xvfb


def kind(stem: str) -> str:
    """The output kind of a demo file: frames_labelled_train1 → frames, geotags_seen_train2 → geotags."""
    for name in sorted(RENDERERS, key=len, reverse=True):
        if stem.startswith(name):
            return name
    raise KeyError(stem)


def look_at(project: Path, screen: str, work: Path) -> dict:
    """QGIS on a screen of ``screen`` (WxHxD) with the probe; its report and output."""
    prefix = screen.rsplit("x", 1)[0]
    return run_probe(PROBE, work, DESKTOP_TIMEOUT_S, SCREENSHOTS / f"{prefix}_timeout.png",
                     report_copy=SCREENSHOTS / f"{prefix}_report.json",  # beside the screenshots, for a look
                     screen=screen, BIRDSEYE_MAP_PROJECT=str(project), BIRDSEYE_MAP_SCREENSHOTS=str(SCREENSHOTS),
                     BIRDSEYE_MAP_PREFIX=prefix)


@pytest.fixture(scope="module", params=sorted(SCREENS))
def seen(request, demo_project, tmp_path_factory) -> dict:
    screenshot_folder(SCREENSHOTS, old=f"{request.param}_*.png")
    return look_at(demo_project, SCREENS[request.param], tmp_path_factory.mktemp(f"map-{request.param}"))


def birdseye_layers(report) -> list:
    return [layer for layer in report["layers"] if layer["vector"]]


def test_the_probe_looked_at_every_view(seen):
    report = seen["report"]
    assert report["errors"] == [] and report["timeouts"] == [], report
    assert report["project_opened"]
    invalid = [layer["name"] for layer in report["layers"] if not layer["valid"]]
    assert invalid == [], invalid
    from qgis.PyQt.QtGui import QImage

    assert set(report["screenshots"]) == {"project", "training", "heldout"}
    for name, path in report["screenshots"].items():
        image = QImage(path or "")
        assert (image.width(), image.height()) == tuple(report["screen"]), f"{name}: not the whole window"


def test_every_birdseye_layer_has_its_style_with_a_legend_in_words(seen):
    for layer in birdseye_layers(seen["report"]):
        assert layer["renderer"] == RENDERERS[kind(layer["stem"])], layer
        legend = layer["legend"]
        assert legend, f"{layer['name']}: no legend entries"
        for label in legend:
            words = re.findall(r"[A-Za-z]{2,}", label)
            assert len(words) >= 2, f"{layer['name']}: legend entry {label!r} does not say what it means in words"
        assert len(set(legend)) == len(legend), f"{layer['name']}: two legend entries read the same: {legend}"


def test_layer_names_are_short_and_unique(seen):
    names = [layer["name"] for layer in seen["report"]["layers"]]
    assert len(set(names)) == len(names), sorted(names)
    for name in names:
        assert len(name) <= MAX_NAME_CHARS, name
    starts = [name[:MAX_NAME_CHARS] for name in names]
    assert len(set(starts)) == len(starts), f"names that differ only after {MAX_NAME_CHARS} characters: {names}"


def test_no_layer_name_is_cut_off_in_the_layers_panel(seen):
    cut = [layer["name"] for layer in seen["report"]["layers"] if layer["text_end"] > layer["room"]]
    assert cut == [], f"the Layers panel cuts off {cut}"


def test_flights_are_told_apart_by_name(seen):
    by_stem = {layer["stem"]: layer["name"] for layer in seen["report"]["layers"]}
    for key, words in {"train1": "training 1", "train2": "training 2", "heldout": "held-out"}.items():
        for stem in (f"geotags_{key}", f"frames_{key}", f"track_{key}"):
            assert words in by_stem[stem], (stem, by_stem[stem])


def test_frame_footprints_are_outlines(seen):
    frames = [layer for layer in birdseye_layers(seen["report"]) if kind(layer["stem"]) == "frames"]
    assert frames
    for layer in frames:
        assert layer["fill_opacity"] and max(layer["fill_opacity"]) <= MAX_FILL_OPACITY, layer


def test_the_survey_is_drawn_over_everything_else(seen):
    """The held-out flight's geotags, detections and clusters shown, drawn in that order over its frames."""
    layers = {layer["stem"]: layer for layer in seen["report"]["layers"]}
    order = seen["report"]["drawing_order"]
    stems = ("geotags_heldout", "detections", "clusters", "frames_heldout")
    assert all(layers[stem]["visible"] for stem in stems)
    assert [order.index(stem) for stem in stems] == sorted(order.index(stem) for stem in stems), order
