"""birdseye:processodm through the Processing registry, against a local stub of the NodeODM API."""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from camera_solutions import truth, write_opensfm
from nodeodm_stub import NodeOdmStub


def test_frames_come_back_from_the_node(birdseye_provider, tmp_path):
    import processing

    images = tmp_path / "images"
    images.mkdir()
    for i in range(5):
        (images / f"DJI_{i:04d}.JPG").write_bytes(b"\xff\xd8" + bytes([i]))
    r, c, g = truth(seed=1)
    write_opensfm(tmp_path / "reconstruction.json", r, c, g)
    with NodeOdmStub({"opensfm/reconstruction.json": (tmp_path / "reconstruction.json").read_bytes()}) as node:
        result = processing.run("birdseye:processodm", {
            "IMAGES": str(images), "NODE_URL": node.url, "ODM_OPTIONS": "feature-quality=high",
            "OUTPUT_FOLDER": str(tmp_path / "odm"), "OUTPUT": "TEMPORARY_OUTPUT"})
    assert result["FRAME_COUNT"] == 5
    assert (tmp_path / "odm" / "opensfm" / "reconstruction.json").is_file()
    assert {f["flags"] for f in result["OUTPUT"].getFeatures()} == {"camera_solution"}
