"""Shared base of every BirdsEye Processing algorithm: naming, groups, help, errors, progress."""
from __future__ import annotations

import functools
import html
import math
import os
import re
import sys
import textwrap
from pathlib import Path
from typing import NamedTuple

from qgis.core import (
    QgsApplication,
    QgsProcessingAlgorithm,
    QgsProcessingException,
    QgsProcessingOutputLayerDefinition,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterFolderDestination,
    QgsProcessingParameterNumber,
    QgsProcessingParameterRasterDestination,
    QgsProcessingParameterVectorDestination,
    QgsProperty,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP, QCoreApplication
from qgis.PyQt.QtGui import QIcon, QTextCharFormat, QTextDocument, QTextFormat, QTextListFormat

from ...birdseye_qgis import dependencies
from ...birdseye_qgis.__about__ import HELP_DIR, ICON_PATH
from ...birdseye_qgis.core.errors import Cancelled, InputError
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE

GROUPS = {
    "field": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "1 · Field data"),
    "plan": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "2 · Flight planning"),
    "labels": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "3 · Training labels"),
    "detect": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "4 · Detection and review"),
    "design": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "5 · Platform design"),
    "simulate": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "6 · Simulation"),
}
#: Each group's algorithms in workflow order. The toolbox sorts a group's algorithms by display name, so each
#: is shown as "<group>.<step> · <name>" ("1.2 · Import flight log"); the ids stay as they are (they are public).
WORKFLOW = {
    "field": ("importgeotags", "importflightlog", "importdjiimages", "importcameras", "refineposes", "processodm",
              "preparefieldsurvey", "surveyreport", "partitionfield"),
    "plan": ("planflight",),
    "labels": ("writelabels", "writelabelsraster", "traindetector"),
    "detect": ("detect", "detectraster", "clusterdetections", "evaluatedetections", "comparedetectors",
               "sweepoperatingpoints", "screencheckpoints", "selectarms", "sealpreregistration"),
    "design": ("sensorbound", "montecarlobound", "terrainslope"),
    "simulate": ("simulatecampaign",),
}
#: Units a parameter's label names in brackets ("Feature image size (px, longer side)"), for range messages.
LABEL_UNIT = re.compile(r"[(\[]\s*(px|cm/px|frames/s|m/s|cm|m|deg|degrees|°|%|s|min|minutes|Hz|dB)[\s,;)\]]")
#: Decimals a number box shows for the unit in its label (QGIS shows 6: "10.000000" px); more where the default
#: or the smallest value allowed needs them (a focal length 4264.4945 px, EPS 0.025 m). Without a unit: 3
#: (thresholds, fractions).
UNIT_DECIMALS = {"px": 1, "cm/px": 2, "frames/s": 1, "m/s": 1, "cm": 1, "m": 2, "deg": 1, "degrees": 1, "°": 1,
                 "%": 0, "s": 1, "min": 1, "minutes": 1, "Hz": 1, "dB": 1}
UNITLESS_DECIMALS = 3


class BirdsEyeAlgorithm(QgsProcessingAlgorithm):
    """Subclasses set ``ALG_ID``, ``DISPLAY_NAME`` (in ``QT_TRANSLATE_NOOP`` with the class name as context,
    so ``make translations`` finds it) and ``GROUP`` (a key of :data:`GROUPS`).

    Help text lives in ``resources/help/<ALG_ID>.md`` (CommonMark: paragraphs, ``##`` headings, nested
    ``-`` and ``1.`` lists, ``**bold**``, ``*italics*``, ``code``, links; no tables or HTML), so it is
    easy to review and translate.
    """

    ALG_ID = ""
    DISPLAY_NAME = ""
    GROUP = ""

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if "processAlgorithm" in cls.__dict__:
            cls.processAlgorithm = _explaining_missing_packages(cls.__dict__["processAlgorithm"])

    def tr(self, text: str) -> str:
        return QCoreApplication.translate(type(self).__name__, text)

    def addParameter(self, parameter, createOutput=True):  # noqa: N802, N803 — QGIS's names
        """QGIS's, giving a decimal number's box the decimals its unit needs (:func:`number_decimals`) unless the
        parameter names its own (metadata ``widget_wrapper.decimals``)."""
        if isinstance(parameter, QgsProcessingParameterNumber) and parameter.dataType() == NUMBER_DOUBLE:
            widget = dict(parameter.metadata().get("widget_wrapper") or {})
            widget.setdefault("decimals", number_decimals(parameter))
            parameter.setMetadata({**parameter.metadata(), "widget_wrapper": widget})
        return super().addParameter(parameter, createOutput)

    def canExecute(self):  # noqa: N802 — QGIS's name
        """Refused, saying what to install, while a package this algorithm needs on every run is missing
        (``dependencies.USES``); the toolbox, the locator and models ask before opening or running."""
        missing = dependencies.missing_for(self.ALG_ID)
        return (False, missing_packages_message(missing)) if missing else (True, "")

    def name(self) -> str:
        return self.ALG_ID

    def displayName(self) -> str:  # noqa: N802 — QGIS's name
        return f"{self.workflow_step()} · {self.tr(self.DISPLAY_NAME)}"

    def workflow_step(self) -> str:
        """"<group>.<step>": the group's number and this algorithm's place in it (:data:`WORKFLOW`)."""
        if self.ALG_ID not in WORKFLOW.get(self.GROUP, ()):
            raise LookupError(f"{self.ALG_ID} has no place in base.WORKFLOW[{self.GROUP!r}]: add it there")
        return f"{list(GROUPS).index(self.GROUP) + 1}.{WORKFLOW[self.GROUP].index(self.ALG_ID) + 1}"

    def group(self) -> str:
        return QCoreApplication.translate("BirdsEyeAlgorithm", GROUPS[self.GROUP])

    def groupId(self) -> str:
        return self.GROUP

    def icon(self) -> QIcon:
        return QIcon(str(ICON_PATH))

    def createInstance(self):
        return type(self)()

    def shortHelpString(self) -> str:
        """The algorithm's help (:func:`help_markdown`): HTML for the Processing dialog, which shows it as
        rich text; plain text for ``qgis_process help``, which prints it as it is (every QGIS release)."""
        markdown = help_markdown(self.ALG_ID)
        if QgsApplication.platform() == "qgis_process":
            return markdown_to_text(markdown)
        return markdown_to_html(markdown)

    def helpUrl(self) -> str:
        return ""

    def checkParameterValues(self, parameters, context):  # noqa: N802 — QGIS's name
        """QGIS's checks, after two of our own that say what QGIS's "Incorrect parameter value" leaves out: a
        number outside its range (with the range and unit), and an output path that cannot be written (a file
        where a folder goes, a folder where a file goes, a folder without write permission)."""
        for definition in self.parameterDefinitions():
            value = parameters.get(definition.name())
            problem = (self.range_problem(definition, value) if isinstance(definition, QgsProcessingParameterNumber)
                       else self.output_problem(definition, value))
            if problem:
                return False, problem
        return super().checkParameterValues(parameters, context)

    @staticmethod
    def range_problem(definition, value) -> str:
        """Why the number ``value`` is outside ``definition``'s range ("MATCH_SIZE_PX must be between 400 and
        10000 px, got 50"), or "" (in range, empty, not a number: QGIS's own check then says)."""
        try:
            number = float(value)
        except (TypeError, ValueError):
            return ""
        lo, hi = definition.minimum(), definition.maximum()
        if not math.isfinite(number) or lo <= number <= hi:
            return ""
        unit = LABEL_UNIT.search(definition.description())
        unit = f" {unit.group(1)}" if unit else ""
        bounded = [abs(bound) < 1e300 for bound in (lo, hi)]
        if all(bounded):
            text = QCoreApplication.translate(
                "BirdsEyeAlgorithm", "{name} must be between {lo:g} and {hi:g}{unit}, got {value:g}")
        elif bounded[0]:
            text = QCoreApplication.translate("BirdsEyeAlgorithm",
                                              "{name} must be at least {lo:g}{unit}, got {value:g}")
        else:
            text = QCoreApplication.translate("BirdsEyeAlgorithm", "{name} must be at most {hi:g}{unit}, got {value:g}")
        return text.format(name=definition.name(), lo=lo, hi=hi, unit=unit, value=number)

    @staticmethod
    def output_problem(definition, value) -> str:
        """Why an output path given for ``definition`` cannot be written, or "" (fine, temporary, not a file
        path, or for QGIS to judge)."""
        if isinstance(value, QgsProcessingOutputLayerDefinition):
            value = value.sink
        if isinstance(value, QgsProperty):
            value = value.staticValue()  # None for an expression, which only the run can evaluate
        if not isinstance(value, str) or not os.path.isabs(value):
            return ""  # empty, TEMPORARY_OUTPUT, memory:, a provider's URI: QGIS handles these
        path = Path(value)
        if isinstance(definition, QgsProcessingParameterFolderDestination):
            if path.exists() and not path.is_dir():
                return QCoreApplication.translate(
                    "BirdsEyeAlgorithm", "{name}: {path} is a file; give a folder (a new one is made where none "
                    "is).").format(name=definition.name(), path=path)
        elif isinstance(definition, (QgsProcessingParameterFileDestination, QgsProcessingParameterFeatureSink,
                                     QgsProcessingParameterRasterDestination,
                                     QgsProcessingParameterVectorDestination)):
            if path.is_dir():
                return QCoreApplication.translate(
                    "BirdsEyeAlgorithm", "{name}: {path} is a folder; give a file name.").format(
                    name=definition.name(), path=path)
        else:
            return ""
        existing = next(p for p in (path, *path.parents) if p.exists())
        if not os.access(existing, os.W_OK):
            return QCoreApplication.translate(
                "BirdsEyeAlgorithm", "{name}: {path} cannot be written ({folder} is read-only for you); choose "
                "another place.").format(name=definition.name(), path=path, folder=existing)
        return ""

    # -------------------------------------------------------------- helpers for subclasses
    @staticmethod
    def user_error(exc: Exception) -> QgsProcessingException:
        """A QgsProcessingException carrying an input error's message (file, row, field)."""
        return QgsProcessingException(str(exc))

    @staticmethod
    def progress_callbacks(feedback, start: float = 0.0, end: float = 100.0):
        """(progress(fraction), is_canceled()) callables for core functions that take them."""

        def progress(fraction: float) -> None:
            if feedback is not None:
                feedback.setProgress(start + (end - start) * max(0.0, min(1.0, fraction)))

        def is_canceled() -> bool:
            return feedback is not None and feedback.isCanceled()

        return progress, is_canceled

    def run_core(self, function, *args, **kwargs):
        """Call core code, turning its input errors into messages a user can act on."""
        try:
            return function(*args, **kwargs)
        except InputError as exc:
            raise self.user_error(exc) from exc
        except Cancelled:
            raise QgsProcessingException(self.tr("Cancelled by the user.")) from None


def number_decimals(parameter) -> int:
    """The decimals a number box shows: its label's unit's (:data:`UNIT_DECIMALS`), or more where its default or
    smallest allowed value needs them, at most 6."""
    unit = LABEL_UNIT.search(parameter.description())
    wanted = UNIT_DECIMALS.get(unit.group(1), UNITLESS_DECIMALS) if unit else UNITLESS_DECIMALS
    for value in (parameter.defaultValue(), parameter.minimum()):
        try:
            text = f"{float(value):.6f}".rstrip("0")
        except (TypeError, ValueError):
            continue
        if abs(float(value)) < 1e300:
            wanted = max(wanted, len(text.split(".")[1]))
    return min(wanted, 6)


def rounded(values: dict, decimals: dict) -> dict:
    """``values`` with each number named in ``decimals`` rounded to that many decimals (None stays None), so a
    layer or a result holds a figure as precisely as it means something (0.01 px, 1 mm) rather than 15 digits."""
    return {k: round(float(v), decimals[k]) if k in decimals and isinstance(v, float) else v
            for k, v in values.items()}


def file_error_message(exc: OSError) -> str:
    """A file-system error (one that names its file) as a sentence naming the path(s) and the system's reason."""
    paths = " → ".join(str(p) for p in (exc.filename, exc.filename2) if p)
    return QCoreApplication.translate(
        "BirdsEyeAlgorithm", "{paths}: {reason}. Check that the path is right, that its folder can be written, and "
        "that no file has the name a folder needs (or the other way round).").format(
        paths=paths, reason=exc.strerror or exc.__class__.__name__)


def missing_packages_message(packages) -> str:
    installable = [p for p in packages if p.available]
    unavailable = [p for p in packages if not p.available]
    parts = []
    if installable:
        parts.append(QCoreApplication.translate(
            "BirdsEyeAlgorithm",
            "This algorithm needs the Python package(s) {names}, which the Python QGIS runs does not have. In "
            "QGIS, choose BirdsEye › Install dependencies… to install them; or install them yourself: "
            "python -m pip install {pins}").format(names=", ".join(p.distribution for p in installable),
                                                   pins=" ".join(f'"{p.requirement}"' for p in installable)))
    if unavailable:
        parts.append(QCoreApplication.translate(
            "BirdsEyeAlgorithm",
            "This algorithm needs the Python package(s) {names}, which have no release for the Python QGIS "
            "runs (Python {version}); it runs in a QGIS with a newer Python.").format(
                names=", ".join(p.distribution for p in unavailable), version="%d.%d" % sys.version_info[:2]))
    return " ".join(parts)


def _explaining_missing_packages(process_algorithm):
    """``processAlgorithm`` that first checks :meth:`BirdsEyeAlgorithm.canExecute` (``processing.run``
    and ``qgis_process`` do not ask it), turns the import error of a package needed only for some
    inputs (``dependencies.USES``, ``sometimes``) into the same message, and a file-system error no step
    caught (a file where a folder goes, no permission, a full disk: an OSError naming its file) into a
    message naming the path."""

    @functools.wraps(process_algorithm)
    def process(self, parameters, context, feedback):
        can_execute, message = self.canExecute()
        if not can_execute:
            raise QgsProcessingException(message)
        try:
            return process_algorithm(self, parameters, context, feedback)
        except ModuleNotFoundError as exc:
            package = dependencies.package_for_module(exc.name or "")
            if package is None:
                raise
            raise QgsProcessingException(missing_packages_message([package])) from exc
        except OSError as exc:
            if not exc.filename:  # not about a file: a network error, say, which its algorithm reports itself
                raise
            raise QgsProcessingException(file_error_message(exc)) from exc

    return process


# ------------------------------------------------------------------------------------ help texts
# resources/help/<alg_id>.md is CommonMark, parsed by Qt's own Markdown reader (QTextDocument.setMarkdown,
# Qt >= 5.14) and written out from Qt's document: as HTML for the Processing dialog, as plain text for
# qgis_process. Both come from one parse, so they say the same.

#: Column at which the plain-text help (``qgis_process help``) wraps.
HELP_TEXT_WIDTH = 79


def help_context(alg_id: str) -> str:
    """Translation context of the help text of ``birdseye:<alg_id>``; `make translations` files every
    block of ``resources/help/<alg_id>.md`` under it (scripts/help_catalogue.py)."""
    return f"help:{alg_id}"


def help_blocks(markdown: str) -> list[str]:
    """The translatable units of a help text: its blocks, split at blank lines, except where the next
    line is indented (a list item's further paragraphs and sub-lists stay in the item's block).

    Joined again with one blank line between them they are the same Markdown, translated or not."""
    return [block.rstrip() for block in re.split(r"\n\s*\n(?=\S)", markdown.strip())]


def help_markdown(alg_id: str) -> str:
    """The help text of ``birdseye:<alg_id>`` (Markdown), each block in the user's language where the
    plugin's translation has it, else in English; "" when the algorithm has no help file."""
    path = HELP_DIR / f"{alg_id}.md"
    if not path.is_file():
        return ""
    context = help_context(alg_id)
    return "\n\n".join(QCoreApplication.translate(context, block)
                       for block in help_blocks(path.read_text(encoding="utf-8")))


def markdown_to_html(markdown: str) -> str:
    """Markdown as HTML for the Processing dialog's help panel, on one line.

    Only structure and emphasis (``h2``–``h6`` for ``#``–``#####``, ``p``, ``ul``/``ol`` nested as the
    Markdown nests them, ``b``, ``i``, ``code``, ``a``), no styles or fonts: the dialog's own style sheet
    sets the look, and its ``<h2>`` title (the algorithm's name) stays the top heading. A list item's text
    is a ``<p>`` too, which QGIS 3.22's style sheet colours as it colours paragraphs (it leaves ``li``
    alone). One line, because the dialog wraps each line of the help string in a ``<p>`` of its own."""
    out: list[str] = []
    lists: list[str] = []  # "ul"/"ol" of the lists around the current block, outermost first; each has an open <li>
    for block in _markdown_blocks(markdown):
        inline = _inline_html(block.runs, bold=block.kind != "heading")
        while len(lists) > (block.depth if block.kind != "heading" else 0):
            out.append(f"</li></{lists.pop()}>")
        if block.kind == "item":
            if len(lists) == block.depth and block.starts_list:  # another list follows at this level
                out.append(f"</li></{lists.pop()}>")
            if len(lists) == block.depth:
                out.append("</li><li>")
            while len(lists) < block.depth:
                tag = "ol" if block.marker[0].isdigit() else "ul"
                start = int(block.marker.rstrip(".)")) if tag == "ol" else 1
                out.append(f'<{tag} start="{start}"><li>' if start != 1 else f"<{tag}><li>")
                lists.append(tag)
        if block.kind == "heading":
            level = min(block.depth + 1, 6)
            out.append(f"<h{level}>{inline}</h{level}>")
        else:
            out.append(f"<p>{inline}</p>")
    out.extend(f"</li></{tag}>" for tag in reversed(lists))
    return "".join(out)


def markdown_to_text(markdown: str, width: int = HELP_TEXT_WIDTH) -> str:
    """Markdown as plain text for a terminal: paragraphs wrapped at ``width`` columns, headings
    underlined with ``=``, list items marked ``-`` or numbered and indented by nesting, no emphasis marks;
    a link whose text is not its address is followed by the address in parentheses."""
    lines: list[str] = []
    text_column = {0: 0}  # list depth -> column where the text of the current item at that depth starts
    previous = None
    for block in _markdown_blocks(markdown):
        text = _inline_text(block.runs)
        in_same_list = block.kind == "item" and previous == "item" and not (block.starts_list and block.depth == 1)
        if lines and not in_same_list:
            lines.append("")  # a blank line between blocks; a list's items (and its sub-lists) stay together
        if block.kind == "heading":
            lines += [text, "=" * len(text)]
        elif block.kind == "item":
            first = " " * text_column.get(block.depth - 1, 0) + block.marker + " "
            text_column[block.depth] = len(first)
            lines += _wrap(text, first, " " * len(first), width)
        else:
            indent = " " * text_column.get(block.depth, 0)
            lines += _wrap(text, indent, indent, width)
        previous = block.kind
    return "\n".join(lines)


def _wrap(text: str, first: str, rest: str, width: int) -> list[str]:
    """Lines of at most ``width`` columns, breaking only at spaces (a long path or name stays whole)."""
    return textwrap.wrap(text, width, initial_indent=first, subsequent_indent=rest, break_long_words=False,
                         break_on_hyphens=False) or [first.rstrip()]


class _Block(NamedTuple):
    """A block of a Markdown document as Qt read it."""

    kind: str  #: "heading", "item" (of a list) or "paragraph"
    depth: int  #: heading level; list nesting of an item (1 outermost) or of the item a paragraph continues (0: none)
    marker: str  #: an item's "-" or number ("1."); else ""
    runs: list  #: [(text, QTextCharFormat)]
    starts_list: bool = False  #: the first item of its list


def _markdown_document(markdown: str) -> QTextDocument:
    """Markdown parsed by Qt, CommonMark without HTML: Qt 5.15 and 6 drop every word after a tag that is
    never closed (``<model>.pt`` outside backticks), so ``<`` stays text. PyQt6 cannot combine this
    flag with the GitHub dialect (its enum flag drops the combination to 0): pipe tables are not read."""
    document = QTextDocument()
    document.setMarkdown(markdown, QTextDocument.MarkdownFeature.MarkdownNoHTML)
    return document


def _markdown_blocks(markdown: str):
    """The :class:`_Block` s of the Markdown, in order."""
    document = _markdown_document(markdown)
    block = document.begin()
    while block.isValid():
        runs = []
        fragments = block.begin()
        while not fragments.atEnd():
            fragment = fragments.fragment()
            runs.append((fragment.text(), fragment.charFormat()))
            fragments += 1
        text_list = block.textList()
        heading_level = block.blockFormat().headingLevel()
        if text_list is not None:
            ordered = text_list.format().style() == QTextListFormat.Style.ListDecimal
            yield _Block("item", text_list.format().indent(), text_list.itemText(block) if ordered else "-", runs,
                         text_list.itemNumber(block) == 0)
        elif heading_level > 0:
            yield _Block("heading", heading_level, "", runs)
        elif runs:
            yield _Block("paragraph", block.blockFormat().indent(), "", runs)
        block = block.next()


def _is_code(char_format: QTextCharFormat) -> bool:
    # Qt's Markdown reader gives only code a font of its own: the system's fixed-pitch font, which is not
    # always flagged fixed pitch (Qt 5.15 leaves the flag off).
    return char_format.fontFixedPitch() or char_format.hasProperty(QTextFormat.Property.FontFamilies)


def _inline_html(runs, bold: bool = True) -> str:
    """A block's runs as HTML; ``bold=False`` for headings, which are bold by themselves."""
    parts = []
    for text, char_format in runs:
        piece = html.escape(text, quote=False)
        if _is_code(char_format):
            piece = f"<code>{piece}</code>"
        if char_format.fontItalic():
            piece = f"<i>{piece}</i>"
        if bold and char_format.font().bold():
            piece = f"<b>{piece}</b>"
        if char_format.isAnchor() and char_format.anchorHref():
            piece = f'<a href="{html.escape(char_format.anchorHref())}">{piece}</a>'
        parts.append(piece)
    return "".join(parts)


def _inline_text(runs) -> str:
    parts = []
    for text, char_format in runs:
        href = char_format.anchorHref() if char_format.isAnchor() else ""
        parts.append(f"{text} ({href})" if href and href != text else text)
    return "".join(parts)
