"""indices_by_camera: the one grouping of frames by camera, for camera objects and a frame layer's JSON."""

from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.poses import indices_by_camera


def test_groups_equal_cameras_in_order_of_first_appearance():
    a = CameraModel(640, 480, 500.0, 500.0, 319.5, 239.5)
    b = CameraModel(640, 480, 510.0, 510.0, 319.5, 239.5)
    a_again = CameraModel.from_json(a.to_json())  # another object, the same camera
    groups = indices_by_camera([b, a, b, a_again, a])
    assert [g.tolist() for g in groups] == [[0, 2], [1, 3, 4]]
    json_groups = indices_by_camera([c.to_json() for c in (b, a, b, a_again, a)])
    assert [g.tolist() for g in json_groups] == [[0, 2], [1, 3, 4]]
    assert all(g.dtype.kind == "i" for g in groups)
    assert indices_by_camera([]) == []
