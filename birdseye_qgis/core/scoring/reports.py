"""HTML reports and figures of evaluations, sweeps and screenings."""
from __future__ import annotations

import math
from typing import Iterable, Sequence

import numpy as np

from .evaluation import Evaluation
from .operating_point import OperatingPoint
from .post_review import POINT_VALUE_ASSUMPTIONS
from .screening import CheckpointScreen
from .sweep import SweepResult
from .transfer import SurveyDensity, TransferReport


def figure_data_uri(fig) -> str:
    """A matplotlib figure as a base64 PNG data URI (for self-contained HTML reports)."""
    import base64
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def new_figure(width_in: float, height_in: float):
    """A matplotlib Figure drawn by Agg without pyplot: safe in QGIS's worker threads, whatever
    backend the desktop uses."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width_in, height_in))
    FigureCanvasAgg(fig)
    return fig


def html_table(header: Sequence[str], rows: Iterable[Sequence]) -> str:
    import html

    def cell(v):
        if v is None:
            return "–"
        if isinstance(v, float):
            return f"{v:.3f}"
        return html.escape(str(v))

    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{cell(v)}</td>" for v in row) + "</tr>" for row in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def html_page(title: str, body: str) -> str:
    import html

    style = ("body{font-family:sans-serif;max-width:60em;margin:1em auto;color:#222}"
             "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #bbb;padding:.2em .5em;"
             "text-align:right}th{background:#eee}td:first-child{text-align:left}"
             ".note{color:#555;font-size:90%}img{max-width:100%}")
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
            f"<style>{style}</style></head><body><h1>{html.escape(title)}</h1>{body}</body></html>")


#: What the survey density is and why it stands beside GMCF (evaluation and screening reports).
SURVEY_DENSITY_NOTE = ("Survey density: the geotags in view of each processed frame, summarised over the frames "
                       "(p10–p90: the 10th and 90th percentiles). A cluster is a hit only where the survey put a "
                       "geotag: where fewer of the real targets were surveyed, more clusters go unmatched and GMCF "
                       "falls with the detector unchanged, so GMCF compares across sites only with their densities.")


def survey_density_html(densities) -> str:
    """A table of survey densities: ``densities`` maps a flight's name (or "pooled") to its
    :class:`~.transfer.SurveyDensity`."""
    def span(low, high):
        return None if low is None else f"{low:.1f}–{high:.1f}"

    rows = [[name, d.n_frames, d.mean, d.median, span(d.p10, d.p90), None if d.min is None else f"{d.min}–{d.max}",
             None if d.frames_without_geotag is None else f"{d.frames_without_geotag:.0%}"]
            for name, d in densities.items()]
    return (html_table(["flight", "frames", "geotags per frame (mean)", "median", "p10–p90", "min–max",
                        "frames without a geotag"], rows)
            + f"<p class='note'>{SURVEY_DENSITY_NOTE}</p>")


def evaluation_report_html(evaluation: Evaluation) -> str:
    """The map-free HTML report of evaluatedetections: definitions, tables and plots."""
    import html

    d = evaluation.to_dict()
    rows = [[f["name"], f["n_frames"], f["n_detections"], f["n_in_view"], f["n_recovered"], f["recall_pre"],
             f["n_clusters"], f["n_hit_clusters"], f["gmcf_pre"]] for f in d["flights"]]
    rows.append(["pooled (micro-average)", sum(f["n_frames"] for f in d["flights"]),
                 sum(f["n_detections"] for f in d["flights"]), d["n_in_view"], d["n_recovered"],
                 d["recall_pre"], d["n_clusters"], d["n_hit_clusters"], d["gmcf_pre"]])
    body = ["<h2>Before review</h2>",
            html_table(["flight", "frames", "detections", "geotags in view", "recovered", "recall_pre",
                        "clusters", "hit clusters", "gmcf_pre"], rows),
            "<p class='note'>recall_pre = recovered / in view. gmcf_pre = hit clusters / clusters: the "
            "geotag-matched cluster fraction, a lower bound on precision, not precision (surveys are never "
            "exhaustive). Flights pool by micro-averaging: counts are summed, then divided once.</p>"]
    body.append(operating_point_note(evaluation.op))
    densities = {f.name: SurveyDensity.of([f.in_view.per_frame]) for f in evaluation.flights}
    densities["pooled"] = evaluation.survey_density
    body += ["<h2>Survey density</h2>", survey_density_html(densities)]
    if evaluation.post is not None:
        post_rows = [[conv, p["c"], p["a"], p["gmcf_post"], p["recall_post"]] for conv, p in d["post"].items()]
        body += ["<h2>After review</h2>",
                 html_table(["convention", "c (confirmed, not hit)", "a (added where nothing fired)", "gmcf_post",
                             "recall_post"], post_rows),
                 "<p class='note'>gmcf_post = (hit clusters + c) / clusters; recall_post = (recovered + c) / "
                 "(in view + c + a), with a = added targets in view where no cluster fired and no geotag "
                 "lies within EPS_PRED. With a = 0 it is printed “≥ x”: a lower bound on the recall over "
                 "the known targets, since a real cluster left unconfirmed would raise it. With a &gt; 0 it is "
                 "a point value of the recall over every real target in view, assuming: "
                 f"{html.escape(POINT_VALUE_ASSUMPTIONS)}. Real targets nobody surveyed, found or added are "
                 "in no term, so where the search for missed targets was not exhaustive the figure overstates "
                 "the recall over all real targets. Uncertain and unreviewed verdicts are abstentions; "
                 "the spread between the conventions is part of the result.</p>"]
        for note in d["review_notes"]:
            body.append(f"<p class='note'>{html.escape(note)}</p>")

    fig = new_figure(10, 3.6)
    axes = fig.subplots(1, 2)
    names = [r[0] for r in rows]
    x = np.arange(len(rows))
    for off, key, label in ((-0.2, 5, "recall_pre"), (0.2, 8, "gmcf_pre")):
        axes[0].bar(x + off, [np.nan if r[key] is None else r[key] for r in rows], 0.4, label=label)
    axes[0].set_xticks(x, names, rotation=20, ha="right", fontsize=8)
    axes[0].set_ylim(0, 1.05)
    axes[0].legend(fontsize=8)
    axes[0].set_title("Scores per flight and pooled", fontsize=10)
    sizes_hit = np.concatenate([f.clustering.summary.n_detections[f.score.cluster_hit] for f in evaluation.flights])
    sizes_miss = np.concatenate([f.clustering.summary.n_detections[~f.score.cluster_hit] for f in evaluation.flights])
    top = max(2, int(max(sizes_hit.max(initial=1), sizes_miss.max(initial=1))))
    bins = np.unique(np.geomspace(1, top + 1, 20).astype(int))
    axes[1].hist([sizes_hit, sizes_miss], bins=bins, label=["hit clusters", "unmatched clusters"], stacked=True)
    axes[1].set_xscale("log")
    axes[1].set_xlabel("detections per cluster")
    axes[1].set_ylabel("clusters")
    axes[1].legend(fontsize=8)
    axes[1].set_title("Cluster sizes", fontsize=10)
    body.append(f"<img alt='scores and cluster sizes' src='{figure_data_uri(fig)}'>")
    return html_page("BirdsEye — detection scores", "".join(body))


def operating_point_note(op: OperatingPoint) -> str:
    """The operating point as a note under a report's tables."""
    return "<p class='note'>" + ", ".join(f"{k} = {v}" for k, v in op.to_dict().items() if v is not None) + "</p>"


def _screen_table(screens: Sequence[CheckpointScreen]) -> str:
    rows = [[s.checkpoint, "yes" if s.healthy else "no", s.counts.recall_pre, s.counts.gmcf_pre, s.f1_geo,
             s.detections_per_frame, s.review_load, s.f1_pixel] for s in screens]
    return html_table(["checkpoint", "healthy", "recall_pre", "gmcf_pre", "f1_geo", "detections per frame",
                       "review load", "pixel F1"], rows)


def screening_report_html(op: OperatingPoint, screens: Sequence[CheckpointScreen], densities,
                          heldout: Sequence[CheckpointScreen] | None = None, heldout_densities=None,
                          transfer: TransferReport | None = None) -> str:
    """The HTML report of screencheckpoints: the checkpoints on the validation flights and their survey
    density; with held-out flights, the same there and the transfer (:mod:`.transfer`)."""
    import html

    body = ["<h2>Validation flights</h2>", _screen_table(screens),
            "<p class='note'>Pooled over every block of every flight by micro-averaging. f1_geo = 2·recall·GMCF / "
            "(recall + GMCF); review load = detections per frame / the lightest healthy checkpoint's; pixel F1 is "
            "for choosing checkpoints only, never a field score. Healthy: neither collapsed nor too sparse.</p>",
            "<h3>Survey density</h3>", survey_density_html(densities)]
    if heldout is not None:
        body += ["<h2>Held-out flights</h2>", _screen_table(heldout), "<h3>Survey density</h3>",
                 survey_density_html(heldout_densities)]
    if transfer is not None:
        rows = [[t.checkpoint, "yes" if t.healthy_on_validation else "no", t.validation.recall_pre,
                 t.heldout.recall_pre, t.delta_recall, t.validation.gmcf_pre, t.heldout.gmcf_pre, t.delta_gmcf]
                for t in transfer.checkpoints]
        ranks = []
        for figure, rank in (("recall", transfer.recall), ("GMCF", transfer.gmcf)):
            value = html.escape(rank.note) if rank.rho is None else f"ρ = {rank.rho:.3f} over {rank.n} checkpoints"
            ranks.append(f"<li>Spearman's rank correlation of {figure}, validation vs held-out: {value}</li>")
        body += ["<h2>Validation → held-out</h2>",
                 html_table(["checkpoint", "healthy (validation)", "recall validation", "recall held-out", "ΔRecall",
                             "GMCF validation", "GMCF held-out", "ΔGMCF"], rows),
                 "<ul>" + "".join(ranks) + "</ul>",
                 "<p class='note'>Δ = held-out − validation. Spearman's ρ is taken over the checkpoints healthy on the "
                 "validation flights (tied figures share their average rank): near 1, the validation ranking of the "
                 "checkpoints holds on the held-out flights; near 0 or below, it does not. GMCF depends on how "
                 "densely each site was surveyed (the survey densities above), so a GMCF that changes, or a "
                 "ranking that does not hold, says as much about the surveys as about the checkpoints.</p>"]
    body.append(operating_point_note(op))
    body.append(f"<img alt='checkpoints on the validation flights' src='{figure_data_uri(screen_figure(screens))}'>")
    return html_page("BirdsEye — checkpoint screening", "".join(body))


def frontier_figure(points, title: str):
    """Scatter of (gmcf_pre, recall_pre) with the Pareto front drawn through its points.

    ``points``: iterable of (gmcf, recall, kind, label) with kind "front", "eligible" or "excluded".
    """
    fig = new_figure(6.4, 4.8)
    ax = fig.subplots()
    styles = {"excluded": dict(c="#bbbbbb", marker="x", s=14, label="not credible / unhealthy"),
              "eligible": dict(c="#1f77b4", marker="o", s=14, label="credible / healthy"),
              "front": dict(c="#d62728", marker="o", s=30, label="Pareto front")}
    pts = [(g, r, k, lab) for g, r, k, lab in points if g is not None and r is not None
           and math.isfinite(g) and math.isfinite(r)]
    for kind, style in styles.items():
        sel = [(g, r) for g, r, k, _ in pts if k == kind]
        if sel:
            ax.scatter(*zip(*sel), **style)
    front = sorted((g, r) for g, r, k, _ in pts if k == "front")
    if len(front) > 1:
        ax.plot(*zip(*front), c="#d62728", lw=1)
    for g, r, k, lab in pts:
        if lab and k != "excluded":
            ax.annotate(lab, (g, r), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("gmcf_pre (a lower bound on precision)")
    ax.set_ylabel("recall_pre")
    ax.set_xlim(-0.02, 1.02)
    ax.set_ylim(-0.02, 1.02)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    ax.set_title(title, fontsize=10)
    return fig


def sweep_figure(result: SweepResult):
    """Every configuration of every checkpoint on one frontier plot, titled with their number."""
    credible, front = result.credible.ravel(), result.pareto.ravel()
    kinds = np.where(front, "front", np.where(credible, "eligible", "excluded"))
    n_checkpoints = len(result.checkpoints)
    title = (f"Operating points ({result.size:,} configurations: {n_checkpoints} checkpoints × "
             f"{result.grid.size:,})" if n_checkpoints > 1 else f"Operating points ({result.size:,} configurations)")
    return frontier_figure(zip(result.gmcf_pre.ravel().tolist(), result.recall_pre.ravel().tolist(), kinds,
                               [""] * len(kinds)), title)


def screen_figure(screens: Sequence[CheckpointScreen]):
    return frontier_figure(((s.counts.gmcf_pre, s.counts.recall_pre,
                             "front" if s.frontier else ("eligible" if s.healthy else "excluded"), s.checkpoint)
                            for s in screens), "Checkpoints at one threshold")


def comparison_report_html(comparison) -> str:
    """The HTML report of comparedetectors: the figures side by side and the changes
    (:class:`.compare.Comparison`)."""
    import html

    from .compare import CHANGES

    d = comparison.to_dict()
    before, after = html.escape(d["before"]["name"]), html.escape(d["after"]["name"])
    rows = [[r["figure"], r["before"], r["after"], r["difference"]] for r in d["side_by_side"]]
    counts = d["changes"]
    body = [f"<p>Before: <b>{before}</b> (model {html.escape(d['before'].get('model') or '–')}); after: "
            f"<b>{after}</b>. Both scored as Evaluate detections scores them, on the same frames and geotags.</p>",
            "<h2>Figures side by side</h2>",
            html_table(["figure", "before", "after", "after − before"], rows),
            "<p class='note'>recall_pre = recovered / geotags in view; gmcf_pre = hit clusters / clusters, a lower "
            "bound on precision, not precision; f1_geo = 2·recall·GMCF / (recall + GMCF); detections per frame = "
            "detections / processed frames (the review load). POST figures appear when a review is given.</p>",
            "<h2>What changed</h2>",
            html_table(["change", "count"], [[name, counts[name]] for name in CHANGES]),
            "<p class='note'>Targets: each in-view geotag by whether each detector recovered it. False clusters: "
            "clusters no in-view geotag matches; two clusters are the same spot when a core point of one lies "
            "within EPS_PRED of a core point of the other. The change layer shows each on the map.</p>",
            operating_point_note(comparison.before.op)]
    return html_page("BirdsEye — detectors compared", "".join(body))
