"""What the review dock's tables show: the unit table model and the scores table."""
from __future__ import annotations

from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP, QAbstractTableModel, QModelIndex, Qt
from qgis.PyQt.QtGui import QColor, QFont
from qgis.PyQt.QtWidgets import QTableWidgetItem

from ...__about__ import tr
from ...core.review.units import ADDED_PREFIX
from ...core.scoring.verdicts import CONVENTIONS

CONVENTION_TEXT = {"positive_wins": "positive-wins", "majority_wins": "majority-wins",
                   "hard_negative_wins": "hard-negative-wins"}

VERDICT_COLOURS = {"confirmed_real": "#2e7d32", "hard_negative": "#c62828", "uncertain": "#ef8f00",
                   "unreviewed": "#757575", "added": "#00897b"}
VERDICT_TEXT = {"confirmed_real": "Confirmed real", "hard_negative": "Hard negative", "uncertain": "Uncertain",
                "unreviewed": "Unreviewed", "added": "Added target"}


def format_number(value, digits=3) -> str:
    return "–" if value is None else f"{value:.{digits}f}"


class UnitTableModel(QAbstractTableModel):
    HEADERS = ["#", "Verdict", "Geotag", "Frames", "Score"]

    def __init__(self, dock):
        super().__init__()
        self.dock = dock
        self.keys: list[str] = []

    def set_keys(self, keys):
        self.beginResetModel()
        self.keys = list(keys)
        self.endResetModel()

    def refresh(self):
        if self.keys:
            self.dataChanged.emit(self.index(0, 0), self.index(len(self.keys) - 1, len(self.HEADERS) - 1))

    def rowCount(self, parent=QModelIndex()):
        return 0 if parent.isValid() else len(self.keys)

    def columnCount(self, parent=QModelIndex()):
        return 0 if parent.isValid() else len(self.HEADERS)

    def headerData(self, section, orientation, role=Qt.ItemDataRole.DisplayRole):
        if orientation == Qt.Orientation.Horizontal and role == Qt.ItemDataRole.DisplayRole:
            return self.HEADERS[section]
        return None

    def data(self, index, role=Qt.ItemDataRole.DisplayRole):
        if not index.isValid() or self.dock.session is None or index.row() >= len(self.keys):
            return None
        key, col = self.keys[index.row()], index.column()
        d = self.dock
        if role == Qt.ItemDataRole.DisplayRole:
            return self.cell_text(key, col)
        if role == Qt.ItemDataRole.DecorationRole and col == 1:
            return QColor(VERDICT_COLOURS[d.display_verdict(key)])
        if role == Qt.ItemDataRole.ToolTipRole:
            return self.row_tooltip(key)
        if role == Qt.ItemDataRole.TextAlignmentRole and col in (0, 3, 4):
            return int(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
        if role == Qt.ItemDataRole.FontRole and key == d.current_key:
            font = QFont()
            font.setBold(True)
            return font
        return None

    def cell_text(self, key, col) -> str:
        if col == 0:
            return str(self.dock.entries.position[key] + 1)
        if key.startswith(ADDED_PREFIX):
            return ["", tr("Added target"), "", "", ""][col]
        i = self.dock.units.index[key]
        s = self.dock.status(key)
        if col == 1:
            if s.direct != "unreviewed":
                text = VERDICT_TEXT[s.direct]
            elif s.reviewed:
                text = "↳ " + VERDICT_TEXT[s.resolved["majority_wins"]]
            else:
                text = "—"
            return text + ("  ⚠" if s.conflict else "")
        if col == 2:
            ids = self.dock.units.matched_geotags[i]
            return ", ".join(map(str, ids)) if ids else "–"
        if col == 3:
            return str(int(self.dock.units.n_frames[i]))
        return format_number(float(self.dock.units.max_score[i]), 2)

    def row_tooltip(self, key) -> str:
        if key.startswith(ADDED_PREFIX):
            return key
        return f"{key}\n{tr('fired by')}: {', '.join(self.dock.units.layers_fired[self.dock.units.index[key]])}"


SCORE_NAMES = (QT_TRANSLATE_NOOP("@default", "recall"), QT_TRANSLATE_NOOP("@default", "GMCF"))


def size_score_names(t) -> None:
    """Column 0 of the scores table as wide as its row names (the layer titles span the table)."""
    t.setColumnWidth(0, max(t.fontMetrics().horizontalAdvance(tr(n)) for n in SCORE_NAMES) + 12)


def fill_scores_table(t, result) -> None:
    """One block per flight: recall and GMCF before review and after it under each convention."""
    t.clearSpans()
    t.setRowCount(3 * len(result))
    names = tuple(tr(n) for n in SCORE_NAMES)
    bold = QFont()
    bold.setBold(True)
    for k, (name, d) in enumerate(result.items()):
        post = d.get("post", {})
        title = QTableWidgetItem(name)
        title.setFont(bold)
        title.setBackground(QColor("#eef1f5"))
        t.setItem(3 * k, 0, title)
        t.setSpan(3 * k, 0, 1, 5)
        # The counts under the value: on one line, counts of two digits or more widen the column past what the
        # narrowest dock leaves the conventions' headers.
        recall = [names[0], f"{format_number(d['recall_pre'])}\n({d['n_recovered']}/{d['n_in_view']})"] + \
            [post.get(c, {}).get("recall_post") or "–" for c in CONVENTIONS]
        gmcf = [names[1], f"{format_number(d['gmcf_pre'])}\n({d['n_hit_clusters']}/{d['n_clusters']})"] + \
            [format_number(post.get(c, {}).get("gmcf_post")) for c in CONVENTIONS]
        tips = [f"c = {post[c]['c']} (confirmed, not hit), a = {post[c]['a']} (added)" if c in post else ""
                for c in CONVENTIONS]
        for r, cells in ((3 * k + 1, recall), (3 * k + 2, gmcf)):
            for c, text in enumerate(cells):
                item = QTableWidgetItem(text)
                item.setTextAlignment(Qt.AlignmentFlag.AlignCenter if c
                                      else Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter)
                if c >= 2:
                    item.setToolTip(tips[c - 2])
                t.setItem(r, c, item)
    size_score_names(t)
    t.resizeRowsToContents()
    fit_scores_height(t)


def fit_scores_height(t) -> None:
    """The scores table exactly as tall as its rows (none before the first scores: its header alone)."""
    t.setFixedHeight(t.horizontalHeader().sizeHint().height() +
                     sum(t.rowHeight(i) for i in range(t.rowCount())) + 2 * t.frameWidth())


def unit_summary_html(key, units, entries, status, eps_pred_m, on_raster: bool = False) -> str:
    """What the dock says about a unit: its geotag match, the layers that fired (and where: in how many frames,
    or on the raster for detections found on one), votes and resolutions."""
    i = units.index[key]
    s = status
    ids = units.matched_geotags[i]
    match = (tr("geotag {ids} within {eps:.2f} m").format(ids=", ".join(map(str, ids)), eps=eps_pred_m)
             if ids else "<span style='color:#c62828'>" + tr("no geotag within {eps:.2f} m").format(
                 eps=eps_pred_m) + "</span>")
    fired = ", ".join(units.layers_fired[i])
    resolved = " · ".join(f"{CONVENTION_TEXT[c]} <span style='color:{VERDICT_COLOURS[v]}'>{v}</span>"
                          for c, v in s.resolved.items())
    votes = ", ".join(f"{v} ({'direct' if p == 'direct' else 'from ' + p.rsplit('/', 1)[-1]})"
                      for p, v in sorted(s.votes.items())) or tr("none yet")
    warn = " <b style='color:#ef8f00'>⚠ " + tr("the conventions disagree") + "</b>" if s.conflict else ""
    where = tr("on the raster") if on_raster else f"{tr('in')} {int(units.n_frames[i])} {tr('frames')}"
    return (
        f"<b>{tr('Unit')} {entries.position[key] + 1}</b> · {match}<br>"
        f"{tr('fired by')} <b>{fired}</b> · {int(units.n_detections[i])} {tr('detection(s)')} {where} · "
        f"{tr('best score')} "
        f"{format_number(float(units.max_score[i]), 2)}"
        f"<br>{tr('Votes')}: {votes}{warn}<br><span style='font-size:11px;color:#555'>{resolved}</span>"
        f"<br><span style='font-size:10px;color:#888'>{key}</span>")
