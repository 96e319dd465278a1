"""Human-readable sensor-bound results: the λ_max field plot and a self-contained HTML report.

Everything here *presents* numbers computed by ``sensor_bound`` (``evaluate_bounds`` and
``lmax_field``); no formula is repeated. The report is one HTML file with its plots embedded as
base64 PNGs, so it can be mailed or archived alone. Pixels are (u, v) in the OpenCV convention
(pixel (0, 0) = centre of the top-left pixel); sigmas are in the interface units of ``sensor_bound``
(x, y, z in metres; roll, pitch, yaw in degrees).
"""
from __future__ import annotations

import base64
import html
import io
import math
from typing import Optional

from .sensor_bound import (
    AXES,
    METHOD_MOUNT,
    SIGMA_UNITS,
    CameraMount,
    Intrinsics,
    camera_mount,
    frame_grid,
    lambda_target,
    lmax_field,
)

# The field plots sample at most this many grid points: finer than the figure's own pixels.
PLOT_MAX_POINTS = 200_000
ACCEPT_COLOUR = "#1a7f37"
REJECT_COLOUR = "#c62828"
TOLERANCE_COLOUR = "#e53935"


def stride_for(intr, max_points: int = PLOT_MAX_POINTS) -> int:
    """Smallest whole-pixel grid stride whose frame grid has at most ``max_points`` points."""
    def points(stride):
        us, vs = frame_grid(intr, stride)
        return us.size * vs.size

    stride = max(1, int(math.sqrt(intr.width * intr.height / max_points)))
    while points(stride) > max_points:
        stride += 1
    return stride


class LmaxFieldPlot:
    """``λ_max(Σ_u)`` (px²) over the frame, drawn on a matplotlib ``figure``.

    The colour scale runs from 0 to the larger of the field's maximum and ``λ_target = (r/3)²``; the
    λ_target contour is drawn in red (the tolerance boundary: pixels beyond it would break the label
    radius) and marked on the colour bar. The principal point is marked with a cross and the worst
    pixel, when given, with a circle. The artists are made once and updated in place by
    :meth:`update`, so a dock can redraw on every edit.
    """

    def __init__(self, figure):
        from matplotlib import patheffects

        self.figure = figure
        figure.clear()
        figure.set_layout_engine("constrained")
        self.ax = ax = figure.add_subplot(1, 1, 1)
        self.image = ax.imshow([[0.0]], origin="upper", cmap="viridis", interpolation="nearest")
        # An inset colour bar follows the image's aspect-fixed box (one attached by the layout would
        # span the whole cell); constrained layout still makes room for its labels.
        self.colorbar = figure.colorbar(self.image, cax=ax.inset_axes([1.03, 0.0, 0.035, 1.0]))
        self.colorbar.set_label(r"$\lambda_\mathrm{max}$ [px²]")
        self.colorbar_mark = self.colorbar.ax.axhline(0.0, color=TOLERANCE_COLOUR, lw=2.5)
        self.contour = None
        outline = [patheffects.withStroke(linewidth=3, foreground="black")]
        (self.principal,) = ax.plot([], [], marker="+", color="white", ms=11, mew=1.6, ls="none",
                                    path_effects=outline, label="principal point")
        (self.worst,) = ax.plot([], [], marker="o", mfc="none", mec=TOLERANCE_COLOUR, ms=11, mew=2, ls="none",
                                clip_on=False, label="worst pixel")
        (self.target,) = ax.plot([], [], color=TOLERANCE_COLOUR, lw=1.6, label="λ_target")
        ax.set_xlabel("u [px]")
        ax.set_ylabel("v [px]")
        self.legend = figure.legend(loc="outside lower center", ncol=3, fontsize=8, frameon=False)

    def update(self, intr, altitude_m: float, sigmas, tolerance_px: float, stride_px: Optional[int] = None,
               worst_pixel=None, mount: CameraMount = METHOD_MOUNT) -> None:
        """Show the field of ``sigmas`` (interface units, on ``mount``) at ``altitude_m``, sampled every
        ``stride_px`` (default :func:`stride_for`)."""
        stride = stride_px or stride_for(intr)
        us, vs = frame_grid(intr, stride)
        field = lmax_field(intr, altitude_m, sigmas, stride, mount=mount)
        lam = lambda_target(tolerance_px)
        top = float(field.max())
        du = (us[-1] - us[0]) / max(1, us.size - 1)
        dv = (vs[-1] - vs[0]) / max(1, vs.size - 1)
        extent = (us[0] - du / 2, us[-1] + du / 2, vs[-1] + dv / 2, vs[0] - dv / 2)
        self.image.set_data(field)
        self.image.set_extent(extent)
        self.image.set_clim(0.0, max(top, lam) * 1.02)
        self.colorbar_mark.set_ydata([lam, lam])
        if self.contour is not None:
            self.contour.remove()
            self.contour = None
        if top >= lam:
            self.contour = self.ax.contour(us, vs, field, levels=[lam], colors=TOLERANCE_COLOUR, linewidths=1.6)
        self.principal.set_data([intr.cx], [intr.cy])
        self.worst.set_data(([worst_pixel[0]], [worst_pixel[1]]) if worst_pixel is not None else ([], []))
        self.legend.get_texts()[2].set_text(rf"$\lambda_\mathrm{{target}}$ = {lam:.4g} px²")
        self.ax.set_title(rf"$\lambda_\mathrm{{max}}(\Sigma_u)$ at {altitude_m:g} m: max {top:.4g} px² "
                          rf"= {100.0 * top / lam:.0f} % of $\lambda_\mathrm{{target}}$", fontsize=10)
        self.ax.set_xlim(extent[0], extent[1])
        self.ax.set_ylim(extent[2], extent[3])


def lmax_field_png(intr, altitude_m: float, sigmas, tolerance_px: float, stride_px: Optional[int] = None,
                   worst_pixel=None, size_in=(6.4, 4.3), dpi: int = 110, mount: CameraMount = METHOD_MOUNT) -> bytes:
    """The :class:`LmaxFieldPlot` as PNG bytes (Agg canvas: the host's backend is left alone)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=size_in, dpi=dpi)
    FigureCanvasAgg(figure)
    LmaxFieldPlot(figure).update(intr, altitude_m, sigmas, tolerance_px, stride_px, worst_pixel, mount)
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png")
    return buffer.getvalue()


# ---------------------------------------------------------------------------------------- formatting
def format_sigma(value: float, unit: str) -> str:
    """A sigma in its interface unit: metres to 0.1 mm, degrees to 0.001°."""
    return f"{value:.4f} m" if unit == "m" else f"{value:.3f}°"


def format_kappa(kappa) -> str:
    """κ* with three significant digits; ``None`` (a zero budget) is unbounded."""
    return "∞" if kappa is None else f"{kappa:.3g}"


def verdict_word(verdict: str) -> str:
    return "ACCEPT" if verdict == "accept" else "REJECT"


def altitude_summary(entry: dict) -> str:
    """One line per altitude for logs: suprema, κ*, verdicts, worst pixel, the balanced exact budget."""
    budget = ", ".join(f"{axis} {format_sigma(value, unit)}"
                       for axis, unit, value in zip(AXES, SIGMA_UNITS, entry["balanced_exact_sigma"]))
    u, v = entry["worst_pixel"]
    return (f"{entry['altitude_m']:g} m: sup tr Σ = {entry['sup_trace_px2']:.4g} px², "
            f"sup λ_max = {entry['sup_lmax_px2']:.4g} px² (λ_target {entry['lambda_target_px2']:.4g} px²) → "
            f"trace κ* = {format_kappa(entry['kappa_trace'])} {verdict_word(entry['verdict_trace'])}, "
            f"exact κ* = {format_kappa(entry['kappa_exact'])} {verdict_word(entry['verdict_exact'])}; "
            f"worst pixel ({u:.0f}, {v:.0f}); balanced exact budget: {budget}")


# ---------------------------------------------------------------------------------------- HTML
_CSS = """
body { font-family: "Segoe UI", Helvetica, Arial, sans-serif; color: #1f2933; margin: 2em auto;
       max-width: 1100px; padding: 0 1em; line-height: 1.45; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; } h2 { font-size: 1.25em; margin-top: 1.8em;
     border-bottom: 1px solid #d0d7de; padding-bottom: 0.2em; }
.lead { color: #52606d; margin-top: 0; }
table { border-collapse: collapse; margin: 0.6em 0 1em 0; font-size: 0.92em; }
th, td { border: 1px solid #d0d7de; padding: 0.3em 0.65em; text-align: right; }
th { background: #f3f5f7; } td.name, th.name { text-align: left; }
.accept { color: #fff; background: %(accept)s; font-weight: 600; text-align: center; }
.reject { color: #fff; background: %(reject)s; font-weight: 600; text-align: center; }
.bar { display: inline-block; height: 0.8em; background: #3f7cac; vertical-align: middle; margin-right: 0.4em; }
.altitude { display: flex; flex-wrap: wrap; gap: 1.5em; align-items: flex-start; }
.note { color: #52606d; font-size: 0.88em; }
img { max-width: 100%%; border: 1px solid #e4e7eb; }
""" % {"accept": ACCEPT_COLOUR, "reject": REJECT_COLOUR}


def _verdict_cell(verdict: str) -> str:
    return f'<td class="{verdict}">{verdict_word(verdict)}</td>'


def _summary_table(entries) -> str:
    rows = []
    for e in entries:
        u, v = e["worst_pixel"]
        rows.append(
            f"<tr><td>{e['altitude_m']:g}</td><td>{e['sup_trace_px2']:.4g}</td><td>{e['sup_lmax_px2']:.4g}</td>"
            f"<td>{format_kappa(e['kappa_trace'])}</td><td>{format_kappa(e['kappa_exact'])}</td>"
            f"{_verdict_cell(e['verdict_trace'])}{_verdict_cell(e['verdict_exact'])}"
            f"<td>({u:.0f}, {v:.0f})</td></tr>")
    return ("<table><tr><th>Altitude [m]</th><th>sup tr Σ<sub>u</sub> [px²]</th><th>sup λ<sub>max</sub> [px²]</th>"
            "<th>κ* trace</th><th>κ* exact</th><th>Trace bound</th><th>Exact bound</th>"
            "<th>Worst pixel (u, v)</th></tr>" + "".join(rows) + "</table>")


def _budget_table(entry: dict, sigmas) -> str:
    rows = []
    for axis, unit, deployed, trace, exact, share in zip(AXES, SIGMA_UNITS, sigmas, entry["balanced_trace_sigma"],
                                                         entry["balanced_exact_sigma"], entry["budget_share"]):
        bar = f'<span class="bar" style="width:{100.0 * share:.1f}px"></span>'
        rows.append(f'<tr><td class="name">{axis}</td><td>{format_sigma(deployed, unit)}</td>'
                    f"<td>{format_sigma(trace, unit)}</td><td>{format_sigma(exact, unit)}</td>"
                    f'<td class="name">{bar}{100.0 * share:.1f} %</td></tr>')
    return ('<table><tr><th class="name">Axis</th><th>Deployed σ</th><th>Balanced σ (trace)</th>'
            '<th>Balanced σ (exact)</th><th class="name">Share of deployed budget</th></tr>'
            + "".join(rows) + "</table>")


def build_report_html(result: dict, title: str = "Sensor bound", source: str = "",
                      plot_stride_px: Optional[int] = None) -> str:
    """The HTML report of an ``evaluate_bounds`` result (its JSON dict), plots embedded.

    ``source`` names where the intrinsics came from (a calibration file or "typed"); the λ_max field
    plots are sampled with ``plot_stride_px`` (default :func:`stride_for` — plots need no more).
    """
    inputs = result["inputs"]
    intr = Intrinsics(**inputs["intrinsics"])
    sigmas = inputs["sigmas"]
    mount = camera_mount(inputs["mount"])
    entries = result["altitudes"]
    lam = inputs["lambda_target_px2"]
    esc = html.escape
    camera = (f"{intr.width}×{intr.height} px, f<sub>x</sub> {intr.fx:.4f}, f<sub>y</sub> {intr.fy:.4f}, "
              f"c<sub>x</sub> {intr.cx:.4f}, c<sub>y</sub> {intr.cy:.4f} px")
    deployed = ", ".join(f"{axis} {format_sigma(s, unit)}" for axis, unit, s in zip(AXES, SIGMA_UNITS, sigmas))
    parts = [
        "<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">', f"<title>{esc(title)}</title>",
        f"<style>{_CSS}</style></head><body>",
        f"<h1>{esc(title)}</h1>",
        f'<p class="lead">Camera {camera}{" from " + esc(source) if source else ""}. '
        f"Label tolerance r = {inputs['tolerance_px']:g} px at 3σ → λ<sub>target</sub> = (r/3)² = {lam:.4g} px² "
        f"(σ<sub>label</sub> = {math.sqrt(lam):.4g} px). Pose sigmas (1σ): {deployed}; camera mount: "
        f"{esc(mount.name)}. "
        f"Grid stride {inputs['stride_px']} px over the pixel centres u = 0…{intr.width - 1}, "
        f"v = 0…{intr.height - 1}.</p>",
        "<h2>Verdicts</h2>", _summary_table(entries),
        '<p class="note">The <b>trace bound</b> (sup tr Σ<sub>u</sub> ≤ λ<sub>target</sub>) is sufficient but '
        "pessimistic; the <b>exact bound</b> (sup λ<sub>max</sub>(Σ<sub>u</sub>) ≤ λ<sub>target</sub>) is "
        "necessary and sufficient. κ* = λ<sub>target</sub> / sup is the largest factor by which every variance "
        "of the deployed budget may grow (every sigma by √κ*) while the label stays inside r at 3σ: accept when "
        "κ* ≥ 1.</p>",
        '<p class="note">Per altitude below: the <b>balanced budgets</b> maximise Σ log σ<sub>i</sub>² under '
        "each bound, so no axis is starved (under the trace bound every axis takes a sixth of the tolerance); "
        "the <b>share</b> splits the deployed budget's tr Σ at the worst pixel among the axes: the largest "
        "share is the sensor to improve first.</p>",
    ]
    for entry in entries:
        png = lmax_field_png(intr, entry["altitude_m"], sigmas, inputs["tolerance_px"], plot_stride_px,
                             entry["worst_pixel"], mount=mount)
        parts += [
            f"<h2>{entry['altitude_m']:g} m above the ground</h2>",
            '<div class="altitude"><div>', _budget_table(entry, sigmas), "</div>",
            f'<img alt="λ_max field at {entry["altitude_m"]:g} m" '
            f'src="{as_png_data_uri(png)}"></div>',
        ]
    parts += [
        "<h2>Conventions</h2>",
        f'<p class="note">Axes: {esc(inputs["axis_convention"])}. Nadir pinhole camera over level ground at '
        "depth = altitude; lens distortion is ignored. Pose errors are a left perturbation of the camera pose "
        "with Σ<sub>0</sub> = diag(σ<sub>x</sub>², …, σ<sub>yaw</sub>²).</p>",
        "</body></html>",
    ]
    return "\n".join(parts)


def write_report(path, result: dict, **kwargs) -> str:
    """Write :func:`build_report_html` to ``path`` (UTF-8) and return the path as a string."""
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(build_report_html(result, **kwargs))
    return str(path)


def as_png_data_uri(png: bytes) -> str:
    """PNG bytes as a ``data:`` URI for an ``<img src>``."""
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")
