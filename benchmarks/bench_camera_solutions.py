"""Benchmark: import camera solutions of 5,000 cameras (goal: under 5 s each).

A Metashape export, the same chunk saved as a project (.psx + zipped documents; one sensor, 5,000
aligned cameras, a chunk transform), and an OpenSfM reconstruction (5,000 shots and 50,000 tie points,
which give each frame its ground height), all of a 5,000-frame block over 1 km² at 40 m. Timed:
``core.field.solutions.import_camera_solution`` (parse, conversion to frames, tie-point ground or a stated
ground height, footprints). Baseline: parsing the file alone (ElementTree / json; for the project,
unzipping and parsing its chunk document), the floor any reader pays; the ratio says what the
conversion costs on top.
"""
from __future__ import annotations

import json
import tempfile
import time
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import _path  # noqa: F401
import numpy as np

from birdseye.birdseye_qgis.core.field.solutions import import_camera_solution
from birdseye.birdseye_qgis.core.geometry.geodesy import geodetic_to_ecef, rotation_ecef_enu

N_CAMERAS = 5_000
GOAL_S = 5.0
SITE = (-27.55, 151.95, 400.0)


def block(seed=0):
    rng = np.random.default_rng(seed)
    side = int(np.ceil(np.sqrt(N_CAMERAS)))
    xy = np.stack(np.meshgrid(np.arange(side) * 14.0, np.arange(side) * 10.0), -1).reshape(-1, 2)[:N_CAMERAS]
    centres = np.column_stack([xy, 40 + rng.normal(scale=0.2, size=N_CAMERAS)])
    nadir = np.diag([1.0, -1.0, -1.0])
    yaw = rng.uniform(-np.pi, np.pi, N_CAMERAS)
    c, s = np.cos(yaw), np.sin(yaw)
    rz = np.zeros((N_CAMERAS, 3, 3))
    rz[:, 0, 0], rz[:, 0, 1], rz[:, 1, 0], rz[:, 1, 1], rz[:, 2, 2] = c, -s, s, c, 1
    return centres, rz @ nadir


def write_metashape(path, centres, rotations):
    r_ecef_enu = rotation_ecef_enu(SITE[0], SITE[1])
    origin = geodetic_to_ecef(*SITE).reshape(3)
    doc = ET.Element("document", version="2.0.0")
    chunk = ET.SubElement(doc, "chunk")
    sensor = ET.SubElement(ET.SubElement(chunk, "sensors"), "sensor", id="0", label="P1", type="frame")
    calib = ET.SubElement(sensor, "calibration", type="frame", **{"class": "adjusted"})
    ET.SubElement(calib, "resolution", width="8192", height="5460")
    for key, value in dict(f=8200.0, cx=3.1, cy=-2.2, k1=-0.01, k2=0.002, p1=1e-5, p2=-2e-5).items():
        ET.SubElement(calib, key).text = repr(value)
    cameras = ET.SubElement(chunk, "cameras")
    for i, (centre, r) in enumerate(zip(centres, rotations)):
        t = np.eye(4)
        t[:3, :3], t[:3, 3] = r_ecef_enu @ r, origin + r_ecef_enu @ centre
        cam = ET.SubElement(cameras, "camera", id=str(i), sensor_id="0", label=f"IMG_{i:05d}")
        ET.SubElement(cam, "transform").text = " ".join(f"{v:.10g}" for v in t.ravel())
    ET.SubElement(chunk, "reference").text = 'GEOGCS["WGS 84"]'
    ET.SubElement(ET.SubElement(chunk, "transform"), "scale").text = "1"
    ET.ElementTree(doc).write(path)
    return chunk


def write_metashape_project(psx, chunk):
    """The same chunk as a saved project: the .psx, and .files/ with project.zip → 0/chunk.zip."""
    files = psx.with_suffix(".files")
    (files / "0").mkdir(parents=True)
    psx.write_text('<document version="1.2.0" path="{projectname}.files/project.zip"/>')
    project = ET.Element("document", version="1.2.0")
    ET.SubElement(ET.SubElement(project, "chunks", active_id="0"), "chunk", id="0", path="0/chunk.zip")
    for target, element in ((files / "project.zip", project), (files / "0" / "chunk.zip", chunk)):
        with zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as archive:
            archive.writestr("doc.xml", ET.tostring(element))


def parse_project(psx):
    with zipfile.ZipFile(psx.with_suffix(".files") / "0" / "chunk.zip") as archive:
        return ET.fromstring(archive.read("doc.xml"))


def write_opensfm(path, centres, rotations, rng):
    from scipy.spatial.transform import Rotation

    rotvec = Rotation.from_matrix(np.swapaxes(rotations, 1, 2)).as_rotvec()
    shots = {f"IMG_{i:05d}.JPG": {"rotation": rotvec[i].tolist(),
                                  "translation": (-rotations[i].T @ centres[i]).tolist(), "camera": "p1"}
             for i in range(len(centres))}
    lo, hi = centres[:, :2].min(axis=0), centres[:, :2].max(axis=0)
    pts = np.column_stack([rng.uniform(lo, hi, (50_000, 2)), rng.normal(scale=0.3, size=50_000)])
    rec = {"cameras": {"p1": {"projection_type": "brown", "width": 8192, "height": 5460, "focal_x": 1.0,
                              "focal_y": 1.0, "c_x": 0.0, "c_y": 0.0, "k1": -0.01, "k2": 0.0, "k3": 0.0,
                              "p1": 0.0, "p2": 0.0}},
           "shots": shots, "points": {str(k): {"coordinates": p.tolist()} for k, p in enumerate(pts)},
           "reference_lla": {"latitude": SITE[0], "longitude": SITE[1], "altitude": SITE[2]}}
    path.write_text(json.dumps([rec]))


def timed(function, *args):
    start = time.perf_counter()
    out = function(*args)
    return out, time.perf_counter() - start


def main():
    centres, rotations = block()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        chunk = write_metashape(tmp / "cameras.xml", centres, rotations)
        write_metashape_project(tmp / "block.psx", chunk)
        write_opensfm(tmp / "reconstruction.json", centres, rotations, np.random.default_rng(1))
        for label, path, parse in (("Metashape XML", tmp / "cameras.xml", ET.parse),
                                   ("Metashape project (.psx)", tmp / "block.psx", parse_project),
                                   ("OpenSfM JSON", tmp / "reconstruction.json",
                                    lambda p: json.loads(Path(p).read_text()))):
            _, floor = timed(parse, path)
            # The Metashape export has no tie points: its footprints stand on a stated level ground.
            result, seconds = timed(lambda p: import_camera_solution(p, ground_height=SITE[2]), path)
            assert len(result.frames) == N_CAMERAS
            print(f"{label}: {N_CAMERAS} cameras in {seconds:.2f} s (goal < {GOAL_S:g} s: "
                  f"{'met' if seconds < GOAL_S else 'MISSED'}); parsing alone {floor:.2f} s, ratio "
                  f"{seconds / floor:.1f}×; frames with a ground height "
                  f"{int(np.isfinite(result.frames.ground_h).sum())}")


if __name__ == "__main__":
    main()
