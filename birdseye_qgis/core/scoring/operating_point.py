"""The operating point a detector is scored at: threshold and clustering parameters."""
from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Mapping

from ..detect.clustering import (
    CORE_COUNT_CELLS,
    CORE_COUNTS,
    DEFAULT_CORE_COUNT,
    DEFAULT_DEDUP_CM,
    DEFAULT_EPS_M,
    DEFAULT_MIN_SAMPLES,
    check_core_count,
)
from ..errors import InputError

#: The method's match radius, with its clustering defaults (``detect.clustering``).
DEFAULT_EPS_PRED_M = 0.20
DEFAULT_EDGE_BUFFER_PX = 0.0
#: What an operating point recorded without ``core_count`` counted: BirdsEye recorded no ``core_count``
#: while its DBSCAN counted cells, so an older sweep table, arms file, sealed rule or review log was
#: computed that way, and reads back that way (a sealed rule then still verifies and scores as sealed).
RECORDED_WITHOUT_CORE_COUNT = CORE_COUNT_CELLS


@dataclass(frozen=True)
class OperatingPoint:
    """A full operating point: detection threshold and the clustering/scoring parameters
    (``core_count``: what DBSCAN's core test counts, :mod:`~..detect.clustering`)."""

    threshold: float | None = None
    dedup_cm: float = DEFAULT_DEDUP_CM
    eps_m: float = DEFAULT_EPS_M
    min_samples: int = DEFAULT_MIN_SAMPLES
    eps_pred_m: float = DEFAULT_EPS_PRED_M
    edge_buffer_px: float = DEFAULT_EDGE_BUFFER_PX
    core_count: str = DEFAULT_CORE_COUNT

    def __post_init__(self):
        for name in ("dedup_cm", "eps_m", "eps_pred_m"):
            if not getattr(self, name) > 0:
                raise InputError(f"must be larger than 0 (got {getattr(self, name)})", field=name.upper())
        if int(self.min_samples) != self.min_samples or self.min_samples < 1:
            raise InputError(f"must be a whole number ≥ 1 (got {self.min_samples})", field="MIN_SAMPLES")
        if self.threshold is not None and not 0.0 <= self.threshold <= 1.0:
            raise InputError(f"must be a probability in [0, 1] (got {self.threshold})", field="THRESHOLD")
        if self.edge_buffer_px < 0:
            raise InputError(f"must be ≥ 0 px (got {self.edge_buffer_px})", field="EDGE_BUFFER_PX")
        check_core_count(self.core_count)

    def to_dict(self) -> dict:
        return {"threshold": None if self.threshold is None else float(self.threshold),
                "dedup_cm": float(self.dedup_cm), "eps_m": float(self.eps_m),
                "min_samples": int(self.min_samples), "eps_pred_m": float(self.eps_pred_m),
                "edge_buffer_px": float(self.edge_buffer_px), "core_count": self.core_count}

    @classmethod
    def from_dict(cls, d: Mapping, source: str = "operating point") -> "OperatingPoint":
        """The operating point of a :meth:`to_dict` mapping; one without ``core_count`` reads as
        :data:`RECORDED_WITHOUT_CORE_COUNT`, what it was computed with."""
        unknown = set(d) - {f.name for f in fields(cls)}
        if unknown:
            raise InputError(f"has unknown key(s) {', '.join(sorted(unknown))}", source=source)
        d = dict(d)
        core_count = d.pop("core_count", RECORDED_WITHOUT_CORE_COUNT)
        if core_count not in CORE_COUNTS:
            raise InputError(f"core_count is {core_count!r}, expected one of {', '.join(CORE_COUNTS)}",
                             source=source, field="core_count")
        try:
            values = {k: (None if v is None else float(v)) for k, v in d.items()}
        except (TypeError, ValueError) as exc:
            raise InputError(f"has a value that is not a number ({exc})", source=source) from exc
        samples = values.get("min_samples")
        if samples is not None:
            if samples != int(samples):
                raise InputError(f"min_samples must be a whole number of detections, got {samples:g}", source=source,
                                 field="min_samples")
            values["min_samples"] = int(samples)
        return cls(**values, core_count=core_count)
