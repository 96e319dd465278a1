"""The frame-layer contract read back into poses."""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.frame_records import FRAME_FIELD_NAMES, euler_degrees, poses_from_records
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
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
