"""Evaluate detections of one or more flights against geotags, from geodetic inputs."""
from __future__ import annotations

from dataclasses import asdict, dataclass, field, replace
from typing import Sequence

import numpy as np

from ..detect.clustering import Clustering, GroundPositions, cluster_detections
from ..errors import InputError, check_cancel
from ..field.geotags import Geotags
from ..geometry.geodesy import LocalFrame
from ..geometry.ground_record import RASTER, GroundRecord
from ..geometry.poses import FramePoses
from .matching import InView, in_view
from .operating_point import OperatingPoint
from .post_review import ReviewedFlight, countable_added_targets, post_scores
from .pre_review import FlightScore, PreCounts, pool, score_flight
from .transfer import SurveyDensity
from .verdicts import VerdictLog, units_of_clusters


@dataclass
class Detections:
    """One detection layer: WGS84 positions (ellipsoidal heights, NaN allowed), frame ids, scores, and
    the ground model Detect placed them with (``ground``)."""

    lat: np.ndarray
    lon: np.ndarray
    height: np.ndarray
    frame_id: np.ndarray
    score: np.ndarray
    name: str = "detections"
    model: str = ""
    model_digest: str = ""
    threshold: float | None = None
    ground: GroundRecord = GroundRecord()

    def __post_init__(self):
        for n in ("lat", "lon", "height", "score"):
            setattr(self, n, np.asarray(getattr(self, n), dtype=float).reshape(-1))
        self.frame_id = np.asarray(self.frame_id).reshape(-1)

    def __len__(self) -> int:
        return len(self.lat)

    def ground_positions(self, local: LocalFrame) -> GroundPositions:
        return GroundPositions.from_geodetic(local, self.lat, self.lon, self.height)


@dataclass
class Flight:
    """One flight to score: its detections, its processed frames (pose groups, one per camera) and the
    ground-model factory the detections were placed with (``detections.ground.factory(dem)``; None = the
    level plane), which the in-view test stands on.

    ``view_mask`` (G,): for detections found on a raster (``ground`` RASTER, :func:`mosaic_flight`), the geotags
    in view (its valid pixels cover them) instead of the frames' test; for frame detections, the geotags the
    frames' test may count (the others are left out: a comparison with a mosaic over the same targets).
    ``covers(lat, lon) -> (N,) bool``: for raster detections, which points the raster covers (the plugin reads the
    raster the layer records): the geotags in view when there is no ``view_mask``, and the targets a reviewer
    added that count (:func:`added_in_view`)."""

    detections: Detections
    pose_groups: Sequence[FramePoses]
    name: str = ""
    ground: object = None
    view_mask: np.ndarray | None = None
    covers: object = None

    @property
    def seen_once(self) -> bool:
        """Whether each target can be detected once only (a raster: one image), not once per frame."""
        return self.detections.ground.model == RASTER


def min_samples_for(detections: Detections, min_samples: int) -> int:
    """DBSCAN's core test for ``detections``: ``min_samples``, or 1 for detections found on a raster — one image
    shows a target once, so one detection is a whole target there."""
    return 1 if detections.ground.model == RASTER else int(min_samples)


def mosaic_flight(detections: Detections, pose_groups: Sequence[FramePoses], inside_raster, frames_in_view=None,
                  name: str = "") -> Flight:
    """The :class:`Flight` of detections found on a raster: the geotags in view are those ``inside_raster``
    (G,) covers with valid pixels — and, given ``frames_in_view`` (G,), in view of the flight's frames too, so a
    frames-against-mosaic comparison counts one set of targets for both."""
    mask = np.asarray(inside_raster, dtype=bool)
    if frames_in_view is not None:
        mask = mask & np.asarray(frames_in_view, dtype=bool)
    return Flight(detections, pose_groups, name or detections.name, None, mask)


@dataclass
class FlightEvaluation:
    name: str
    clustering: Clustering
    score: FlightScore
    in_view: InView
    n_detections: int
    n_added: int = 0
    cluster_units: list = field(default_factory=list)
    ground: GroundRecord = GroundRecord()


@dataclass
class Evaluation:
    """PRE (and POST when reviewed) scores of one or several flights, and the local frame used."""

    op: OperatingPoint
    local: LocalFrame
    flights: list
    pooled: PreCounts
    post: dict | None = None
    review_notes: list = field(default_factory=list)

    @property
    def survey_density(self) -> SurveyDensity:
        """In-view geotags per processed frame over every flight's frames (:mod:`.transfer`)."""
        return SurveyDensity.of(f.in_view.per_frame for f in self.flights)

    def to_dict(self) -> dict:
        """The JSON of evaluatedetections: pooled keys at the top, per-flight rows, the POST block."""
        out = dict(self.pooled.to_dict())
        out["parameters"] = self.op.to_dict()
        out["pooling"] = "micro-average over flights (sums of counts, one division)"
        out["survey_density"] = self.survey_density.to_dict()
        out["flights"] = []
        for i, f in enumerate(self.flights):
            row = {"name": f.name, "n_detections": int(f.n_detections), "n_frames": int(f.in_view.n_frames),
                   "n_frames_without_ground": int(f.in_view.n_frames_without_ground),
                   "ground": asdict(f.ground), "survey_density": SurveyDensity.of([f.in_view.per_frame]).to_dict()}
            row.update(f.score.counts.to_dict())
            if self.post is not None:
                row["post"] = {conv: p.flights[i].to_dict() for conv, p in self.post.items()}
            out["flights"].append(row)
        if self.post is not None:
            out["post"] = {conv: p.pooled.to_dict() for conv, p in self.post.items()}
            out["review_notes"] = list(self.review_notes)
        return out


def raster_view(mask, n_geotags: int) -> InView:
    """The :class:`InView` of a raster's geotags in view: one image, no frames counted."""
    mask = np.asarray(mask, dtype=bool).reshape(-1)
    if len(mask) != n_geotags:
        raise InputError(f"the raster's in-view mask has {len(mask)} entries for {n_geotags} geotags")
    return InView(mask, 0, 0, np.empty(0, dtype=int))


def added_in_view(flight: Flight, local: LocalFrame, added_lat, added_lon, added_local,
                  edge_buffer_px: float) -> np.ndarray:
    """Which targets a reviewer added ``flight`` sees — WGS84 ``added_lat``, ``added_lon`` (A,), the same points in
    ``local`` as ``added_local`` (A, 3) — by the rule its geotags follow: for detections found on a raster, the
    points the raster covers (``covers``; a flight without it — a mosaic compared with frames — counts by its
    frames, as its geotags must be in their view too); for frame detections, the frames' in-view test on the
    flight's ground."""
    if flight.seen_once and flight.covers is not None:
        return np.asarray(flight.covers(np.asarray(added_lat, dtype=float), np.asarray(added_lon, dtype=float)),
                          dtype=bool).reshape(-1)
    return in_view(flight.pose_groups, local, added_local, edge_buffer_px, flight.ground).mask


def local_frame_for(pose_groups: Sequence[FramePoses], geotags: Geotags | None = None) -> LocalFrame:
    """A local frame at the middle of every frame (and geotag) position, at the median ground height."""
    pose_groups = list(pose_groups)
    lat = np.concatenate([p.lat for p in pose_groups] +
                         ([geotags.lat] if geotags is not None and len(geotags) else []))
    lon = np.concatenate([p.lon for p in pose_groups] +
                         ([geotags.lon] if geotags is not None and len(geotags) else []))
    h = np.concatenate([p.ground_height for p in pose_groups] or [np.empty(0)])
    if len(lat) == 0:
        raise InputError("there are no frames to score against")
    return LocalFrame.around(lat, lon, h[np.isfinite(h)] if np.isfinite(h).any() else None)


def evaluate_flights(flights: Sequence[Flight], geotags: Geotags, op: OperatingPoint = OperatingPoint(),
                     log: VerdictLog | None = None, local: LocalFrame | None = None,
                     progress=None, is_canceled=None) -> Evaluation:
    """Cluster and score every flight, pool them, and compute POST scores when a verdict log is given.

    Detections below ``op.threshold`` (when set) are left out before clustering.
    """
    if not flights:
        raise InputError("give at least one detection layer")
    local = local or local_frame_for([p for f in flights for p in f.pose_groups], geotags)
    geotag_local = geotags.in_local(local)
    unit_keys, unit_xy, added, notes = [], np.empty((0, 2)), [], []
    if log is not None:
        unit_keys, ulat, ulon, unplaced = log.unit_positions()
        if len(unit_keys):
            unit_xy = local.from_geodetic(ulat, ulon, np.full(len(ulat), local.h0))[:, :2]
        if unplaced:
            notes.append(f"{len(unplaced)} reviewed unit(s) have no position (lat, lon) and could not be "
                         f"attached to clusters, e.g. {', '.join(unplaced[:3])}")
        added = log.added_targets()
    added_lat, added_lon = np.array([r.lat for r in added], dtype=float), np.array([r.lon for r in added], dtype=float)
    added_local = local.from_geodetic(added_lat, added_lon, np.full(len(added), local.h0)) if added else None
    results = []
    n = len(flights)
    for i, flight in enumerate(flights):
        check_cancel(is_canceled)
        det = flight.detections
        keep = np.ones(len(det), dtype=bool) if op.threshold is None else det.score >= op.threshold
        positions = det.ground_positions(local).subset(keep)
        clustering = cluster_detections(positions, det.frame_id[keep], det.score[keep], op.dedup_cm, op.eps_m,
                                        min_samples_for(det, op.min_samples), core_count=op.core_count)
        if flight.seen_once:
            if flight.view_mask is not None:
                view = raster_view(flight.view_mask, len(geotag_local))
            elif flight.covers is not None:
                view = raster_view(flight.covers(geotags.lat, geotags.lon), len(geotag_local))
            else:
                raise InputError("detections found on a raster are scored over the geotags the raster covers: "
                                 "give the raster", source=det.name)
        else:
            view = in_view(flight.pose_groups, local, geotag_local, op.edge_buffer_px, flight.ground)
            if flight.view_mask is not None:
                view = replace(view, mask=view.mask & np.asarray(flight.view_mask, dtype=bool))
        score = score_flight(clustering, geotag_local[:, :2], view.mask, op.eps_pred_m)
        ev = FlightEvaluation(flight.name or det.name, clustering, score, view, int(keep.sum()), ground=det.ground)
        if log is not None:
            ev.cluster_units = units_of_clusters(clustering, unit_xy, unit_keys, op.eps_pred_m)
            if added:
                seen = added_in_view(flight, local, added_lat, added_lon, added_local, op.edge_buffer_px)
                ev.n_added = int(countable_added_targets(added_local[:, :2], seen, clustering, geotag_local[:, :2],
                                                         op.eps_pred_m).sum())
        results.append(ev)
        if progress is not None:
            progress((i + 1) / n)
    pooled = pool(r.score.counts for r in results)
    post = None
    if log is not None:
        post = post_scores(log, [ReviewedFlight(r.score.counts, r.score.cluster_hit, r.cluster_units,
                                                r.n_added) for r in results])
    return Evaluation(op, local, results, pooled, post, notes)
