"""A real Metashape project through the Processing registry: Import camera solution reads the .psx, writes the
surveyed markers as a geotag layer and the pinned marks as a check layer; Write labels with that layer puts
each marker's label where the person marked it (shared/data/real_solutions, Metashape 1.7.2)."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest
from qgis.core import QgsProcessingException
from registry import run

REAL = Path(__file__).resolve().parents[3] / "shared" / "data" / "real_solutions"


def test_project_markers_are_labelled_on_their_pinned_marks(birdseye_provider, tmp_path):
    psx = REAL / "metashape_wheat_tanashi" / "wheat_tanashi.psx"
    assert psx.is_file(), f"the real Metashape project is missing: {psx}"
    result = run("importcameras", {"CAMERAS": str(psx), "OUTPUT": "TEMPORARY_OUTPUT",
                                   "OUTPUT_CONTROL": "TEMPORARY_OUTPUT", "OUTPUT_MARK_CHECK": "TEMPORARY_OUTPUT"})
    assert result["FRAME_COUNT"] == 138
    assert result["MARKS_MEDIAN_PX"] <= 6.0 and result["MARKS_P90_PX"] <= 10.0
    frames, control, check = result["OUTPUT"], result["OUTPUT_CONTROL"], result["OUTPUT_MARK_CHECK"]
    assert frames.crs().authid() == "EPSG:32654"
    assert control.featureCount() == 6 and control.crs().authid() == "EPSG:32654"
    marks = {(f["image"], f["label"]): (f["u_mark"], f["v_mark"], f["error_px"]) for f in check.getFeatures()}
    assert len(marks) == 23 and all(not f.geometry().isEmpty() for f in check.getFeatures())

    run("writelabels", {"GEOTAGS": control, "FRAMES": frames, "SIGMA_PX": 5.0, "WRITE_RASTERS": False,
                        "OUTPUT_FOLDER": str(tmp_path / "labels"), "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None})
    with open(tmp_path / "labels" / "labels.csv", newline="", encoding="utf-8") as fh:
        labels = {(Path(r["image"]).stem, r["label"]): (float(r["u"]), float(r["v"])) for r in csv.DictReader(fh)}
    errors = []
    for key, (u_mark, v_mark, reported) in marks.items():
        u, v = labels[key]
        errors.append(np.hypot(u - u_mark, v - v_mark))
        # The same computation; the layers' UTM round trip and labels.csv's decimals differ by micrometres.
        assert errors[-1] == pytest.approx(reported, abs=0.01), "the check measures what Write labels writes"
    assert np.median(errors) <= 6.0 and np.percentile(errors, 90) <= 10.0


def test_local_project_is_refused_saying_why(birdseye_provider):
    with pytest.raises(QgsProcessingException, match="goya_test.psx.*local coordinate system"):
        run("importcameras", {"CAMERAS": str(REAL / "metashape_goya_local" / "goya_test.psx"),
                              "OUTPUT": "TEMPORARY_OUTPUT"})
