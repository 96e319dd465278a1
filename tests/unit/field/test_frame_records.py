"""The frame-layer contract read back into poses."""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.frame_records import (
    FRAME_FIELD_NAMES,
    camera_cut_at,
    euler_degrees,
    join_camera,
    poses_from_records,
    split_camera,
    split_cameras,
)
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.heights import EGM96_REFERENCE, ELLIPSOIDAL_REFERENCE
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat

CAM_A = CameraModel(1920, 1200, 4264.0, 4262.0, 958.0, 592.0)
CAM_B = CameraModel(4000, 2250, 2300.0, 2300.0, 1999.5, 1124.5)


def record(i, cam, **kw):
    q = rotmat_to_quat(euler_zyx_to_rotmat(0.01 * i, -0.02, np.radians(10.0 * i)))
    rec = dict.fromkeys(FRAME_FIELD_NAMES, "")
    rec.update(frame_id=i, lat=-27.5 + 1e-5 * i, lon=151.9, height_m=410.0, qw=q[0], qx=q[1], qy=q[2],
               qz=q[3], ground_h_m=400.0, camera=cam.to_json())
    rec.update(kw)
    return rec


def test_records_group_by_camera_in_input_order():
    recs = [record(0, CAM_A), record(1, CAM_B), record(2, CAM_A)]
    groups = poses_from_records(recs)
    assert [g[1].tolist() for g in groups] == [[0, 2], [1]]
    poses, idx = groups[0]
    assert poses.camera == CAM_A and poses.frame_id.tolist() == [0, 2]
    np.testing.assert_allclose(poses.height, 410.0)
    roll, pitch, yaw = euler_degrees(poses.quat)
    np.testing.assert_allclose(yaw, [0.0, 20.0], atol=1e-9)


def test_bad_records_name_the_row_and_field():
    recs = [record(0, CAM_A), record(1, CAM_A, qw=None)]
    with pytest.raises(InputError, match=r"frames\.gpkg, row 2, field 'qw'"):
        poses_from_records(recs, source="frames.gpkg")
    with pytest.raises(InputError, match="not a BirdsEye frame layer: missing field"):
        poses_from_records([{"frame_id": 1, "lat": 0.0}], source="points")
    with pytest.raises(InputError, match="row 1, field 'camera'"):
        poses_from_records([record(0, CAM_A, camera="")])
    with pytest.raises(InputError, match="has no frames"):
        poses_from_records([])


def test_a_camera_split_for_short_text_fields_joins_back():
    long_cam = CameraModel(4000, 3000, 2964.123456789, 2963.987654321, 2001.25, 1498.75,
                           dist=(-0.1123456789, 0.0212345678, 1.2e-4, -3.4e-5, 0.0011223344), source="x" * 250)
    text = long_cam.to_json()
    assert len(text) > 2 * 254
    parts = split_camera(text, 254)
    assert len(parts) == 3 and all(len(p) <= 254 for p in parts) and join_camera(parts) == text
    assert split_camera("", 254) == [""] and join_camera(["abc", None, ""]) == "abc"
    # The records: the fields the longest camera needs, each record's parts; a short camera leaves the rest out.
    fields, records = split_cameras([record(0, long_cam), record(1, CAM_A)], 254)
    assert [f[0] for f in fields] == ["camera_2", "camera_3"] and all(f[1] == "string" for f in fields)
    assert [records[0]["camera"], records[0]["camera_2"], records[0]["camera_3"]] == parts
    assert records[1]["camera"] == CAM_A.to_json() and "camera_2" not in records[1]
    assert split_cameras([record(0, CAM_A)], 1000)[0] == []
    assert poses_from_records([{**r, "camera": join_camera([r["camera"], r.get("camera_2"), r.get("camera_3")])}
                               for r in records])[0][0].camera == long_cam


def test_a_cut_camera_is_told_from_a_whole_or_a_broken_one():
    text = CAM_A.to_json()
    assert camera_cut_at([text[:100]], [100]) == 100                 # filled its field, not JSON: cut
    assert camera_cut_at([text[:100], text[100:120]], [254, 20]) == 20   # its second part was cut
    assert camera_cut_at(split_camera(text, 100), [100] * len(split_camera(text, 100))) is None   # whole
    assert camera_cut_at([text[:100]], [0]) is None                   # no field length: no evidence of a cut
    assert camera_cut_at(["{not json"], [254]) is None                # broken, but not by the field
    assert camera_cut_at([None], [254]) is None and camera_cut_at([""], [254]) is None


def test_every_frame_says_what_its_heights_are_measured_from():
    """height_ref (one per layer) and ground_src (per frame) travel into the poses; a layer written before the
    fields existed reads as it always did (ellipsoidal, the altimeter's ground); a mix of references, or a
    reference nobody knows, is refused naming the row."""
    dji = [record(i, CAM_A, height_ref="EGM96", ground_src="takeoff") for i in range(2)]
    refined = dji + [record(2, CAM_A, height_ref="EGM96", ground_src="tie_points")]
    poses, _ = poses_from_records(refined)[0]
    assert poses.reference == EGM96_REFERENCE and poses.ground_source.tolist() == ["takeoff", "takeoff", "tie_points"]
    old = [{k: v for k, v in record(i, CAM_A).items() if k not in ("height_ref", "ground_src")} for i in range(2)]
    poses, _ = poses_from_records(old)[0]
    assert poses.reference == ELLIPSOIDAL_REFERENCE and poses.ground_source.tolist() == ["altimeter"] * 2
    mixed = dji + [record(2, CAM_B, height_ref="ellipsoidal", ground_src="altimeter")]
    with pytest.raises(InputError, match=r"frames\.gpkg, field 'height_ref': mixes vertical references: above mean "
                                         r"sea level \(EGM96 geoid\) \(rows 1, 2\); ellipsoidal \(WGS84\) \(rows 3\)"):
        poses_from_records(mixed, source="frames.gpkg")
    with pytest.raises(InputError, match=r"row 2, field 'height_ref': 'NAVD88' is not a vertical reference"):
        poses_from_records([dji[0], record(1, CAM_A, height_ref="NAVD88")], source="frames.gpkg")
    with pytest.raises(InputError, match=r"row 1, field 'ground_src': 'radar' is not a ground source"):
        poses_from_records([record(0, CAM_A, height_ref="EGM96", ground_src="radar")], source="frames.gpkg")
