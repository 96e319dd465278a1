"""Review units, verdict actions, input digests and image chips for the review dock.

Everything the review dock decides lives here, free of QGIS and Qt; ``review_store`` persists it and
``gui/review`` shows it. Scores are never computed here: the dock calls
:func:`.scoring.evaluate_flights`, exactly as ``birdseye:evaluatedetections`` does.

Review units
------------
One or several detection layers of one flight (checkpoints, thresholds) are reviewed together, so each
physical spot is judged once whichever model fired there:

* the detections of every layer are placed in the local metric frame of the flight
  (:func:`.scoring.local_frame_for`, the frame the scores use), pooled, de-duplicated on the
  ``dedup_cm`` grid and DBSCAN-clustered (``eps_m``, ``min_samples``, ``core_count``) with
  :func:`.clustering.cluster_detections` — the chain a single layer goes through. Each cluster of the
  union is one **review unit**; the record keeps which layers fired in it. Noise is no unit.
* a unit's **position** is its core point (de-duplicated cell) nearest the mean of its detections:
  always on the detections, so a verdict attaches (within ``eps_pred_m``) to the clusters the layers
  formed there, even for a long, chained unit whose mean lies between detections.
* a unit's **key** is ``u`` + its latitude and longitude to 7 decimals (about 1 cm), e.g.
  ``u-27.5500131+151.9500099``: the same inputs and parameters give the same keys, so a review resumes
  on the same units; an added target is keyed ``a`` + its position the same way.
* a unit is **matched** when an in-view geotag lies within ``eps_pred_m`` of its core points (the hit
  test of :func:`.scoring.score_flight`). Order: unmatched units first (they need a person), then by
  frames that saw the unit (most first), highest score, key.

These consensus units are the default (one verdict per spot suits several layers best). The
**method's units** (``ReviewParameters(units="method")``, :func:`.units.build_method_units`) are
built as the method builds them, for reproducing its review:

* every detection (all layers pooled) is matched on its own: it is set aside, in no unit, when an
  in-view geotag lies within ``eps_pred_m`` (horizontal) of its ground position;
* per frame, the detections that stay unmatched are grouped by complete linkage on their pixel
  positions, cut at ``group_px`` (30 px): every two detections of a group are at most 30 px apart
  (:func:`.units.complete_linkage_groups`). Each group is one unit, seen in one frame; so one spot is
  judged once per frame that saw it, and a cluster of a layer resolves once over all those
  judgements (:meth:`.scoring.verdicts.VerdictLog.resolve_cluster`);
* a unit's position is its detection nearest the group's mean ground position; its key is the
  position key followed by ``@<frame id>`` (``u-27.5500131+151.9500099@101``), since the same spot
  sits at the same position in every frame; no unit is matched; the order rule is the one above.

Verdict actions (the log is append-only)
----------------------------------------
Rows follow :mod:`.scoring`'s verdict-log API (unit_key, verdict, provenance, time, reviewer, lat, lon,
sequence = fid). Every user action appends one group of rows sharing an ``action_id``:

* **verdict** — a direct row for the unit; with propagation on, a row for every other unit of its
  propagation group (DBSCAN over unit positions, ε = :data:`PROPAGATION_EPS_M`, one point per
  neighbourhood) with provenance ``propagated:dbscan_0.20m/<source key>``. One provenance per source
  keeps every source's vote, so a spot two neighbours disagree on is a conflict the three conventions
  resolve (:data:`.scoring.CONVENTIONS`), not a silent overwrite. Votes a source has propagated follow
  its later verdicts (also with propagation off), so a propagated vote never contradicts its source.
  Rows that would not change their slot (unit, provenance) are not written.
* **add** — an ``added`` row for a target the reviewer placed (the ``a`` term).
* **undo** — for every row of the latest action not yet undone, a row restoring that slot's verdict
  from before the action (``unreviewed`` when it had none); the undo row names the action it undoes.
  Nothing is ever deleted, and the undo history is rebuilt from the log when a review resumes.

Input digests
-------------
:func:`content_digest` is a SHA-256 over a layer's relevant content (CRS, the listed fields, the
geometry), independent of feature order; every row records the digests of the inputs it was made
against, and :func:`check_inputs` reports verdicts recorded against other contents or parameters.

Chips
-----
:func:`plan_unit_chips` picks the frames that detected a unit (highest score first), a crop window of
``window_px`` around the detection (moved inside the image), the unit's detections in that frame and
the geotags nearby projected into it (:func:`.projection.project_pairs` on the level ground);
:func:`render_chip` draws them (detections as circles, geotags as crosses). Pixels follow the OpenCV
convention (docs/design.md#camera): (0, 0) is the centre of the top-left pixel.

Detections found on a raster (an orthomosaic: frame 0, ``u``, ``v`` its pixels) are reviewed without frames:
the units take the geotags the raster covers as in view (``build_units(view_mask=…)``, the mask Evaluate
detections uses), one detection is a target (:func:`.scoring.evaluation.min_samples_for`), and each unit has
one chip, a window of raster pixels around its best detection (:func:`plan_raster_unit_chips` over a
:class:`RasterIndex`); the pixels are read by ``qgis_io.raster_reader.RasterPixels``, window by window.
"""
