"""DJI images: gimbal orientation convention, XMP/EXIF reading, camera precedence, flags, real frames."""
from __future__ import annotations

import io
import math
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
import pytest
from PIL import Image
from PIL.TiffImagePlugin import IFDRational

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.dji import (
    T_CAM_GIMBAL,
    dji_camera,
    dji_pose,
    import_dji_images,
    read_dji_metadata,
)
from birdseye.birdseye_qgis.core.field.frame_records import poses_from_records
from birdseye.birdseye_qgis.core.field.frames import frame_records
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel, camera_from_dji_dewarp
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat

FIXTURES = Path(__file__).resolve().parents[2] / "data" / "brighton_beach"
ORIGINALS = Path(__file__).resolve().parents[4] / "shared" / "data" / "brighton_beach"


# ------------------------------------------------------------------------------------ orientation
def camera_axes(roll, pitch, yaw, lat=45.0, lon=7.0):
    """Columns: camera x (image right), y (image down), z (optical axis) in local ENU."""
    cam = CameraModel(400, 300, 300.0, 300.0, 199.5, 149.5, T_cam_imu=T_CAM_GIMBAL)
    q = rotmat_to_quat(euler_zyx_to_rotmat(*np.radians([roll, pitch, yaw])))
    poses = FramePoses([0], [lat], [lon], [100.0], q[None], [60.0], cam)
    geometry = FrameGeometry(poses, LocalFrame(lat, lon, 60.0))
    return geometry, geometry.R_local_cam[0]


def test_gimbal_nadir_yaw0_looks_down_with_north_up():
    _, r = camera_axes(0.0, -90.0, 0.0)
    np.testing.assert_allclose(r[:, 2], [0, 0, -1], atol=1e-9)   # optical axis down
    np.testing.assert_allclose(-r[:, 1], [0, 1, 0], atol=1e-9)   # image top north
    np.testing.assert_allclose(r[:, 0], [1, 0, 0], atol=1e-9)    # image right east (not mirrored)


@pytest.mark.parametrize("yaw", [30.0, 90.0, 200.0])
def test_gimbal_yaw_turns_the_image_top(yaw):
    _, r = camera_axes(0.0, -90.0, yaw)
    y = math.radians(yaw)
    np.testing.assert_allclose(-r[:, 1], [math.sin(y), math.cos(y), 0], atol=1e-9)
    np.testing.assert_allclose(r[:, 2], [0, 0, -1], atol=1e-9)


def test_gimbal_pitch_tilts_the_optical_axis_along_the_heading():
    _, r = camera_axes(0.0, -60.0, 30.0)
    p, y = math.radians(-60.0), math.radians(30.0)
    np.testing.assert_allclose(r[:, 2], [math.sin(y) * math.cos(p), math.cos(y) * math.cos(p), math.sin(p)],
                               atol=1e-9)
    _, r = camera_axes(0.0, 0.0, 0.0)  # level gimbal: looks north, image bottom is down
    np.testing.assert_allclose(r[:, 2], [0, 1, 0], atol=1e-9)
    np.testing.assert_allclose(r[:, 1], [0, 0, -1], atol=1e-9)


def test_ground_points_project_where_the_map_says():
    geometry, _ = camera_axes(0.0, -90.0, 0.0)
    below = geometry.ground_point[0]
    pts = below + np.array([[0.0, 5.0, 0.0], [5.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    uv = geometry.camera.project(geometry.to_camera(np.zeros(3, int), pts))
    assert uv[0, 1] < 149.5 - 30 and abs(uv[0, 0] - 199.5) < 1e-6   # north → above the centre
    assert uv[1, 0] > 199.5 + 30 and abs(uv[1, 1] - 149.5) < 1e-6   # east → right of the centre
    np.testing.assert_allclose(uv[2], [199.5, 149.5], atol=1e-9)
    assert uv[0, 1] == pytest.approx(149.5 - 300.0 * 5.0 / 40.0)    # f·d/depth at 40 m


# ------------------------------------------------------------------------------------ synthetic JPEGs
def xmp_packet(tags: dict, element_form=()) -> bytes:
    attrs = "\n".join(f'   drone-dji:{k}="{v}"' for k, v in tags.items() if k not in element_form)
    elems = "".join(f"<drone-dji:{k}>{tags[k]}</drone-dji:{k}>" for k in element_form)
    return (b"http://ns.adobe.com/xap/1.0/\x00" + (
        '<x:xmpmeta xmlns:x="adobe:ns:meta/"><rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#">'
        '<rdf:Description rdf:about="DJI Meta Data" xmlns:drone-dji="http://www.dji.com/drone-dji/1.0/"\n'
        f"{attrs}>{elems}</rdf:Description></rdf:RDF></x:xmpmeta>").encode())


def write_jpeg(path, size=(80, 60), xmp: dict | None = None, element_form=(), exif_size=None, f35=None,
               gps=(47.5, 8.5, 500.0), when="2021:05:04 10:20:30"):
    exif = Image.Exif()
    exif[0x010F], exif[0x0110] = "DJI", "FC6310"
    sub = {0x9003: when}
    if exif_size:
        sub[0xA002], sub[0xA003] = exif_size
    if f35:
        sub[0xA405] = f35
    exif[0x8769] = sub
    if gps:
        def dms(v):
            d = int(abs(v))
            m = int((abs(v) - d) * 60)
            return (IFDRational(d), IFDRational(m), IFDRational(round(((abs(v) - d) * 60 - m) * 60 * 1e4), 10000))
        exif[0x8825] = {1: "N" if gps[0] >= 0 else "S", 2: dms(gps[0]), 3: "E" if gps[1] >= 0 else "W",
                        4: dms(gps[1]), 5: b"\x00", 6: IFDRational(round(gps[2] * 100), 100)}
    buf = io.BytesIO()
    Image.new("RGB", size, (90, 110, 70)).save(buf, "JPEG", exif=exif.tobytes())
    data = buf.getvalue()
    if xmp is not None:
        payload = xmp_packet(xmp, element_form)
        segment = b"\xff\xe1" + (len(payload) + 2).to_bytes(2, "big") + payload
        data = data[:2] + segment + data[2:]
    Path(path).write_bytes(data)
    return Path(path)


RTK_TAGS = {"GpsLatitude": "47.123456789", "GpsLongtitude": "8.987654321", "AbsoluteAltitude": "+612.50",
            "RelativeAltitude": "+30.00", "GimbalRollDegree": "+0.00", "GimbalPitchDegree": "-90.00",
            "GimbalYawDegree": "-120.50", "FlightRollDegree": "+1.0", "FlightPitchDegree": "-2.0",
            "FlightYawDegree": "-118.0", "RtkFlag": "50", "RtkStdLon": "0.012", "RtkStdLat": "0.011",
            "RtkStdHgt": "0.025",
            "DewarpData": "2020-01-01;3700.0,3690.0,12.5,-8.25,-0.27,0.11,0.0004,-0.0003,-0.03"}


def test_metadata_pose_camera_and_import_of_an_rtk_image(tmp_path):
    folder = tmp_path / "flight"
    folder.mkdir()
    path = write_jpeg(folder / "DJI_0001.JPG", size=(547, 365), xmp=RTK_TAGS,
                      element_form=("RtkStdHgt",), exif_size=(5472, 3648))
    meta = read_dji_metadata(path)
    assert (meta.width, meta.height, meta.exif_width) == (547, 365, 5472)
    assert meta.tag("RtkStdHgt") == 0.025 and meta.xmp["GimbalYawDegree"] == "-120.50"
    assert meta.time_s == datetime(2021, 5, 4, 10, 20, 30, tzinfo=timezone.utc).timestamp()
    pose = dji_pose(meta)
    assert (pose.lat, pose.lon) == (47.123456789, 8.987654321)  # XMP position beats EXIF GPS
    assert pose.ground_h == pytest.approx(582.5) and pose.yaw_deg == pytest.approx(239.5)
    assert pose.rtk_status == 3 and pose.rtk_std == (0.012, 0.011, 0.025) and pose.flags == []
    cam, flags = dji_camera(meta)
    full = camera_from_dji_dewarp(RTK_TAGS["DewarpData"], 5472, 3648)
    s = 547 / 5472
    assert flags == ["resized"]
    assert cam.fx == pytest.approx(full.fx * s) and cam.fy == pytest.approx(full.fy * 365 / 3648)
    assert cam.cx == pytest.approx((full.cx + 0.5) * s - 0.5) and cam.dist == full.dist
    np.testing.assert_array_equal(cam.T_cam_imu, T_CAM_GIMBAL)

    result = import_dji_images(folder)
    rec = next(frame_records(result.frames, result.footprints))
    assert rec["rtk_status"] == 3 and rec["rtk_std_hgt_m"] == 0.025 and rec["depth_m"] == pytest.approx(30.0)
    assert (rec["roll_deg"], rec["pitch_deg"], rec["yaw_deg"]) == (0.0, -90.0, 239.5)
    assert rec["flags"] == "resized" and rec["sync_offset_s"] is None
    (poses, _), = poses_from_records([rec])
    assert poses.camera == cam


def test_intrinsics_precedence_and_calibration_size(tmp_path):
    tags = {k: v for k, v in RTK_TAGS.items() if k != "DewarpData"}
    calibrated = dict(tags, CalibratedFocalLength="3666.67", CalibratedOpticalCenterX="2736.0",
                      CalibratedOpticalCenterY="1824.0")
    cam, _ = dji_camera(read_dji_metadata(write_jpeg(tmp_path / "a.jpg", (5472 // 8, 3648 // 8), calibrated,
                                                     exif_size=(5472, 3648), f35=24)))
    assert cam.fx == pytest.approx(3666.67 / 8) and cam.cx == pytest.approx((2736.0 - 0.5 + 0.5) / 8 - 0.5)
    cam, flags = dji_camera(read_dji_metadata(write_jpeg(tmp_path / "b.jpg", (400, 300), tags, f35=24)))
    assert cam.fx == pytest.approx(24 / 36 * 400) and cam.cx == 199.5 and "approx_intrinsics" in flags
    with pytest.raises(InputError, match="no camera intrinsics"):
        dji_camera(read_dji_metadata(write_jpeg(tmp_path / "c.jpg", (400, 300), tags)))
    calibration = CameraModel(800, 600, 700.0, 700.0, 399.5, 299.5, source="kalibr:x.yaml")
    meta = read_dji_metadata(write_jpeg(tmp_path / "d.jpg", (400, 300), tags, exif_size=(800, 600)))
    cam, _ = dji_camera(meta, calibration)  # a half-size copy of the calibrated image size
    assert cam.fx == 350.0 and cam.cx == pytest.approx(199.5)
    np.testing.assert_array_equal(cam.T_cam_imu, T_CAM_GIMBAL)
    with pytest.raises(InputError, match="400×300 px but the calibration"):
        dji_camera(read_dji_metadata(write_jpeg(tmp_path / "e.jpg", (400, 300), tags)), calibration)


def test_flags_and_fallbacks(tmp_path):
    def pose(**changes):
        tags = {k: v for k, v in RTK_TAGS.items() if k not in changes or changes[k] is not None}
        tags.update({k: v for k, v in changes.items() if v is not None})
        return dji_pose(read_dji_metadata(write_jpeg(tmp_path / "x.jpg", xmp=tags)))

    assert "yaw_mismatch" in pose(FlightYawDegree="-100.0").flags
    assert "yaw_mismatch" not in pose(GimbalYawDegree="179.0", FlightYawDegree="-178.0").flags  # wraps
    assert "non_nadir" in pose(GimbalPitchDegree="-70.0").flags
    p = pose(GimbalYawDegree=None)
    assert "yaw_from_flight" in p.flags and p.yaw_deg == pytest.approx(242.0)
    assert pose(RtkFlag="34").flags == ["rtk_float"] and pose(RtkFlag="16").rtk_status == 1
    p = pose(GpsLatitude=None, GpsLongtitude=None)  # falls back to EXIF GPS (47.5, 8.5)
    assert p.lat == pytest.approx(47.5, abs=1e-7) and p.lon == pytest.approx(8.5, abs=1e-7)
    with pytest.raises(InputError, match="RelativeAltitude"):
        pose(RelativeAltitude=None)
    with pytest.raises(InputError, match="field 'drone-dji:GimbalPitchDegree'"):
        pose(GimbalPitchDegree="level")


def test_images_that_cannot_be_placed_are_listed(tmp_path):
    """What cannot be placed at all (no GPS, not a JPEG) is listed; an image whose height above the ground is
    unknown (no relative altitude, flight height or DEM) is still imported, flagged, without a footprint."""
    write_jpeg(tmp_path / "DJI_0001.JPG", xmp=RTK_TAGS)
    write_jpeg(tmp_path / "phone.jpg", f35=26)                       # no DJI tags, no height above ground
    write_jpeg(tmp_path / "indoors.jpg", f35=26, gps=None)           # no GPS fix
    (tmp_path / "broken.jpg").write_bytes(b"not a jpeg at all")
    (tmp_path / "notes.txt").write_text("ignored")
    result = import_dji_images(tmp_path)
    assert result.frames.frame_id.tolist() == [0, 3]
    phone = 1
    assert "no_ground_height" in result.frames.flags[phone] and math.isnan(result.frames.ground_h[phone])
    assert result.frames.ground_source == ["takeoff", ""] and result.footprints.rings[phone] is None
    assert result.report.counts["no_ground_height"] == 1
    assert any("frame(s) flagged no_ground_height" in n and "Refine frame poses" in n for n in result.report.notes)
    reasons = {Path(e.source).name: str(e) for e in result.report.unplaced}
    assert "no GPS position" in reasons["indoors.jpg"] and "not a JPEG" in reasons["broken.jpg"]
    assert "2 of 4 image(s) cannot be placed" in result.report.errors[0]
    (tmp_path / "DJI_0001.JPG").unlink()
    (tmp_path / "phone.jpg").unlink()
    with pytest.raises(InputError, match="none of its 2 JPEG image"):
        import_dji_images(tmp_path)
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(InputError, match="holds no JPEG"):
        import_dji_images(empty)


# ------------------------------------------------------------------------------------ real frames
@pytest.fixture(scope="module")
def brighton():
    return import_dji_images(FIXTURES)


def test_brighton_beach_fixtures_keep_the_original_metadata():
    if not ORIGINALS.is_dir():
        pytest.skip("original Brighton Beach images not available")
    for fixture in sorted(FIXTURES.glob("*.JPG")):
        small, full = read_dji_metadata(fixture), read_dji_metadata(ORIGINALS / fixture.name)
        assert small.xmp == full.xmp and (small.exif_lat, small.exif_lon) == (full.exif_lat, full.exif_lon)
        assert (small.width, small.exif_width, full.width) == (400, 4000, 4000)


def test_brighton_beach_footprints_under_gps_with_size_and_heading(brighton):
    frames, fp = brighton.frames, brighton.footprints
    assert len(frames) == 6 and brighton.report.unplaced == []
    for f in range(6):
        meta = read_dji_metadata(frames.image[f])
        rel, gimbal_yaw = meta.tag("RelativeAltitude"), meta.tag("GimbalYawDegree")
        assert fp.depth_m[f] == pytest.approx(rel, abs=1e-6)
        assert frames.ground_h[f] == pytest.approx(meta.tag("AbsoluteAltitude") - rel)
        ring = fp.rings[f]
        lat, lon = fp.crs.to_geodetic(ring[:, 0], ring[:, 1])
        local = LocalFrame(meta.exif_lat, meta.exif_lon, frames.ground_h[f])
        enu = local.from_geodetic(lat, lon, ring[:, 2])
        k = len(ring) // 4
        tl, tr, br, bl = enu[[0, k, 2 * k, 3 * k], :2]
        # Under the GPS position: gimbal pitch −89.9° leans the view by 40 m · tan 0.1° = 7 cm.
        np.testing.assert_allclose((tl + tr + br + bl) / 4, [0.0, 0.0], atol=0.1)
        # Size from the 35 mm equivalent (20 mm over the 36 mm film side) and RelativeAltitude.
        width = 36.0 / meta.focal_35mm * rel
        assert np.linalg.norm(tr - tl) == pytest.approx(width, rel=2e-3)
        assert np.linalg.norm(bl - tl) == pytest.approx(width * 2250 / 4000, rel=2e-3)
        # Image top towards the gimbal yaw (true north, the local frame has no grid convergence).
        up = (tl + tr - bl - br) / 2
        assert np.degrees(np.arctan2(up[0], up[1])) == pytest.approx(gimbal_yaw, abs=0.1)
    assert all("yaw_mismatch" not in f and "non_nadir" not in f for f in frames.flags)
    assert fp.crs.crs == "EPSG:32615"
    assert frames.time_s[0] == datetime(2016, 6, 23, 16, 31, 59, tzinfo=timezone.utc).timestamp()


# ------------------------------------------------------------------------------------ one camera, dewarped
# A DewarpData for the FC300S's full 4000 × 2250 frame (the Brighton frames carry none; made up, of the
# size DJI's are).
FC300S_DEWARP = "2016-06-01;2285.5,2284.9,-11.25,7.5,-0.118,0.104,0.0006,-0.0004,-0.021"


def with_xmp(source: Path, target: Path, tags: dict) -> Path:
    """A copy of a real frame with one more XMP packet holding ``tags`` (read together with its own)."""
    data = source.read_bytes()
    payload = xmp_packet(tags)
    Path(target).write_bytes(data[:2] + b"\xff\xe1" + (len(payload) + 2).to_bytes(2, "big") + payload + data[2:])
    return Path(target)


def brighton_copies(folder: Path, tags_of) -> Path:
    """The six Brighton frames copied into ``folder``, each with the tags ``tags_of(index)``."""
    folder.mkdir()
    for i, source in enumerate(sorted(FIXTURES.glob("*.JPG"))):
        with_xmp(source, folder / source.name, tags_of(i))
    return folder


def test_frames_of_one_camera_share_one_camera_model(tmp_path):
    folder = brighton_copies(tmp_path / "one", lambda i: {"DewarpData": FC300S_DEWARP, "CameraSerialNumber": "SN-A"})
    result = import_dji_images(folder)
    cams = result.frames.cameras
    assert len(cams) == 6 and all(c is cams[0] for c in cams)
    assert cams[0].source == "dji:DewarpData DJI FC300S SN-A"   # the camera, not a file
    full = camera_from_dji_dewarp(FC300S_DEWARP, 4000, 2250)
    assert cams[0].fx == pytest.approx(full.fx / 10) and cams[0].dist == full.dist
    # A second camera of the same model (another serial number) is another camera model.
    folder = brighton_copies(tmp_path / "two", lambda i: {"DewarpData": FC300S_DEWARP,
                                                         "CameraSerialNumber": "SN-A" if i < 4 else "SN-B"})
    cams = import_dji_images(folder).frames.cameras
    assert len({id(c) for c in cams}) == 2 and cams[3] is cams[0] and cams[4] is cams[5] is not cams[0]
    assert cams[5].source.endswith("SN-B") and cams[5].to_dict() | {"source": ""} == cams[0].to_dict() | {"source": ""}
    # Without a serial number in XMP, EXIF BodySerialNumber names the camera.
    meta = read_dji_metadata(with_xmp(FIXTURES / "DJI_0018.JPG", tmp_path / "x.jpg", {"DewarpData": FC300S_DEWARP}))
    assert meta.serial == "" and dji_camera(meta)[0].source == "dji:DewarpData DJI FC300S"
    exif = Image.Exif()
    exif[0x8769] = {0xA431: "BODY-7"}
    Image.new("RGB", (40, 30)).save(tmp_path / "z.jpg", exif=exif.tobytes())
    assert read_dji_metadata(tmp_path / "z.jpg").serial == "BODY-7"


def test_dewarp_flag_one_means_no_distortion_is_applied_again(tmp_path):
    raw_tags = {"DewarpData": FC300S_DEWARP, "CameraSerialNumber": "SN-A", "DewarpFlag": "0"}
    raw = dji_camera(read_dji_metadata(with_xmp(FIXTURES / "DJI_0018.JPG", tmp_path / "raw.jpg", raw_tags)))
    done = dji_camera(read_dji_metadata(with_xmp(FIXTURES / "DJI_0018.JPG", tmp_path / "dewarped.jpg",
                                                 dict(raw_tags, DewarpFlag="1"))))
    assert raw[1] == ["resized"] and done[1] == ["resized", "dewarped"]
    assert raw[0].dist == camera_from_dji_dewarp(FC300S_DEWARP, 4000, 2250).dist and done[0].dist == (0.0,) * 5
    intrinsics = ("fx", "fy", "cx", "cy")
    assert [getattr(done[0], k) for k in intrinsics] == [getattr(raw[0], k) for k in intrinsics]
    # The dewarped image is a pinhole image: u = fx·x/z + cx; the raw one bends off-centre points.
    p = np.array([[0.6, -0.3, 1.0]])
    pinhole = [done[0].fx * 0.6 + done[0].cx, done[0].fy * -0.3 + done[0].cy]
    np.testing.assert_allclose(done[0].project(p)[0], pinhole, atol=1e-9)
    assert np.hypot(*(raw[0].project(p)[0] - pinhole)) > 1.0
    # A calibration file describes the raw lens: a dewarped frame drops its distortion too.
    calibration = CameraModel(400, 225, 230.0, 230.0, 199.5, 112.0, (-0.1, 0.05, 0.0, 0.0, 0.0), source="kalibr:c")
    meta = read_dji_metadata(tmp_path / "dewarped.jpg")
    assert dji_camera(meta, calibration)[0].dist == (0.0,) * 5
    # Frames of one camera, some dewarped: two camera models, and the report says which.
    folder = brighton_copies(tmp_path / "mixed", lambda i: dict(raw_tags, DewarpFlag=str(i % 2)))
    result = import_dji_images(folder)
    assert len({id(c) for c in result.frames.cameras}) == 2
    assert [("dewarped" in f) for f in result.frames.flags] == [False, True] * 3
    assert result.report.counts["dewarped"] == 3 and any("DewarpFlag 1" in n for n in result.report.notes)


def test_a_dem_is_checked_once_against_the_flights_take_off_height(tmp_path):
    """Brighton frames (take-off 158.51 m MSL, 39.8–40.1 m up) over a field 13 m below the take-off
    point, a knoll at the take-off height 150 m away: honest relief, accepted, footprints 53/40 larger.
    A DEM 40 m off every terrain around is refused, once, naming the take-off height."""
    from birdseye.birdseye_qgis.core.sim.terrain import synthetic_terrain

    level = import_dji_images(FIXTURES)
    lat, lon = float(np.mean(level.frames.lat)), float(np.mean(level.frames.lon))

    def field(height, knoll):
        dem = synthetic_terrain(lat, lon, "plane", base_height_m=height, size_m=600.0, cell_m=2.0,
                                vertical_datum="msl")
        x, y = dem.cell_centres()
        dem.heights[np.ix_(np.abs(y - y.mean()) < 5.0, np.abs(x - x.mean() - 150.0) < 5.0)] = knoll
        return dem

    draped = import_dji_images(FIXTURES, dem=field(158.51 - 13.0, 158.51))
    for f in range(6):
        ratio = math.sqrt(polygon_area(draped.footprints.rings[f]) / polygon_area(level.footprints.rings[f]))
        assert ratio == pytest.approx((level.footprints.depth_m[f] + 13.0) / level.footprints.depth_m[f], rel=0.01)
    with pytest.raises(InputError) as err:
        import_dji_images(FIXTURES, dem=field(158.51 + 40.0, 158.51 + 40.0))
    assert "take-off height (158.51 m, the median over 6 frames" in str(err.value)
    assert "40.00 m below the lowest" in str(err.value)


def polygon_area(ring) -> float:
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))
