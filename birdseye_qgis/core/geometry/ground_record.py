"""The ground model detections were placed with, as Detect records it in the detection layer.

Detect places each detection on a ground model (``docs/design.md#ground``): the level plane, the
method's plane or a DEM. Everything that later asks "is this geotag in view?" or "where is this
detection in that frame?" — scores, the sweep, screening, the review's units and chips — must stand on
the same ground, or recall denominators and matches differ from what Detect saw. A :class:`GroundRecord`
is that choice as data: the detection layer carries it per feature (``qgis_io/detections.py``), and
:meth:`GroundRecord.factory` turns it back into the ground-model factory core code takes as ``ground``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from .dem import DemGroundFactory, DemRaster
from .ground import MethodPlaneGround

LEVEL_PLANE, METHOD_PLANE, DEM = "level", "method_plane", "dem"
#: Detections found on a raster (an orthomosaic, ``birdseye:detectraster``): on the map itself, no frame between.
RASTER = "raster"
GROUND_MODELS = (LEVEL_PLANE, METHOD_PLANE, DEM, RASTER)


@dataclass(frozen=True)
class GroundRecord:
    """``model`` (one of :data:`GROUND_MODELS`); for a DEM, where it came from: ``dem_source`` (the
    raster's file, as its layer names it), ``dem_datum`` (what its heights are measured from, one of
    ``dem.VERTICAL_DATUMS``) and ``geoid_undulation_m`` (N given with it, None when not)."""

    model: str = LEVEL_PLANE
    dem_source: str = ""
    dem_datum: str = ""
    geoid_undulation_m: float | None = None

    def __post_init__(self):
        if self.model not in GROUND_MODELS:
            raise InputError(f"ground model {self.model!r} is not one of {', '.join(GROUND_MODELS)}")

    @classmethod
    def of(cls, dem: DemRaster | None, dem_source: str = "", method_plane: bool = False) -> "GroundRecord":
        """The record of a run placing on ``dem`` (read from ``dem_source``), else on the method's plane
        or the level plane."""
        if dem is not None:
            n = dem.geoid_undulation_m
            return cls(DEM, dem_source, dem.vertical_datum, None if n is None or not math.isfinite(n) else float(n))
        return cls(METHOD_PLANE if method_plane else LEVEL_PLANE)

    def describe(self) -> str:
        """The ground in words, for messages."""
        if self.model == DEM:
            undulation = "" if self.geoid_undulation_m is None else f", N = {self.geoid_undulation_m:g} m"
            return f"the DEM {self.dem_source or '(source not recorded)'} (heights {self.dem_datum}{undulation})"
        if self.model == METHOD_PLANE:
            return "the method's plane (normal to the optical axis at the raw altimeter range)"
        if self.model == RASTER:
            return f"the raster {self.dem_source or '(source not recorded)'} itself (found on the map)"
        return "the level plane at each frame's altimeter ground"

    def factory(self, dem: DemRaster | None, source: str | None = None, dem_field: str = "DEM"):
        """The ground-model factory (``FrameGeometry -> GroundModel``, None = the level plane) that stands on
        the recorded ground: the DEM given for a DEM record, the method's or the level plane otherwise.

        A DEM record without ``dem``, or ``dem`` for a plane record, is refused (naming ``source``, the
        detection layer, and ``dem_field``): the in-view test would stand on other ground than the
        detections, and the recall denominator would change with it.
        """
        if self.model == RASTER:
            raise InputError(f"its detections were found on {self.describe()}, not in frames: frames cannot say "
                             "which geotags they saw. Cluster detections, Evaluate detections and Compare detectors "
                             "score them against the raster they were found on; this tool takes frame detections "
                             "only", source=source)
        if self.model == DEM:
            if dem is None:
                raise InputError(f"its detections were placed on {self.describe()}: give that DEM ({dem_field}, "
                                 "with its vertical datum) so geotags are counted in view on the same ground",
                                 source=source, field=dem_field)
            return DemGroundFactory(dem)
        if dem is not None:
            raise InputError(f"its detections were placed on {self.describe()}, not on a DEM: leave {dem_field} "
                             "empty (a DEM would count geotags in view on other ground than the detections "
                             "stand on), or run Detect targets again with the DEM", source=source, field=dem_field)
        return MethodPlaneGround if self.model == METHOD_PLANE else None


def common_ground(records, names) -> GroundRecord:
    """The ground several detection layers (``names``, one per record) were all placed on. Layers placed
    on different grounds are refused: pooled, compared or reviewed together, the same target would stand
    at different places and be in view of different frames."""
    records, names = list(records), list(names)
    if not records:
        raise InputError("give at least one detection layer")
    grounds = {}
    for record, name in zip(records, names):
        grounds.setdefault(record, []).append(str(name))
    if len(grounds) > 1:
        listed = "; ".join(f"{', '.join(layers)} on {record.describe()}" for record, layers in grounds.items())
        raise InputError(f"the detection layers were placed on different grounds ({listed}): use layers that Detect "
                         "placed on the same ground (the same DEM, or the same plane)", field="ground")
    return records[0]
