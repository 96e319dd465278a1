"""What a field survey cost in people's time, and how to split the next field among the people (docs/design.md
§4.10, "Survey report and field partitions").

The method surveys a field with RTK rovers, one geotag per target, and reports its field work as geotags per
worker-hour; it splits a field into partitions of about one hour of surveying per person. This module gives
both from the geotags' capture times (``time_utc``) and the worker who took each (``worker``).

**Sessions and working time (the one rule of every figure).** A worker's captures, sorted by time, form
sessions: a gap longer than ``session_gap_s`` (default 20 min, :data:`DEFAULT_SESSION_GAP_S`) between two
consecutive captures starts a new session. A worker's *typical interval* is the median of the intervals between
consecutive captures within their sessions (all workers' pooled when the worker has none: each of their sessions
holds one capture). A session's working time is

    last capture − first capture + one typical interval,

so a session of n evenly spaced captures counts n intervals (the walk to the first target is counted as one
interval, as every other target's walk is), and a single-capture session counts one interval. A group of geotags
(a worker's, a partition's, a flight's, all) is worked for the sum, over its workers, of the working time of that
worker's captures in the group, split into sessions by the same gap: time a worker spent elsewhere for longer than
the gap is not counted. Geotags per worker-hour = geotags with a time / worker-hours; worker-hours are the sum
over workers, never the elapsed time times the people (two people for 6 h are 12 worker-hours; the elapsed field
time, first to last capture of anyone, is reported apart). Geotags without a capture time are counted, and left
out of the rates.

**Partitions.** :func:`partition_field` cuts a field across its long axis (the long side of its minimum-area
bounding rectangle) into pieces of equal area, each what one person surveys in about ``hours_per_piece`` (area per
hour = geotags per hour / targets per hectare), their number rounded up to a multiple of the people so everyone
gets as many pieces; each worker gets one contiguous block of pieces (:func:`partition_field` says why). Core gives
the cut positions (found by bisection on the area of the field below a cut); the Processing algorithm cuts the
layer's geometry with them.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from ..errors import InputError
from .geotags import utc_text

#: A gap between two consecutive captures of one worker longer than this (s) starts a new session: a break, a
#: walk back to the car, another field.
DEFAULT_SESSION_GAP_S = 20 * 60.0
#: The name of the worker of geotags without one (a layer without a ``worker`` field is one unnamed worker).
UNNAMED_WORKER = ""
#: Partition field's defaults when no survey report is given: one geotag every 30 s (walk to the target, set
#: the pole, a few seconds of RTK averaging) and 100 targets per hectare. Both are placeholders to replace with
#: the figures of your own survey (Survey report's geotags per worker-hour; your targets' density).
DEFAULT_GEOTAGS_PER_HOUR = 120.0
DEFAULT_TARGETS_PER_HA = 100.0
#: Schema of the survey report JSON.
REPORT_SCHEMA = "birdseye-survey-report/1"
M2_PER_HA = 10_000.0
#: The partition layer (Partition field's output), one feature per piece.
PARTITION_FIELDS = [
    ("field", "int", "the field (feature of the area layer, 1.. in its order) the piece was cut from"),
    ("partition", "int", "partition number, 1.. over all fields, along each field's long axis"),
    ("worker", "int", "the person who surveys it, 1..N"),
    ("order", "int", "walking order among the worker's pieces, 1.."),
    ("area_ha", "double", "area of the piece (ha)"),
    ("expected_hours", "double", "one person's surveying time for the piece (h)"),
    ("expected_geotags", "double", "targets expected in the piece (area × targets per ha)"),
]


# ------------------------------------------------------------------------------------------ time rule
def capture_seconds(texts, source: str = "", field_name: str = "time_utc") -> np.ndarray:
    """Each capture time (ISO 8601 text; without a zone it is UTC, as the field is named) as seconds since
    1970-01-01 UTC; NaN where empty. A text that is not a date and time is refused, naming its row (1..)."""
    out = np.full(len(texts), np.nan)
    for row, text in enumerate(texts, start=1):
        if text is None or not str(text).strip():
            continue
        iso = utc_text(str(text), zone_less_is_utc=True)
        if iso is None:
            raise InputError(f"'{text}' is not a date and time (expected ISO 8601, e.g. 2026-05-20T15:27:09Z)",
                             source=source, row=row, field=field_name)
        out[row - 1] = datetime.fromisoformat(iso.replace("Z", "+00:00")).timestamp()
    return out


def sessions(times_s, gap_s: float = DEFAULT_SESSION_GAP_S) -> list[np.ndarray]:
    """The capture times (s) sorted and split into sessions: a gap longer than ``gap_s`` starts a new one."""
    times = np.sort(np.asarray(times_s, dtype=float))
    if not len(times):
        return []
    return np.split(times, np.flatnonzero(np.diff(times) > gap_s) + 1)


def within_session_intervals(times_s, gap_s: float = DEFAULT_SESSION_GAP_S) -> np.ndarray:
    """The intervals (s) between consecutive captures of one session."""
    return np.concatenate([np.diff(s) for s in sessions(times_s, gap_s)] or [np.empty(0)])


def working_seconds(times_s, typical_interval_s: float, gap_s: float = DEFAULT_SESSION_GAP_S) -> float:
    """One worker's working time (s) for these captures: over their sessions, Σ (last − first + one typical
    interval) — the module's rule."""
    return float(sum(s[-1] - s[0] + typical_interval_s for s in sessions(times_s, gap_s)))


# ------------------------------------------------------------------------------------------ report
@dataclass(frozen=True)
class Figures:
    """The field figures of a group of geotags (a worker's, a partition's, a flight's, all of them).

    ``geotags``: in the group; ``timed``: of them with a capture time; ``sessions``: the workers' sessions over
    the timed ones; ``worker_hours``: their working time (module docstring); ``workers``: workers with a timed
    geotag in the group."""

    name: str
    geotags: int
    timed: int
    sessions: int
    worker_hours: float
    workers: int

    @property
    def geotags_per_worker_hour(self) -> float | None:
        return self.timed / self.worker_hours if self.worker_hours > 0 else None

    def to_dict(self) -> dict:
        return {"name": self.name, "geotags": self.geotags, "geotags_with_time": self.timed,
                "sessions": self.sessions, "worker_hours": self.worker_hours, "workers": self.workers,
                "geotags_per_worker_hour": self.geotags_per_worker_hour}


@dataclass(frozen=True)
class SurveyReport:
    """:func:`survey_report`'s result. ``typical_interval_s``: per worker; ``partitions``/``flights``: empty when
    none were given; ``outside``: geotags in no partition; ``elapsed_hours``: first to last capture of anyone."""

    session_gap_s: float
    overall: Figures
    workers: list
    typical_interval_s: dict
    elapsed_hours: float
    first_utc: str
    last_utc: str
    partitions: list
    outside: int
    flights: list
    label_count: int | None = None
    frame_count: int | None = None

    @property
    def people(self) -> int:
        return self.overall.workers

    @property
    def partitions_surveyed(self) -> int:
        return sum(p.geotags > 0 for p in self.partitions)

    def per_worker_hour(self, count: int | None) -> float | None:
        """``count`` (labels, frames) per worker-hour of the whole survey."""
        hours = self.overall.worker_hours
        return count / hours if count is not None and hours > 0 else None

    def to_dict(self) -> dict:
        return {
            "schema": REPORT_SCHEMA,
            "rule": RULE_TEXT.format(gap_min=self.session_gap_s / 60.0),
            "session_gap_min": self.session_gap_s / 60.0,
            "overall": {**self.overall.to_dict(), "people": self.people, "elapsed_hours": self.elapsed_hours,
                        "first_utc": self.first_utc, "last_utc": self.last_utc,
                        "label_count": self.label_count, "frame_count": self.frame_count,
                        "labels_per_worker_hour": self.per_worker_hour(self.label_count),
                        "frames_per_worker_hour": self.per_worker_hour(self.frame_count)},
            "workers": [{**w.to_dict(), "typical_interval_s": self.typical_interval_s.get(w.name)}
                        for w in self.workers],
            "partitions": [p.to_dict() for p in self.partitions],
            "coverage": {"partitions": len(self.partitions),
                         "partitions_with_geotags": self.partitions_surveyed,
                         "geotags_outside_partitions": self.outside},
            "flights": [f.to_dict() for f in self.flights],
        }


#: The rule in one sentence, as the HTML report and the JSON state it.
RULE_TEXT = ("A worker's captures split into sessions wherever two are more than {gap_min:g} min apart; a session "
             "counts from its first to its last capture plus one typical interval (the worker's median time between "
             "captures), and worker-hours add up every worker's sessions.")


def survey_report(times, workers=None, partition_of=None, partitions=(), flights=None,
                  session_gap_s: float = DEFAULT_SESSION_GAP_S, label_count: int | None = None,
                  frame_count: int | None = None, source: str = "") -> SurveyReport:
    """The field figures of a survey (module docstring for the rule).

    ``times``: per geotag its capture time, ISO 8601 text ("" or None: unknown; :func:`capture_seconds`);
    ``workers``: per geotag its worker's name (None, "": :data:`UNNAMED_WORKER`; None for all: one unnamed
    worker); ``partition_of``: per geotag its partition's id, None outside every partition, and ``partitions``
    every partition's id (those without a geotag count in the coverage); ``flights``: {flight name: per geotag
    True when it lies in one of the flight's footprints}; ``label_count``, ``frame_count``: labels and frames of
    the survey's training set, reported per worker-hour. Refused: no geotag with a capture time, or a survey in
    which no two captures of one worker lie within ``session_gap_s`` (no interval to count a session by); a gap of
    0 s or less."""
    if not session_gap_s > 0:
        raise InputError(f"the session gap must be longer than 0 s, got {session_gap_s:g}", field="SESSION_GAP_MIN")
    seconds = capture_seconds(times, source)
    n = len(seconds)
    names = np.array([UNNAMED_WORKER if w is None else str(w).strip() for w in
                      (workers if workers is not None else [None] * n)], dtype=object)
    timed = np.isfinite(seconds)
    if not timed.any():
        raise InputError(f"none of the {n} geotag(s) has a capture time: the report needs the time_utc field filled "
                         "(Import geotags fills it from the rover's time column)", source=source, field="time_utc")
    worker_names = sorted(set(names[timed]))
    intervals = {w: within_session_intervals(seconds[timed & (names == w)], session_gap_s) for w in worker_names}
    pooled = np.concatenate(list(intervals.values()))
    if not len(pooled):
        raise InputError(f"no two captures of one worker lie within {session_gap_s / 60:g} min of each other, so no "
                         "session has a typical interval to count its time by; check the times, or raise the "
                         "session gap", source=source, field="time_utc")
    typical = {w: float(np.median(intervals[w] if len(intervals[w]) else pooled)) for w in worker_names}

    def figures(name: str, member) -> Figures:
        member = np.asarray(member, dtype=bool)
        count_sessions, hours, busy = 0, 0.0, 0
        for w in worker_names:
            own = seconds[member & timed & (names == w)]
            if len(own):
                busy += 1
                count_sessions += len(sessions(own, session_gap_s))
                hours += working_seconds(own, typical[w], session_gap_s) / 3600.0
        return Figures(name, int(member.sum()), int((member & timed).sum()), count_sessions, hours, busy)

    first, last = float(seconds[timed].min()), float(seconds[timed].max())
    inside = list(partition_of) if partition_of is not None else [None] * n
    return SurveyReport(
        session_gap_s=session_gap_s,
        overall=figures("all", np.ones(n, dtype=bool)),
        workers=[figures(w, names == w) for w in sorted(set(names))],
        typical_interval_s=typical,
        elapsed_hours=(last - first) / 3600.0,
        first_utc=_iso(first), last_utc=_iso(last),
        partitions=[figures(str(p), [q == p for q in inside]) for p in partitions],
        outside=sum(q is None for q in inside) if partitions else 0,
        flights=[figures(name, member) for name, member in (flights or {}).items()],
        label_count=label_count, frame_count=frame_count)


def _iso(seconds: float) -> str:
    return datetime.fromtimestamp(seconds, tz=timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")


def label_counts(summary_path) -> tuple[int, int]:
    """(labels, frames with labels) of a Write labels folder's ``summary.json`` (or the folder itself)."""
    path = Path(summary_path)
    path = path / "summary.json" if path.is_dir() else path
    try:
        summary = json.loads(path.read_text(encoding="utf-8"))
        return int(summary["n_labels"]), int(summary["n_frames_with_labels"])
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise InputError(f"is not a Write labels summary.json with n_labels and n_frames_with_labels ({exc})",
                         source=str(path)) from exc


def report_geotags_per_hour(report_path) -> float:
    """The geotags per worker-hour of a survey report JSON (:meth:`SurveyReport.to_dict`)."""
    path = Path(report_path)
    try:
        report = json.loads(path.read_text(encoding="utf-8"))
        rate = report["overall"]["geotags_per_worker_hour"] if report.get("schema") == REPORT_SCHEMA else None
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
        raise InputError(f"cannot be read as a Survey report JSON ({exc})", source=str(path)) from exc
    if not (isinstance(rate, (int, float)) and rate > 0):
        raise InputError(f"is not a Survey report JSON ({REPORT_SCHEMA}) with geotags per worker-hour",
                         source=str(path))
    return float(rate)


def survey_report_html(report: SurveyReport) -> str:
    """The report for a reader who does not program: short tables, units in the headers, figures rounded to what
    they mean (hours to 0.01 h, rates to 0.1, intervals to 1 s), the rule stated once."""
    from ..scoring.reports import html_page, html_table

    def hours(v):
        return None if v is None else f"{v:.2f}"

    def rate(v):
        return None if v is None else f"{v:,.1f}"

    d = report.to_dict()
    o = d["overall"]
    rows = [["Geotags (with a capture time)", f"{o['geotags']} ({o['geotags_with_time']})"],
            ["People (workers)", o["people"]],
            ["Worker-hours [h] (sum over workers)", hours(o["worker_hours"])],
            ["Geotags per worker-hour", rate(o["geotags_per_worker_hour"])],
            ["Elapsed field time, first to last capture [h]", hours(o["elapsed_hours"])],
            ["First capture (UTC)", o["first_utc"]], ["Last capture (UTC)", o["last_utc"]]]
    for key, label in (("label_count", "Labels"), ("frame_count", "Frames with labels")):
        if o[key] is not None:
            rows += [[label, f"{o[key]:,}"], [f"{label} per worker-hour", rate(report.per_worker_hour(o[key]))]]
    body = ["<h2>Survey</h2>", html_table(["figure", "value"], rows),
            f"<p class='note'>{d['rule']} Geotags without a capture time are counted but left out of the rates.</p>",
            "<h2>Workers</h2>",
            html_table(["worker", "geotags", "sessions", "typical interval [s]", "working time [h]",
                        "geotags per worker-hour"],
                       [[w["name"] or "(unnamed)", w["geotags"], w["sessions"],
                         None if w["typical_interval_s"] is None else f"{w['typical_interval_s']:.0f}",
                         hours(w["worker_hours"]), rate(w["geotags_per_worker_hour"])] for w in d["workers"]])]
    if d["partitions"]:
        c = d["coverage"]
        body += ["<h2>Partitions</h2>",
                 html_table(["partition", "geotags", "workers", "worker-hours [h]", "geotags per worker-hour"],
                            [[p["name"], p["geotags"], p["workers"], hours(p["worker_hours"]),
                              rate(p["geotags_per_worker_hour"])] for p in d["partitions"]]),
                 f"<p class='note'>{c['partitions_with_geotags']} of {c['partitions']} partitions hold a geotag; "
                 f"{c['geotags_outside_partitions']} geotag(s) lie outside every partition.</p>"]
    if d["flights"]:
        body += ["<h2>Flights</h2>",
                 html_table(["flight", "geotags in its footprints", "field time [h]", "geotags per worker-hour"],
                            [[f["name"], f["geotags"], hours(f["worker_hours"]), rate(f["geotags_per_worker_hour"])]
                             for f in d["flights"]]),
                 "<p class='note'>A flight's field time is the working time of the captures of the geotags its "
                 "footprints hold, by the same rule.</p>"]
    return html_page("Survey report", "".join(body))


# ------------------------------------------------------------------------------------------ partitions
@dataclass(frozen=True)
class Piece:
    """One partition: ``partition`` (1.. along the axis), its ``worker`` (1..N) and walking ``order`` within the
    worker's pieces (1..), its area (m²), the hours one person needs for it and the geotags expected in it;
    ``lo_m``, ``hi_m``: its cut positions along the axis (m from the plan's origin)."""

    partition: int
    worker: int
    order: int
    area_m2: float
    expected_hours: float
    expected_geotags: float
    lo_m: float
    hi_m: float


@dataclass(frozen=True)
class FieldPartition:
    """:func:`partition_field`'s result: the pieces, and the frame they are cut in (``origin`` (2,), ``axis`` the
    unit vector of the long axis, ``across`` the field's extent (min, max) perpendicular to it, m)."""

    pieces: list
    origin: np.ndarray
    axis: np.ndarray
    across: tuple
    area_m2: float
    area_per_hour_m2: float

    def strip(self, piece: Piece, margin_m: float = 1.0) -> np.ndarray:
        """The rectangle (4, 2) of ``piece``'s strip, across the whole field; the first and last pieces' outer
        ends and both sides reach ``margin_m`` beyond the field, so cutting the field with it leaves no sliver."""
        lo = piece.lo_m - (margin_m if piece.partition == 1 else 0.0)
        hi = piece.hi_m + (margin_m if piece.partition == len(self.pieces) else 0.0)
        c0, c1 = self.across[0] - margin_m, self.across[1] + margin_m
        normal = np.array([-self.axis[1], self.axis[0]])
        return np.array([self.origin + s * self.axis + c * normal for s, c in ((lo, c0), (hi, c0), (hi, c1),
                                                                              (lo, c1))])


def partition_field(polygon_xy, n_people: int, hours_per_piece: float = 1.0,
                    geotags_per_hour: float = DEFAULT_GEOTAGS_PER_HOUR,
                    targets_per_ha: float = DEFAULT_TARGETS_PER_HA) -> FieldPartition:
    """A field cut into pieces of about ``hours_per_piece`` of one person's surveying, shared by ``n_people``.

    ``polygon_xy``: the field as polygons, each a list of rings (K, 2) in metres of a projected CRS, its exterior
    first and then its holes. A person surveys ``geotags_per_hour / targets_per_ha`` ha per hour; a piece may hold
    that much times ``hours_per_piece``. The count is ceil(area / that), rounded up to a multiple of
    ``n_people``, so each piece takes at most ``hours_per_piece`` and everyone gets as many pieces. Pieces are
    strips of equal area cut perpendicular to the long axis (the long side of the field's minimum-area bounding
    rectangle: strips run across the field's short way); the cuts are found by bisection on the area of the field
    below a cut.

    Workers get contiguous blocks: pieces 1..m go to worker 1, m+1..2m to worker 2, and so on, each walked in
    axis order. Neighbouring strips share a cut line, so a worker walks from one piece straight into the next and
    never crosses another's ground; round-robin dealing would interleave the workers and send each across the
    others' strips between pieces. (In a concave field a strip may fall in two parts; the pieces stay equal in
    area and in order along the axis.)"""
    if n_people < 1:
        raise InputError(f"needs at least one person, got {n_people}", field="N_PEOPLE")
    for name, value in (("HOURS_PER_PIECE", hours_per_piece), ("GEOTAGS_PER_HOUR", geotags_per_hour),
                        ("TARGETS_PER_HA", targets_per_ha)):
        if not (math.isfinite(value) and value > 0):
            raise InputError(f"must be greater than 0, got {value:g}", field=name)
    polygons = [[np.asarray(ring, dtype=float)[:, :2] for ring in polygon] for polygon in polygon_xy]
    exterior = np.vstack([polygon[0] for polygon in polygons if len(polygon)] or [np.empty((0, 2))])
    if len(exterior) < 3:
        raise InputError("the field has no polygon to partition")
    origin = exterior.mean(axis=0)  # metres of a projected CRS are large: cut near the field, not near 0
    polygons = [[ring - origin for ring in polygon] for polygon in polygons]
    axis = long_axis(exterior - origin)
    normal = np.array([-axis[1], axis[0]])
    along = (exterior - origin) @ axis
    across = (exterior - origin) @ normal
    area = area_below(polygons, axis, math.inf)
    if not area > 0:
        raise InputError("the field's polygon has no area")
    area_per_hour = geotags_per_hour / targets_per_ha * M2_PER_HA
    # A hair of tolerance: a field of exactly 4 pieces' area must not become 5 by rounding.
    count = max(1, math.ceil(area / (area_per_hour * hours_per_piece) - 1e-9))
    count = math.ceil(count / n_people) * n_people
    cuts = [float(along.min())]
    for k in range(1, count):
        cuts.append(_cut_at(polygons, axis, k * area / count, cuts[-1], float(along.max())))
    cuts.append(float(along.max()))
    per_worker = count // n_people
    piece_area = area / count
    pieces = [Piece(partition=i + 1, worker=i // per_worker + 1, order=i % per_worker + 1, area_m2=piece_area,
                    expected_hours=piece_area / area_per_hour,
                    expected_geotags=piece_area / M2_PER_HA * targets_per_ha, lo_m=cuts[i], hi_m=cuts[i + 1])
              for i in range(count)]
    return FieldPartition(pieces, origin, axis, (float(across.min()), float(across.max())), area, area_per_hour)


def partition_records(plans) -> list:
    """(plan, piece, record) of every piece of several fields' :class:`FieldPartition` s, in order: partitions
    numbered on from one field to the next, and each worker's walking order going on into the next field (the
    worker finishes their pieces of one field, then walks to the next). ``record`` has the
    :data:`PARTITION_FIELDS`."""
    out, walked = [], {}
    for field_row, plan in enumerate(plans, start=1):
        for piece in plan.pieces:
            walked[piece.worker] = walked.get(piece.worker, 0) + 1
            out.append((plan, piece, {
                "field": field_row, "partition": len(out) + 1, "worker": piece.worker, "order": walked[piece.worker],
                "area_ha": round(piece.area_m2 / M2_PER_HA, 4), "expected_hours": round(piece.expected_hours, 3),
                "expected_geotags": round(piece.expected_geotags, 1)}))
    return out


def long_axis(points) -> np.ndarray:
    """The unit vector of the long side of the minimum-area rectangle around ``points`` (N, 2): one of its sides
    lies along an edge of their convex hull, so each hull edge's direction is tried."""
    hull = convex_hull(points)
    best = None
    for a, b in zip(hull, np.roll(hull, -1, axis=0)):
        edge = b - a
        length = math.hypot(*edge)
        if length == 0:
            continue
        u = edge / length
        v = np.array([-u[1], u[0]])
        extent_u, extent_v = np.ptp(hull @ u), np.ptp(hull @ v)
        if best is None or extent_u * extent_v < best[0]:
            best = (extent_u * extent_v, u if extent_u >= extent_v else v)
    return best[1]


def convex_hull(points) -> np.ndarray:
    """Andrew's monotone chain: the hull's vertices (H, 2), counter-clockwise."""
    pts = sorted(set(map(tuple, np.asarray(points, dtype=float))))
    if len(pts) < 3:
        return np.array(pts)

    def half(sequence):
        chain = []
        for p in sequence:
            while len(chain) >= 2 and _cross(chain[-2], chain[-1], p) <= 0:
                chain.pop()
            chain.append(p)
        return chain[:-1]

    return np.array(half(pts) + half(reversed(pts)))


def _cross(o, a, b) -> float:
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def area_below(polygons, axis, cut: float) -> float:
    """The area (m²) of the polygons where (x · axis) ≤ ``cut``: each exterior ring's clipped area, less its holes'.

    Each ring is clipped to the half-plane by Sutherland–Hodgman, which is exact for a convex clip region (a
    half-plane is one); a concave ring comes out as one ring with edges doubled back along the cut line, which
    add no area, so the shoelace area is still the area of the clipped part."""
    total = 0.0
    for polygon in polygons:
        for index, ring in enumerate(polygon):
            clipped = _clip_below(ring, axis, cut)
            total += (1.0 if index == 0 else -1.0) * abs(_shoelace(clipped))
    return total


def _clip_below(ring, axis, cut: float) -> np.ndarray:
    """Sutherland–Hodgman of a ring against the half-plane (x · axis) ≤ cut."""
    s = ring @ axis
    out = []
    for i in range(len(ring)):
        j = (i + 1) % len(ring)
        if s[i] <= cut:
            out.append(ring[i])
        if (s[i] <= cut) != (s[j] <= cut):
            t = (cut - s[i]) / (s[j] - s[i])
            out.append(ring[i] + t * (ring[j] - ring[i]))
    return np.array(out) if out else np.empty((0, 2))


def _shoelace(ring) -> float:
    if len(ring) < 3:
        return 0.0
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _cut_at(polygons, axis, target_m2: float, lo: float, hi: float) -> float:
    """The cut position in [lo, hi] with ``target_m2`` of the field below it, by bisection (the area below a cut
    grows with the cut); 60 halvings leave a bracket of 2⁻⁶⁰ of the field's length."""
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if area_below(polygons, axis, mid) < target_m2:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)
