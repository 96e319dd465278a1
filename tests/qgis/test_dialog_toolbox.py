"""BirdsEye in the Processing toolbox: each group's algorithms in workflow order, whatever their names.

The toolbox sorts a group's algorithms by display name (``QgsProcessingToolboxProxyModel``); each display name
starts with its step ("1.2 · Import flight log"), so the sorted order is the workflow's (base.WORKFLOW). The ids,
which are public, do not change.
"""
from __future__ import annotations

from qgis.core import QgsApplication
from qgis.gui import QgsProcessingToolboxProxyModel
from qgis.PyQt.QtCore import QModelIndex

from birdseye.processing.algorithms.base import GROUPS, WORKFLOW


def toolbox_tree(model, parent=QModelIndex()) -> list:
    """(text, algorithm id or None, children) of every row under ``parent``, as the toolbox shows them."""
    rows = []
    for row in range(model.rowCount(parent)):
        index = model.index(row, 0, parent)
        algorithm = model.toolboxModel().algorithmForIndex(model.mapToSource(index))
        rows.append((model.data(index), algorithm.id() if algorithm else None, toolbox_tree(model, index)))
    return rows


def test_the_toolbox_lists_each_group_in_workflow_order(birdseye_provider):
    model = QgsProcessingToolboxProxyModel(None, QgsApplication.processingRegistry())
    [(_, _, groups)] = [row for row in toolbox_tree(model) if row[0] == birdseye_provider.name()]
    shown = {text: [algorithm_id for _, algorithm_id, _ in children] for text, _, children in groups}
    assert list(shown) == list(GROUPS.values()), "the groups, numbered, in workflow order"
    for key, label in GROUPS.items():
        assert shown[label] == [f"birdseye:{alg_id}" for alg_id in WORKFLOW[key]], label


def test_every_algorithm_has_its_step_and_keeps_its_id(birdseye_provider):
    listed = sorted(alg_id for ids in WORKFLOW.values() for alg_id in ids)
    assert listed == sorted(alg.name() for alg in birdseye_provider.algorithms()), "WORKFLOW names every algorithm"
    detect = QgsApplication.processingRegistry().algorithmById("birdseye:detect")
    assert detect.displayName() == "4.1 · Detect targets (ONNX heatmap model)"
    assert detect.id() == "birdseye:detect" and detect.groupId() == "detect"
