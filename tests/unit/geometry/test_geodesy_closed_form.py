"""WGS84 geodetic ↔ ECEF in closed form, checked against PROJ; PROJ kept off threads Python did not create."""
import _thread
import ast
import threading
from pathlib import Path

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.geometry import geodesy


@pytest.fixture(scope="module")
def points():
    rng = np.random.default_rng(3)
    lat = np.concatenate([[90.0, -90.0, 0.0, 89.9999999, -45.0], rng.uniform(-90, 90, 20000)])
    lon = np.concatenate([[0.0, 123.0, -180.0, 180.0, 179.9999999], rng.uniform(-180, 180, 20000)])
    h = np.concatenate([[0.0, -100.0, 8848.0, 30.0, 10000.0], rng.uniform(-500.0, 10000.0, 20000)])
    return lat, lon, h


def test_geodetic_to_ecef_equals_proj(points):
    lat, lon, h = points
    x, y, z = geodesy._transformer("EPSG:4979", "EPSG:4978").transform(lon, lat, h)
    np.testing.assert_allclose(geodesy.geodetic_to_ecef(lat, lon, h), np.stack([x, y, z], -1), rtol=0, atol=1e-6)


def test_ecef_to_geodetic_equals_proj_and_round_trips(points):
    lat, lon, h = points
    xyz = np.stack(geodesy._transformer("EPSG:4979", "EPSG:4978").transform(lon, lat, h), -1)
    plon, plat, ph = geodesy._transformer("EPSG:4978", "EPSG:4979").transform(*xyz.T)
    glat, glon, gh = geodesy.ecef_to_geodetic(xyz)
    metres_per_deg = 111_700.0
    east = ((glon - plon + 180.0) % 360.0 - 180.0) * np.cos(np.radians(plat)) * metres_per_deg
    assert np.abs(glat - plat).max() * metres_per_deg < 1e-4 and np.abs(east).max() < 1e-4
    assert np.abs(gh - ph).max() < 1e-4
    back = geodesy.ecef_to_geodetic(geodesy.geodetic_to_ecef(lat, lon, h))
    assert np.abs(back[0] - lat).max() * metres_per_deg < 1e-7 and np.abs(back[2] - h).max() < 1e-7


def test_shapes_and_missing_values_follow_the_inputs():
    assert geodesy.geodetic_to_ecef(10.0, 2.0, 3.0).shape == (3,)
    assert geodesy.geodetic_to_ecef([10.0], [2.0], [3.0]).shape == (1, 3)
    assert np.isnan(geodesy.geodetic_to_ecef([10.0, np.nan], [2.0, 2.0], [np.nan, 0.0])).all()
    lat, lon, h = geodesy.ecef_to_geodetic(geodesy.geodetic_to_ecef(-33.5, 151.2, 40.0))
    assert np.shape(lat) == () and (float(lat), float(lon), float(h)) == pytest.approx((-33.5, 151.2, 40.0))


def test_the_local_frame_never_calls_proj(monkeypatch):
    monkeypatch.setattr(geodesy, "_transformer", lambda *a: pytest.fail("LocalFrame called pyproj"))
    frame = geodesy.LocalFrame(-33.87, 151.21, 25.0)
    enu = frame.from_geodetic([-33.8701, -33.87], [151.2101, 151.21], [30.0, 25.0])
    np.testing.assert_allclose(enu[1], 0.0, atol=1e-9)
    np.testing.assert_allclose(np.stack(frame.to_geodetic(enu), -1)[0], [-33.8701, 151.2101, 30.0], atol=1e-9)


def test_proj_runs_on_a_python_thread_when_called_from_one_python_did_not_start():
    # _thread's threads are, like Qt's, unknown to `threading` (a dummy thread there): the case to route.
    seen, done = {}, threading.Event()

    @geodesy.on_python_thread
    def where():
        return threading.current_thread()

    def foreign():
        try:
            seen["caller"] = threading.current_thread()
            seen["ran_on"] = where()
            seen["utm"] = geodesy.ProjectedCRS(32756).from_geodetic(-33.87, 151.21)
        finally:
            done.set()

    assert where() is threading.current_thread()        # the main thread runs it itself
    _thread.start_new_thread(foreign, ())
    assert done.wait(60)
    assert isinstance(seen["caller"], threading._DummyThread)
    assert not isinstance(seen["ran_on"], threading._DummyThread) and seen["ran_on"].name.startswith("birdseye-proj")
    x, y = geodesy.ProjectedCRS(32756).from_geodetic(-33.87, 151.21)
    assert (float(seen["utm"][0]), float(seen["utm"][1])) == (float(x), float(y))


def test_every_function_that_uses_pyproj_is_kept_off_qt_threads():
    """A function that imports pyproj must be wrapped by geodesy.on_python_thread (see its docstring):
    the plugin's code may run on a thread Qt started, where pyproj 3.7 crashes QGIS."""
    root = Path(__file__).resolve().parents[3]
    unwrapped = []
    for path in [*(root / "birdseye_qgis").rglob("*.py"), *(root / "processing").rglob("*.py")]:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            imports = [n for n in ast.walk(node) if isinstance(n, (ast.Import, ast.ImportFrom))]
            uses = any((isinstance(n, ast.Import) and any(a.name.split(".")[0] == "pyproj" for a in n.names))
                       or (isinstance(n, ast.ImportFrom) and (n.module or "").split(".")[0] == "pyproj")
                       for n in imports)
            wrapped = any(isinstance(d, ast.Name) and d.id == "on_python_thread" for d in node.decorator_list)
            if uses and not wrapped:
                unwrapped.append(f"{path.relative_to(root)}:{node.lineno} {node.name}")
    assert not [n for n in ast.walk(ast.parse((root / "birdseye_qgis" / "core" / "geometry" / "geodesy.py")
                                              .read_text(encoding="utf-8")))
                if isinstance(n, ast.Import) and n.col_offset == 0 and any(a.name == "pyproj" for a in n.names)]
    assert unwrapped == [], "decorate these with @on_python_thread (from core.geometry.geodesy)"
