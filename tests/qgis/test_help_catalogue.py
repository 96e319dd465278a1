"""The help texts in the translation catalogue, and a translation of them used at run time.

`make translations` files every block of ``resources/help/<alg_id>.md`` (``base.help_blocks``) under the
context ``base.help_context(alg_id)`` of i18n/birdseye_en.ts (scripts/help_catalogue.py);
``shortHelpString`` asks ``QCoreApplication.translate`` for each block with that context, so a filled-in
and compiled copy of the catalogue changes the help a user reads.
"""
from __future__ import annotations

import importlib.util
import os
import shutil
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from qgis.core import QgsApplication
from qgis.PyQt.QtCore import QCoreApplication, QTranslator

from birdseye.birdseye_qgis.__about__ import HELP_DIR
from birdseye.processing.algorithms import base

REPO_ROOT = Path(__file__).resolve().parents[2]
CATALOGUE = REPO_ROOT / "i18n" / "birdseye_en.ts"
HELP_IDS = sorted(p.stem for p in HELP_DIR.glob("*.md"))


def catalogue_messages(path: Path) -> dict[str, list[tuple[str, str]]]:
    """{context: [(source, location file), …]} of a .ts file."""
    return {context.findtext("name"): [(m.findtext("source"), m.find("location").get("filename"))
                                       for m in context.findall("message")]
            for context in ET.parse(path).getroot()}


def test_every_help_file_is_in_the_catalogue_block_by_block():
    messages = catalogue_messages(CATALOGUE)
    for alg_id in HELP_IDS:
        blocks = base.help_blocks((HELP_DIR / f"{alg_id}.md").read_text(encoding="utf-8"))
        filed = messages.get(base.help_context(alg_id))
        assert filed is not None, f"{alg_id}.md is not in {CATALOGUE.name}: run make translations"
        assert [source for source, _ in filed] == blocks, \
            f"{CATALOGUE.name} holds another version of {alg_id}.md: run make translations"
        assert {location for _, location in filed} == {f"../resources/help/{alg_id}.md"}
    stale = {c for c in messages if c.startswith(base.help_context("")) and c not in
             {base.help_context(a) for a in HELP_IDS}}
    assert stale == set(), f"help texts no longer in resources/help: {sorted(stale)}"


def test_help_catalogue_script_leaves_an_up_to_date_catalogue_unchanged(tmp_path):
    """What `make translations` runs after pylupdate5: run on the committed catalogue, nothing changes
    (no duplicate contexts, the rest of the file kept byte for byte)."""
    spec = importlib.util.spec_from_file_location("help_catalogue", REPO_ROOT / "scripts" / "help_catalogue.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
    copy = tmp_path / CATALOGUE.name
    shutil.copy(CATALOGUE, copy)
    assert script.main([str(copy)]) == 0
    # the copy's locations are relative to the copy, as pylupdate5 writes them relative to the .ts file
    relocated = copy.read_text(encoding="utf-8").replace(
        f'filename="{Path(os.path.relpath(HELP_DIR, tmp_path)).as_posix()}/', 'filename="../resources/help/')
    assert relocated == CATALOGUE.read_text(encoding="utf-8")


@pytest.fixture
def french_help(tmp_path, birdseye_provider):
    """A catalogue with two blocks of selectarms.md translated (a paragraph and a list), compiled by
    lrelease as `make translations` compiles it and installed for the rest of the test."""
    lrelease = shutil.which("lrelease")
    if lrelease is None:
        pytest.skip("needs lrelease (Debian qttools5-dev-tools; make setup installs it)")
    blocks = base.help_blocks((HELP_DIR / "selectarms.md").read_text(encoding="utf-8"))
    paragraph = blocks[0]
    bullets = next(b for b in blocks if b.startswith("- **max_f1**"))
    translations = {
        paragraph: "Applique les trois règles de sélection de la méthode et écrit les trois **bras**.",
        bullets: "- **max_f1** : le plus haut *f1_geo*.\n- **max_recall** : le plus haut rappel.\n"
                 "- **lowest_review_burden** : le moins de détections par image.",
    }
    tree = ET.parse(CATALOGUE)
    context = next(c for c in tree.getroot() if c.findtext("name") == base.help_context("selectarms"))
    for message in context.findall("message"):
        if message.findtext("source") in translations:
            translation = message.find("translation")
            translation.text = translations[message.findtext("source")]
            translation.attrib.pop("type", None)
    ts, qm = tmp_path / "birdseye_fr.ts", tmp_path / "birdseye_fr.qm"
    tree.write(ts, encoding="utf-8", xml_declaration=True)
    subprocess.run([lrelease, "-silent", str(ts), "-qm", str(qm)], check=True, timeout=60)
    translator = QTranslator()
    assert translator.load(str(qm))
    QCoreApplication.installTranslator(translator)
    yield translations
    QCoreApplication.removeTranslator(translator)


def test_a_translated_help_shows_in_the_dialog(french_help):
    help_html = QgsApplication.processingRegistry().algorithmById("birdseye:selectarms").shortHelpString()
    assert "<p>Applique les trois règles de sélection de la méthode et écrit les trois <b>bras</b>.</p>" in help_html
    assert "<li><p><b>max_f1</b> : le plus haut <i>f1_geo</i>.</p></li>" in help_html
    assert "Applies the method" not in help_html and "Ties: the higher recall" not in help_html
    assert "Sweep operating points" in help_html, "blocks without a translation stay in English"
