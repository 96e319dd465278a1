"""Camera-solution readers against oracles that owe nothing to our reading of the formats.

COLMAP: the model is built and written by pycolmap itself (binary and text), and the pixel of a point is
what pycolmap's own camera gives (``Camera.img_from_cam`` of ``Image.cam_from_world * X``), less 0.5
because COLMAP puts pixel (0, 0) at the corner of the top-left pixel and BirdsEye at its centre
(docs/design.md §3.3).

OpenSfM / ODM: the pixel is computed here with OpenSfM's published formulas, typed from its documentation
("Geometric Models", https://opensfm.org/docs/geometry.html, source doc/source/geometry.rst of
https://github.com/mapillary/OpenSfM): camera models give normalised image coordinates, and pixel
coordinates are ``H·(u, v, 1)`` with ``H = [[s, 0, (w−1)/2], [0, s, (h−1)/2]]``, ``s = max(w, h)``. Where
that page is silent or wrong the test follows OpenSfM's source and says so: the JSON keys of each camera
(``opensfm/io.py``, ``camera_to_json``/``camera_from_json``), and ``fisheye_opencv``, whose documented
formula (k1…k3 plus tangential terms) is not what OpenSfM computes (``FisheyeOpencvCamera =
ProjectGeneric<FisheyeProjection, Disto2468, Affine>`` in ``opensfm/src/geometry/camera_instances.h``:
θd = θ(1 + k1θ² + k2θ⁴ + k3θ⁶ + k4θ⁸), no tangential terms).

Both readers' geographic part is checked against PROJ (pyproj): the topocentric (east-north-up) frame at a
geodetic origin, inverted to ECEF, and that origin against EPSG:4979 → EPSG:4978.

Our side is only what a reader returns: each image's camera → ECEF pose and its :class:`CameraModel`.
"""
import json

import numpy as np
import pyproj
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.solutions.colmap import SUPPORTED_MODELS, read_colmap
from birdseye.birdseye_qgis.core.field.solutions.opensfm import read_reconstruction

SITE = (50.8203, -0.1359, 48.0)  # lat, lon, ellipsoidal height (Brighton)
W, H = 1600, 1200
# Forward projections of the same double-precision point: anything above 1e-6 px is a convention error,
# not rounding; 1e-3 px leaves room for ECEF coordinates (≈4e6 m) differenced at a few tens of metres.
TOL_PX = 1e-3
# Pixels (our pixel-centre convention) that the test points are sent through: the four outer corners of
# the image, its edges and a grid inside, so that distortion is exercised where it is largest.
_u, _v = np.meshgrid(np.linspace(-0.5, W - 0.5, 9), np.linspace(-0.5, H - 0.5, 7))
TARGET_PIXELS = np.column_stack([_u.ravel(), _v.ravel()])


def enu_to_ecef(enu, site=SITE):
    """ECEF of east-north-up coordinates at ``site``, by PROJ's topocentric conversion run backwards."""
    lat, lon, h = site
    topo = pyproj.Transformer.from_pipeline(f"+proj=topocentric +ellps=WGS84 +lat_0={lat!r} +lon_0={lon!r} "
                                            f"+h_0={h!r}")
    enu = np.atleast_2d(np.asarray(enu, dtype=float))
    return np.column_stack(topo.transform(enu[:, 0], enu[:, 1], enu[:, 2], direction="INVERSE"))


def our_pixels(solved, points_ecef):
    """Pixels of ECEF points through what the reader returned: camera → ECEF pose, then the camera model."""
    x_cam = (np.asarray(points_ecef) - solved.centre_ecef) @ solved.R_ecef_cam
    return solved.camera.project(x_cam)


def by_name(solution):
    return {c.name: c for c in solution.cameras}


def assert_agree(expected, got, label):
    """Every point agrees within TOL_PX, and the points cover the image out to its corners."""
    assert np.all(np.isfinite(expected)), f"{label}: the oracle lost points"
    err = np.hypot(*(np.asarray(got) - expected).T)
    assert np.all(np.isfinite(err)) and err.max() < TOL_PX, f"{label}: max {np.nanmax(err):.3g} px"
    reach = np.hypot(expected[:, 0] - (W - 1) / 2, expected[:, 1] - (H - 1) / 2).max()
    assert reach > 0.99 * np.hypot(W, H) / 2, f"{label}: points reach only {reach:.0f} px from the centre"
    return float(err.max())


def rodrigues(rotvec):
    """Rotation matrix of an axis-angle vector (Rodrigues' formula)."""
    rotvec = np.asarray(rotvec, dtype=float)
    theta = np.linalg.norm(rotvec)
    k = rotvec / theta
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(theta) * kx + (1.0 - np.cos(theta)) * kx @ kx


# Nadir in ENU (x east, y south, z down), then tilted: one near-nadir and one oblique view per camera.
NADIR_ENU_FROM_CAM = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]])
VIEWS = [  # (camera → ENU rotation, ENU centre)
    (rodrigues([0.03, -0.05, 0.4]) @ NADIR_ENU_FROM_CAM, np.array([4.0, -7.5, 41.0])),
    (rodrigues([0.45, 0.2, -2.1]) @ NADIR_ENU_FROM_CAM, np.array([-12.0, 9.0, 36.5])),
]
DEPTHS = np.random.default_rng(7).uniform(3.0, 90.0, len(TARGET_PIXELS))


# ---------------------------------------------------------------------------------------------- COLMAP
COLMAP_PARAMS = {  # pycolmap's parameter order (Camera.params_info); non-trivial in every term
    "SIMPLE_PINHOLE": [1450.0, 811.3, 593.9],
    "PINHOLE": [1452.0, 1447.5, 788.4, 606.2],
    "SIMPLE_RADIAL": [1450.0, 805.25, 597.75, -0.08],
    "RADIAL": [1450.0, 805.25, 597.75, -0.09, 0.05],
    "OPENCV": [1452.0, 1449.5, 805.25, 597.75, -0.1, 0.08, 2e-4, -3e-4],
    "FULL_OPENCV": [1452.0, 1449.5, 805.25, 597.75, -0.1, 0.08, 2e-4, -3e-4, -0.02, 0.0, 0.0, 0.0],
    "OPENCV_FISHEYE": [1100.0, 1098.0, 806.5, 596.0, 0.03, -0.01, 0.002, -0.0004],
    "SIMPLE_RADIAL_FISHEYE": [1100.0, 806.5, 596.0, 0.04],
    "RADIAL_FISHEYE": [1100.0, 806.5, 596.0, 0.03, -0.008],
}


def test_every_supported_colmap_model_is_covered():
    assert set(COLMAP_PARAMS) == set(SUPPORTED_MODELS)


def _colmap_scene(reference):
    """pycolmap cameras, poses (cam_from_world, in the model's frame) and world points seen by each image.

    ``ecef``: the model frame is ECEF. ``enu``: it is east-north-up at SITE. The points are sent from the
    camera through TARGET_PIXELS by pycolmap's own inverse (cam_from_img), then to the model frame.
    """
    import pycolmap

    if reference == "ecef":
        origin = enu_to_ecef([0.0, 0.0, 0.0])[0]
        # ENU axes in ECEF from PROJ itself, made exactly orthonormal (the differences are good to ~1e-9).
        axes = enu_to_ecef(np.eye(3) * 1000.0) - origin
        u, _, vt = np.linalg.svd(axes.T / 1000.0)
        r_frame_enu = u @ vt
        to_frame = enu_to_ecef
    else:
        r_frame_enu = np.eye(3)

        def to_frame(enu):
            return np.atleast_2d(enu)

    scene = []
    for k, (model, params) in enumerate(COLMAP_PARAMS.items()):
        camera = pycolmap.Camera(model=model, width=W, height=H, params=params, camera_id=k + 1)
        rays = camera.cam_from_img(TARGET_PIXELS + 0.5)
        x_cam = np.column_stack([rays, np.ones(len(rays))]) * DEPTHS[:, None]
        for j, (r_enu_cam, centre_enu) in enumerate(VIEWS):
            r_frame_cam = r_frame_enu @ r_enu_cam
            centre = to_frame(centre_enu)[0]
            cam_from_world = pycolmap.Rigid3d(pycolmap.Rotation3d(r_frame_cam.T), -r_frame_cam.T @ centre)
            world = cam_from_world.inverse() * x_cam
            scene.append((f"{model.lower()}_{j}.jpg", camera, cam_from_world, world))
    return scene


@pytest.fixture(scope="module")
def colmap_models(tmp_path_factory):
    """Each (reference, format) → (folder written by pycolmap, scene)."""
    import pycolmap

    out = {}
    for reference in ("ecef", "enu"):
        scene = _colmap_scene(reference)
        rec = pycolmap.Reconstruction()
        for cam in {id(c): c for _, c, _, _ in scene}.values():
            rec.add_camera_with_trivial_rig(cam)
        for image_id, (name, camera, pose, _) in enumerate(scene, start=1):
            rec.add_image_with_trivial_frame(pycolmap.Image(name=name, camera_id=camera.camera_id,
                                                            image_id=image_id), pose)
        for fmt in ("bin", "txt"):
            folder = tmp_path_factory.mktemp(f"colmap_{reference}_{fmt}")
            (rec.write_binary if fmt == "bin" else rec.write_text)(str(folder))
            assert (folder / ("cameras." + fmt)).is_file()
            out[reference, fmt] = folder, scene
    return out


@pytest.mark.parametrize("fmt", ["bin", "txt"])
@pytest.mark.parametrize("reference", ["ecef", "enu"])
@pytest.mark.parametrize("model", SUPPORTED_MODELS)
def test_colmap_reader_projects_as_pycolmap(colmap_models, model, reference, fmt):
    folder, scene = colmap_models[reference, fmt]
    ref = "ecef" if reference == "ecef" else "enu:{!r},{!r},{!r}".format(*SITE)
    solved = by_name(read_colmap(folder, reference=ref))
    assert len(solved) == len(scene)
    for name, camera, cam_from_world, world in scene:
        if not name.startswith(model.lower() + "_"):
            continue
        expected = camera.img_from_cam(cam_from_world * world) - 0.5
        points_ecef = world if reference == "ecef" else enu_to_ecef(world)
        assert_agree(expected, our_pixels(solved[name], points_ecef), f"{model} {reference} {fmt} {name}")


def test_colmap_centres_are_pycolmaps_projection_centres(colmap_models):
    folder, scene = colmap_models["ecef", "txt"]
    solved = by_name(read_colmap(folder, reference="ecef"))
    for name, _, cam_from_world, _ in scene:
        np.testing.assert_allclose(solved[name].centre_ecef, cam_from_world.inverse().translation, atol=1e-6)


def test_colmap_rational_terms_are_refused_not_dropped(tmp_path):
    """FULL_OPENCV's k4–k6 divide the radial term; no CameraModel holds them, so reading must fail."""
    import pycolmap
    rec = pycolmap.Reconstruction()
    params = COLMAP_PARAMS["FULL_OPENCV"][:9] + [0.01, 0.0, 0.0]
    rec.add_camera_with_trivial_rig(pycolmap.Camera(model="FULL_OPENCV", width=W, height=H, params=params,
                                                    camera_id=1))
    rec.add_image_with_trivial_frame(pycolmap.Image(name="a.jpg", camera_id=1, image_id=1),
                                     pycolmap.Rigid3d(pycolmap.Rotation3d(np.eye(3)), np.zeros(3)))
    rec.write_text(str(tmp_path))
    with pytest.raises(InputError, match="k4–k6"):
        read_colmap(tmp_path, reference="ecef")


# ---------------------------------------------------------------------------------------------- OpenSfM
# Each camera as OpenSfM's camera_to_json writes it (opensfm/io.py): one "focal" for perspective and
# fisheye, "focal_x"/"focal_y" and the principal point "c_x"/"c_y" for the others.
SFM_CAMERAS = {
    "perspective": {"focal": 0.905, "k1": -0.08, "k2": 0.03},
    "brown": {"focal_x": 0.905, "focal_y": 0.9031, "c_x": 0.0071, "c_y": -0.0043, "k1": -0.09, "k2": 0.07,
              "p1": 3e-4, "p2": -5e-4, "k3": -0.015},
    "fisheye": {"focal": 0.69, "k1": 0.02, "k2": -0.005},
    "fisheye_opencv": {"focal_x": 0.69, "focal_y": 0.6875, "c_x": -0.0062, "c_y": 0.0048, "k1": 0.03,
                       "k2": -0.01, "k3": 0.002, "k4": -0.0004},
    "radial": {"focal_x": 0.905, "focal_y": 0.9022, "c_x": 0.0053, "c_y": 0.0031, "k1": -0.085, "k2": 0.04},
    "simple_radial": {"focal_x": 0.905, "focal_y": 0.9044, "c_x": -0.0047, "c_y": 0.0066, "k1": -0.07},
}


def opensfm_normalized(kind, cam, x_cam):
    """Normalised image coordinates (u, v) of camera-frame points, by the documented camera models."""
    x, y, z = x_cam.T
    if kind in ("fisheye", "fisheye_opencv"):
        r = np.hypot(x, y)
        theta = np.arctan2(r, z)
        # θ/r → 1/z on the optical axis, where the formula as written is 0/0.
        theta_r = np.where(r > 0, theta / np.where(r > 0, r, 1.0), 1.0 / z)
        if kind == "fisheye":
            d = 1 + cam["k1"] * theta ** 2 + cam["k2"] * theta ** 4
            return np.column_stack([cam["focal"] * d * theta_r * x, cam["focal"] * d * theta_r * y])
        t2 = theta ** 2
        d = 1 + cam["k1"] * t2 + cam["k2"] * t2 ** 2 + cam["k3"] * t2 ** 3 + cam["k4"] * t2 ** 4
        return np.column_stack([cam["focal_x"] * d * theta_r * x + cam["c_x"],
                                cam["focal_y"] * d * theta_r * y + cam["c_y"]])
    xn, yn = x / z, y / z
    r2 = xn ** 2 + yn ** 2
    if kind == "perspective":
        d = 1 + cam["k1"] * r2 + cam["k2"] * r2 ** 2
        return np.column_stack([cam["focal"] * d * xn, cam["focal"] * d * yn])
    if kind == "simple_radial":
        d = 1 + cam["k1"] * r2
        return np.column_stack([cam["focal_x"] * d * xn + cam["c_x"], cam["focal_y"] * d * yn + cam["c_y"]])
    if kind == "radial":
        d = 1 + cam["k1"] * r2 + cam["k2"] * r2 ** 2
        return np.column_stack([cam["focal_x"] * d * xn + cam["c_x"], cam["focal_y"] * d * yn + cam["c_y"]])
    # brown: the page writes "r² + 2x" for r² + 2·x_n², as OpenSfM's TangentialDistortion computes it.
    dr = 1 + cam["k1"] * r2 + cam["k2"] * r2 ** 2 + cam["k3"] * r2 ** 3
    dtx = 2 * cam["p1"] * xn * yn + cam["p2"] * (r2 + 2 * xn ** 2)
    dty = 2 * cam["p2"] * xn * yn + cam["p1"] * (r2 + 2 * yn ** 2)
    return np.column_stack([cam["focal_x"] * (dr * xn + dtx) + cam["c_x"],
                            cam["focal_y"] * (dr * yn + dty) + cam["c_y"]])


def opensfm_pixels(kind, cam, x_cam, width=W, height=H):
    """Pixel coordinates (origin at the centre of the top-left pixel) by the documented matrix H."""
    uv = opensfm_normalized(kind, cam, x_cam)
    s = max(width, height)
    return np.column_stack([s * uv[:, 0] + (width - 1) / 2.0, s * uv[:, 1] + (height - 1) / 2.0])


def rays_through(kind, cam, pixels):
    """Camera-frame directions (z = 1) whose documented projection is ``pixels``: Newton's method on the
    oracle itself, with a numerical Jacobian, so the test points reach the image corners."""
    xy = (pixels - [(W - 1) / 2.0, (H - 1) / 2.0]) / (max(W, H) * 0.8)
    step = 1e-7

    def f(p):
        return opensfm_pixels(kind, cam, np.column_stack([p, np.ones(len(p))]))

    for _ in range(30):
        res = f(xy) - pixels
        if np.abs(res).max() < 1e-9:
            break
        jx = (f(xy + [step, 0.0]) - f(xy - [step, 0.0])) / (2 * step)
        jy = (f(xy + [0.0, step]) - f(xy - [0.0, step])) / (2 * step)
        det = jx[:, 0] * jy[:, 1] - jy[:, 0] * jx[:, 1]
        xy = xy - np.column_stack([(jy[:, 1] * res[:, 0] - jy[:, 0] * res[:, 1]) / det,
                                   (jx[:, 0] * res[:, 1] - jx[:, 1] * res[:, 0]) / det])
    assert np.abs(f(xy) - pixels).max() < 1e-6
    return np.column_stack([xy, np.ones(len(xy))])


def _write_reconstruction(path, kinds):
    """A reconstruction.json as OpenSfM writes it; returns {shot: (kind, rotation, translation, ENU points)}."""
    from scipy.spatial.transform import Rotation

    cameras, shots, scene = {}, {}, {}
    for kind in kinds:
        key = f"v2 test camera {W} {H} {kind} 0.9"
        cameras[key] = {"projection_type": kind, "width": W, "height": H, **SFM_CAMERAS[kind]}
        x_cam = rays_through(kind, SFM_CAMERAS[kind], TARGET_PIXELS) * DEPTHS[:, None]
        for j, (r_enu_cam, centre) in enumerate(VIEWS):
            r_cam_world = r_enu_cam.T
            # The shot's rotation as OpenSfM stores it: the axis-angle vector of the world → camera rotation.
            # scipy rather than the half-angle formula: near-nadir rotations are close to π.
            rotation = Rotation.from_matrix(r_cam_world).as_rotvec()
            translation = -rodrigues(rotation) @ centre
            name = f"{kind}_{j}.JPG"
            shots[name] = {"rotation": rotation.tolist(), "translation": translation.tolist(), "camera": key,
                           "orientation": 1, "capture_time": 0.0, "gps_dop": 5.0}
            world = (x_cam - translation) @ rodrigues(rotation)  # R⁻¹ (x_cam − t)
            scene[name] = kind, rotation, translation, world
    points = {str(k): {"color": [0.0, 0.0, 0.0], "coordinates": p.tolist()}
              for k, p in enumerate(np.concatenate([s[3][:5] for s in scene.values()]))}
    rec = {"cameras": cameras, "shots": shots, "points": points, "biases": {},
           "reference_lla": {"latitude": SITE[0], "longitude": SITE[1], "altitude": SITE[2]}}
    path.write_text(json.dumps([rec]))
    return scene, np.array([p["coordinates"] for p in points.values()])


@pytest.mark.parametrize("kind", list(SFM_CAMERAS))
def test_opensfm_reader_projects_as_the_documented_model(tmp_path, kind):
    scene, _ = _write_reconstruction(tmp_path / "reconstruction.json", [kind])
    solved = by_name(read_reconstruction(tmp_path / "reconstruction.json"))
    assert set(solved) == set(scene)
    for name, (_, rotation, translation, world) in scene.items():
        expected = opensfm_pixels(kind, SFM_CAMERAS[kind], world @ rodrigues(rotation).T + translation)
        np.testing.assert_allclose(expected, TARGET_PIXELS, atol=1e-6)
        assert_agree(expected, our_pixels(solved[name], enu_to_ecef(world)), f"{kind} {name}")


def test_opensfm_geographic_reference_agrees_with_proj(tmp_path):
    """Centres and tie points land where PROJ puts the topocentric coordinates; the topocentric origin is
    PROJ's EPSG:4979 → EPSG:4978 of reference_lla."""
    scene, points = _write_reconstruction(tmp_path / "reconstruction.json", list(SFM_CAMERAS))
    solution = read_reconstruction(tmp_path / "reconstruction.json")
    solved = by_name(solution)
    for name, (_, rotation, translation, _) in scene.items():
        centre_enu = -rodrigues(rotation).T @ translation
        np.testing.assert_allclose(solved[name].centre_ecef, enu_to_ecef(centre_enu)[0], atol=1e-6)
    np.testing.assert_allclose(solution.points_ecef, enu_to_ecef(points), atol=1e-6)
    geocentric = pyproj.Transformer.from_crs("EPSG:4979", "EPSG:4978", always_xy=True)
    np.testing.assert_allclose(enu_to_ecef([0.0, 0.0, 0.0])[0], geocentric.transform(SITE[1], SITE[0], SITE[2]),
                               atol=1e-6)


@pytest.mark.parametrize("kind,missing", [("brown", "focal_x"), ("radial", "focal_y"), ("perspective", "focal")])
def test_opensfm_camera_without_its_focal_is_refused(tmp_path, kind, missing):
    """OpenSfM itself requires the focal keys; a default of 0 would put every point on the principal point."""
    _write_reconstruction(tmp_path / "reconstruction.json", [kind])
    doc = json.loads((tmp_path / "reconstruction.json").read_text())
    for cam in doc[0]["cameras"].values():
        del cam[missing]
    (tmp_path / "reconstruction.json").write_text(json.dumps(doc))
    with pytest.raises(InputError, match=f"incomplete or malformed.*{missing}"):
        read_reconstruction(tmp_path / "reconstruction.json")
