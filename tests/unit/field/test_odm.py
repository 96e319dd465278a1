"""Processing on an OpenDroneMap node, against a local stub of the NodeODM API: upload, wait, download
only the reconstruction, import it; failures and cancel say what happened."""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "data"))
from camera_solutions import truth, write_opensfm
from nodeodm_stub import NodeOdmStub

from birdseye.birdseye_qgis.core.errors import Cancelled, InputError
from birdseye.birdseye_qgis.core.field.odm import RECONSTRUCTION_OUTPUTS, parse_options, process_on_node
from birdseye.birdseye_qgis.core.field.solutions import import_camera_solution


@pytest.fixture
def flight(tmp_path):
    images = tmp_path / "images"
    images.mkdir()
    for i in range(5):
        (images / f"DJI_{i:04d}.JPG").write_bytes(b"\xff\xd8 not really a jpeg " + bytes([i]))
    r, c, g = truth(seed=1)
    write_opensfm(tmp_path / "reconstruction.json", r, c, g)
    return images, {"opensfm/reconstruction.json": (tmp_path / "reconstruction.json").read_bytes()}


def test_images_go_up_and_the_reconstruction_comes_back(flight, tmp_path):
    images, archive = flight
    fractions = []
    with NodeOdmStub(archive) as node:
        path = process_on_node(images, node.url, tmp_path / "odm", {"feature-quality": "high"},
                               progress=fractions.append)
        assert sorted(node.uploaded) == sorted(p.name.encode() for p in images.iterdir())
        # Only the reconstruction is asked for, and the options reach the node.
        assert json.dumps(RECONSTRUCTION_OUTPUTS).encode() in node.init_fields
        assert b"feature-quality" in node.init_fields
    assert fractions[-1] == 1.0 and fractions == sorted(fractions)
    frames = import_camera_solution(path, images).frames
    assert len(frames) == 5 and all(Path(p).is_file() for p in frames.image)
    assert np.all(np.isfinite(frames.ground_h))


def test_a_failed_task_and_an_unreachable_node_say_so(flight, tmp_path):
    images, archive = flight
    with NodeOdmStub(archive, fail=True) as node:
        with pytest.raises(InputError, match="OpenDroneMap failed on the node"):
            process_on_node(images, node.url, tmp_path / "odm")
    with pytest.raises(InputError, match="did not answer"):
        process_on_node(images, "http://127.0.0.1:9", tmp_path / "odm")


def removed_within(node, seconds=10.0):
    """The stub's removed tasks, once it has removed one (the upload's thread cleans up after the return)."""
    deadline = time.monotonic() + seconds
    while not node.removed and time.monotonic() < deadline:
        time.sleep(0.05)
    return node.removed


def test_cancel_while_processing_cancels_and_removes_the_task_on_the_node(flight, tmp_path):
    images, archive = flight
    with NodeOdmStub(archive, polls_until_done=100) as node:
        with pytest.raises(Cancelled):
            process_on_node(images, node.url, tmp_path / "odm", progress=lambda f: None,
                            is_canceled=lambda: any(t["polls"] >= 1 for t in list(node.tasks.values())))
        assert len(node.cancelled) == 1 and node.removed == node.cancelled and not node.tasks


def test_cancel_during_the_upload_returns_at_once_and_removes_the_task(flight, tmp_path):
    """pyodm looks at its callback only between images; cancel must not wait for the images in flight,
    and the half-uploaded task must not stay on the node."""
    images, archive = flight
    with NodeOdmStub(archive, upload_delay_s=1.5) as node:
        with pytest.raises(Cancelled):
            process_on_node(images, node.url, tmp_path / "odm", is_canceled=lambda: bool(node.tasks))
        # The stub records an image only after its 1.5 s upload: none is recorded yet, so the call did not
        # wait for the images in flight.
        assert node.uploaded == [], "cancel waited for an upload to finish"
        assert len(removed_within(node)) == 1 and node.cancelled == node.removed
        assert not node.tasks and node.downloads == 0


def test_cancel_stops_sending_images(flight, tmp_path):
    """More images than pyodm uploads at once: those not yet sent never are."""
    _, archive = flight
    many = tmp_path / "many"
    many.mkdir()
    for i in range(30):
        (many / f"DJI_{i:04d}.JPG").write_bytes(b"\xff\xd8 " + bytes([i]))
    with NodeOdmStub(archive, upload_delay_s=0.5) as node:
        with pytest.raises(Cancelled):
            process_on_node(many, node.url, tmp_path / "odm", is_canceled=lambda: bool(node.tasks))
        assert len(removed_within(node)) == 1 and not node.tasks
        assert len(node.uploaded) < 30


def test_cancel_during_the_download_removes_the_task_and_leaves_no_archive(flight, tmp_path):
    images, archive = flight
    with NodeOdmStub(archive, polls_until_done=1) as node:
        with pytest.raises(Cancelled):
            process_on_node(images, node.url, tmp_path / "odm", is_canceled=lambda: node.downloads > 0)
        assert node.downloads == 1 and len(node.removed) == 1 and not node.tasks
    assert not list((tmp_path / "odm").rglob("*"))


def test_options_parse_as_the_node_expects():
    assert parse_options("feature-quality=high; min-num-features=12000, fast-orthophoto=true\nres=2.5") == {
        "feature-quality": "high", "min-num-features": 12000, "fast-orthophoto": True, "res": 2.5}
    with pytest.raises(InputError, match="name=value"):
        parse_options("fast-orthophoto")
