"""No tile teaches a target as background; targets.csv; σ measured on a label check; the relief check.

One undistorted nadir camera 10 m above level ground: a ground point (east, north) relative to the camera's nadir
lands at u = cx + f·east/10, v = cy − f·north/10 — every expected tile below follows from that by hand.
"""
import csv
import json

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.geotags import Geotags
from birdseye.birdseye_qgis.core.field.surveyed_area import surveyed_area
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.dem import DemRaster
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame, ProjectedCRS
from birdseye.birdseye_qgis.core.geometry.poses import FramePoses
from birdseye.birdseye_qgis.core.labels.mark_check import measured_sigma
from birdseye.birdseye_qgis.core.labels.relief import TargetRelief, dem_relief_m, relief_displacement_m
from birdseye.birdseye_qgis.core.labels.training_set import (
    LabelRequest,
    project_labels,
    read_targets,
    tile_origins,
    tile_outlines_px,
    write_label_set,
)

NADIR = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
SITE = LocalFrame(-27.55, 151.95, 400.0)
F, DEPTH = 1400.0, 10.0
TILE = 128


def camera(width=640, height=400):
    t = np.eye(4)
    t[:3, :3] = NADIR
    return CameraModel(width, height, F, F, (width - 1) / 2, (height - 1) / 2, T_cam_imu=t)


def frames(xy, cam=None, ground=400.0):
    """Level nadir frames 10 m above the ground at local ``xy`` (m), ids 101.."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    lat, lon, h = SITE.to_geodetic(np.column_stack([xy, np.full(len(xy), DEPTH)]))
    quat = np.tile([1.0, 0.0, 0.0, 0.0], (len(xy), 1))
    return FramePoses(np.arange(101, 101 + len(xy)), np.atleast_1d(lat), np.atleast_1d(lon), np.atleast_1d(h), quat,
                      np.full(len(xy), ground), cam or camera())


def tags(xy, ids=None, labels=None, heights=None, provenance=None):
    """Geotags at local ground ``xy`` (m), ellipsoidal heights those of the ground unless given."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    lat, lon, h = SITE.to_geodetic(np.column_stack([xy, np.zeros(len(xy))]))
    return Geotags(list(range(1, len(xy) + 1)) if ids is None else ids, np.atleast_1d(lat), np.atleast_1d(lon),
                   np.atleast_1d(h) if heights is None else heights, labels or ["burrow"] * len(xy), provenance)


def ground_at(u, v):
    """Ground (east, north) m under pixel (u, v) of a frame at the origin (the pinhole relation inverted)."""
    cam = camera()
    return [(u - cam.cx) * DEPTH / F, -(v - cam.cy) * DEPTH / F]


def grey_images(poses, folder):
    import cv2

    paths = []
    for fid in poses.frame_id:
        path = folder / f"{fid}.png"
        cv2.imwrite(str(path), np.full((poses.camera.height, poses.camera.width, 3), 90, np.uint8))
        paths.append(str(path))
    return paths


ALL_TILES = {(y0, x0) for y0 in tile_origins(400, TILE) for x0 in tile_origins(640, TILE)}  # 4 × 5 = 20


def written(out, frame_id=101):
    return {tuple(int(k) for k in p.stem.split("_")[1:]) for p in (out / "tiles" / "images").glob(f"{frame_id}_*")}


def request(**kw):
    # Ratio 100: every negative candidate is written, so a tile missing from the folder was skipped.
    return LabelRequest(**{"sigma_px": 3.0, "write_rasters": False, "tile_size": TILE, "negative_ratio": 100.0, **kw})


def test_a_target_in_the_edge_buffer_leaves_its_tile_out_instead_of_making_it_negative(tmp_path):
    """u = 8 px lies within a 20 px edge buffer: not a positive, and its tile (y0 128, x0 0: v = 199.5) is not
    written either; the label radius 3σ = 9 px reaches no other tile. Without a buffer it is the positive there."""
    poses = frames([[0.0, 0.0]])
    geotags = tags([ground_at(8.0, 199.5), ground_at(361.5, 171.5)])
    images = grey_images(poses, tmp_path)
    labels = project_labels(poses, geotags, edge_buffer_px=20.0, local=SITE, reach_px=9.0)
    np.testing.assert_allclose(labels[0].uv, [[8.0, 199.5], [361.5, 171.5]], atol=1e-3)
    assert labels[0].edge.tolist() == [True, False]
    result = write_label_set(poses, images, geotags, labels, tmp_path / "edge", request(edge_buffer_px=20.0))
    assert written(tmp_path / "edge") == ALL_TILES - {(128, 0)}
    tiles = result.summary["tiles"]
    assert (tiles["positive"], tiles["negative"], tiles["skipped"]["unlabelled_target"]) == (1, 18, 1)
    labels = project_labels(poses, geotags, local=SITE, reach_px=9.0)
    result = write_label_set(poses, images, geotags, labels, tmp_path / "none", request())
    assert written(tmp_path / "none") == ALL_TILES and result.summary["tiles"]["positive"] == 2


def test_a_target_just_beyond_the_border_leaves_its_tile_out(tmp_path):
    """Centre at u = −5 px, 4.5 px outside the image, label radius 9 px: it reaches into tile (128, 0), which is
    left out. Without the reach the target is not seen and that tile would be written as a negative."""
    poses = frames([[0.0, 0.0]])
    geotags = tags([ground_at(-5.0, 199.5)])
    images = grey_images(poses, tmp_path)
    labels = project_labels(poses, geotags, local=SITE, reach_px=9.0)
    assert labels[0].edge.tolist() == [True] and labels[0].margin_px == pytest.approx([-4.5], abs=1e-3)
    result = write_label_set(poses, images, geotags, labels, tmp_path / "reach", request())
    assert written(tmp_path / "reach") == ALL_TILES - {(128, 0)}
    assert result.summary["n_beyond_border"] == 1 and result.summary["n_edge"] == 0
    assert result.summary["geotags_never_in_view"] == [1]
    blind = project_labels(poses, geotags, local=SITE)
    assert len(blind[0].uv) == 0


def test_an_unresolved_cluster_and_a_frame_without_ground_give_no_negative_tiles(tmp_path):
    """An unresolved review cluster at (600, 50) may be a target: tile (0, 512) is left out. A frame without a
    ground height has targets nobody could place: none of its tiles is written (it used to give a negative)."""
    poses = frames([[0.0, 0.0], [40.0, 0.0]])
    poses.ground_height[1] = np.nan
    geotags = tags([ground_at(361.5, 171.5)])
    unresolved = tags([ground_at(600.0, 50.0)], ids=["det#3"], heights=[np.nan], provenance=["review"])
    images = grey_images(poses, tmp_path)
    labels = project_labels(poses, geotags, local=SITE, reach_px=9.0)
    assert labels[0].ground is not None and labels[1].ground is None
    result = write_label_set(poses, images, geotags, labels, tmp_path / "out", request(),
                             unresolved_labels=project_labels(poses, unresolved, local=SITE, reach_px=9.0))
    assert written(tmp_path / "out") == ALL_TILES - {(0, 512)}
    assert written(tmp_path / "out", 102) == set()
    tiles = result.summary["tiles"]
    assert tiles["skipped"] == {"unlabelled_target": 1, "outside_surveyed_area": 0, "frames_without_ground": 1}
    assert tiles["frames_without_ground"] == [102] and result.summary["n_unresolved_in_view"] == 1


def test_a_tile_outline_runs_along_its_pixels_outer_edges():
    """Tile (y0 10, x0 20) of 4 px covers pixel centres u 20…23, v 10…13: its edges lie half a pixel out."""
    np.testing.assert_array_equal(tile_outlines_px([(10, 20)], 4, per_side=2)[0], [
        [19.5, 9.5], [21.5, 9.5], [23.5, 9.5], [23.5, 11.5], [23.5, 13.5], [21.5, 13.5], [19.5, 13.5], [19.5, 11.5]])


def test_no_negative_tile_outside_a_drawn_area_while_a_positive_there_is_kept(tmp_path):
    """The drawn area is east ∈ [−30, 0] m. Tile columns x0 = 0 and 128 span east −2.28 … −0.46 m: inside. Column
    256 spans −0.46 … +0.46 m and crosses the boundary; the rest lie east of it. So the negatives are the 8 tiles
    of the first two columns; the positive tile (128, 256) (target 0.3 m east) lies outside and is kept; the
    other 11 tiles are skipped for lying outside."""
    poses = frames([[0.0, 0.0]])
    geotags = tags([[0.3, 0.2]])
    images = grey_images(poses, tmp_path)
    rect = np.array([[-30.0, -30.0], [0.0, -30.0], [0.0, 30.0], [-30.0, 30.0]])
    lat, lon, _ = SITE.to_geodetic(np.column_stack([rect, np.zeros(4)]))
    area = surveyed_area([], [], drawn=[(lat, lon)])
    labels = project_labels(poses, geotags, local=SITE, reach_px=9.0)
    result = write_label_set(poses, images, geotags, labels, tmp_path / "out", request(), surveyed=area)
    inside = {(y0, x0) for y0, x0 in ALL_TILES if x0 in (0, 128)}
    assert written(tmp_path / "out") == inside | {(128, 256)}
    tiles = result.summary["tiles"]
    assert (tiles["positive"], tiles["negative"], tiles["skipped"]["outside_surveyed_area"]) == (1, 8, 11)
    assert result.summary["surveyed_area"] == {"source": "drawn", "rings": 1}


def test_targets_csv_lists_the_targets_written_with_their_heights(tmp_path):
    poses = frames([[0.0, 0.0]])
    geotags = tags([[0.3, 0.2], [100.0, 100.0]]) + tags([[-0.5, 0.4]], ids=["det#7"], heights=[np.nan],
                                                         provenance=["review"])
    labels = project_labels(poses, geotags, local=SITE)
    write_label_set(poses, ["a.jpg"], geotags, labels, tmp_path, LabelRequest(write_rasters=False))
    with open(tmp_path / "targets.csv", newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["geotag_id", "label", "provenance", "lat", "lon", "height_m", "height_ref"]
    assert rows[1] == ["1", "burrow", "survey", f"{geotags.lat[0]:.9f}", f"{geotags.lon[0]:.9f}",
                       f"{geotags.height[0]:.3f}", "ellipsoidal"]
    assert rows[2] == ["det#7", "burrow", "review", f"{geotags.lat[2]:.9f}", f"{geotags.lon[2]:.9f}", "", ""]
    assert len(rows) == 3  # geotag 2 is never in view: not in labels.csv, not here
    assert abs(float(rows[1][5]) - 400.0) < 0.01

    # Read back as Train detector reads it: the targets written, heights ellipsoidal, a review target's unknown.
    back = read_targets(tmp_path)
    assert list(back.ids) == ["1", "det#7"] and list(back.provenance) == ["survey", "review"]
    assert back.lat[0] == pytest.approx(geotags.lat[0], abs=1e-9) and back.height[0] == pytest.approx(400.0, abs=0.01)
    assert np.isnan(back.height[1])
    assert read_targets(tmp_path / "elsewhere") is None
    # A height in another reference (an edited file) is refused, naming its row and field.
    text = (tmp_path / "targets.csv").read_text(encoding="utf-8")
    (tmp_path / "targets.csv").write_text(text.replace(",ellipsoidal", ",EGM96"), encoding="utf-8")
    with pytest.raises(InputError, match=r"row 2.*height_ref.*EGM96 geoid.*ellipsoidal") as err:
        read_targets(tmp_path)
    assert err.value.row == 2


def test_sigma_measured_on_a_label_check_is_the_per_axis_rms():
    """Check-point residuals (3, 4), (−1, 0), (0, −2), (2, 2): Σ(Δu² + Δv²) = 25 + 1 + 4 + 8 = 38 over 4 marks,
    σ = √(38 / 4 / 2) = √4.75. The control point's residual (30, 0) and the check point without a label stay out."""
    def mark(kind, du, dv, u=500.0, v=300.0):
        return {"kind": kind, "u_mark": u, "v_mark": v, "u_label": None if du is None else u + du,
                "v_label": None if dv is None else v + dv}

    records = [mark("check_point", 3, 4), mark("check_point", -1, 0), mark("control_point", 30, 0),
               mark("check_point", 0, -2), mark("check_point", 2, 2), mark("check_point", None, None)]
    got = measured_sigma(records, "wheat.gpkg")
    assert got.sigma_px == pytest.approx(np.sqrt(4.75))
    assert (got.kind, got.n_marks, got.n_without_label) == ("check_point", 4, 1)
    assert got.rms_u_px == pytest.approx(np.sqrt(14 / 4)) and got.rms_v_px == pytest.approx(np.sqrt(24 / 4))
    assert got.max_px == pytest.approx(5.0) and got.few and got.relative_uncertainty == pytest.approx(0.25)
    assert got.to_dict()["marks"] == "check_point" and got.to_dict()["file"] == "wheat.gpkg"
    only_control = measured_sigma([mark("control_point", 6, 8)])
    assert only_control.kind == "control_point" and only_control.sigma_px == pytest.approx(np.sqrt(50))
    with pytest.raises(InputError, match=r"wheat.gpkg, row 2, field 'v_mark'.*not a number"):
        measured_sigma([mark("check_point", 1, 1), {**mark("check_point", 1, 1), "v_mark": "x"}], "wheat.gpkg")
    with pytest.raises(InputError, match=r"row 1, field 'kind'"):
        measured_sigma([{**mark("check_point", 1, 1), "kind": "marker"}])
    with pytest.raises(InputError, match=r"no mark with a label"):
        measured_sigma([mark("check_point", None, None)])


def test_relief_displacement_is_h_r_over_d_against_the_label_radius(tmp_path):
    """A target 2.5 m east of the nadir, 10 m below the camera, standing 0.52 m proud: h·r/d = 0.13 m, which at
    f/d = 140 px/m is 18.2 px. With σ = 5 px (radius 15 px = 10.71 cm at 10 m) the frame is over; with σ = 7 px
    (radius 21 px) it is not."""
    poses = frames([[0.0, 0.0]], cam=camera(1400, 1000))
    geotags = tags([[2.5, 0.0]])
    labels = project_labels(poses, geotags, local=SITE)
    assert labels[0].nadir_distance_m == pytest.approx([2.5], abs=1e-4)
    assert labels[0].height_m == pytest.approx([10.0], abs=1e-4)
    assert relief_displacement_m(0.52, 2.5, 10.0) == pytest.approx(0.13)
    relief = TargetRelief(np.array([0.52]), "RELIEF_M = 0.52 m")
    over = write_label_set(poses, ["a.jpg"], geotags, labels, tmp_path / "a",
                           LabelRequest(sigma_px=5.0, write_rasters=False), relief=relief).summary["relief"]
    assert over["n_frames_over"] == 1 and over["n_labels_checked"] == 1
    frame = over["frames_over"][0]
    assert (frame["frame_id"], frame["geotag_id"]) == (101, 1)
    assert frame["displacement_cm"] == pytest.approx(13.0, abs=0.01)
    assert frame["displacement_px"] == pytest.approx(18.2, abs=0.01)
    assert frame["label_radius_cm"] == pytest.approx(15 * 10 / 1400 * 100, abs=0.01)
    within = write_label_set(poses, ["a.jpg"], geotags, labels, tmp_path / "b",
                             LabelRequest(sigma_px=7.0, write_rasters=False), relief=relief).summary["relief"]
    assert within["n_frames_over"] == 0 and within["max_displacement_px"] == pytest.approx(18.2, abs=0.01)
    assert json.loads((tmp_path / "b" / "summary.json").read_text())["relief"]["source"] == "RELIEF_M = 0.52 m"


def test_relief_from_a_dem_is_its_height_range_within_a_metre():
    """A plane rising 0.1 m per metre eastwards: within 1 m of a target the range is 2 × 0.1 m. On a node raised
    by 0.4 m the range runs from that top down to the plane 1 m west, 0.1 m below the node: 0.5 m; 5 m east of
    it the bump is out of reach."""
    crs = "EPSG:32756"
    x0, y0 = (float(v) for v in ProjectedCRS(crs).from_geodetic(SITE.lat0, SITE.lon0))
    cols = np.arange(41)
    heights = np.tile(100.0 + 0.1 * (cols + 0.5) * 0.5, (41, 1))  # cells of 0.5 m, centres at x0 − 10 + …
    heights[20, 20] += 0.4
    dem = DemRaster(heights, (x0 - 10.25, 0.5, y0 + 10.25, -0.5), crs, "ellipsoidal")
    lat, lon = [], []
    for dx in (0.0, 5.0):  # the bumped node lies under the site's origin
        a, b = ProjectedCRS(crs).to_geodetic(x0 + dx, y0)
        lat.append(float(a)), lon.append(float(b))
    np.testing.assert_allclose(dem_relief_m(dem, lat, lon), [0.4 + 0.1, 0.2], atol=1e-6)
