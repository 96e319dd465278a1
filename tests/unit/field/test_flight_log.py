"""Pose-log parsing, image listing, strobe↔image sync, ground heights, footprints, flight_data.db."""
from __future__ import annotations

import sqlite3
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "data"))
from synthetic_flight import HEADER, make_flight, write_images

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.flight_log import import_flight_log, import_pose_log
from birdseye.birdseye_qgis.core.field.flight_track import flight_track
from birdseye.birdseye_qgis.core.field.frame_records import FRAME_FIELD_NAMES, euler_degrees, poses_from_records
from birdseye.birdseye_qgis.core.field.frames import FRAME_LAYER_FIELDS, frame_records, ground_heights
from birdseye.birdseye_qgis.core.field.images import list_images, sync_strobes
from birdseye.birdseye_qgis.core.field.pose_log import read_pose_log
from birdseye.birdseye_qgis.core.geometry.camera import load_calibration
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame, ProjectedCRS
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat

ROW = "100.{k:02d},52.0,5.0,60.0,1,0,0,0,3,15.0,20.0,{strobe}"


@pytest.fixture(scope="module")
def flight(tmp_path_factory):
    return make_flight(tmp_path_factory.mktemp("flight"), n_frames=40, leg_m=15.0)


@pytest.fixture(scope="module")
def camera(flight):
    return load_calibration(flight["calibration"])


# ------------------------------------------------------------------------------------ pose log
def test_read_pose_log_round_trip(flight):
    log = read_pose_log(flight["pose_log"])
    cols = flight["cols"]
    assert len(log) == len(cols["time_s"])
    np.testing.assert_allclose(log.time_s, cols["time_s"], atol=1e-6)
    np.testing.assert_allclose(log.lat, cols["lat_deg"], atol=1e-9)
    np.testing.assert_allclose(log.quat[:, 2], cols["qy"], atol=1e-8)
    assert log.strobe.sum() == 40 and log.problems.count == 0
    assert log.row[0] == 2  # line 1 is the header


def test_pose_log_bad_rows_are_reported_with_line_and_field(tmp_path):
    lines = [HEADER,
             ROW.format(k=0, strobe=1),
             "100.01,52.0,abc,60.0,1,0,0,0,3,15.0,20.0,0",      # text in lon
             "100.02,52.0,5.0,60.0,1,0,0,0,3,15.0,20.0",          # a column short
             "100.03,95.0,5.0,60.0,1,0,0,0,3,15.0,20.0,0",        # latitude out of range
             "100.04,52.0,5.0,60.0,0,0,0,0,3,15.0,20.0,0",        # zero quaternion
             "100.05,52.0,5.0,60.0,1,0,0,0,3,15.0,20.0,2",        # strobe 2
             "100.06,52.0,5.0,60.0,1,0,0,0,3,,,0",                # no altimeter reading: fine
             ROW.format(k=7, strobe=1)]
    path = tmp_path / "log.csv"
    path.write_text("\n".join(lines) + "\n")
    for chunk in (2, 1000):  # the result must not depend on where chunks break
        log = read_pose_log(path, chunk_lines=chunk)
        assert log.row.tolist() == [2, 8, 9]
        assert np.isnan(log.radalt[1]) and log.radalt[2] == 15.0
        got = sorted((e.row, e.field) for e in log.problems.examples)
        assert got == [(3, "lon_deg"), (4, None), (5, "lat_deg"), (6, "qw"), (7, "strobe")]
        assert log.problems.count == 5
        text = {e.row: str(e) for e in log.problems.examples}
        assert text[3].startswith(f"{path}, row 3, field 'lon_deg': 'abc' is not a number")
        assert "unit quaternion" in text[6]


def test_pose_log_header_problems(tmp_path):
    path = tmp_path / "log.csv"
    path.write_text("time_s,lat_deg,lon_deg\n1,2,3\n")
    with pytest.raises(InputError, match=r"row 1: header has no column\(s\) height_m, qw"):
        read_pose_log(path)
    path.write_text("")
    with pytest.raises(InputError, match="is empty"):
        read_pose_log(path)
    # Columns in another order and without the optional SNR column.
    path.write_text("strobe,time_s,qw,qx,qy,qz,lat_deg,lon_deg,height_m,rtk_status,radalt_m,extra\n"
                    "1,5.0,1,0,0,0,10.0,20.0,30.0,3,12.5,x\n")
    log = read_pose_log(path)
    assert log.time_s.tolist() == [5.0] and log.lat.tolist() == [10.0] and log.radalt.tolist() == [12.5]
    assert np.isinf(log.radalt_snr[0]) and log.strobe.tolist() == [True]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(junk=st.lists(st.text(alphabet=st.characters(blacklist_categories=("Cs",)), max_size=60)
                     .map(lambda s: s.replace("\n", " ").replace("\r", " ")), max_size=8),
       positions=st.lists(st.integers(0, 6), max_size=8))
def test_fuzz_pose_log_keeps_every_good_row(tmp_path, junk, positions):
    good = [ROW.format(k=k, strobe=k % 2) for k in range(6)]
    lines = list(good)
    for text, pos in zip(junk, positions):
        lines.insert(min(pos, len(lines)), text)
    path = tmp_path / "fuzz.csv"
    path.write_text(HEADER + "\n" + "\n".join(lines) + "\n", encoding="utf-8")
    try:
        log = read_pose_log(path, chunk_lines=3)
    except InputError:
        pytest.fail("a log with good rows must import them")
    kept = set(np.round(log.time_s, 6).tolist())
    assert {100.0 + k / 100 for k in range(6)} <= kept


# ------------------------------------------------------------------------------------ images
def test_list_images_from_names_and_from_csv(tmp_path):
    folder = tmp_path / "names"
    write_images(folder, [1700000000.25, 1700000000.5])
    (folder / "notes.txt").touch()
    images = list_images(folder)
    np.testing.assert_allclose(images.time_s, [1700000000.25, 1700000000.5], atol=1e-6)
    assert images.ignored == ["notes.txt"]
    assert Path(images.path[0]).is_absolute() and Path(images.path[0]).name == "1700000000.250000000.png"
    # nsec is nanoseconds, not a decimal fraction: "12.5" is 12 s + 5 ns.
    (tmp_path / "ns").mkdir()
    (tmp_path / "ns" / "12.5.jpg").touch()
    assert list_images(tmp_path / "ns").time_s[0] == pytest.approx(12.000000005, abs=1e-12)

    folder = tmp_path / "csv"
    write_images(folder, [10.0, 10.2, 10.4], images_csv=True)
    with open(folder / "images.csv", "a") as f:
        f.write("abc,frame_x.jpg\n10.6,missing.jpg\n")
    images = list_images(folder)
    assert images.time_s.tolist() == [10.0, 10.2, 10.4]
    assert [(e.row, e.field) for e in images.problems.examples] == [(5, "time_s"), (6, "file")]


def test_list_images_without_images_is_an_error(tmp_path):
    (tmp_path / "photo.png").touch()
    with pytest.raises(InputError, match=r"holds no images.*photo\.png"):
        list_images(tmp_path)


# ------------------------------------------------------------------------------------ sync
def test_sync_pairs_nearest_and_reports_the_rest():
    strobes = np.array([0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.0])   # last two share a timestamp
    images = np.array([0.01, 0.21, 0.61, 0.79, 5.0, 5.0, 5.5])  # 0.4's image is missing
    sync = sync_strobes(strobes, images, fps=5.0)
    assert sync.image_of[:5].tolist() == [0, 1, -1, 2, 3]
    np.testing.assert_allclose(sync.offset_s[[0, 1, 3, 4]], [0.01, 0.01, 0.01, -0.01])
    assert sync.duplicate_strobes.tolist() == [5, 6]
    assert sync.duplicate_images.tolist() == [4, 5]
    assert sync.unmatched_strobes.tolist() == [2]
    assert sync.unmatched_images.tolist() == [6]


def test_sync_is_globally_nearest_not_first_come():
    # The first strobe's image is missing. Taking strobes in time order, strobe 0 would grab strobe
    # 1's image (0.19 s away, within 1/fps) and shift every later pair by one frame; nearest pairs
    # first keeps strobes 1 and 2 with their own images and leaves strobe 0 unmatched.
    sync = sync_strobes([0.0, 0.2, 0.4], [0.19, 0.39], fps=5.0)
    assert sync.image_of.tolist() == [-1, 0, 1]
    assert sync.unmatched_strobes.tolist() == [0]
    with pytest.raises(InputError, match="FPS"):
        sync_strobes([0.0], [0.0], fps=0.0)


# ------------------------------------------------------------------------------------ ground
def test_ground_heights_tilt_correction_and_interpolation():
    t = np.arange(10) * 0.1
    roll, pitch = np.radians(10.0), np.radians(-5.0)
    quat = np.tile(rotmat_to_quat(euler_zyx_to_rotmat(roll, pitch, 0.3)), (10, 1))
    h = np.full(10, 100.0)
    radalt = np.full(10, 20.0)
    good = np.ones(10, dtype=bool)
    good[[4, 5]] = False
    radalt[3], radalt[6] = 22.0, 26.0
    gh, interp = ground_heights(t, h, quat, radalt, good, np.array([0, 3, 4, 5, 6]))
    expected = 100.0 - np.array([20.0, 22.0, 26.0]) * np.cos(roll) * np.cos(pitch)
    np.testing.assert_allclose(gh[[0, 1, 4]], expected)
    # 4 and 5 lie 1/3 and 2/3 of the way from sample 3 to sample 6.
    np.testing.assert_allclose(gh[2:4], expected[1] + np.array([1 / 3, 2 / 3]) * (expected[2] - expected[1]))
    assert interp.tolist() == [False, False, True, True, False]
    gh, interp = ground_heights(t, h, quat, radalt, good, np.array([4]), window_s=0.05)
    assert np.isnan(gh[0]) and not interp[0]


def test_ground_heights_lever_arm():
    quat = np.array([[1.0, 0.0, 0.0, 0.0]])
    gh, _ = ground_heights(np.zeros(1), np.array([50.0]), quat, np.array([10.0]), np.ones(1, bool),
                           np.array([0]), t_imu_rad=(0.0, 0.0, 0.3))
    assert gh[0] == pytest.approx(50.0 - 0.3 - 10.0)  # altimeter 0.3 m below the IMU (body z down)


# ------------------------------------------------------------------------------------ import
def test_import_geometry_matches_closed_form(flight, camera):
    result = import_pose_log(flight["pose_log"], flight["images"], camera, fps=5.0)
    frames, fp = result.frames, result.footprints
    assert len(frames) == 40 and result.report.counts["matched"] == 40
    np.testing.assert_allclose(frames.sync_offset_s, 0.004, atol=2e-6)
    np.testing.assert_allclose(frames.ground_h, 45.0, atol=2e-3)   # synthetic ground height
    np.testing.assert_allclose(fp.depth_m, 12.0, atol=0.05)        # level flight at 12 m (tilt < 10°)
    np.testing.assert_allclose(fp.gsd_cm, fp.depth_m / 800.0 * 100.0)
    assert fp.crs.crs == "EPSG:32631"  # 5° E, 52° N
    # Footprint corners back in WGS84 → local frame: the ring encloses the point below the camera and
    # its sides are ~W/fx·depth and ~H/fy·depth long (tilt ≤ a few degrees).
    local = LocalFrame(52.0, 5.0, 45.0)
    for f in (0, 17, 39):
        ring = fp.rings[f]
        lat, lon = fp.crs.to_geodetic(ring[:, 0], ring[:, 1])
        enu = local.from_geodetic(lat, lon, ring[:, 2])
        below = local.from_geodetic(frames.lat[f], frames.lon[f], 45.0).reshape(-1)
        k = len(ring) // 4
        corners = enu[[0, k, 2 * k, 3 * k], :2]
        top = np.linalg.norm(corners[1] - corners[0])
        side = np.linalg.norm(corners[3] - corners[0])
        assert top == pytest.approx(640 / 800 * fp.depth_m[f], rel=0.08)
        assert side == pytest.approx(480 / 800 * fp.depth_m[f], rel=0.08)
        assert np.all(corners.min(axis=0) < below[:2]) and np.all(corners.max(axis=0) > below[:2])
        # The image top points along the heading (yaw): north on even legs, south on odd ones.
        up = corners[0] - corners[3]
        bearing = np.degrees(np.arctan2(up[0], up[1]))
        yaw = euler_degrees(frames.quat[f:f + 1])[2][0]
        assert abs((bearing - yaw + 180) % 360 - 180) < 6.0
    assert {round(euler_degrees(frames.quat)[2][f]) % 360 for f in range(40)} == {0, 180}


def test_frame_records_round_trip_to_poses(flight, camera):
    result = import_pose_log(flight["pose_log"], flight["images"], camera)
    records = list(frame_records(result.frames, result.footprints))
    assert list(records[0]) == [name for name, _, _ in FRAME_LAYER_FIELDS]
    assert set(FRAME_FIELD_NAMES) <= set(records[0])
    (poses, idx), = poses_from_records(records)
    assert idx.tolist() == list(range(40))
    assert poses.camera == camera
    local = LocalFrame.around(poses.lat, poses.lon, poses.height)
    back = FrameGeometry(poses, local)
    np.testing.assert_allclose(back.depth_below(), result.footprints.depth_m, atol=1e-6)


def test_rtk_filter_and_altimeter_gaps(tmp_path, camera):
    flight = make_flight(tmp_path, n_frames=20)
    lines = flight["pose_log"].read_text().splitlines()
    out = [lines[0]]
    for i, line in enumerate(lines[1:]):  # 50 Hz rows; frame k is row 10·k (t = 0.2·k s)
        cells = line.split(",")
        if 30 <= i < 40:
            cells[8] = "2"            # RTK float around frame 3
        if 50 <= i < 60:
            cells[10] = "5.0"         # weak altimeter around frame 5: interpolated across 0.2 s
        if i >= 100:
            cells[9] = ""             # altimeter lost from frame 10 (t = 2.0 s) on
        out.append(",".join(cells))
    flight["pose_log"].write_text("\n".join(out) + "\n")
    result = import_pose_log(flight["pose_log"], flight["images"], camera)
    flags = result.frames.flags
    assert "rtk_float" in flags[3] and result.frames.rtk_status[3] == 2
    assert "radalt_interpolated" in flags[5] and "radalt_interpolated" in flags[10]
    np.testing.assert_allclose(result.frames.ground_h[[5, 10]], 45.0, atol=0.01)
    # 1.02 s after the last good reading (t = 1.98 s): beyond the 1 s window.
    assert np.all(np.isnan(result.frames.ground_h[15:])) and "no_ground_height" in flags[15]
    assert result.footprints.rings[15] is None and result.footprints.rings[14] is not None
    assert result.report.counts["no_ground_height"] == 5
    fixed = import_pose_log(flight["pose_log"], flight["images"], camera, fixed_only=True)
    assert 3 not in fixed.frames.frame_id.tolist() and len(fixed.frames) == 19
    assert any("fixed only" in n for n in fixed.report.notes)


def test_unmatched_and_bad_inputs_are_reported(tmp_path, camera):
    flight = make_flight(tmp_path, n_frames=10)
    images = sorted(flight["images"].iterdir())
    images[3].unlink()
    (flight["images"] / "1.000000000.png").touch()
    result = import_pose_log(flight["pose_log"], flight["images"], camera)
    assert result.report.counts["unmatched_strobes"] == 1 and result.report.counts["unmatched_images"] == 1
    assert len(result.frames) == 9 and 3 not in result.frames.frame_id.tolist()
    notes = " ".join(result.report.notes)
    assert "1 strobe(s) found no image" in notes and "1.000000000.png" in notes

    no_strobe = tmp_path / "nostrobe.csv"
    no_strobe.write_text(HEADER + "\n" + ROW.format(k=0, strobe=0) + "\n")
    with pytest.raises(InputError, match="no strobe rows"):
        import_pose_log(no_strobe, flight["images"], camera)
    other = tmp_path / "other"
    write_images(other, [5.0, 5.2])
    with pytest.raises(InputError, match="no image matches a strobe"):
        import_pose_log(flight["pose_log"], other, camera)


def test_flight_track_splits_at_gaps():
    t = np.concatenate([np.arange(0, 10, 0.02), np.arange(20, 25, 0.02)])
    lat = 52.0 + np.arange(len(t)) * 1e-6
    segs = flight_track(t, lat, np.full(len(t), 5.0), np.full(len(t), 60.0), ProjectedCRS(32631),
                        frame_times=[1.0, 2.0, 21.0])
    assert [s.attributes["n_frames"] for s in segs] == [1 + 1, 1]
    assert segs[0].attributes["duration_s"] == pytest.approx(9.98)
    assert segs[0].xyz.shape[0] <= 10 / 0.2 + 2  # thinned to one vertex per 0.2 s
    assert segs[0].attributes["length_m"] == pytest.approx(499 * 1e-6 * 111_250, rel=0.01)


# ------------------------------------------------------------------------------------ flight_data.db
def make_db(path, flight, crs=32631, table="cam0_images_flight_data"):
    cols = flight["cols"]
    s = cols["strobe"] == 1
    x, y = ProjectedCRS(crs).from_geodetic(cols["lat_deg"][s], cols["lon_deg"][s])
    con = sqlite3.connect(path)
    con.execute(f"CREATE TABLE {table} (x REAL, y REAL, z REAL, q REAL, u REAL, a REAL, t REAL, "
                "rtk_status INTEGER, radalt REAL, save_loc TEXT)")
    names = sorted(p.name for p in flight["images"].iterdir())
    rows = [(x[i], y[i], cols["height_m"][s][i], cols["qx"][s][i], cols["qy"][s][i], cols["qz"][s][i],
             cols["qw"][s][i], 3, cols["radalt_m"][s][i], f"/payload/images/{names[i]}") for i in range(len(x))]
    rows[2] = rows[2][:3] + ("oops",) + rows[2][4:]
    con.executemany(f"INSERT INTO {table} VALUES (?,?,?,?,?,?,?,?,?,?)", rows)
    con.commit()
    con.close()


def test_flight_db_gives_the_same_frames_as_the_pose_log(tmp_path, flight, camera):
    db = tmp_path / "flight_data.db"
    make_db(db, flight)
    result = import_flight_log(db, flight["images"], camera, utm_crs="EPSG:32631")
    reference = import_pose_log(flight["pose_log"], flight["images"], camera)
    keep = np.delete(np.arange(40), 2)
    assert len(result.frames) == 39 and result.report.counts["bad_rows"] == 1
    assert "row 3, field 'q'" in result.report.errors[0]
    np.testing.assert_allclose(result.frames.lat, reference.frames.lat[keep], atol=1e-8)
    np.testing.assert_allclose(result.frames.ground_h, reference.frames.ground_h[keep], atol=1e-3)
    np.testing.assert_allclose(result.footprints.depth_m, reference.footprints.depth_m[keep], atol=1e-3)
    assert result.frames.image[0] == reference.frames.image[0]  # save_loc found in IMAGES by name
    np.testing.assert_allclose(result.frames.time_s, reference.frames.time_s[keep] + 0.004, atol=1e-5)
    with pytest.raises(InputError, match="UTM_CRS"):
        import_flight_log(db, flight["images"], camera)
    with pytest.raises(InputError, match="UTM_CRS"):
        import_flight_log(db, flight["images"], camera, utm_crs="EPSG:4326")
    wrong = tmp_path / "wrong.db"
    make_db(wrong, flight, table="something_else")
    with pytest.raises(InputError, match="no table 'cam0_images_flight_data'.*something_else"):
        import_flight_log(wrong, flight["images"], camera, utm_crs="EPSG:32631")


def test_progress_and_cancel(flight, camera):
    seen = []
    import_pose_log(flight["pose_log"], flight["images"], camera, progress=seen.append)
    assert seen == sorted(seen) and seen[-1] == 1.0 and len(seen) > 2
    from birdseye.birdseye_qgis.core.errors import Cancelled

    with pytest.raises(Cancelled):
        import_pose_log(flight["pose_log"], flight["images"], camera, is_canceled=lambda: True)


def test_pose_log_with_windows_line_ends(tmp_path):
    path = tmp_path / "log.csv"
    path.write_bytes((HEADER + "\r\n" + ROW.format(k=0, strobe=1) + "\r\n"
                      + "100.01,52.0,5.0,60.0,1,0,0,0,3,,,0\r\n").encode())
    log = read_pose_log(path)
    assert log.time_s.tolist() == [100.0, 100.01] and log.problems.count == 0
    assert log.radalt[0] == 15.0 and np.isnan(log.radalt[1])
