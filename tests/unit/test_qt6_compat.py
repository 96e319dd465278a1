"""Every Qt name the plugin spells exists in PyQt6 (QGIS 4), checked without QGIS 4.

``scripts/check_qt6.py`` runs in ``.venv-qt6`` (PyQt6 from PyPI, made by ``make setup``); these tests
first show it catches what QGIS 4 would reject, then run it over the plugin. The review dock's pure-Qt
parts then run under PyQt6 (tests/qt6/probe_pure_qt.py).
"""
from __future__ import annotations

import configparser
import os
import re
import subprocess
import textwrap
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
QT6_PYTHON = REPO_ROOT / ".venv-qt6" / "bin" / "python"
CHECKER = REPO_ROOT / "scripts" / "check_qt6.py"
PURE_QT_PROBE = REPO_ROOT / "tests" / "qt6" / "probe_pure_qt.py"


def run_checker(*args) -> subprocess.CompletedProcess:
    if not QT6_PYTHON.exists():
        pytest.fail(f"{QT6_PYTHON} is missing: run `make setup` (it installs PyQt6 there)")
    return subprocess.run([str(QT6_PYTHON), str(CHECKER), *map(str, args)], capture_output=True, text=True,
                          timeout=120)


def test_checker_reports_what_pyqt6_lacks_and_fixes_unscoped_enums(tmp_path):
    source = tmp_path / "widget.py"
    source.write_text(textwrap.dedent("""\
        from qgis.core import Qgis
        from qgis.PyQt.QtCore import Qt
        from qgis.PyQt.QtWidgets import QDialog, QMessageBox, QSizePolicy
        from PyQt5.QtCore import QTimer

        try:
            from qgis.PyQt.QtGui import QAction
        except ImportError:
            from qgis.PyQt.QtWidgets import QAction
        from qgis.PyQt.QtWidgets import QActionGroup

        ALIGN = Qt.AlignLeft | Qt.AlignmentFlag.AlignTop
        POLICY = QSizePolicy.Expanding
        BUTTON = QMessageBox.StandardButton.Yes
        ROLE = Qt.ItemDataRole.DisplayRole
        OLD = Qt.MidButton if Qgis.QGIS_VERSION_INT < 34000 else Qt.MouseButton.MiddleButton


        def ask(dialog: QDialog):
            return dialog.exec_()
        """))
    result = run_checker(source)
    assert result.returncode == 1
    problems = result.stdout.splitlines()
    assert f"{source}:4: imports from PyQt5.QtCore directly; import from qgis.PyQt" in problems
    assert f"{source}:12: Qt.AlignLeft does not exist in PyQt6 (use Qt.AlignmentFlag.AlignLeft)" in problems
    assert f"{source}:13: QSizePolicy.Expanding does not exist in PyQt6 (use QSizePolicy.Policy.Expanding)" \
        in problems
    assert f"{source}:20: exec_() is gone in PyQt6; call exec()" in problems
    assert f"{source}:10: QActionGroup is not in PyQt6.QtWidgets (it is in PyQt6.QtGui)" in problems
    assert len(problems) == 5, problems  # the scoped names and the version-guarded 3.22 spelling pass

    fixed = run_checker("--fix", source)
    text = source.read_text()
    assert "ALIGN = Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignTop" in text
    assert "POLICY = QSizePolicy.Policy.Expanding" in text
    assert sorted(fixed.stdout.splitlines()) == sorted(p for p in problems if ":4:" in p or ":20:" in p or ":10:" in p)


def test_checker_refuses_qgis_enum_names_deprecated_since_they_moved(tmp_path):
    source = tmp_path / "algorithm.py"
    source.write_text(textwrap.dedent("""\
        from qgis.core import Qgis, QgsFeatureSink, QgsProcessing, QgsWkbTypes
        from qgis.gui import QgsVertexMarker as Marker

        SOURCES = [QgsProcessing.TypeVectorPoint]
        GEOMETRY = QgsWkbTypes.PointZ
        KIND = QgsWkbTypes.geometryType(GEOMETRY)
        FAST = QgsFeatureSink.Flag.FastInsert
        LEVEL = Qgis.Warning
        if Qgis.QGIS_VERSION_INT >= 33600:
            POINTS = Qgis.ProcessingSourceType.VectorPoint
        else:
            POINTS = QgsProcessing.TypeVectorPoint
        ICON = Marker.ICON_CROSS
        TYPO = Qgis.ProcessingSourceType.VectorPoints
        """))
    result = run_checker(source)
    assert result.returncode == 1
    lines = sorted(int(line.split(":")[1]) for line in result.stdout.splitlines())
    # the methods, the scoped spellings and the 3.22 branch of the version guard pass
    assert lines == [4, 5, 8, 13, 14], result.stdout
    assert "Qgis.ProcessingSourceType.VectorPoints is not in the QGIS API (qgis-stubs)" in result.stdout
    assert "QgsProcessing.TypeVectorPoint is deprecated" in result.stdout
    assert "SOURCE_… of birdseye_qgis/qgis_enums.py" in result.stdout
    assert "Marker.ICON_CROSS is deprecated" in result.stdout and "QgsVertexMarker.IconType" in result.stdout


def test_metadata_lets_qgis_4_load_the_plugin():
    """QGIS 4 lists only plugins that declare Qt 6 support and a maximum version of 4.x."""
    metadata = configparser.ConfigParser(interpolation=None)
    metadata.read(REPO_ROOT / "metadata.txt", encoding="utf-8")
    general = metadata["general"]
    assert general["supportsQt6"] == "True"
    assert (general["qgisMinimumVersion"], general["qgisMaximumVersion"]) == ("3.22", "4.99")


def test_the_plugin_names_only_what_pyqt6_has():
    result = run_checker()
    assert result.returncode == 0, "Qt 6 problems:\n" + result.stdout


def test_the_review_docks_pure_qt_parts_run_under_pyqt6():
    """The unit table model in a real view, the scores table, the chip strip, the review keys and the chip
    loader's thread pool, with ``qgis.PyQt`` being PyQt6 (see the probe's docstring)."""
    if not QT6_PYTHON.exists():
        pytest.fail(f"{QT6_PYTHON} is missing: run `make setup` (it installs PyQt6 there)")
    result = subprocess.run([str(QT6_PYTHON), str(PURE_QT_PROBE)], capture_output=True, text=True, timeout=300,
                            env={**os.environ, "QT_QPA_PLATFORM": "offscreen"})
    assert result.returncode == 0, result.stdout + result.stderr
    assert re.search(r"^pure-Qt probe: \d+ checks passed \(PyQt 6\.", result.stdout, re.MULTILINE), result.stdout
