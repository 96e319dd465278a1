"""The session driver every desktop probe shares (``qgis --code <name>_probe.py``, started by tests/gui's tests).

A probe's session is a generator: each ``yield`` hands :func:`play` a :class:`Wait`, a condition polled every 100 ms
on the Qt event loop (so QGIS keeps painting and running its tasks meanwhile) for at most ``timeout_s``, followed by
``settle_ms`` more for the widgets to paint before the next screenshot. A condition that never comes true is named in
the report's ``timeouts`` and the session goes on. Every exception is recorded in the report's ``errors``, never shown
in a dialog, so the desktop never waits for a click. At the end :func:`finish` writes the JSON report, closes the
project and quits QGIS.

A ``--code`` script has no ``__file__`` to find this module by: a probe imports it from ``BIRDSEYE_PROBE_DIR`` (this
folder; ``test_desktop.desktop_env`` sets it)::

    sys.path.insert(0, os.environ["BIRDSEYE_PROBE_DIR"])
    from probe_session import Wait, play  # noqa: E402
"""
import json
import os
import time
import traceback

from qgis.core import QgsApplication
from qgis.PyQt.QtCore import QTimer
from qgis.PyQt.QtWidgets import QTabWidget, QWidget
from qgis.utils import iface


class Wait:
    """Wait until ``ready()`` is true (at most ``timeout_s``; ``what`` names it in the report), then ``settle_ms``
    more for painting."""

    def __init__(self, ready, timeout_s: float, what: str, settle_ms: int = 0):
        self.ready, self.timeout_s, self.what, self.settle_ms = ready, timeout_s, what, settle_ms


def settle(ms: int, what: str = "painting") -> Wait:
    """Nothing to wait for but ``ms`` of painting."""
    return Wait(lambda: True, 0, what, settle_ms=ms)


def canvas_idle(settle_ms: int = 800) -> Wait:
    """The map canvas done drawing (at most 30 s), and painted."""
    canvas = iface.mapCanvas()
    return Wait(lambda: not canvas.isDrawing(), 30, "map canvas drawing", settle_ms=settle_ms)


def file_stem(layer) -> str:
    """The name of the file a layer is read from, without its extension ("" for none)."""
    return os.path.splitext(os.path.basename(layer.source().split("|")[0]))[0] if layer is not None else ""


def message_log() -> dict:
    """Text of every tab of QGIS's Log Messages panel (it records from start-up on)."""
    tabs = {}
    for viewer in [w for w in iface.mainWindow().findChildren(QWidget)
                   if w.metaObject().className() == "QgsMessageLogViewer"]:
        for tab_widget in viewer.findChildren(QTabWidget):
            for i in range(tab_widget.count()):
                page = tab_widget.widget(i)
                tabs[tab_widget.tabText(i)] = page.toPlainText() if hasattr(page, "toPlainText") else ""
    return tabs


def finish(result: dict, result_path: str, last_records=None) -> None:
    """Let ``last_records()`` add the probe's last records, write ``result`` to ``result_path`` and quit QGIS."""
    if last_records is not None:
        try:
            last_records()
        except Exception:  # noqa: BLE001 — reported to the test
            result["errors"].append(traceback.format_exc())
    with open(result_path, "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1)
    # Close the project while the window still exists: QGIS 3.22 crashes (signal 11 in
    # setMapStyleDockLayer) when it removes a project's layers during its own shutdown.
    iface.newProject(False)
    QTimer.singleShot(500, QgsApplication.instance().quit)


def play(steps, result: dict, result_path: str, last_records=None, start_ms: int = 1000) -> None:
    """Play the session ``steps`` (a generator of :class:`Wait`) once QGIS has been up for ``start_ms``, then
    :func:`finish` with ``last_records``. ``result`` needs an ``errors`` list."""
    def done():
        QTimer.singleShot(200, lambda: finish(result, result_path, last_records))

    def drive(waiting=None, started=None) -> None:
        """Advance the session to its next wait, then poll that wait every 100 ms."""
        try:
            if waiting is not None:
                if not waiting.ready():
                    if time.monotonic() - started < waiting.timeout_s:
                        QTimer.singleShot(100, lambda: drive(waiting, started))
                        return
                    result.setdefault("timeouts", []).append(waiting.what)
                if waiting.settle_ms and not getattr(waiting, "settled", False):
                    waiting.settled = True  # let the widgets paint before the next screenshot
                    QTimer.singleShot(waiting.settle_ms, lambda: drive(waiting, started))
                    return
            following = next(steps)
            QTimer.singleShot(0, lambda: drive(following, time.monotonic()))
        except StopIteration:
            done()
        except Exception:  # noqa: BLE001 — reported to the test
            result["errors"].append(traceback.format_exc())
            done()

    QTimer.singleShot(start_ms, drive)
