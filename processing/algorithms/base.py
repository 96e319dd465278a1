"""Shared base of every BirdsEye Processing algorithm: naming, groups, help, errors, progress."""
from __future__ import annotations

import functools
import sys

from qgis.core import QgsProcessingAlgorithm, QgsProcessingException
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP, QCoreApplication
from qgis.PyQt.QtGui import QIcon

from ...birdseye_qgis import dependencies
from ...birdseye_qgis.__about__ import HELP_DIR, ICON_PATH
from ...birdseye_qgis.core.errors import Cancelled, InputError

GROUPS = {
    "field": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "1 · Field data"),
    "plan": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "2 · Flight planning"),
    "labels": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "3 · Training labels"),
    "detect": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "4 · Detection and review"),
    "design": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "5 · Platform design"),
    "simulate": QT_TRANSLATE_NOOP("BirdsEyeAlgorithm", "6 · Simulation"),
}


class BirdsEyeAlgorithm(QgsProcessingAlgorithm):
    """Subclasses set ``ALG_ID``, ``DISPLAY_NAME`` (in ``QT_TRANSLATE_NOOP`` with the class name as context,
    so ``make translations`` finds it) and ``GROUP`` (a key of :data:`GROUPS`).

    Help text lives in ``resources/help/<ALG_ID>.md`` (Markdown-ish: blank-line paragraphs, ``- ``
    bullets, ``**bold**``), so it is easy to review and translate.
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

    def canExecute(self):  # noqa: N802 — QGIS's name
        """Refused, saying what to install, while a package this algorithm needs on every run is missing
        (``dependencies.USES``); the toolbox, the locator and models ask before opening or running."""
        missing = dependencies.missing_for(self.ALG_ID)
        return (False, missing_packages_message(missing)) if missing else (True, "")

    def name(self) -> str:
        return self.ALG_ID

    def displayName(self) -> str:
        return self.tr(self.DISPLAY_NAME)

    def group(self) -> str:
        return QCoreApplication.translate("BirdsEyeAlgorithm", GROUPS[self.GROUP])

    def groupId(self) -> str:
        return self.GROUP

    def icon(self) -> QIcon:
        return QIcon(str(ICON_PATH))

    def createInstance(self):
        return type(self)()

    def shortHelpString(self) -> str:
        path = HELP_DIR / f"{self.ALG_ID}.md"
        if not path.is_file():
            return ""
        return markdown_to_html(self.tr(path.read_text(encoding="utf-8")))

    def helpUrl(self) -> str:
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
    and ``qgis_process`` do not ask it) and turns the import error of a package needed only for some
    inputs (``dependencies.USES``, ``sometimes``) into the same message."""

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

    return process


def markdown_to_html(text: str) -> str:
    """The small Markdown subset our help files use, as the HTML the Processing dialog shows."""
    import html
    import re

    blocks = [b.strip() for b in re.split(r"\n\s*\n", text.strip()) if b.strip()]
    out = []
    for block in blocks:
        lines = block.splitlines()
        esc = [re.sub(r"\*\*(.+?)\*\*", r"<b>\1</b>", html.escape(line)) for line in lines]
        esc = [re.sub(r"`(.+?)`", r"<code>\1</code>", line) for line in esc]
        if lines[0].startswith("#"):
            out.append(f"<h3>{esc[0].lstrip('#').strip()}</h3>")
            esc = esc[1:]
            lines = lines[1:]
            if not esc:
                continue
        if all(line.lstrip().startswith("- ") for line in lines):
            items = "".join(f"<li>{line.lstrip()[2:]}</li>" for line in esc)
            out.append(f"<ul>{items}</ul>")
        else:
            out.append(f"<p>{' '.join(esc)}</p>")
    return "\n".join(out)
