"""Help texts as the Processing dialog shows them (``shortHelpString`` in the desktop, rendered by Qt's
Markdown reader in ``processing/algorithms/base.py``).

The list structure a help file should have is read from its source lines (indentation and markers),
independently of Qt; the HTML is parsed with the standard library's parser. The dialog itself is QGIS's
``QgsProcessingAlgorithmDialogBase`` (its help panel, its style sheet and its wrapping of each line of the
help string in a ``<p>``), at the size it opens with; screenshots go to build/screenshots/help_*.png.
"""
from __future__ import annotations

import re
from html.parser import HTMLParser
from pathlib import Path

import pytest
from qgis.core import QgsApplication
from qgis.PyQt.QtGui import QImage, QPainter
from qgis.PyQt.QtWidgets import QApplication, QTextBrowser

from birdseye.birdseye_qgis.__about__ import HELP_DIR
from birdseye.processing.algorithms import base

REPO_ROOT = Path(__file__).resolve().parents[2]
SCREENSHOTS = REPO_ROOT / "build" / "screenshots"
HELP_IDS = sorted(p.stem for p in HELP_DIR.glob("*.md"))
ALGORITHM_IDS = sorted(p.stem for p in (REPO_ROOT / "processing" / "algorithms").glob("*.py")
                       if p.stem not in {"__init__", "base"})
LIST_ITEM = re.compile(r"^( *)(-|\*|\+|\d+[.)]) ")
EMPHASIS = re.compile(r"(?<![\w*])\*[^\s*](?:[^*]*?[^\s*])?\*(?![\w*])")
HTML_TAG_NAMES = ("h1", "h2", "h3", "h4", "h5", "h6", "p", "ul", "ol", "li", "b", "i", "code", "a")


# ------------------------------------------------------------------------------ what the source says
def source_items(markdown: str) -> list[tuple[int, bool]]:
    """(nesting depth, numbered) of every list item, from the lines' indentation: an item indented
    further than the open item before it is nested in it."""
    items, open_indents = [], []
    for line in markdown.splitlines():
        match = LIST_ITEM.match(line)
        if not line.strip() or (not match and not line.startswith(" ")):
            if not match and line.strip():
                open_indents = []  # a paragraph at the margin ends every list
            continue
        if match:
            indent = len(match.group(1))
            while open_indents and open_indents[-1] >= indent:
                open_indents.pop()
            open_indents.append(indent)
            items.append((len(open_indents), match.group(2)[0].isdigit()))
    return items


class Structure(HTMLParser):
    """The tags of an HTML fragment: (list depth, kind of the innermost list) of every <li>, the other
    tags seen, and whether every tag closed in order."""

    def __init__(self, text: str):
        super().__init__(convert_charrefs=True)
        self.items, self.tags, self.stack, self.balanced, self.text = [], [], [], True, []
        self.feed(text)
        self.close()
        self.balanced &= not self.stack

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        if tag == "li":
            lists = [t for t in self.stack if t in ("ul", "ol")]
            self.items.append((len(lists), lists[-1] == "ol" if lists else None))
        self.stack.append(tag)

    def handle_endtag(self, tag):
        self.balanced &= bool(self.stack) and self.stack.pop() == tag

    def handle_data(self, data):
        self.text.append(data)


def help_html(alg_id: str) -> str:
    return base.markdown_to_html(base.help_markdown(alg_id))


# ------------------------------------------------------------------------------ the renderer
SAMPLE = """Para with *italics*, **bold**, `a <b> code`, <model>.pt outside code and a [link](https://example.org).
A second line of the same paragraph.

## Section

1. first
2. second
   - nested a
   - nested b

   second paragraph of item 2
3. third

- other list
"""


def test_markdown_to_html_keeps_structure_and_emphasis():
    assert base.markdown_to_html(SAMPLE) == (
        "<p>Para with <i>italics</i>, <b>bold</b>, <code>a &lt;b&gt; code</code>, &lt;model&gt;.pt outside code "
        'and a <a href="https://example.org">link</a>. A second line of the same paragraph.</p>'
        "<h3>Section</h3>"
        "<ol><li><p>first</p></li><li><p>second</p><ul><li><p>nested a</p></li><li><p>nested b</p></li></ul>"
        "<p>second paragraph of item 2</p></li><li><p>third</p></li></ol>"
        "<ul><li><p>other list</p></li></ul>")


def test_markdown_to_text_for_a_terminal():
    assert base.markdown_to_text(SAMPLE, width=60) == "\n".join([
        "Para with italics, bold, a <b> code, <model>.pt outside code",
        "and a link (https://example.org). A second line of the same",
        "paragraph.",
        "",
        "Section",
        "=======",
        "",
        "1. first",
        "2. second",
        "   - nested a",
        "   - nested b",
        "",
        "   second paragraph of item 2",
        "",
        "3. third",
        "",
        "- other list",
    ])


def test_long_names_are_not_broken():
    text = base.markdown_to_text("- " + "word " * 10 + "`" + "a_very_long_file_name/" * 5 + "`", width=40)
    assert "a_very_long_file_name/" * 5 in text.splitlines()[-1]


def test_help_blocks_keep_indented_continuations():
    markdown = "A\nB\n\n\n- item\n\n  more of the item\n- next\n\nC  \n"
    blocks = base.help_blocks(markdown)
    assert blocks == ["A\nB", "- item\n\n  more of the item\n- next", "C"]
    assert base.markdown_to_html("\n\n".join(blocks)) == base.markdown_to_html(markdown)


# ------------------------------------------------------------------------------ every help file
@pytest.mark.parametrize("alg_id", HELP_IDS)
def test_help_source_has_no_title_or_unsupported_markup(alg_id):
    """The dialog shows the algorithm's name above the help: a `#` title would repeat it. Pipe tables
    are not read (see base._markdown_document)."""
    lines = (HELP_DIR / f"{alg_id}.md").read_text(encoding="utf-8").splitlines()
    assert not [line for line in lines if line.startswith("# ")], "a level-1 heading (the title) in the help file"
    assert not [line for line in lines if re.match(r"^\s*\|?\s*:?-{3,}:?\s*\|", line)], "a pipe table"


@pytest.mark.parametrize("alg_id", HELP_IDS)
def test_help_html_has_no_markdown_left_and_real_lists(alg_id):
    markdown = base.help_markdown(alg_id)
    html = help_html(alg_id)
    structure = Structure(html)
    text = "".join(structure.text)
    assert "\n" not in html, "the dialog would cut the help into a paragraph per line"
    assert structure.balanced, html
    assert set(structure.tags) <= set(HTML_TAG_NAMES), set(structure.tags) - set(HTML_TAG_NAMES)
    assert "`" not in text, "a backtick left in the text"
    assert "**" not in text, "bold markup left in the text"
    assert not EMPHASIS.search(text), "a pair of emphasis asterisks left in the text (κ* alone is a symbol)"
    expected = source_items(markdown)
    assert [depth for depth, _ in structure.items] == [depth for depth, _ in expected], "list nesting differs"
    assert [numbered for _, numbered in structure.items] == [numbered for _, numbered in expected], \
        "numbered and bulleted lists differ"
    assert "h1" not in structure.tags and "h2" not in structure.tags, "the dialog's title is the only <h2>"


@pytest.mark.parametrize("alg_id", HELP_IDS)
def test_help_html_keeps_every_character_of_the_text(alg_id):
    """What the help says, character for character, once the Markdown marks (list markers, headings'
    #, ** and * around emphasis, backticks) are taken out: nothing is swallowed (Qt's reader drops the rest
    of a document after an HTML tag that is never closed, unless HTML is off) and nothing is added."""
    markdown = base.help_markdown(alg_id)
    source = re.sub(r"(?m)^\s*(?:[-*+]|\d+[.)]|#+)\s", " ", markdown).replace("**", "").replace("`", "")
    source = EMPHASIS.sub(lambda m: m.group(0)[1:-1], source)
    shown = "".join(Structure(help_html(alg_id)).text)
    assert "".join(shown.split()) == "".join(source.split())


@pytest.mark.parametrize("alg_id", ALGORITHM_IDS)
def test_desktop_help_is_the_html_without_the_title(birdseye_provider, alg_id):
    assert QgsApplication.platform() != "qgis_process"
    alg = QgsApplication.processingRegistry().algorithmById(f"birdseye:{alg_id}")
    assert alg.shortHelpString() == help_html(alg_id)
    assert not alg.shortHelpString().startswith("<h"), "the help starts with a title; the dialog shows one"
    name = re.sub(r"^[\d.]+\s*·\s*", "", alg.displayName()).split(" (")[0].casefold()  # "1.5 · Refine … (…)"
    headings = re.findall(r"<h\d>(.*?)</h\d>", alg.shortHelpString())
    assert [h for h in headings if re.sub(r"<[^>]+>", "", h).casefold().startswith(name)] == []
    italics = re.findall(r"(?<![*\w])\*([^*\s][^*]*?)\*(?![*\w])", base.help_markdown(alg_id))
    assert [i for i in italics if f"<i>{i}</i>" not in alg.shortHelpString()] == []


# ------------------------------------------------------------------------------ the dialog, as a user sees it
@pytest.fixture
def help_dialog(qgis_app, birdseye_provider):
    """QGIS's Processing dialog (its base class: the parameters panel is not needed to show the help)
    opened on a BirdsEye algorithm; returns (dialog, help browser)."""
    from qgis.gui import QgsProcessingAlgorithmDialogBase

    class HelpOnlyDialog(QgsProcessingAlgorithmDialogBase):
        pass

    dialogs = []

    def open_dialog(alg_id: str):
        dialog = HelpOnlyDialog()
        dialog.setAlgorithm(QgsApplication.processingRegistry().createAlgorithmById(f"birdseye:{alg_id}"))
        dialog.show()
        QApplication.processEvents()
        dialogs.append(dialog)
        return dialog, dialog.findChild(QTextBrowser, "textShortHelp")

    yield open_dialog
    for dialog in dialogs:
        dialog.close()
        dialog.deleteLater()


def save_full_help(browser: QTextBrowser, path: Path) -> None:
    """The whole help document at the panel's width, as the panel shows it when scrolled through."""
    document = browser.document().clone()
    document.setTextWidth(browser.viewport().width())
    image = QImage(int(document.textWidth()), int(document.size().height()) + 1, QImage.Format.Format_RGB32)
    image.fill(browser.palette().base().color())
    painter = QPainter(image)
    document.drawContents(painter)
    painter.end()
    assert image.save(str(path))


@pytest.mark.parametrize("alg_id", ["refineposes", "writelabels", "sensorbound"])
def test_dialog_shows_the_help_with_its_lists(help_dialog, alg_id):
    dialog, browser = help_dialog(alg_id)
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    assert dialog.grab().save(str(SCREENSHOTS / f"help_{alg_id}.png"))
    save_full_help(browser, SCREENSHOTS / f"help_{alg_id}_full.png")

    name = dialog.algorithm().displayName()
    shown = browser.toPlainText()
    assert shown.count(name) == 1, "the algorithm's name is shown once, as the title"
    first_sentence = base.markdown_to_text(base.help_markdown(alg_id), width=10**6).split(". ")[0]
    assert " ".join(first_sentence.split()) in " ".join(shown.split())
    document = browser.document()
    blocks = [document.findBlockByNumber(i) for i in range(document.blockCount())]
    depths = [b.textList().format().indent() for b in blocks if b.textList() is not None]
    assert depths == [depth for depth, _ in source_items(base.help_markdown(alg_id))], \
        "the dialog does not show the help's lists as nested lists"
    assert not [b.text() for b in blocks if b.textList() is None and not b.text().strip()
                and b.blockNumber() > 1], "empty paragraphs in the help panel"
