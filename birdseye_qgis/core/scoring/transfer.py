"""The transfer report: survey density, and how checkpoint scores on validation flights carry over to held-out flights.

Survey density
--------------
A flight's **survey density** is its in-view geotags per processed frame: for every frame, how many
geotags pass the in-view test *in that frame* (:func:`.matching.in_view`: on the ground the detections
were placed on, with ``edge_buffer_px``), summarised over the frames (:class:`SurveyDensity`): mean,
median, 10th and 90th percentiles (linear interpolation), minimum, maximum and the fraction of frames
that see no geotag. Flights pool by putting their frames together, so the pooled mean is every
(frame, geotag) sighting over every frame.

Why it is reported: a cluster is a hit only where the survey put a geotag. Where a site is surveyed more
sparsely than it holds targets, more real targets go unsurveyed, more clusters go unmatched and GMCF
falls with the detector unchanged; recall, taken over the surveyed targets alone, does not move that
way. The density says how much of a GMCF is the survey's and not the detector's.

Validation → held-out
---------------------
Per checkpoint (:class:`CheckpointTransfer`): the pooled (micro-averaged) ``recall_pre`` and
``gmcf_pre`` on the validation flights and on the held-out flights, each scored as screening scores
them (:func:`.screening.screen_checkpoints`, one threshold, blocks and operating point for both), and
the changes ``delta_recall = recall(held-out) − recall(validation)`` and ``delta_gmcf`` likewise (None
where either figure is undefined).

Across checkpoints (:func:`rank_correlation`): **Spearman's ρ** between the validation and the held-out
figure, for recall and for GMCF. ρ near 1: the validation ranking of the checkpoints holds on the
held-out site; near 0 or below: it does not, and a checkpoint chosen by that figure on validation flights
is not the best there. It is taken over the checkpoints healthy on the validation flights — those a
screening chooses from; a collapsed model, bad everywhere, would make any ranking look stable — whose
figure is defined on both sides. Tied figures take their average rank (``scipy.stats.spearmanr``). With
fewer than :data:`MIN_CHECKPOINTS_FOR_RANKS` checkpoints no ρ is given ("not enough checkpoints": with
two, ρ is ±1 whatever the figures); nor when every checkpoint has the same figure on one side (no
ranking to compare).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, Sequence

import numpy as np

from ..errors import InputError
from .pre_review import PreCounts
from .screening import CheckpointScreen

#: Spearman's ρ needs at least this many checkpoints (with two it is ±1 whatever the figures).
MIN_CHECKPOINTS_FOR_RANKS = 3


@dataclass(frozen=True)
class SurveyDensity:
    """In-view geotags per processed frame, summarised over ``n_frames`` frames (None without frames)."""

    n_frames: int
    mean: float | None
    median: float | None
    p10: float | None
    p90: float | None
    min: int | None
    max: int | None
    frames_without_geotag: float | None

    @classmethod
    def of(cls, per_frame: Iterable) -> "SurveyDensity":
        """The summary of per-frame counts: one array per flight (or one array), pooled by concatenation."""
        parts = [np.asarray(p, dtype=np.int64).reshape(-1) for p in per_frame]
        counts = np.concatenate(parts) if parts else np.empty(0, dtype=np.int64)
        if len(counts) == 0:
            return cls(0, None, None, None, None, None, None, None)
        p10, median, p90 = (float(v) for v in np.percentile(counts, [10, 50, 90]))
        return cls(len(counts), float(counts.mean()), median, p10, p90, int(counts.min()), int(counts.max()),
                   float(np.mean(counts == 0)))

    def to_dict(self) -> dict:
        return {"n_frames": self.n_frames, "mean": self.mean, "median": self.median, "p10": self.p10,
                "p90": self.p90, "min": self.min, "max": self.max,
                "frames_without_geotag": self.frames_without_geotag}


@dataclass(frozen=True)
class RankCorrelation:
    """Spearman's ρ over ``n`` checkpoints, or None with ``note`` saying why it is not given."""

    rho: float | None
    n: int
    note: str = ""

    def to_dict(self) -> dict:
        return {"spearman_rho": self.rho, "n_checkpoints": self.n, "note": self.note}


def rank_correlation(validation: Sequence[float | None], heldout: Sequence[float | None]) -> RankCorrelation:
    """Spearman's ρ between paired figures (one pair per checkpoint), pairs with a None left out."""
    from scipy.stats import spearmanr

    pairs = [(a, b) for a, b in zip(validation, heldout) if a is not None and b is not None]
    n = len(pairs)
    if n < MIN_CHECKPOINTS_FOR_RANKS:
        return RankCorrelation(None, n, f"not enough checkpoints: {n} with the figure on both sets, Spearman's ρ "
                                        f"needs at least {MIN_CHECKPOINTS_FOR_RANKS}")
    a, b = np.array(pairs, dtype=float).T
    for values, side in ((a, "validation"), (b, "held-out")):
        if np.all(values == values[0]):
            return RankCorrelation(None, n, f"no ranking: every checkpoint has the same {side} figure "
                                            f"({values[0]:.3f})")
    return RankCorrelation(float(spearmanr(a, b)[0]), n)


def _difference(after: float | None, before: float | None) -> float | None:
    return None if after is None or before is None else after - before


@dataclass(frozen=True)
class CheckpointTransfer:
    """One checkpoint's pooled counts on the validation and on the held-out flights."""

    checkpoint: str
    validation: PreCounts
    heldout: PreCounts
    healthy_on_validation: bool

    @property
    def delta_recall(self) -> float | None:
        return _difference(self.heldout.recall_pre, self.validation.recall_pre)

    @property
    def delta_gmcf(self) -> float | None:
        return _difference(self.heldout.gmcf_pre, self.validation.gmcf_pre)

    def to_dict(self) -> dict:
        v, h = self.validation, self.heldout
        return {"checkpoint": self.checkpoint, "healthy_on_validation": self.healthy_on_validation,
                "recall_validation": v.recall_pre, "recall_heldout": h.recall_pre, "delta_recall": self.delta_recall,
                "gmcf_validation": v.gmcf_pre, "gmcf_heldout": h.gmcf_pre, "delta_gmcf": self.delta_gmcf,
                "validation": {k: v.to_dict()[k] for k in ("n_in_view", "n_recovered", "n_clusters", "n_hit_clusters")},
                "heldout": {k: h.to_dict()[k] for k in ("n_in_view", "n_recovered", "n_clusters", "n_hit_clusters")}}


@dataclass(frozen=True)
class TransferReport:
    """Per checkpoint (screening order) and the rank correlations across the healthy ones."""

    checkpoints: list
    recall: RankCorrelation
    gmcf: RankCorrelation

    def to_dict(self) -> dict:
        return {"checkpoints": [c.to_dict() for c in self.checkpoints],
                "spearman": {"recall": self.recall.to_dict(), "gmcf": self.gmcf.to_dict(),
                             "over": "checkpoints healthy on the validation flights with the figure on both sets; "
                                     "ties take their average rank"},
                "delta": "held-out − validation"}


def transfer_report(validation: Sequence[CheckpointScreen], heldout: Sequence[CheckpointScreen]) -> TransferReport:
    """The transfer of each checkpoint's screening figures from the validation to the held-out flights."""
    by_name = {s.checkpoint: s for s in heldout}
    missing = [s.checkpoint for s in validation if s.checkpoint not in by_name]
    if missing or len(by_name) != len(validation):
        raise InputError(f"the held-out flights were screened with other checkpoints than the validation flights "
                         f"(not on held-out flights: {', '.join(missing) or 'none'})", field="HELDOUT_FRAMES")
    rows = [CheckpointTransfer(s.checkpoint, s.counts, by_name[s.checkpoint].counts, s.healthy) for s in validation]
    ranked = [r for r in rows if r.healthy_on_validation]
    return TransferReport(rows,
                          rank_correlation([r.validation.recall_pre for r in ranked],
                                           [r.heldout.recall_pre for r in ranked]),
                          rank_correlation([r.validation.gmcf_pre for r in ranked],
                                           [r.heldout.gmcf_pre for r in ranked]))
