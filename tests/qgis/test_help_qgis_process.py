"""``qgis_process help birdseye:<id>`` prints the help as plain text, saying what the dialog shows.

qgis_process prints ``shortHelpString()`` as it is (QGIS 3.22 to 4, src/process/qgsprocess.cpp), so the
plugin gives it plain text there (``QgsApplication.platform()`` is ``qgis_process``) and HTML in the
desktop. Run through scripts/qgis_process.sh, as a user runs `make qgis-process`.
"""
from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path

import pytest
from qgis.core import QgsApplication
from qgis.PyQt.QtGui import QTextDocument

from birdseye.processing.algorithms import base

REPO_ROOT = Path(__file__).resolve().parents[2]
WRAPPER = REPO_ROOT / "scripts" / "qgis_process.sh"
#: A numbered list with nested bullets and a paragraph inside an item; a bulleted list with bold names.
ALGORITHMS = ["refineposes", "selectarms"]
HTML_TAG = re.compile(r"</?(?:p|b|i|u|ul|ol|li|h[1-6]|code|a|br|span|div|pre|table|tr|td|th)\b[^>]*>", re.I)
HTML_ENTITY = re.compile(r"&(?:#\d+|#x[0-9a-fA-F]+|[a-zA-Z]+);")
EMPHASIS = re.compile(r"(?<![\w*])\*[^\s*](?:[^*]*?[^\s*])?\*(?![\w*])")

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def shell_help(tmp_path_factory) -> dict[str, str]:
    """The Description section of ``qgis_process help`` for each algorithm, in a fresh settings folder."""
    config = tmp_path_factory.mktemp("qgis-process-help")
    env = {k: v for k, v in os.environ.items() if k not in {"QGIS_CUSTOM_CONFIG_PATH", "QGIS_PLUGINPATH", "PYTHONPATH"}}
    env.update(BIRDSEYE_QGIS_CONFIG=str(config))
    sections = {}
    for alg_id in ALGORITHMS:
        result = subprocess.run([str(WRAPPER), "help", f"birdseye:{alg_id}"], env=env, capture_output=True,
                                text=True, timeout=120, check=False)
        assert result.returncode == 0, result.stderr
        match = re.search(r"\nDescription\n-+\n(.*?)\n-+\nArguments\n", result.stdout, re.S)
        assert match, result.stdout
        sections[alg_id] = match.group(1)
    return sections


def words(text: str) -> str:
    return " ".join(text.split())


@pytest.mark.parametrize("alg_id", ALGORITHMS)
def test_shell_help_is_plain_text(shell_help, alg_id):
    text = shell_help[alg_id]
    assert not HTML_TAG.search(text), HTML_TAG.search(text).group(0)
    assert not HTML_ENTITY.search(text), HTML_ENTITY.search(text).group(0)
    assert "`" not in text and "**" not in text and not EMPHASIS.search(text), "Markdown left in the text"
    long_lines = [line for line in text.splitlines() if len(line) > base.HELP_TEXT_WIDTH and " " in line.strip()]
    assert long_lines == [], "lines not wrapped for a terminal"


@pytest.mark.parametrize("alg_id", ALGORITHMS)
def test_shell_help_says_what_the_dialog_shows(birdseye_provider, shell_help, alg_id):
    """Every paragraph, heading and list item of the dialog's help, in the same order, and the lists
    marked: numbered items by their numbers, bullets by "-", nested ones indented."""
    dialog = QTextDocument()
    dialog.setHtml(QgsApplication.processingRegistry().algorithmById(f"birdseye:{alg_id}").shortHelpString())
    shell = words(shell_help[alg_id])
    position = 0
    for block in filter(str.strip, dialog.toPlainText().splitlines()):
        found = shell.find(words(block), position)
        assert found >= 0, f"not in the shell's help (in this order): {block!r}"
        position = found + len(words(block))
    lines = shell_help[alg_id].splitlines()
    if alg_id == "refineposes":
        assert [line[:3] for line in lines if re.match(r"\d\. ", line)] == ["1. ", "2. ", "3. ", "4. ", "5. "]
        assert any(line.startswith("   - a calibrated camera") for line in lines), "a nested item, indented"
        assert any(line.startswith("   The report says which was done") for line in lines), \
            "an item's second paragraph, under the item"
    else:
        assert any(line.startswith("- max_f1: the highest f1_geo") for line in lines)
