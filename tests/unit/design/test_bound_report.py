"""The sensor-bound report: it must show the core's numbers, not compute its own.

Checked against ``evaluate_bounds`` results: the HTML parses into balanced tags, holds one verdict per
criterion per altitude with the right class, the budgets in their units and one decodable PNG per
altitude; the plot's image is exactly ``lmax_field``, its colour scale and contour follow λ_target.
"""
import base64
import html
import io
import math
import re
from html.parser import HTMLParser

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from birdseye.birdseye_qgis.core.design import bound_report as br
from birdseye.birdseye_qgis.core.design import sensor_bound as sb

DEPLOYED = sb.Intrinsics(fx=4264.4945, fy=4262.8927, cx=958.4594, cy=592.5033, width=1920, height=1200)
DEPLOYED_SIGMAS = [0.010, 0.010, 0.060, 0.04, 0.04, 0.13]
VOID_TAGS = {"meta", "img", "br", "hr", "link", "input"}


@pytest.fixture(scope="module")
def result():
    return sb.evaluate_bounds(DEPLOYED, [10.0, 20.0], DEPLOYED_SIGMAS, 30.0, stride_px=8)


class TagChecker(HTMLParser):
    """Collects table cells and images, and fails on unbalanced tags."""

    def __init__(self):
        super().__init__()
        self.stack, self.cells, self.images, self._cell = [], [], [], None

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "img":
            self.images.append(attrs["src"])
        if tag in VOID_TAGS:
            return
        self.stack.append(tag)
        if tag == "td":
            self._cell = [attrs.get("class"), ""]

    def handle_endtag(self, tag):
        assert self.stack and self.stack[-1] == tag, f"</{tag}> closes <{self.stack[-1] if self.stack else None}>"
        self.stack.pop()
        if tag == "td":
            self.cells.append(tuple(self._cell))
            self._cell = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell[1] += data


def parse(text):
    checker = TagChecker()
    checker.feed(text)
    checker.close()
    assert checker.stack == [], f"unclosed tags {checker.stack}"
    return checker


def test_report_holds_the_verdicts_budgets_and_one_plot_per_altitude(result):
    text = br.build_report_html(result, title="Test <bound>", source="cam & lens.yaml", plot_stride_px=16)
    page = parse(text)
    assert "<title>Test &lt;bound&gt;</title>" in text and "cam &amp; lens.yaml" in text
    verdict_cells = [(cls, data) for cls, data in page.cells if cls in ("accept", "reject")]
    expected = [(e[key], e[key].upper()) for e in result["altitudes"] for key in ("verdict_trace", "verdict_exact")]
    assert verdict_cells == expected
    assert [v for v, _ in expected] == ["reject", "accept", "accept", "accept"]
    for entry in result["altitudes"]:
        cells = [data for _, data in page.cells]
        assert f"{entry['sup_lmax_px2']:.4g}" in cells and f"{entry['kappa_trace']:.3g}" in cells
        for axis_value, unit in zip(entry["balanced_exact_sigma"], sb.SIGMA_UNITS):
            assert br.format_sigma(axis_value, unit) in cells
        shares = [float(re.search(r"([\d.]+) %", d).group(1)) for d in cells if d.endswith(" %")]
        assert len(shares) == 12 and sum(shares[:6]) == pytest.approx(100.0, abs=0.3)
    assert len(page.images) == 2
    for src in page.images:
        assert src.startswith("data:image/png;base64,")
        assert base64.b64decode(src.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
    assert "λ<sub>target</sub> = (r/3)² = 100 px²" in text and "σ<sub>label</sub> = 10 px" in text


def test_write_report_round_trips(result, tmp_path):
    path = br.write_report(tmp_path / "r.html", result, plot_stride_px=32)
    assert open(path, encoding="utf-8").read() == br.build_report_html(result, plot_stride_px=32)


def test_plot_shows_the_core_field_with_the_tolerance(result):
    figure = Figure(figsize=(5, 4))
    FigureCanvasAgg(figure)
    plot = br.LmaxFieldPlot(figure)
    entry = result["altitudes"][0]
    plot.update(DEPLOYED, 10.0, DEPLOYED_SIGMAS, 30.0, stride_px=8, worst_pixel=entry["worst_pixel"])
    np.testing.assert_array_equal(plot.image.get_array(), sb.lmax_field(DEPLOYED, 10.0, DEPLOYED_SIGMAS, 8))
    lam = sb.lambda_target(30.0)
    # the field stays below λ_target: no contour, scale topped by λ_target (marked on the colour bar)
    assert plot.contour is None and plot.image.get_clim() == pytest.approx((0.0, 1.02 * lam))
    assert list(plot.colorbar_mark.get_ydata()) == [lam, lam]
    assert list(plot.worst.get_xdata()) == [1919.0] and list(plot.worst.get_ydata()) == [1199.0]
    # the frame keeps its aspect and is shown whole (edges ± half a grid step)
    x0, x1 = plot.ax.get_xlim()
    step = 1919 / 240   # pixel centres 0, 8, …, 1912 and the last one, 1919
    assert (x0, x1) == pytest.approx((-step / 2, 1919 + step / 2)) and plot.ax.get_aspect() == 1.0

    # a budget 1.5× too large in every variance: the contour appears at λ_target
    loud = list(np.array(DEPLOYED_SIGMAS) * math.sqrt(1.5 * entry["kappa_exact"]))  # variances × 1.5 κ*
    plot.update(DEPLOYED, 10.0, loud, 30.0, stride_px=8)
    field = sb.lmax_field(DEPLOYED, 10.0, loud, 8)
    assert field.max() == pytest.approx(1.5 * lam, rel=1e-9)
    assert plot.contour is not None and list(plot.contour.levels) == [lam]
    assert plot.image.get_clim()[1] == pytest.approx(1.02 * field.max())
    assert len(plot.worst.get_xdata()) == 0
    figure.canvas.draw()
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png")
    assert buffer.getvalue()[:4] == b"\x89PNG"


@pytest.mark.parametrize("width, height, max_points", [(1920, 1200, 200_000), (8192, 5460, 150_000),
                                                       (640, 480, 1_000_000), (1920, 1200, 1000)])
def test_stride_for_is_the_smallest_stride_within_the_budget(width, height, max_points):
    intr = sb.Intrinsics(fx=1000.0, fy=1000.0, cx=width / 2, cy=height / 2, width=width, height=height)

    def points(stride):
        us, vs = sb.frame_grid(intr, stride)
        return us.size * vs.size

    stride = br.stride_for(intr, max_points)
    assert points(stride) <= max_points
    assert stride == 1 or points(stride - 1) > max_points


def test_altitude_summary_reads_well(result):
    line = br.altitude_summary(result["altitudes"][0])
    assert line.startswith("10 m: sup tr Σ = ")
    assert "REJECT" in line and "exact κ* = 1.34 ACCEPT" in line and "worst pixel (1919, 1199)" in line
    assert "x 0.0136 m" in line and "yaw 0.302°" in line
    zero = sb.evaluate_bounds(DEPLOYED, [10.0], [0.0] * 6, 30.0, stride_px=64)["altitudes"][0]
    assert "trace κ* = ∞ ACCEPT" in br.altitude_summary(zero)


def test_report_and_plot_follow_the_camera_mount():
    sigmas = [0.01, 0.01, 0.06, 0.30, 0.05, 0.13]   # roll ≠ pitch: the mount matters
    nadir = sb.evaluate_bounds(DEPLOYED, [10.0], sigmas, 30.0, stride_px=16, mount=sb.NADIR_MOUNT)
    method = sb.evaluate_bounds(DEPLOYED, [10.0], sigmas, 30.0, stride_px=16)
    assert (nadir["inputs"]["mount"], method["inputs"]["mount"]) == ("nadir_top_forward", "method")
    text = br.build_report_html(nadir, plot_stride_px=32)
    assert html.escape(sb.NADIR_MOUNT.name) in text and html.escape(sb.NADIR_MOUNT.convention) in text
    figure = Figure(figsize=(5, 4))
    FigureCanvasAgg(figure)
    plot = br.LmaxFieldPlot(figure)
    fields = {}
    for mount in sb.MOUNTS:
        plot.update(DEPLOYED, 10.0, sigmas, 30.0, stride_px=16, mount=mount)
        fields[mount.key] = np.asarray(plot.image.get_array())
        np.testing.assert_array_equal(fields[mount.key], sb.lmax_field(DEPLOYED, 10.0, sigmas, 16, mount=mount))
    assert not np.allclose(fields["method"], fields["nadir_top_forward"], rtol=0.01)
