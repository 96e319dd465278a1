"""Images from any drone: track headings by hand, Parrot's attitude conventions, and the real Brighton Beach
frames with their XMP removed (what a drone writing only EXIF gives), alone and mixed with DJI frames."""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "data"))
from strip_xmp import XMP_HEADER, strip_xmp

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.dji import import_dji_images, read_dji_metadata
from birdseye.birdseye_qgis.core.field.drone_images import (
    drone_camera,
    import_drone_images,
    maker_attitude,
    pix4d_to_gimbal,
    track_headings,
)
from birdseye.birdseye_qgis.core.field.frames import frame_records
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.heights import EGM96_REFERENCE
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat

DATA = Path(__file__).resolve().parents[2] / "data"
BRIGHTON = DATA / "brighton_beach"
BRIGHTON_960 = DATA / "brighton_beach_960"
ORIGINALS = Path(__file__).resolve().parents[4] / "shared" / "data" / "brighton_beach"


# ------------------------------------------------------------------------------------ track heading
def positions(points_en, lat0=47.0, lon0=8.0):
    """(lat, lon) of points given in metres east and north of (lat0, lon0)."""
    enu = np.column_stack([np.asarray(points_en, dtype=float), np.zeros(len(points_en))])
    lat, lon, _ = LocalFrame(lat0, lon0).to_geodetic(enu)
    return lat, lon


def test_track_heading_by_hand():
    # A lawnmower leg: north 0 → 10 → 20 m, east to (10, 20), back south to (10, 10). Names are out of
    # capture order: the times put them in track order.
    track = [(0, 0), (0, 10), (0, 20), (10, 20), (10, 10)]
    shuffle = [3, 0, 4, 1, 2]                      # name position → track position
    lat, lon = positions([track[k] for k in shuffle])
    heading, flags = track_headings(lat, lon, [100.0 + 2 * k for k in shuffle])
    by_track = {k: (heading[i], flags[i]) for i, k in enumerate(shuffle)}
    # first: towards the next (north); then previous → next: (0,0)→(0,20) north; (0,10)→(10,20) 45°;
    # (0,20)→(10,10) 135°; last: from the previous, (10,20)→(10,10) south.
    expected = [0.0, 0.0, 45.0, 135.0, 180.0]
    for k, want in enumerate(expected):
        assert by_track[k][0] == pytest.approx(want, abs=1e-3)
    # The legs turn by 90° at (0, 20) and (10, 20); the straight frames are not flagged.
    assert [by_track[k][1] for k in range(5)] == [[], [], ["track_turn"], ["track_turn"], []]


def test_track_heading_hovering_missing_times_and_a_lone_frame():
    # Frames 1–3 hover within 0.2 m of (10, 10): frame 2's neighbours are 0.1 m apart, so its window
    # widens to frames 0 → 4.
    pts = [(0, 0), (10, 10), (10, 10.2), (10, 10.1), (20, 30)]
    lat, lon = positions(pts)
    heading, flags = track_headings(lat, lon, [1.0, 2.0, 3.0, 4.0, 5.0])

    def bearing(a, b):
        return math.degrees(math.atan2(pts[b][0] - pts[a][0], pts[b][1] - pts[a][1])) % 360.0

    expected = [bearing(0, 1), bearing(0, 2), bearing(0, 4), bearing(2, 4), bearing(3, 4)]
    assert expected == pytest.approx([45.0, 44.43, 33.69, 26.79, 26.68], abs=0.01)
    np.testing.assert_allclose(heading, expected, atol=1e-3)
    assert flags == [[]] * 5    # legs under 1 m are not judged for turns
    # Without capture times the name order is the track order: reversed names, reversed headings.
    heading, _ = track_headings(lat[::-1], lon[::-1], [math.nan] * 5)
    np.testing.assert_allclose(heading, [bearing(4, 3), bearing(4, 2), bearing(4, 0), bearing(2, 0), bearing(1, 0)],
                               atol=1e-3)
    heading, flags = track_headings(lat[:1], lon[:1], [1.0])
    assert heading.tolist() == [0.0] and flags == [["heading_unknown"]]
    heading, flags = track_headings(lat[1:3], lon[1:3], [1.0, 2.0])   # 0.2 m apart: no movement
    assert heading.tolist() == [0.0, 0.0] and flags == [["heading_unknown"]] * 2


# ------------------------------------------------------------------------------------ other makers' XMP
# Parrot's photo-metadata documentation (developer.parrot.com, "Embedded Photo Metadata", ANAFI Ai) gives
# one photo's attitude twice: Camera:Roll/Pitch/Yaw in Pix4D's convention and drone-parrot:Camera*Degree
# in NED.
PARROT_PIX4D = {"Yaw": 146.781036, "Pitch": 38.011101, "Roll": -0.041258}
PARROT_NED = {"CameraRollDegree": -0.052789, "CameraPitchDegree": -51.988888, "CameraYawDegree": 146.848038}


def test_parrots_two_conventions_give_the_same_camera():
    roll, pitch, yaw = pix4d_to_gimbal(PARROT_PIX4D["Yaw"], PARROT_PIX4D["Pitch"], PARROT_PIX4D["Roll"])
    assert (roll, pitch, yaw) == pytest.approx((-0.052789, -51.988888, 146.848038), abs=1e-4)
    # The opposite roll sign misses by 0.08°: the example settles it.
    flipped = pix4d_to_gimbal(PARROT_PIX4D["Yaw"], PARROT_PIX4D["Pitch"], -PARROT_PIX4D["Roll"])
    assert abs(flipped[2] - 146.848038) > 0.1
    # Pitch 0 is nadir with the image top along the yaw; pitch 90 would look forward (OpenDroneMap's
    # reading of the convention), so pitch 10 tilts the optical axis 10° towards the yaw.
    assert pix4d_to_gimbal(30.0, 0.0, 0.0) == pytest.approx((0.0, -90.0, 30.0), abs=1e-9)
    axis = euler_zyx_to_rotmat(*np.radians(pix4d_to_gimbal(30.0, 10.0, 0.0)))[:, 0]   # NED
    s10, c10, s30, c30 = (math.sin(math.radians(a)) for a in (10, 80, 30, 60))
    np.testing.assert_allclose(axis, [s10 * c30, s10 * s30, c10], atol=1e-9)


def with_packet(source: Path, target: Path, body: str) -> Path:
    """A copy of ``source`` (XMP removed) with one XMP packet holding ``body`` in an rdf:Description."""
    stripped = strip_xmp(source, target)
    payload = XMP_HEADER + (
        '<x:xmpmeta xmlns:x="adobe:ns:meta/"><rdf:RDF xmlns:rdf="http://www.w3.org/1999/02/22-rdf-syntax-ns#">'
        '<rdf:Description rdf:about="" xmlns:Camera="http://pix4d.com/camera/1.0/" '
        f'xmlns:drone-parrot="http://www.parrot.com/drone-parrot/1.0/">{body}</rdf:Description>'
        "</rdf:RDF></x:xmpmeta>").encode()
    data = stripped.read_bytes()
    target.write_bytes(data[:2] + b"\xff\xe1" + (len(payload) + 2).to_bytes(2, "big") + payload + data[2:])
    return target


def test_other_makers_attitude_is_read_and_placed(tmp_path):
    folder = tmp_path / "parrot"
    folder.mkdir()
    pix4d = "".join(f"<Camera:{k}>{v}</Camera:{k}>" for k, v in PARROT_PIX4D.items())
    ned = "".join(f"<drone-parrot:{k}>{v}</drone-parrot:{k}>" for k, v in PARROT_NED.items())
    both = with_packet(BRIGHTON / "DJI_0018.JPG", folder / "P_0001.JPG",
                       pix4d + ned + "<Camera:AboveGroundAltitude>10485760/262144</Camera:AboveGroundAltitude>")
    only_pix4d = with_packet(BRIGHTON / "DJI_0019.JPG", folder / "P_0002.JPG", pix4d)
    assert maker_attitude(read_dji_metadata(both)) == pytest.approx((-0.052789, -51.988888, 146.848038))
    assert maker_attitude(read_dji_metadata(only_pix4d)) == pytest.approx((-0.052789, -51.988888, 146.848038),
                                                                         abs=1e-4)
    result = import_drone_images(folder, flight_height_m=40.0)
    recs = list(frame_records(result.frames, result.footprints))
    assert [r["yaw_deg"] for r in recs] == pytest.approx([146.848038] * 2, abs=1e-4)
    # AboveGroundAltitude (40 m as an XMP rational) is the depth; the other frame takes the flight height.
    assert recs[0]["ground_h_m"] == pytest.approx(198.309 - 40.0) and "ground_from" not in recs[0]["flags"]
    assert "ground_from_flight_height" in recs[1]["flags"]
    assert all("non_nadir" in r["flags"] and "attitude_from_track" not in r["flags"] for r in recs)


# ------------------------------------------------------------------------------------ real frames, EXIF only
def stripped_copy(source_dir: Path, folder: Path, names=None, prefix="") -> Path:
    folder.mkdir(exist_ok=True)
    for path in sorted(source_dir.glob("*.JPG")):
        if names is None or path.name in names:
            strip_xmp(path, folder / f"{prefix}{path.name}")
    return folder


@pytest.fixture(scope="module")
def dji_reference():
    return import_dji_images(BRIGHTON)


def track_bearings(lat, lon):
    """Previous → next bearings (deg) of points in order, worked out in a local ENU frame."""
    enu = LocalFrame(float(np.mean(lat)), float(np.mean(lon))).from_geodetic(lat, lon, np.zeros(len(lat)))
    idx = np.arange(len(lat))
    prev, nxt = np.maximum(idx - 1, 0), np.minimum(idx + 1, len(lat) - 1)
    d = enu[nxt] - enu[prev]
    return np.degrees(np.arctan2(d[:, 0], d[:, 1])) % 360.0


def test_exif_only_frames_are_placed_like_the_dji_import(tmp_path, dji_reference):
    folder = stripped_copy(BRIGHTON, tmp_path / "exif")
    meta = read_dji_metadata(folder / "DJI_0018.JPG")
    assert meta.xmp == {} and meta.xmp_text == ""                       # the XMP is gone
    assert (meta.make, meta.model, meta.focal_mm, meta.focal_35mm, meta.focal_plane_px_per_mm) == (
        "DJI", "FC300S", 3.61, 20.0, None)                               # what the EXIF holds
    # Without a flight height or a DEM the frames are imported all the same, their ground unknown: flagged,
    # without a footprint, and the report says what gives them one.
    unknown = import_drone_images(folder)
    assert len(unknown.frames) == 6 and unknown.report.unplaced == []
    assert np.all(np.isnan(unknown.frames.ground_h)) and unknown.frames.ground_source == [""] * 6
    assert all(ring is None for ring in unknown.footprints.rings)
    assert all("no_ground_height" in f for f in unknown.frames.flags)
    assert unknown.frames.reference == EGM96_REFERENCE
    assert any("6 frame(s) flagged no_ground_height" in n and "FLIGHT_HEIGHT_M" in n for n in unknown.report.notes)

    result = import_drone_images(folder, flight_height_m=40.0)
    frames, ref = result.frames, dji_reference.frames
    assert len(frames) == 6 and result.report.unplaced == []
    assert frames.ground_source == ["flight_height"] * 6 and ref.ground_source == ["takeoff"] * 6
    cams = frames.cameras
    assert all(c is cams[0] for c in cams) and cams[0].source == "exif:FocalLengthIn35mmFilm DJI FC300S"
    assert cams[0].fx == pytest.approx(20.0 / 36.0 * 400) and cams[0].dist == (0.0,) * 5
    assert (cams[0].cx, cams[0].cy) == (199.5, 112.0)
    # The same positions as the DJI import (both from EXIF GPS); heights 1 mm apart (EXIF 198.309 m,
    # XMP AbsoluteAltitude 198.31 m).
    np.testing.assert_array_equal(frames.lat, ref.lat)
    np.testing.assert_array_equal(frames.lon, ref.lon)
    np.testing.assert_allclose(frames.height, ref.height, atol=0.0011)
    # Ground: the median GPS altitude (198.559 m) minus the 40 m flown.
    np.testing.assert_allclose(frames.ground_h, np.median(frames.height) - 40.0)
    np.testing.assert_allclose(result.footprints.depth_m, frames.height - frames.ground_h, atol=1e-6)
    # Nadir, heading along the track; the DJI gimbal yaw agrees within 3.6° on this flight.
    yaw = frames.euler_deg[:, 2]
    np.testing.assert_allclose(yaw, track_bearings(ref.lat, ref.lon), atol=1e-3)
    gimbal = ref.euler_deg[:, 2]
    assert np.max(np.abs((yaw - gimbal + 180.0) % 360.0 - 180.0)) < 3.6
    np.testing.assert_array_equal(frames.euler_deg[:, :2], [[0.0, -90.0]] * 6)
    for flags in frames.flags:
        assert {"attitude_from_track", "approx_intrinsics", "ground_from_flight_height", "resized"} <= set(flags)
    assert result.report.counts["attitude_from_track"] == 6
    assert any("image top towards the direction of travel" in n for n in result.report.notes)


def test_exif_only_frames_over_a_dem(tmp_path, dji_reference):
    from birdseye.birdseye_qgis.core.sim.terrain import synthetic_terrain

    folder = stripped_copy(BRIGHTON, tmp_path / "exif")
    lat, lon = float(np.mean(dji_reference.frames.lat)), float(np.mean(dji_reference.frames.lon))
    dem = synthetic_terrain(lat, lon, "plane", base_height_m=150.0, size_m=600.0, cell_m=2.0, vertical_datum="msl")
    result = import_drone_images(folder, dem=dem)
    assert all("ground_from_dem" in f for f in result.frames.flags) and result.frames.ground_source == ["dem"] * 6
    np.testing.assert_allclose(result.frames.ground_h, 150.0, atol=0.01)
    np.testing.assert_allclose(result.footprints.depth_m, result.frames.height - 150.0, atol=0.01)


def test_sensor_width_table_when_the_exif_has_only_the_focal_length(tmp_path):
    meta = read_dji_metadata(strip_xmp(BRIGHTON / "DJI_0018.JPG", tmp_path / "a.jpg"))
    meta.focal_35mm = None
    cam, flags = drone_camera(meta)
    assert cam.fx == pytest.approx(3.61 * 4000 / 6.17 / 10) and "approx_intrinsics" in flags
    assert cam.source == "exif:FocalLength+sensor width 6.17 mm DJI FC300S"
    meta.model = "FC9999"
    with pytest.raises(InputError, match="no camera intrinsics"):
        drone_camera(meta)


def test_mixed_folder_two_cameras_dji_and_exif_only(tmp_path, dji_reference):
    """400 px frames 18–20 stripped and 21–23 with their DJI XMP: one camera; the 960 px copies, stripped:
    another. Each camera's track is its own."""
    folder = stripped_copy(BRIGHTON, tmp_path / "mixed", names={"DJI_0018.JPG", "DJI_0019.JPG", "DJI_0020.JPG"})
    for name in ("DJI_0021.JPG", "DJI_0022.JPG", "DJI_0023.JPG"):
        (folder / name).write_bytes((BRIGHTON / name).read_bytes())
    stripped_copy(BRIGHTON_960, folder, prefix="W960_")
    result = import_drone_images(folder, flight_height_m=40.0)
    frames = result.frames
    assert len(frames) == 12 and result.report.unplaced == []
    names = [Path(p).name for p in frames.image]
    small = [i for i, n in enumerate(names) if n.startswith("DJI_")]
    large = [i for i, n in enumerate(names) if n.startswith("W960_")]
    assert len({id(c) for c in frames.cameras}) == 2
    assert all(frames.cameras[i] is frames.cameras[small[0]] for i in small)
    assert all(frames.cameras[i] is frames.cameras[large[0]] for i in large)
    assert (frames.cameras[large[0]].width, frames.cameras[large[0]].fx) == (960, pytest.approx(20 / 36 * 960))
    ref = dji_reference.frames
    # The DJI frames keep their gimbal yaw and take-off ground; the stripped ones follow the track,
    # which is the same for both cameras (the same flight).
    bearings = track_bearings(ref.lat, ref.lon)
    for k, i in enumerate(small):
        if k < 3:
            assert "attitude_from_track" in frames.flags[i] and frames.euler_deg[i, 2] == pytest.approx(bearings[k])
        else:
            assert "attitude_from_track" not in frames.flags[i]
            assert frames.euler_deg[i, 2] == ref.euler_deg[k, 2] and frames.ground_h[i] == ref.ground_h[k]
    np.testing.assert_allclose(frames.euler_deg[large, 2], bearings, atol=1e-6)
    assert result.report.counts["attitude_from_track"] == 9


@pytest.mark.skipif(not ORIGINALS.is_dir(), reason="original Brighton Beach images not available")
def test_full_size_exif_only_frames(tmp_path):
    result = import_drone_images(stripped_copy(ORIGINALS, tmp_path / "full"), flight_height_m=40.0)
    cam = result.frames.cameras[0]
    assert (cam.width, cam.height, cam.fx) == (4000, 2250, pytest.approx(20 / 36 * 4000))
    assert all("resized" not in f for f in result.frames.flags)
    # 36/20 of the depth wide, 2250/4000 of that high.
    for ring, depth in zip(result.footprints.rings, result.footprints.depth_m):
        x, y = ring[:, 0], ring[:, 1]
        area = 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))
        assert area == pytest.approx((1.8 * depth) ** 2 * 2250 / 4000, rel=0.01)
