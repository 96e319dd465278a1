"""The ground model travels with the detections: Detect → Cluster → Evaluate on a simulated 20° slope.

The campaign of ``test_terrain_labels`` (a plane tilted by 20°, noise off, flown terrain-following at
10 m) is imported with its DEM, and three frames lose their altimeter ground (``ground_h_m`` empty,
flag ``no_ground_height``), as frames of a camera solution without tie points do. Detect places the
detections on the DEM and records it in the layer; Cluster detections and Evaluate detections then
need that DEM and count geotags in view on it, every frame included.

The expectation is independent of the ground models: a target is in view when its true position (the
simulator's ``truth/targets.csv``, on the terrain) projects, through a frame's pose and the calibration
alone, into that frame's image (the whole image: EDGE_BUFFER_PX is 0). The level-plane in-view test, which
leaves the three frames out and puts every geotag on each frame's altimeter plane, counts otherwise.
"""
from __future__ import annotations

import json

import numpy as np
import pytest
from qgis.core import (
    QgsFeatureRequest,
    QgsProcessingContext,
    QgsProcessingException,
)
from registry import Recorder, rows, run, simulated_terrain_campaign

from birdseye.birdseye_qgis.core.geometry.camera import load_calibration
from birdseye.birdseye_qgis.core.geometry.ground_record import DEM, LEVEL_PLANE
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.scoring.evaluation import local_frame_for
from birdseye.birdseye_qgis.core.scoring.matching import in_view
from birdseye.birdseye_qgis.qgis_io.detections import read_detections, read_pose_groups
from birdseye.birdseye_qgis.qgis_io.layers import read_geotag_layer

CAMPAIGN = {"SEED": 7, "N_TARGETS": 14, "FIELD_WIDTH_M": 8.0, "FIELD_LENGTH_M": 6.0, "IMAGE_WIDTH": 640,
            "IMAGE_HEIGHT": 400, "FPS": 2.0, "N_MISSED": 0, "N_SPURIOUS": 0, "NOISE_OFF": True,
            "TERRAIN": 1, "SLOPE_DEG": 20.0, "SLOPE_ASPECT_DEG": 250.0}
WITHOUT_GROUND = 3


@pytest.fixture(scope="module")
def slope(birdseye_provider, tmp_path_factory):
    base = tmp_path_factory.mktemp("ground_travels")
    folder = base / "campaign"
    imported = simulated_terrain_campaign(folder, CAMPAIGN)
    sim, dem, geotags, frames = imported, imported["dem"], imported["geotags"], imported["frames"]
    # Frames spread over the flight lose their altimeter ground.
    ids = sorted(f.id() for f in frames.getFeatures())
    lost = ids[len(ids) // 4::len(ids) // WITHOUT_GROUND][:WITHOUT_GROUND]
    frames.startEditing()
    for fid in lost:
        feature = frames.getFeature(fid)
        frames.changeAttributeValue(fid, frames.fields().indexOf("ground_h_m"), None)
        frames.changeAttributeValue(fid, frames.fields().indexOf("flags"),
                                    ",".join(filter(None, [feature["flags"] or "", "no_ground_height"])))
    assert frames.commitChanges()
    detected = run("detect", {"FRAMES": frames, "THRESHOLD": 0.05, "DEM": dem, "DEM_VERTICAL_DATUM": 0,
                              "OUTPUT": "TEMPORARY_OUTPUT"})
    return {"folder": folder, "dem": dem, "dem_path": sim["DEM"], "geotags": geotags, "frames": frames,
            "detected": detected, "detections": detected["OUTPUT"], "base": base}


def true_views(slope) -> dict:
    """Per frame id, which targets' true positions project into the frame's image (pinhole + distortion,
    the frame's own pose: the noise is off): no ground model involved."""
    folder = slope["folder"]
    camera = load_calibration(folder / "calibration.yaml")
    recs = list(slope["frames"].getFeatures())
    num = lambda name: np.array([float(f[name]) for f in recs])
    poses = FramePoses(np.arange(len(recs)), num("lat"), num("lon"), num("height_m"),
                       np.stack([num(q) for q in ("qw", "qx", "qy", "qz")], axis=1), np.zeros(len(recs)), camera)
    geometry = FrameGeometry(poses, local_frame_for([poses]))
    targets = [r for r in rows(folder / "truth" / "targets.csv") if r["geotag_row"]]
    xyz = geometry.local.from_geodetic(*(np.array([float(r[c]) for r in targets]) for c in ("lat", "lon", "h_ground")))
    fi, ti = np.repeat(np.arange(len(recs)), len(xyz)), np.tile(np.arange(len(xyz)), len(recs))
    cam = geometry.to_camera(fi, xyz[ti])
    seen = ((cam[:, 2] > 0) & camera.in_frame(camera.project(cam), 0.0)).reshape(len(recs), len(xyz))
    return {f["frame_id"]: seen[k] for k, f in enumerate(recs)}


def level_in_view(frames, geotag_layer):
    """The level-plane in-view test on a frame layer's frames."""
    groups = read_pose_groups(frames)[0]
    geotags = read_geotag_layer(geotag_layer)
    local = local_frame_for(groups, geotags)
    return in_view(groups, local, local.from_geodetic(geotags.lat, geotags.lon, geotags.height))


def test_detect_records_the_dem_on_every_detection_and_places_every_frame(slope):
    detections = slope["detections"]
    assert slope["detected"]["FRAMES_SKIPPED"] == 0
    assert slope["detected"]["FRAMES_PROCESSED"] == slope["frames"].featureCount()
    values = {(f["ground"], f["dem_source"], f["dem_datum"]) for f in detections.getFeatures()}
    assert values == {(DEM, slope["dem"].source(), "ellipsoidal")}
    det, _ = read_detections(detections, QgsProcessingContext())
    assert (det.ground.model, det.ground.dem_source, det.ground.dem_datum) == (DEM, slope["dem"].source(),
                                                                               "ellipsoidal")


def test_evaluate_counts_geotags_in_view_on_the_dem_with_every_frame(slope):
    """A flight of one frame with an altimeter ground and the three without: the level plane leaves those
    three out and misplaces the geotags near the edges of the one; the DEM counts exactly the true view."""
    truth = true_views(slope)
    frames = slope["frames"]
    lost = [f for f in frames.getFeatures() if f["ground_h_m"] is None or f["ground_h_m"] != f["ground_h_m"]]
    assert len(lost) == WITHOUT_GROUND
    lost_ids = {f.id() for f in lost}

    def flight_of(*features):
        return frames.materialize(QgsFeatureRequest().setFilterFids([f.id() for f in features]))

    # The first frame where the slope alone makes the level plane miscount: it sees other geotags than the
    # frame truly does.
    one = next(f for f in frames.getFeatures() if f.id() not in lost_ids and
               int(level_in_view(flight_of(f), slope["geotags"]).mask.sum()) != int(truth[f["frame_id"]].sum()))
    chosen = flight_of(one, *lost)
    expected = int(np.any([truth[f["frame_id"]] for f in chosen.getFeatures()], axis=0).sum())
    level = level_in_view(chosen, slope["geotags"])
    assert level.n_frames_without_ground == WITHOUT_GROUND and int(level.mask.sum()) != expected

    out = slope["base"] / "dem.json"
    run("evaluatedetections", {"DETECTIONS": [slope["detections"]], "GEOTAGS": slope["geotags"],
                               "FRAMES": [chosen], "DEM": slope["dem"], "DEM_VERTICAL_DATUM": 0,
                               "OUTPUT_JSON": str(out), "OUTPUT_REPORT": None})
    result = json.loads(out.read_text())
    flight = result["flights"][0]
    print(f"in view: truth {expected}, DEM {result['n_in_view']}, level plane {int(level.mask.sum())} "
          f"({level.n_frames_without_ground} frames left out)")
    assert (flight["n_frames"], flight["n_frames_without_ground"]) == (1 + WITHOUT_GROUND, 0)
    assert flight["ground"]["model"] == DEM
    assert result["n_in_view"] == expected
    assert result["recall_pre"] == pytest.approx(result["n_recovered"] / expected)


def test_the_whole_flight_is_scored_on_the_dem_without_dropping_a_frame(slope):
    truth = true_views(slope)
    out = slope["base"] / "whole.json"
    run("evaluatedetections", {"DETECTIONS": [slope["detections"]], "GEOTAGS": slope["geotags"],
                               "FRAMES": [slope["frames"]], "DEM": slope["dem"], "DEM_VERTICAL_DATUM": 0,
                               "OUTPUT_JSON": str(out), "OUTPUT_REPORT": None})
    result = json.loads(out.read_text())
    flight = result["flights"][0]
    assert (flight["n_frames"], flight["n_frames_without_ground"]) == (slope["frames"].featureCount(), 0)
    assert result["n_in_view"] == int(np.any(list(truth.values()), axis=0).sum())
    assert result["recall_pre"] == pytest.approx(result["n_recovered"] / result["n_in_view"])


def test_cluster_and_evaluate_need_the_recorded_dem_and_refuse_it_for_a_level_layer(slope):
    common = {"DETECTIONS": slope["detections"], "GEOTAGS": slope["geotags"], "FRAMES": slope["frames"],
              "OUTPUT": "TEMPORARY_OUTPUT"}
    with pytest.raises(QgsProcessingException, match=rf"field 'DEM'.*placed on the DEM {slope['dem'].source()}"):
        run("clusterdetections", common)
    clusters = run("clusterdetections", {**common, "DEM": slope["dem"], "DEM_VERTICAL_DATUM": 0})
    assert clusters["HIT_COUNT"] >= 1
    with pytest.raises(QgsProcessingException, match="give that DEM"):
        run("evaluatedetections", {"DETECTIONS": [slope["detections"]], "GEOTAGS": slope["geotags"],
                                   "FRAMES": [slope["frames"]], "OUTPUT_JSON": str(slope["base"] / "none.json"),
                                   "OUTPUT_REPORT": None})
    # A level-plane layer (Detect without the DEM, on the frames that have a ground height) is scored on
    # the level plane; a DEM given for it is refused.
    level = run("detect", {"FRAMES": slope["frames"], "THRESHOLD": 0.05, "OUTPUT": "TEMPORARY_OUTPUT"})
    assert level["FRAMES_SKIPPED"] == WITHOUT_GROUND
    assert {f["ground"] for f in level["OUTPUT"].getFeatures()} == {LEVEL_PLANE}
    with pytest.raises(QgsProcessingException, match="not on a DEM: leave DEM empty"):
        run("clusterdetections", {**common, "DETECTIONS": level["OUTPUT"], "DEM": slope["dem"],
                                  "DEM_VERTICAL_DATUM": 0})


def test_the_review_stands_on_the_recorded_dem_and_falls_back_with_the_reason(slope):
    from birdseye.birdseye_qgis.core.geometry.dem import DemGroundFactory
    from birdseye.birdseye_qgis.core.geometry.ground_record import GroundRecord
    from birdseye.birdseye_qgis.qgis_io.review_store import read_review_inputs, review_ground

    inputs = read_review_inputs([slope["detections"]], slope["frames"], slope["geotags"])
    assert isinstance(inputs.ground, DemGroundFactory) and inputs.ground_fallback == ""
    gone = GroundRecord(DEM, str(slope["base"] / "moved.tif"), "ellipsoidal")
    ground, reason = review_ground(gone, inputs.pose_groups)
    assert ground is None and "moved.tif: cannot be opened" in reason

def test_write_labels_judges_a_review_of_dem_detections_on_that_dem(slope, tmp_path):
    """A review of DEM-placed detections, acted on by Write labels: with its DEM the review's in-view test
    stands on the terrain, silently; without one the level plane stands in, and the log says so. Every
    cluster was judged a hard negative: those no geotag settles become hard-negative tiles either way."""
    from qgis.core import (
        QgsCoordinateReferenceSystem,
        QgsCoordinateTransform,
        QgsFeature,
        QgsField,
        QgsProject,
        QgsVectorLayer,
    )
    from qgis.PyQt.QtCore import QVariant

    clusters = run("clusterdetections", {"DETECTIONS": slope["detections"], "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    to_wgs84 = QgsCoordinateTransform(clusters.crs(), QgsCoordinateReferenceSystem("EPSG:4326"),
                                      QgsProject.instance())
    verdicts = QgsVectorLayer("None", "verdicts", "memory")
    verdicts.dataProvider().addAttributes([QgsField(n, QVariant.String) for n in
                                           ("unit_key", "verdict", "provenance", "time", "reviewer")] +
                                          [QgsField("lat", QVariant.Double), QgsField("lon", QVariant.Double)])
    verdicts.updateFields()
    rows_added = []
    for k, cluster in enumerate(clusters.getFeatures()):
        point = to_wgs84.transform(cluster["centroid_x"], cluster["centroid_y"])
        row = QgsFeature(verdicts.fields())
        row.setAttributes([f"u{k}", "hard_negative", "direct", "2024-05-01T10:00:00Z", "ana", point.y(), point.x()])
        rows_added.append(row)
    assert rows_added
    verdicts.dataProvider().addFeatures(rows_added)
    base = {"GEOTAGS": slope["geotags"], "FRAMES": slope["frames"], "WRITE_RASTERS": False,
            "REVIEW": verdicts, "REVIEW_DETECTIONS": [slope["detections"]], "OUTPUT_FRAMES": None,
            "OUTPUT_GEOTAGS": None}
    on_dem, without = Recorder(), Recorder()
    with_dem = run("writelabels", {**base, "DEM": slope["dem"], "DEM_VERTICAL_DATUM": 0,
                                   "OUTPUT_FOLDER": str(tmp_path / "dem")}, on_dem)
    level = run("writelabels", {**base, "OUTPUT_FOLDER": str(tmp_path / "level")}, without)
    assert not [w for w in on_dem.warnings if "review's in-view test" in w]
    assert [w for w in without.warnings if "review's in-view test stands on the level plane" in w]
    assert with_dem["HARD_NEGATIVES"] > 0 and level["HARD_NEGATIVES"] > 0
