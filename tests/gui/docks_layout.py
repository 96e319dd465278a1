"""What a person would see cut off in a dock or dialog: the checks the dock tests run on every visible widget.

:func:`layout_problems` walks the visible widgets under a root and names each one whose text does not fit:

* a horizontal scroll bar, or a scroll area whose content is wider than its viewport while its scroll bar is
  off (the content is cut);
* a label, button or check box narrower than its text (``sizeHint``; a word-wrapped label: its longest word);
* a combo box whose shown item is wider than its text field (the text is elided);
* a line edit or spin box whose text (suffix included) is wider than its field, except a file widget's path,
  which scrolls by design;
* a header section or a table cell narrower than its text;
* a widget reaching past the right edge of its parent.

Used inside the QGIS desktop by ``docks_probe.py`` and by the qtbot tests; Qt only, so both can import it.
"""
from __future__ import annotations

from contextlib import contextmanager

from qgis.PyQt.QtCore import QRect, Qt
from qgis.PyQt.QtGui import QFontMetrics
from qgis.PyQt.QtWidgets import (
    QAbstractButton,
    QAbstractItemView,
    QAbstractScrollArea,
    QAbstractSpinBox,
    QApplication,
    QComboBox,
    QHeaderView,
    QLabel,
    QLineEdit,
    QScrollArea,
    QStyle,
    QStyleOptionComboBox,
    QTableView,
    QTreeView,
    QWidget,
)


@contextmanager
def qgis_interface_font(points: float = 9.0):
    """The application font at QGIS's usual interface size while the block runs, then the font it had."""
    font = QApplication.font()
    smaller = QApplication.font()
    smaller.setPointSizeF(points)
    QApplication.setFont(smaller)
    try:
        yield
    finally:
        QApplication.setFont(font)

# Slack for rounding in layouts and style metrics (px).
SLACK = 1


def describe(widget: QWidget) -> str:
    """A widget as a person can find it: its class, object name or text."""
    text = next((str(getattr(widget, getter)()) for getter in ("text", "currentText", "title", "windowTitle")
                 if callable(getattr(widget, getter, None)) and getattr(widget, getter)()), "")
    name = widget.objectName()
    return f"{type(widget).__name__}{f' {name}' if name else ''}{f' {text[:60]!r}' if text else ''}"


def _visible_widgets(root: QWidget):
    for widget in root.findChildren(QWidget):
        if widget.isVisible() and widget.isVisibleTo(root) and widget.width() > 0:
            yield widget


def _inside_file_widget(widget: QWidget) -> bool:
    parent = widget.parentWidget()
    while parent is not None:
        if type(parent).__name__ == "QgsFileWidget":
            return True
        parent = parent.parentWidget()
    return False


def _label_problem(label: QLabel) -> str | None:
    pixmap = label.pixmap()   # Qt 5: None without one; Qt 6: a null pixmap
    if not label.text() or pixmap is not None and not pixmap.isNull():
        return None
    needed = label.minimumSizeHint().width() if label.wordWrap() else label.sizeHint().width()
    if needed > label.width() + SLACK:
        return f"{describe(label)}: text needs {needed} px, has {label.width()} px"
    if label.wordWrap() and label.heightForWidth(label.width()) > label.height() + SLACK:
        return f"{describe(label)}: wrapped text needs {label.heightForWidth(label.width())} px height, " \
               f"has {label.height()} px"
    return None


def _combo_problem(combo: QComboBox) -> str | None:
    if combo.isEditable() and combo.lineEdit() is not None:
        return None  # checked by the line-edit rule
    text = combo.currentText()
    if not text:
        return None
    option = QStyleOptionComboBox()
    combo.initStyleOption(option)
    field = combo.style().subControlRect(QStyle.ComplexControl.CC_ComboBox, option,
                                         QStyle.SubControl.SC_ComboBoxEditField, combo)
    needed = combo.fontMetrics().horizontalAdvance(text)
    if not combo.itemIcon(combo.currentIndex()).isNull():
        needed += combo.iconSize().width() + 4
    if needed > field.width() + SLACK:
        return f"{describe(combo)}: shown item needs {needed} px, has {field.width()} px"
    return None


def _line_edit_problem(edit: QLineEdit) -> str | None:
    if not edit.text() or _inside_file_widget(edit):
        return None
    margins = edit.textMargins()
    room = edit.contentsRect().width() - margins.left() - margins.right() - 4   # QLineEdit's own 2 px padding
    needed = edit.fontMetrics().horizontalAdvance(edit.text())
    if needed > room + SLACK:
        owner = edit.parentWidget() if isinstance(edit.parentWidget(), (QAbstractSpinBox, QComboBox)) else edit
        return f"{describe(owner)}: text {edit.text()!r} needs {needed} px, has {room} px"
    return None


def _header_problems(header: QHeaderView) -> list:
    if header.orientation() != Qt.Orientation.Horizontal or header.model() is None:
        return []
    problems = []
    margin = header.style().pixelMetric(QStyle.PixelMetric.PM_HeaderMargin, None, header)
    for section in range(header.count()):
        if header.isSectionHidden(section):
            continue
        text = str(header.model().headerData(section, Qt.Orientation.Horizontal) or "")
        needed = max((header.fontMetrics().horizontalAdvance(line) for line in text.split("\n")), default=0)
        needed += 2 * margin
        if needed > header.sectionSize(section) + SLACK:
            problems.append(f"{describe(header.parentWidget())}: header {text!r} needs {needed} px, "
                            f"has {header.sectionSize(section)} px")
    return problems


def _cell_problems(view: QAbstractItemView) -> list:
    """Cells of a table or of a tree's top level whose text does not fit the rectangle they are drawn in."""
    model = view.model()
    if model is None:
        return []
    problems = []
    margin = view.style().pixelMetric(QStyle.PixelMetric.PM_FocusFrameHMargin, None, view) + 1
    for row in range(model.rowCount()):
        for column in range(model.columnCount()):
            index = model.index(row, column)
            text = str(model.data(index) or "")
            rect = view.visualRect(index)
            if not text or rect.width() <= 0:
                continue   # hidden, or covered by a spanning cell
            font = model.data(index, Qt.ItemDataRole.FontRole)
            metrics = QFontMetrics(font) if font is not None else view.fontMetrics()
            room = rect.width() - 2 * margin
            for role in (Qt.ItemDataRole.DecorationRole, Qt.ItemDataRole.CheckStateRole):
                if model.data(index, role) is not None:
                    room -= (view.iconSize().width() if view.iconSize().width() > 0 else 16) + margin
            if view.wordWrap():
                wrapped = metrics.boundingRect(QRect(0, 0, max(room, 1), 100_000),
                                               int(Qt.TextFlag.TextWordWrap), text)
                if wrapped.width() > room or wrapped.height() > rect.height():
                    problems.append(f"{describe(view)}: cell {text[:40]!r} (row {row + 1}) needs "
                                    f"{wrapped.width()} × {wrapped.height()} px, has {room} × {rect.height()} px")
                continue
            needed = max(metrics.horizontalAdvance(line) for line in text.split("\n"))
            if needed > room:
                problems.append(f"{describe(view)}: cell {text[:40]!r} (row {row + 1}) needs {needed + 2 * margin} "
                                f"px, has {room + 2 * margin} px")
    return problems


def layout_problems(root: QWidget) -> list:
    """Every visible widget under ``root`` whose text is cut off or that needs scrolling sideways."""
    problems = []
    for widget in _visible_widgets(root):
        if isinstance(widget, QAbstractScrollArea):
            bar = widget.horizontalScrollBar()
            if bar.isVisible() and bar.maximum() > 0:
                problems.append(f"{describe(widget)}: horizontal scroll bar")
            if isinstance(widget, QScrollArea) and widget.widget() is not None:
                content = max(widget.widget().minimumSizeHint().width(), widget.widget().minimumWidth())
                if content > widget.viewport().width() + SLACK:
                    problems.append(f"{describe(widget)}: content needs {content} px, the view shows "
                                    f"{widget.viewport().width()} px")
        if isinstance(widget, QLabel):
            problems.append(_label_problem(widget))
        elif isinstance(widget, QAbstractButton) and widget.text():
            if widget.sizeHint().width() > widget.width() + SLACK:
                problems.append(f"{describe(widget)}: needs {widget.sizeHint().width()} px, has {widget.width()} px")
        elif isinstance(widget, QComboBox):
            problems.append(_combo_problem(widget))
        elif isinstance(widget, QLineEdit):
            problems.append(_line_edit_problem(widget))
        elif isinstance(widget, QHeaderView):
            problems += _header_problems(widget)
        if isinstance(widget, (QTableView, QTreeView)):
            problems += _cell_problems(widget)
        parent = widget.parentWidget()
        if parent is not None and widget is not root and not isinstance(parent, QAbstractItemView) \
                and parent.objectName() != "qt_scrollarea_viewport" \
                and widget.geometry().right() > parent.rect().right() + SLACK:
            problems.append(f"{describe(widget)}: reaches {widget.geometry().right() - parent.rect().right()} px "
                            f"past the right edge of {describe(parent)}")
    return [p for p in problems if p]
