"""A QGIS test session ends with pytest's own exit status, even when layers outlive their tests.

QGIS 3.22 segfaults at interpreter exit when a map layer that went through ``processing.run`` is still
alive: Python's finalisation destroys it after QGIS has shut down (measured here with pytest-qgis alone:
exit 139 after "1 passed"; gdb shows ``QgsRasterPipe::~QgsRasterPipe`` under ``Py_FinalizeEx``). The
suites' ``qgis_app`` fixture (tests/qgis_fixtures.py) deletes such layers while QGIS is still up. These
sessions run that exact situation in a subprocess, once passing and once failing. They also check the
session prints no "proj_create: unrecognized format" (``processing.run`` on a canvas without a CRS did).
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parents[1]

LEAKY_TEST = '''
from qgis.core import QgsRasterLayer

KEPT = []


def test_a_layer_outlives_the_test(qgis_app, qgis_processing, tmp_path):
    import processing
    from osgeo import gdal

    path = tmp_path / "r.tif"
    gdal.GetDriverByName("GTiff").Create(str(path), 4, 4, 1)
    layer = QgsRasterLayer(str(path), "kept")
    KEPT.append(layer)
    processing.run("native:rasterlayerstatistics", {{"INPUT": layer, "BAND": 1}})
    assert {outcome}
'''


@pytest.mark.slow
@pytest.mark.parametrize("outcome, status", [("True", 0), ("False", 1)])
def test_the_session_exits_with_pytests_status(tmp_path, outcome, status):
    (tmp_path / "conftest.py").write_text(f"import sys\nsys.path.insert(0, {str(TESTS)!r})\n"
                                          "pytest_plugins = ['qgis_fixtures']\n")
    (tmp_path / "test_leaky.py").write_text(LEAKY_TEST.format(outcome=outcome))
    pytest_script = Path(sys.executable).with_name("pytest")
    result = subprocess.run([str(pytest_script), "-q", "-s", "-p", "no:cacheprovider", str(tmp_path)], cwd=tmp_path,
                            env={**os.environ, "QT_QPA_PLATFORM": "offscreen"}, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == status, result.stdout[-2000:] + result.stderr[-2000:]
    assert "proj_create" not in result.stdout + result.stderr
