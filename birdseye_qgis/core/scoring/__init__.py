"""Honest scores for a detector: recall and the geotag-matched cluster fraction, before and after review.

Definitions (docs/design.md#scores; the help texts repeat them)
-------------------------------------------------------------------------------------
Detections of all processed frames are back-projected, de-duplicated on a ``dedup_cm`` grid and
clustered with DBSCAN (``eps_m``, ``min_samples``) in a local metric frame (:mod:`.clustering`).

* A geotag is **in view** when it passes the in-frame test (:func:`~.projection.project_in_view`
  over :class:`~.ground.LevelPlaneGround`, ``edge_buffer_px``) in at least one processed frame.
  "Processed" = every frame of the frame layer given (detect ran on all of them); frames without a
  ground height are left out, as detect skips them.
* An in-view geotag is **recovered** when it lies within ``eps_pred_m`` (horizontal distance,
  ``d ≤ eps_pred_m``) of a *core* point of some cluster.
* A cluster is a **hit** when at least one in-view geotag lies within ``eps_pred_m`` of its core
  points. A geotag near two clusters makes both hits; a cluster near two geotags is one hit.
* ``recall_pre = n_recovered / n_in_view``;
  ``gmcf_pre = n_hit_clusters / n_clusters`` — the geotag-matched cluster fraction, a *lower bound on
  precision, not precision*: surveys are never exhaustive, so an unmatched cluster may be real.
* After review (``c`` = clusters confirmed real and not hit, ``a`` = targets a reviewer added that
  are in view): ``gmcf_post = (n_hit_clusters + c) / n_clusters`` and
  ``recall_post ≥ (n_recovered + c) / (n_in_view + c + a)``, printed with "≥" as the method writes it;
  real targets nobody surveyed, found or added are in no term, so the figure bounds the recall over
  all real targets from above. Computed under each tie-break convention (:data:`CONVENTIONS`).
* No F1 is reported in geospatial units (screening's pixel-space F1 is for choosing checkpoints only).
* Several flights pool by **micro-averaging**: numerators and denominators are summed over flights,
  then divided once (:meth:`PreCounts.__add__`); ratios are never averaged. A geotag in view in two
  flights counts once per flight.

Verdict log API (for the review dock)
----------------------------------------------
The dock stores an append-only table; this module needs from each row only::

    unit_key    str   the review unit (a consensus cluster) or an added target
    verdict     str   "confirmed_real" | "hard_negative" | "uncertain" | "unreviewed" | "added"
    provenance  str   "direct", or "propagated:<rule>" (e.g. "propagated:dbscan_0.20m")
    time        str   ISO 8601 (naive = UTC); informational order key, see below
    reviewer    str
    lat, lon    float WGS84 degrees of the unit's centroid / of the added target (required for
                      "added" rows; on unit rows it lets a *headless* scorer place the unit)
    sequence    int   append order (the GeoPackage fid); defaults to the position in the input

Rules (:class:`VerdictLog`):

1. Per (unit_key, provenance) the **latest** row wins: largest (time, sequence). An "unreviewed" row
   withdraws that provenance's vote (undo); an "added" row is undone the same way.
2. A unit's **votes** are the latest verdicts of its provenances, "unreviewed" dropped. They resolve
   under a convention (:func:`combine`):
   ``positive_wins`` — confirmed_real if any vote says so, else hard_negative if any, else uncertain;
   ``hard_negative_wins`` — hard_negative if any, else confirmed_real if any, else uncertain;
   ``majority_wins`` — the verdict with the most votes; a tie between the leaders is "uncertain".
   No vote at all → "unreviewed".
3. A cluster of a detection layer takes the resolved verdicts of the units attached to it (the dock
   knows them; headless, :func:`units_of_clusters` attaches every unit whose position lies within
   ``eps_pred_m`` of the cluster's core points) and combines them under the same convention.
4. ``c`` counts the clusters that are not hits and resolve to confirmed_real; ``a`` counts the added
   targets in view of the flight (same in-view test as geotags).

Feeding it: ``log = VerdictLog.from_records(rows)`` (mappings with the fields above, e.g. GeoPackage
features as dicts in fid order), then per flight a :class:`ReviewedFlight` (its :class:`PreCounts`,
per-cluster hit flags and attached unit keys, and ``n_added``), and
``post_scores(log, flights) -> {convention: PostScores}``. :func:`evaluate_flights` does all of it
from geodetic inputs, exactly as ``birdseye:evaluatedetections`` does.
"""
