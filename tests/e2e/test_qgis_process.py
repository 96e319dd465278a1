"""``scripts/qgis_process.sh``: the plugin loads in QGIS's command-line executor and its algorithms run.

Each QGIS start takes a few seconds, so the listing is made once per module, in a fresh settings
folder (the wrapper must enable the plugin there by itself).
"""
from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
WRAPPER = REPO_ROOT / "scripts" / "qgis_process.sh"
ALGORITHM_DIR = REPO_ROOT / "processing" / "algorithms"
ALGORITHM_MODULES = sorted(p.stem for p in ALGORITHM_DIR.glob("*.py") if p.stem not in {"__init__", "base"})

pytestmark = pytest.mark.slow


def wrapper_env(config_dir: Path, **extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items()
           if k not in {"QGIS_CUSTOM_CONFIG_PATH", "QGIS_PLUGINPATH", "PYTHONPATH"}}
    env.update(BIRDSEYE_QGIS_CONFIG=str(config_dir), **extra)
    return env


def qgis_process(*args: str, config_dir: Path, timeout: float = 120, **extra_env: str):
    return subprocess.run([str(WRAPPER), *args], env=wrapper_env(config_dir, **extra_env),
                          capture_output=True, text=True, timeout=timeout, check=False)


def json_output(result: subprocess.CompletedProcess) -> dict:
    assert result.returncode == 0, f"qgis_process failed ({result.returncode}):\n{result.stderr}"
    return json.loads(result.stdout)


@pytest.fixture(scope="module")
def fresh_config(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("qgis-process-config")


@pytest.fixture(scope="module")
def listing(fresh_config) -> dict:
    return json_output(qgis_process("--json", "list", config_dir=fresh_config))


def test_wrapper_enables_plugin_in_a_fresh_profile(listing, fresh_config):
    ini = fresh_config / "profiles" / "default" / "QGIS" / "QGIS3.ini"
    assert "birdseye=true" in ini.read_text().splitlines()
    assert "birdseye" in listing["providers"], sorted(listing["providers"])


def test_listing_has_every_algorithm(listing):
    provider = listing["providers"]["birdseye"]
    assert provider["name"] == "BirdsEye" and provider["is_active"]
    assert sorted(provider["algorithms"]) == [f"birdseye:{m}" for m in ALGORITHM_MODULES]


def test_wrapper_enables_plugin_without_losing_other_settings(tmp_path):
    """An existing profile where the plugin was switched off: only that one line changes."""
    ini = tmp_path / "profiles" / "default" / "QGIS" / "QGIS3.ini"
    ini.parent.mkdir(parents=True)
    ini.write_text("[PythonPlugins]\nbirdseye=false\nprocessing=true\n\n[qgis]\nsymbolsListGroupsIndex=0\n")
    result = qgis_process("x", config_dir=tmp_path, QGIS_PROCESS_BIN="/bin/true")
    assert result.returncode == 0, result.stderr
    assert ini.read_text() == "[PythonPlugins]\nbirdseye=true\nprocessing=true\n\n[qgis]\nsymbolsListGroupsIndex=0\n"


def test_simulatecampaign_runs_end_to_end(fresh_config, tmp_path):
    """A tiny campaign (a 6 × 4 m field, small frames): files in the contract formats appear."""
    from qgis.PyQt.QtGui import QImage

    out = tmp_path / "campaign"
    n_targets, n_missed, n_spurious, width, height = 3, 1, 1, 320, 200
    result = qgis_process(
        "--json", "run", "birdseye:simulatecampaign", "--",
        "SEED=7", f"OUTPUT_FOLDER={out}", f"N_TARGETS={n_targets}", f"N_MISSED={n_missed}",
        f"N_SPURIOUS={n_spurious}", f"IMAGE_WIDTH={width}", f"IMAGE_HEIGHT={height}",
        "FIELD_WIDTH_M=6", "FIELD_LENGTH_M=4",
        config_dir=fresh_config, timeout=240)
    outputs = json_output(result)["results"]
    assert Path(outputs["OUTPUT_FOLDER"]).resolve() == out.resolve()
    for key in ("GEOTAGS", "POSES", "IMAGES", "CALIBRATION"):
        path = Path(outputs[key])
        assert path.is_file() and path.stat().st_size > 0, f"{key}: {path} was not written"

    geotags = [line for line in Path(outputs["GEOTAGS"]).read_text().splitlines() if line.strip()]
    assert len(geotags) == n_targets - n_missed + n_spurious
    assert all(len(line.split(",")) == 6 for line in geotags), "rover CSV rows have 6 fields"

    frames = [line.split(",") for line in Path(outputs["IMAGES"]).read_text().splitlines()[1:] if line.strip()]
    assert len(frames) == outputs["FRAME_COUNT"] > 0
    for _, file_name in frames[:: max(1, len(frames) // 5)]:
        image = QImage(str(out / file_name.strip()))
        assert (image.width(), image.height()) == (width, height), f"{file_name}: wrong size or unreadable"
