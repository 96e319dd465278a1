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
  are in view where no cluster of the flight fired — no core point within ``eps_pred_m`` — and no
  geotag lies within ``eps_pred_m``): ``gmcf_post = (n_hit_clusters + c) / n_clusters`` and
  ``recall_post = (n_recovered + c) / (n_in_view + c + a)``. Only with ``a = 0`` is it printed "≥ x":
  a lower bound on the recall over the known targets (geotags in view, confirmed clusters), since a
  real cluster left unconfirmed would add one to numerator and denominator alike. With ``a > 0``
  the reviewer searched beyond the detections, and the figure is a point value of the recall over
  every real target in view under :data:`.post_review.POINT_VALUE_ASSUMPTIONS`. Either way real
  targets nobody surveyed, found or added are in no term: where the search for missed targets was
  not exhaustive the figure overstates the recall over all real targets. Computed under each
  convention (:data:`CONVENTIONS`).
* No F1 is reported in geospatial units (screening's pixel-space F1 is for choosing checkpoints only).
* Several flights pool by **micro-averaging**: numerators and denominators are summed over flights,
  then divided once (:meth:`PreCounts.__add__`); ratios are never averaged. A geotag in view in two
  flights counts once per flight.

Verdict log API (for the review dock)
----------------------------------------------
The dock stores an append-only table; this module needs from each row only::

    unit_key    str   the review unit (a consensus cluster, or a per-frame group of the method's
                      construction) or an added target
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
2. A unit's **judgements** are the latest verdicts of its provenances. "uncertain" and "unreviewed"
   are abstentions, not votes: only confirmed_real and hard_negative are counted. They resolve under
   a convention (:func:`combine`):
   ``positive_wins`` — confirmed_real if any vote says so, else hard_negative;
   ``hard_negative_wins`` — hard_negative if any, else confirmed_real;
   ``majority_wins`` — the side with more votes; a tie is "uncertain" (neither side has a majority).
   So [confirmed_real, uncertain] → confirmed_real and [C, C, HN, U, U] → confirmed_real. Only
   abstentions → "uncertain"; no judgement at all → "unreviewed".
3. A cluster of a detection layer is resolved **once over all direct and propagated judgements** of
   the units attached to it (:meth:`VerdictLog.resolve_cluster`; the dock knows the units; headless,
   :func:`units_of_clusters` attaches every unit whose position lies within ``eps_pred_m`` of the
   cluster's core points), under the same convention.
4. ``c`` counts the clusters that are not hits and resolve to confirmed_real; ``a`` counts the added
   targets of :func:`.post_review.countable_added_targets` (in view by the geotags' in-view test, no
   cluster of the flight and no geotag within ``eps_pred_m``).

Feeding it: ``log = VerdictLog.from_records(rows)`` (mappings with the fields above, e.g. GeoPackage
features as dicts in fid order), then per flight a :class:`ReviewedFlight` (its :class:`PreCounts`,
per-cluster hit flags and attached unit keys, and ``n_added`` = a), and
``post_scores(log, flights) -> {convention: PostScores}``. :func:`evaluate_flights` does all of it
from geodetic inputs, exactly as ``birdseye:evaluatedetections`` does.
"""
