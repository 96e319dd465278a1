"""Camera-solution files of Metashape, OpenSfM/ODM and COLMAP written from each format's documented
conventions, and each format's *own* projection formula, evaluated independently of the plugin's readers.

A small block of nadir-ish cameras over a site at Brighton; ground points within ±1 m of the site height.

Numbers are written with ``str``, not ``repr``: under numpy 2 ``repr(np.float64(x))`` is ``np.float64(x)``,
while ``str`` gives the shortest digits that read back exactly under numpy 1 and 2 alike.
"""
import json
import xml.etree.ElementTree as ET

import numpy as np

from birdseye.birdseye_qgis.core.geometry.geodesy import (
    LocalFrame,
    ecef_to_geodetic,
    geodetic_to_ecef,
    rotation_ecef_enu,
)
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.rotations import so3_exp

SITE = (50.8203, -0.1359, 48.0)  # lat, lon, ellipsoidal height of the site (Brighton)
W, H = 1600, 1200
R_ECEF_ENU = rotation_ecef_enu(SITE[0], SITE[1])
ORIGIN = geodetic_to_ecef(*SITE).reshape(3)
# Nadir camera in ENU: x right = east, y down = south, z forward = down.
NADIR = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]]).T


def truth(n=5, seed=0):
    """Camera → ENU rotations and ENU centres of a small block, and ENU ground points under it."""
    rng = np.random.default_rng(seed)
    r_enu_cam = np.stack([so3_exp(rng.normal(scale=0.05, size=3)) @ NADIR @ so3_exp(np.array([0, 0, a]))
                          for a in rng.uniform(-np.pi, np.pi, n)])
    centres = np.column_stack([rng.uniform(-15, 15, n), rng.uniform(-15, 15, n), rng.uniform(35, 45, n)])
    ground = np.column_stack([rng.uniform(-60, 60, 4000), rng.uniform(-60, 60, 4000), rng.uniform(-1, 1, 4000)])
    return r_enu_cam, centres, ground


def to_ecef(enu):
    return enu @ R_ECEF_ENU.T + ORIGIN


def imported_pixels(frames_import, r_enu_cam, centres, ground):
    """Pixels of the ground points in each imported frame, through the plugin's own chain (frame layer
    contract: lat/lon/height, body quaternion, camera with its mount)."""
    frames = frames_import.frames
    local = LocalFrame(*SITE)
    out = []
    for f in range(len(frames)):
        poses = FramePoses([f], frames.lat[[f]], frames.lon[[f]], frames.height[[f]], frames.quat[[f]],
                           frames.ground_h[[f]], frames.cameras[f])
        geometry = FrameGeometry(poses, local)
        pts = local.from_geodetic(*ecef_to_geodetic(to_ecef(ground)))
        cam = geometry.to_camera(np.zeros(len(pts), dtype=int), pts)
        out.append(frames.cameras[f].project(cam))
    return out


def assert_same_pixels(expected, got, width=W, height=H):
    """Every point the format sees inside the frame lands within 0.01 px; the test covers the corners."""
    n_checked = 0
    for e, g in zip(expected, got):
        inside = (e[:, 0] > -0.5) & (e[:, 0] < width - 0.5) & (e[:, 1] > -0.5) & (e[:, 1] < height - 0.5)
        assert inside.sum() > 50
        err = np.hypot(*(e[inside] - g[inside]).T)
        assert err.max() < 0.01, f"max {err.max():.4f} px"
        corner = np.hypot(e[inside, 0] - (width - 1) / 2, e[inside, 1] - (height - 1) / 2).max()
        assert corner > 0.8 * np.hypot(width, height) / 2
        n_checked += int(inside.sum())
    assert n_checked > 500


MS_CAL = dict(f=1450.0, cx=12.5, cy=-8.25, b1=3.2, b2=-1.1, k1=-0.11, k2=0.09, k3=-0.02, k4=0.004,
              p1=4e-4, p2=-6e-4)


def metashape_pixel(x_cam, cal=MS_CAL, fisheye=False):
    """Metashape's frame-camera model (manual, appendix C), then pixel index = coordinate − 0.5."""
    x, y = x_cam[:, 0] / x_cam[:, 2], x_cam[:, 1] / x_cam[:, 2]
    if fisheye:
        r0 = np.hypot(x, y)
        theta = np.arctan(r0)
        x, y = x * theta / r0, y * theta / r0
    r2 = x * x + y * y
    radial = 1 + cal["k1"] * r2 + cal["k2"] * r2 ** 2 + cal["k3"] * r2 ** 3 + cal["k4"] * r2 ** 4
    xp = x * radial + cal["p1"] * (r2 + 2 * x * x) + 2 * cal["p2"] * x * y
    yp = y * radial + cal["p2"] * (r2 + 2 * y * y) + 2 * cal["p1"] * x * y
    u = W * 0.5 + cal["cx"] + xp * (cal["f"] + cal["b1"]) + yp * cal["b2"]
    v = H * 0.5 + cal["cy"] + yp * cal["f"]
    with np.errstate(invalid="ignore"):
        return np.column_stack([np.where(x_cam[:, 2] > 0, u, np.nan), v]) - 0.5


def write_metashape(path, r_enu_cam, centres, cal=MS_CAL, kind="frame", unaligned=("IMG_9999",), components=True):
    """The block at SITE (camera → ENU rotations, ENU centres) as a Metashape export."""
    write_metashape_ecef(path, np.einsum("ij,njk->nik", R_ECEF_ENU, np.asarray(r_enu_cam)), to_ecef(centres),
                         [f"IMG_{i:04d}" for i in range(len(centres))], cal, W, H, kind, unaligned, components)


def write_metashape_ecef(path, r_ecef_cam, centres_ecef, labels, cal, width, height, kind="frame", unaligned=(),
                         components=True):
    """Cameras in the chunk's internal coordinates and one similarity to ECEF, as real files hold it.

    With ``components`` the similarity is the component's ``<transform>`` and the chunk's ``<transform>``
    repeats it (the real Metashape 1.7 and 2.1 files in shared/data do); without, only the chunk has it.
    """
    rng = np.random.default_rng(5)
    sim_s, sim_r = 7.5, so3_exp(rng.normal(size=3))
    sim_t = np.mean(centres_ecef, axis=0) + rng.normal(size=3) * 100
    similarity = np.eye(4)
    similarity[:3, :3], similarity[:3, 3] = sim_s * sim_r, sim_t
    to_internal = np.linalg.inv(similarity)
    chunk_s, chunk_r, chunk_t = sim_s, sim_r, sim_t
    comp_s, comp_r, comp_t = sim_s, sim_r, sim_t
    doc = ET.Element("document", version="2.0.0")
    ch = ET.SubElement(doc, "chunk", label="Chunk 1", enabled="true")
    sensors = ET.SubElement(ch, "sensors")
    sensor = ET.SubElement(sensors, "sensor", id="0", label="FC6310R (8.8mm)", type=kind)
    ET.SubElement(sensor, "resolution", width=str(width), height=str(height))
    calib = ET.SubElement(sensor, "calibration", type=kind, **{"class": "adjusted"})
    ET.SubElement(calib, "resolution", width=str(width), height=str(height))
    for key, value in cal.items():
        ET.SubElement(calib, key).text = str(float(value))
    if components:
        comps = ET.SubElement(ch, "components", active_id="0")
        c = ET.SubElement(comps, "component", id="0", label="Component 1")
        t = ET.SubElement(c, "transform")
        ET.SubElement(t, "rotation", locked="true").text = " ".join(map(str, comp_r.ravel()))
        ET.SubElement(t, "translation", locked="true").text = " ".join(map(str, comp_t))
        ET.SubElement(t, "scale", locked="true").text = str(comp_s)
        part = ET.SubElement(c, "partition")
        ET.SubElement(part, "camera_ids").text = " ".join(str(i) for i in range(len(centres_ecef)))
    cams = ET.SubElement(ch, "cameras")
    for i, (r, c, label) in enumerate(zip(r_ecef_cam, centres_ecef, labels)):
        cam_to_ecef = np.eye(4)
        cam_to_ecef[:3, :3], cam_to_ecef[:3, 3] = r, c
        camera = ET.SubElement(cams, "camera", id=str(i), sensor_id="0", label=label)
        ET.SubElement(camera, "transform").text = " ".join(map(str, (to_internal @ cam_to_ecef).ravel()))
    for k, name in enumerate(unaligned):
        ET.SubElement(cams, "camera", id=str(100 + k), sensor_id="0", label=name)
    ET.SubElement(ch, "reference").text = 'GEOGCS["WGS 84",DATUM["World Geodetic System 1984"]]'
    t = ET.SubElement(ch, "transform")
    ET.SubElement(t, "rotation").text = " ".join(map(str, chunk_r.ravel()))
    ET.SubElement(t, "translation").text = " ".join(map(str, chunk_t))
    ET.SubElement(t, "scale").text = str(chunk_s)
    ET.ElementTree(doc).write(path)


def metashape_calibration(camera):
    """Metashape's calibration of an OpenCV camera, by its documented conventions (inverse of the reader)."""
    k1, k2, p1, p2, k3 = camera.dist
    return dict(f=camera.fy, b1=camera.fx - camera.fy, b2=camera.skew, cx=camera.cx + 0.5 - camera.width / 2.0,
                cy=camera.cy + 0.5 - camera.height / 2.0, k1=k1, k2=k2, k3=k3, k4=camera.k4, p1=p2, p2=p1)


def camera_coordinates(r_enu_cam, centre, ground):
    return (ground - centre) @ r_enu_cam


SFM_CAM = {"projection_type": "brown", "width": W, "height": H, "focal_x": 0.905, "focal_y": 0.9031,
           "c_x": 0.0071, "c_y": -0.0043, "k1": -0.09, "k2": 0.07, "k3": -0.015, "p1": 3e-4, "p2": -5e-4}


def opensfm_pixel(x_cam, cam=SFM_CAM):
    """OpenSfM's Brown camera on normalised coordinates, then denormalised: s·x_n − 0.5 + w/2."""
    x, y = x_cam[:, 0] / x_cam[:, 2], x_cam[:, 1] / x_cam[:, 2]
    r2 = x * x + y * y
    radial = 1 + cam["k1"] * r2 + cam["k2"] * r2 ** 2 + cam["k3"] * r2 ** 3
    xd = x * radial + 2 * cam["p1"] * x * y + cam["p2"] * (r2 + 2 * x * x)
    yd = y * radial + cam["p1"] * (r2 + 2 * y * y) + 2 * cam["p2"] * x * y
    size = max(W, H)
    u = (cam["focal_x"] * xd + cam["c_x"]) * size - 0.5 + W / 2.0
    v = (cam["focal_y"] * yd + cam["c_y"]) * size - 0.5 + H / 2.0
    with np.errstate(invalid="ignore"):
        return np.column_stack([np.where(x_cam[:, 2] > 0, u, np.nan), v])


def rotation_vector(r):
    from scipy.spatial.transform import Rotation

    return Rotation.from_matrix(r).as_rotvec()


def write_opensfm(path, r_enu_cam, centres, ground, reference_in_file=True):
    shots = {}
    for i, (r, c) in enumerate(zip(r_enu_cam, centres)):
        r_cam_world = r.T
        shots[f"DJI_{i:04d}.JPG"] = {"rotation": rotation_vector(r_cam_world).tolist(),
                                     "translation": (-r_cam_world @ c).tolist(), "camera": "v2 dji fc6310"}
    rec = {"cameras": {"v2 dji fc6310": SFM_CAM}, "shots": shots,
           "points": {str(k): {"coordinates": p.tolist(), "color": [0, 0, 0]} for k, p in enumerate(ground[:800])}}
    ref = {"latitude": SITE[0], "longitude": SITE[1], "altitude": SITE[2]}
    if reference_in_file:
        rec["reference_lla"] = ref
    else:
        (path.parent / "reference_lla.json").write_text(json.dumps(ref))
    path.write_text(json.dumps([rec]))


COLMAP_PARAMS = [1452.0, 1449.5, 805.25, 597.75, -0.1, 0.08, 2e-4, -3e-4]  # OPENCV fx fy cx cy k1 k2 p1 p2


def colmap_pixel(x_cam, p=COLMAP_PARAMS):
    """COLMAP's OPENCV model; its pixel origin is the image corner, so index = coordinate − 0.5."""
    fx, fy, cx, cy, k1, k2, p1, p2 = p
    x, y = x_cam[:, 0] / x_cam[:, 2], x_cam[:, 1] / x_cam[:, 2]
    r2 = x * x + y * y
    radial = k1 * r2 + k2 * r2 ** 2
    dx = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    dy = y * radial + 2 * p2 * x * y + p1 * (r2 + 2 * y * y)
    with np.errstate(invalid="ignore"):
        return np.column_stack([np.where(x_cam[:, 2] > 0, fx * (x + dx) + cx, np.nan), fy * (y + dy) + cy]) - 0.5


def quaternion_wxyz(r):
    from scipy.spatial.transform import Rotation

    x, y, z, w = Rotation.from_matrix(r).as_quat()
    return w, x, y, z


def write_colmap_text(folder, r_enu_cam, centres, ground, frame="enu"):
    folder.mkdir(parents=True, exist_ok=True)
    to_model = (lambda v: v) if frame == "enu" else to_ecef
    rot_model = (lambda r: r) if frame == "enu" else (lambda r: R_ECEF_ENU @ r)
    (folder / "cameras.txt").write_text(f"# Camera list\n1 OPENCV {W} {H} {' '.join(map(str, COLMAP_PARAMS))}\n")
    lines = []
    for i, (r, c) in enumerate(zip(r_enu_cam, centres)):
        r_cw = rot_model(r).T
        t = -r_cw @ to_model(c)
        lines += [" ".join(map(str, [i + 1, *quaternion_wxyz(r_cw), *t])) + f" 1 frame_{i:03d}.jpg", ""]
    (folder / "images.txt").write_text("# Image list\n" + "\n".join(lines) + "\n")
    pts = to_model(ground[:500])
    (folder / "points3D.txt").write_text("".join(f"{k + 1} {p[0]} {p[1]} {p[2]} 0 0 0 0.5\n"
                                                 for k, p in enumerate(pts)))
