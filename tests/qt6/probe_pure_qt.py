"""The review dock's pure-Qt parts imported and exercised under PyQt6, as QGIS 4 runs them.

Run by tests/unit/test_qt6_compat.py with ``.venv-qt6/bin/python`` (PyQt6 from PyPI, no QGIS) and
``QT_QPA_PLATFORM=offscreen``. ``tests/qt6/shim`` provides ``qgis.PyQt`` as PyQt6 and stand-ins for
``qgis.core``/``qgis.gui`` that let the modules import but fail if a QGIS class is used, so what runs
here is Qt only: the unit table model inside a real QTableView, the scores table, the chip strip and
its reflow, the review panel's keyboard commands (real QKeyEvents), the chip images built from numpy
arrays, and the chip loader's thread-pool round trip with its cross-thread signal. Prints one line per
check and ``pure-Qt probe: N checks passed``; any failure raises.
"""
from __future__ import annotations

import sys
from pathlib import Path
from types import SimpleNamespace

HERE = Path(__file__).resolve().parent
REPO_ROOT = HERE.parents[1]
sys.path[:0] = [str(HERE / "shim"), str(REPO_ROOT / "build" / "pluginpath")]

import numpy as np  # noqa: E402
from PyQt6 import QtCore as PyQt6Core  # noqa: E402
from qgis.PyQt.QtCore import QEvent, QEventLoop, QModelIndex, Qt, QThreadPool, QTimer  # noqa: E402
from qgis.PyQt.QtGui import QColor, QKeyEvent, QPixmap  # noqa: E402
from qgis.PyQt.QtWidgets import QApplication, QLabel, QTableView, QTableWidget  # noqa: E402

from birdseye.birdseye_qgis.core.review.units import ADDED_PREFIX  # noqa: E402
from birdseye.birdseye_qgis.core.scoring.verdicts import CONVENTIONS  # noqa: E402
from birdseye.birdseye_qgis.gui.review.jobs import ChipLoader  # noqa: E402
from birdseye.birdseye_qgis.gui.review.model import (  # noqa: E402
    VERDICT_COLOURS,
    UnitTableModel,
    fill_scores_table,
    unit_summary_html,
)
from birdseye.birdseye_qgis.gui.review.widgets import (  # noqa: E402
    CHIP_DISPLAY_PX,
    ChipStrip,
    ReviewPanel,
    show_banner,
    show_chips,
    tool_button,
)

CHECKS = []


def check(name: str, condition: bool, detail="") -> None:
    if not condition:
        raise AssertionError(f"{name}: {detail}")
    CHECKS.append(name)
    print(f"ok  {name}")


def fake_dock():
    """What UnitTableModel and unit_summary_html read from the dock: two units and an added target."""
    keys = ["c3", "c7", f"{ADDED_PREFIX}1"]
    units = SimpleNamespace(index={"c3": 0, "c7": 1}, matched_geotags=[[12], []], n_frames=np.array([4, 2]),
                            max_score=np.array([0.91, 0.42]), n_detections=np.array([9, 3]),
                            layers_fired=[["ckpt_a", "ckpt_b"], ["ckpt_a"]])
    status = {"c3": SimpleNamespace(direct="confirmed_real", reviewed=True, conflict=False, votes={"c3": "direct"},
                                    resolved={c: "confirmed_real" for c in CONVENTIONS}),
              "c7": SimpleNamespace(direct="unreviewed", reviewed=True, conflict=True, votes={},
                                    resolved={c: "hard_negative" for c in CONVENTIONS})}
    verdict = {"c3": "confirmed_real", "c7": "uncertain", keys[2]: "added"}
    return SimpleNamespace(session=object(), units=units, entries=SimpleNamespace(position={k: i for i, k in
                                                                                           enumerate(keys)}),
                           status=status.__getitem__, display_verdict=verdict.__getitem__, current_key="c7",
                           keys=keys, run_command=lambda command: None)


def probe_unit_table(dock) -> None:
    model = UnitTableModel(dock)
    model.set_keys(dock.keys)
    view = QTableView()
    view.setModel(model)
    view.resize(500, 200)
    view.show()
    QApplication.processEvents()
    view.grab()  # paints every cell: Qt itself asks the model for every role
    check("model rows and columns", (model.rowCount(), model.columnCount()) == (3, 5))
    check("model header", model.headerData(1, Qt.Orientation.Horizontal, Qt.ItemDataRole.DisplayRole) == "Verdict")
    check("model has no children", model.rowCount(model.index(0, 0)) == 0)
    cell = lambda r, c, role=Qt.ItemDataRole.DisplayRole: model.data(model.index(r, c), role)
    check("unit number", cell(0, 0) == "1" and cell(2, 0) == "3")
    check("direct verdict", cell(0, 1) == "Confirmed real")
    check("resolved verdict with conflict mark", cell(1, 1) == "↳ Hard negative  ⚠", cell(1, 1))
    check("geotag and score", (cell(0, 2), cell(1, 2), cell(0, 4)) == ("12", "–", "0.91"))
    colour = cell(1, 1, Qt.ItemDataRole.DecorationRole)
    check("verdict colour", isinstance(colour, QColor) and colour.name() == VERDICT_COLOURS["uncertain"])
    alignment = cell(0, 3, Qt.ItemDataRole.TextAlignmentRole)
    check("numbers right-aligned", alignment == (Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter).value)
    font = Qt.ItemDataRole.FontRole
    check("current unit bold", cell(1, 2, font).bold() and cell(0, 2, font) is None)
    check("tooltip names the layers", "ckpt_a, ckpt_b" in cell(0, 3, Qt.ItemDataRole.ToolTipRole))
    check("added target row", cell(2, 1) == "Added target")
    check("invalid index", model.data(QModelIndex()) is None)
    html = unit_summary_html("c3", dock.units, dock.entries, dock.status("c3"), 0.2)
    check("unit summary", "<b>Unit 1</b>" in html and "geotag 12 within 0.20 m" in html and "9 detection(s) in" in html)


def probe_scores_table() -> None:
    table = QTableWidget(0, 5)
    post = {c: {"recall_post": "≥ 0.750", "gmcf_post": 0.5 + 0.1 * k, "c": k, "a": 0}
            for k, c in enumerate(CONVENTIONS)}
    fill_scores_table(table, {"flight A": {"recall_pre": 0.5, "n_recovered": 3, "n_in_view": 6, "gmcf_pre": 0.25,
                                           "n_hit_clusters": 2, "n_clusters": 8, "post": post}})
    check("scores rows", table.rowCount() == 3)
    check("flight title spans the table", table.item(0, 0).text() == "flight A" and table.columnSpan(0, 0) == 5)
    check("recall before review", table.item(1, 1).text() == "0.500\n(3/6)")
    check("GMCF after review", [table.item(2, c).text() for c in (2, 3, 4)] == ["0.500", "0.600", "0.700"])
    check("centred cells", table.item(1, 2).textAlignment() == Qt.AlignmentFlag.AlignCenter.value)


def probe_chip_strip() -> None:
    strip = ChipStrip()
    strip.resize(2 * (CHIP_DISPLAY_PX + 12) + 10, 400)
    strip.show()
    pixmap = QPixmap(CHIP_DISPLAY_PX, CHIP_DISPLAY_PX)
    pixmap.fill(QColor("#336699"))
    strip.set_chips([(pixmap, f"frame {i}", f"img{i}.jpg") for i in range(4)])
    QApplication.processEvents()
    cells = sorted(strip.grid.getItemPosition(strip.grid.indexOf(t))[:2] for t in strip.tiles)
    check("four chips in two by two", cells == [(0, 1), (0, 2), (1, 1), (1, 2)], cells)
    strip.resize(4 * (CHIP_DISPLAY_PX + 12) + 10, 400)
    QApplication.processEvents()
    cells = sorted(strip.grid.getItemPosition(strip.grid.indexOf(t))[:2] for t in strip.tiles)
    check("wider strip reflows to one row", cells == [(0, 1), (0, 2), (0, 3), (0, 4)], cells)
    strip.show_message("No frame shows this spot.")
    check("message replaces chips", strip.tiles == [] and strip.message.isVisible())

    legend = QLabel()
    plans = [SimpleNamespace(frame_id=17, score=0.8, image="a.jpg"), SimpleNamespace(frame_id=18, score=None,
                                                                                      image="b.jpg")]
    images = [np.full((60, 80, 3), 200, np.uint8), np.zeros((60, 80, 3), np.uint8)]
    show_chips(strip, legend, plans, images, 5, None, ["ckpt_a"])
    check("chips from numpy images", [p.size().width() for p in strip.pixmaps] == [80, 80]
          and strip.pixmaps[0].toImage().pixelColor(5, 5).red() == 200)
    check("chip legend", "2 of 5 frames" in legend.text() and "ckpt_a" in legend.text())
    show_chips(strip, legend, plans[:1], images[:1], 1, None, ["ckpt_a"], on_raster=True)
    check("a raster's chip", "cut from the raster" in legend.text() and "frames" not in legend.text()
          and any(label.text() == "raster · 0.80" for label in strip.findChildren(QLabel)))
    banner = QLabel()
    show_banner(banner, ["detections changed"], error=True)
    check("error banner", "Cannot start the review" in banner.text() and "<li>detections changed</li>" in banner.text())
    pressed = []
    button = tool_button("Next (N)", lambda: pressed.append(1), "Next unit")
    button.click()
    check("tool button", pressed == [1] and button.toolButtonStyle() == Qt.ToolButtonStyle.ToolButtonTextOnly)


def probe_review_keys(dock) -> None:
    commands = []
    dock.run_command = commands.append
    panel = ReviewPanel(dock)
    key = lambda k, mods=Qt.KeyboardModifier.NoModifier, kind=QEvent.Type.KeyPress: QKeyEvent(kind, k, mods)
    cases = [(key(Qt.Key.Key_1, Qt.KeyboardModifier.KeypadModifier), "confirmed_real"),
             (key(Qt.Key.Key_H), "hard_negative"), (key(Qt.Key.Key_Z, Qt.KeyboardModifier.ControlModifier), "undo"),
             (key(Qt.Key.Key_Right, Qt.KeyboardModifier.ShiftModifier), "next"),
             (key(Qt.Key.Key_N, Qt.KeyboardModifier.AltModifier), None), (key(Qt.Key.Key_Q), None)]
    got = [ReviewPanel.command(event) for event, _ in cases]
    check("keys to commands", got == [c for _, c in cases], got)
    override = key(Qt.Key.Key_A, kind=QEvent.Type.ShortcutOverride)
    check("shortcut override taken", panel.event(override) is True and override.isAccepted())
    QApplication.sendEvent(panel, key(Qt.Key.Key_U))
    check("key press runs the command", commands == ["uncertain"], commands)


def probe_chip_loader() -> None:
    loader = ChipLoader(QThreadPool.globalInstance(), 96)
    loop = QEventLoop()
    arrived = []
    loader.loaded.connect(lambda key: (arrived.append(key), loop.quit()))
    QTimer.singleShot(10000, loop.quit)
    loader.request("c3", lambda key: ([], 0))
    loop.exec()
    check("chips loaded on the thread pool", arrived == ["c3"] and loader.get("c3") == ([], [], 0, None), arrived)


def main() -> int:
    app = QApplication.instance() or QApplication(sys.argv[:1])
    check("qgis.PyQt is PyQt6", Qt is PyQt6Core.Qt and PyQt6Core.PYQT_VERSION_STR.startswith("6."))
    dock = fake_dock()
    probe_unit_table(dock)
    probe_scores_table()
    probe_chip_strip()
    probe_review_keys(dock)
    probe_chip_loader()
    app.processEvents()
    versions = f"PyQt {PyQt6Core.PYQT_VERSION_STR}, Qt {PyQt6Core.QT_VERSION_STR}"
    print(f"pure-Qt probe: {len(CHECKS)} checks passed ({versions})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
