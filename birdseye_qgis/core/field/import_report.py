"""What an import reports (kept, left out and why) and what it returns; filters every importer shares."""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .frames import FLAT_ENVELOPE_DEG, Footprints, Frames
from .pose_log import RTK_FIXED


@dataclass
class ImportReport:
    """Counts and sentences for the Processing log.

    ``errors``: input that was left out because it is bad (rows, images), with count and first
    examples; ``notes``: what a user should check (unmatched frames, flags, filters), shown as warnings;
    ``findings``: results that need no action (what was read, a check's figures), shown as information.
    """

    source: str
    counts: dict = field(default_factory=dict)
    errors: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    findings: list = field(default_factory=list)
    unplaced: list = field(default_factory=list)


@dataclass
class FlightImport:
    """What an importer returns; a camera solution with control points adds them and their mark check."""

    frames: Frames
    footprints: Footprints
    track: list
    report: ImportReport
    control_points: object = None
    mark_check: object = None


def name_list(paths, limit=3) -> str:
    return ", ".join(Path(p).name for p in list(paths)[:limit])


def apply_rtk_filter(frames: Frames, fixed_only: bool, report: ImportReport) -> Frames:
    not_fixed = frames.rtk_status != RTK_FIXED
    report.counts.update(rtk_fixed=int(np.count_nonzero(~not_fixed)), rtk_not_fixed=int(not_fixed.sum()))
    if fixed_only and not_fixed.any():
        report.notes.append(f"{int(not_fixed.sum())} frame(s) without an RTK fixed solution were left out "
                            "(RTK filter: fixed only)")
        report.counts["dropped_not_fixed"] = int(not_fixed.sum())
        return frames.subset(~not_fixed)
    if not_fixed.any():
        report.notes.append(f"{int(not_fixed.sum())} frame(s) have no RTK fixed solution; kept and "
                            "flagged rtk_float / rtk_none")
    return frames


#: What flag ``footprint_unbounded`` means, for import reports.
UNBOUNDED_NOTE = ("see past the ground: some of their border's rays reach no DEM cell (the DEM does not cover their "
                  "whole view) or look above the horizon; they are kept without a footprint")


def report_ground(report: ImportReport, frames: Frames) -> None:
    for flag, text in (("no_ground_height", "have no ground height (no good altimeter reading nearby); "
                        "they are kept without a footprint"),
                       ("footprint_unbounded", UNBOUNDED_NOTE),
                       ("steep_terrain", f"lie on terrain steeper than the level plane's {FLAT_ENVELOPE_DEG:g}° "
                                         "envelope; give the DEM to Write labels and Detect too")):
        n = sum(flag in f for f in frames.flags)
        report.counts[flag] = n
        if n:
            first = [int(frames.frame_id[i]) for i, f in enumerate(frames.flags) if flag in f][:5]
            report.notes.append(f"{n} frame(s) {text} (flag {flag}; frame ids {', '.join(map(str, first))})")
