"""The demo project the real-desktop tests open, made once for the whole session.

``demo_project`` is the small demo (``scripts/demo.py --size small``: frames, geotags, detections, clusters,
waypoints, rasters, the bundled model; a few seconds to a minute), made the first time a test asks for it; set
``BIRDSEYE_E2E_DEMO`` to a folder made by ``make demo`` to use the full demo instead (how the README's screenshots
are made). Tests that only read the demo share it; a test whose session writes into the demo folder (a review
writes its log into the detections' GeoPackage) takes ``demo_project_copy``, its own copy.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
DEMO_VARIABLE = "BIRDSEYE_E2E_DEMO"
DEMO_TIMEOUT_S = 240


@pytest.fixture(scope="session")
def demo_folder(tmp_path_factory) -> Path:
    """The small demo's folder, made once for the session; or ``BIRDSEYE_E2E_DEMO``, a demo folder made before."""
    chosen = os.environ.get(DEMO_VARIABLE)
    if chosen:
        return Path(chosen).resolve()
    out = tmp_path_factory.mktemp("demo") / "birdseye-demo"
    env = {k: v for k, v in os.environ.items() if k not in {"QGIS_CUSTOM_CONFIG_PATH", "PYTHONPATH"}}
    env["QT_QPA_PLATFORM"] = "offscreen"
    result = subprocess.run([sys.executable, str(REPO_ROOT / "scripts" / "demo.py"), "--size", "small",
                             "--out", str(out)], cwd=REPO_ROOT, env=env, capture_output=True, text=True,
                            timeout=DEMO_TIMEOUT_S, check=False)
    assert result.returncode == 0, f"the small demo failed:\n{result.stdout[-3000:]}\n{result.stderr[-3000:]}"
    return out


@pytest.fixture(scope="session")
def demo_project(demo_folder) -> Path:
    """The demo's project, shared by every test that leaves the demo folder as it found it."""
    return demo_folder / "birdseye_demo.qgz"


def copy_of_demo(folder: Path, out: Path) -> Path:
    """A demo folder to start a review in: its GeoPackages copied (the review writes its log into the
    detections'), every other file linked."""
    def copy(source, target):
        if source.endswith(".gpkg"):
            return shutil.copy2(source, target)
        os.link(source, target)
        return target

    shutil.copytree(folder, out, copy_function=copy, ignore=shutil.ignore_patterns("*.gpkg-wal", "*.gpkg-shm"))
    return out / "birdseye_demo.qgz"


@pytest.fixture(scope="module")
def demo_project_copy(demo_folder, tmp_path_factory) -> Path:
    """The project of a copy of the demo, one per test module, for a session that writes into the demo folder."""
    return copy_of_demo(demo_folder, tmp_path_factory.mktemp("demo-copy") / "birdseye-demo")
