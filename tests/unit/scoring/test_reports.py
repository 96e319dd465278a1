"""Figures of sweeps: the plot counts every configuration it draws."""
import numpy as np

from birdseye.birdseye_qgis.core.detect.clustering import GroundPositions
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.scoring.reports import sweep_figure
from birdseye.birdseye_qgis.core.scoring.sweep import SweepFlight, SweepGrid, sweep


def flight(checkpoint):
    spot = np.array([[0.0, 0.0], [0.05, 0.0], [0.0, 0.05]])
    site = LocalFrame(-27.55, 151.95)
    return SweepFlight({0.3: GroundPositions.from_local(site, spot), 0.5: GroundPositions.from_local(site, spot[:2])},
                       np.array([[0.0, 0.0]]), 4, "f", checkpoint, checkpoint.upper())


def test_the_sweep_plot_is_titled_with_every_checkpoints_configurations():
    grid = SweepGrid([0.3, 0.5], [0.1, 0.2, 0.3], [1, 2], [0.2])          # 2 × 3 × 2 × 1 = 12 per checkpoint
    three = sweep([flight("a.onnx"), flight("b.onnx"), flight("c.onnx")], grid)
    ax = sweep_figure(three).axes[0]
    assert ax.get_title() == "Operating points (36 configurations: 3 checkpoints × 12)"
    one = sweep([flight("a.onnx")], grid)
    assert sweep_figure(one).axes[0].get_title() == "Operating points (12 configurations)"
