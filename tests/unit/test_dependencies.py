"""birdseye_qgis/dependencies.py without QGIS: the pins, what is missing, the interpreter, pip.

The installer runs the real pip of this Python against a wheel folder made here (tiny hand-built
wheels, no network): what it installs, what it refuses, how it reports progress and stops on cancel.
"""
from __future__ import annotations

import ast
import importlib
import os
import sys
import textwrap
import threading
import time
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from fake_wheels import make_wheel, offline_pip  # noqa: E402

from birdseye.birdseye_qgis import dependencies as deps
from birdseye.birdseye_qgis.core.errors import Cancelled, InputError

REPO_ROOT = Path(__file__).resolve().parents[2]
ALGORITHM_IDS = {p.stem for p in (REPO_ROOT / "processing" / "algorithms").glob("*.py")} - {"__init__", "base"}


# ------------------------------------------------------------------------------ the pins and their uses
def test_requirements_and_uses_list_the_same_packages():
    """requirements.txt is the one list of pins; USES must say something about each, and nothing else."""
    pinned = {deps.normalized(p.distribution) for p in deps.read_requirements()}
    assert pinned == {deps.normalized(name) for name in deps.USES}
    assert all(p.version[0].isdigit() for p in deps.read_requirements())


def test_uses_name_existing_algorithms_once():
    for name, use in deps.USES.items():
        named = use.always + use.sometimes
        assert set(named) <= ALGORITHM_IDS, f"{name}: {set(named) - ALGORITHM_IDS} are not algorithms"
        assert len(set(named)) == len(named), f"{name}: an algorithm is listed twice"


def imported_top_modules(path: Path) -> set[str]:
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.add(node.module.split(".")[0])
    return found


def test_every_module_in_uses_is_imported_by_the_plugin():
    """A package the plugin no longer imports must leave requirements.txt and USES: a stale entry
    would make users install, and algorithms refuse to run for, a package nothing uses."""
    sources = [p for folder in ("birdseye_qgis", "processing") for p in (REPO_ROOT / folder).rglob("*.py")
               if p.name != "dependencies.py"]
    imported = set().union(*(imported_top_modules(p) for p in sources))
    assert {use.module for use in deps.USES.values()} - imported == set()


def plugin_module_file(dotted: str) -> Path | None:
    """The source file of ``birdseye.<dotted>`` in this tree, or None (a name, not a module)."""
    path = REPO_ROOT.joinpath(*dotted.split(".")[1:])
    if (path / "__init__.py").is_file():
        return path / "__init__.py"
    return path.with_suffix(".py") if path.with_suffix(".py").is_file() else None


def reachable_packages(algorithm_id: str) -> set[str]:
    """Top-level modules imported anywhere (module level or inside functions) in the plugin modules an
    algorithm's module imports, transitively: every package it could possibly reach."""
    todo, seen, found = [f"birdseye.processing.algorithms.{algorithm_id}"], set(), set()
    while todo:
        name = todo.pop()
        path = plugin_module_file(name)
        if name in seen or path is None:
            continue
        seen.add(name)
        package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                found |= {alias.name.split(".")[0] for alias in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                found.add(node.module.split(".")[0])
            elif isinstance(node, ast.ImportFrom):
                base = ".".join(package[:len(package) - node.level + 1] + ([node.module] if node.module else []))
                todo += [base] + [f"{base}.{alias.name}" for alias in node.names]
    return found


def test_an_algorithm_said_to_need_a_package_can_reach_it():
    """USES is checked against the code: each algorithm it names imports, somewhere down its imports,
    the package it is said to need (an algorithm that stopped using one must not be refused for it)."""
    stale = [f"{algorithm} → {use.module}" for use in deps.USES.values()
             for algorithm in use.always + use.sometimes if use.module not in reachable_packages(algorithm)]
    assert stale == []
    assert "onnxruntime" in reachable_packages("detect") and "fast_tsp" not in reachable_packages("detect")


def write(path: Path, text: str) -> Path:
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


def test_read_requirements_keeps_pins_and_skips_comments(tmp_path):
    path = write(tmp_path / "requirements.txt", """\
        # runtime
        onnxruntime==1.20.1   # the detector

        scikit_learn==1.5.2
        """)
    packages = deps.read_requirements(path)
    assert [(p.distribution, p.version, p.module) for p in packages] == [
        ("onnxruntime", "1.20.1", "onnxruntime"), ("scikit-learn", "1.5.2", "sklearn")]
    assert packages[1].requirement == "scikit-learn==1.5.2"


@pytest.mark.parametrize("line, expected", [
    ("onnxruntime>=1.20", "is not a pin 'name==version'"),
    ("onnxruntime", "is not a pin"),
    ("onnxruntime==1.20.1 ; python_version<'4'", "is not a pin"),
])
def test_read_requirements_names_the_bad_row(tmp_path, line, expected):
    path = write(tmp_path / "requirements.txt", f"# pins\nscipy==1.13.1\n{line}\n")
    with pytest.raises(InputError) as info:
        deps.read_requirements(path)
    assert str(info.value).startswith(f"{path}, row 3: ") and expected in str(info.value)


def test_a_pin_uses_does_not_know_is_still_installed(tmp_path):
    path = write(tmp_path / "requirements.txt", "Some.New_Package==2.0\n")
    [package] = deps.read_requirements(path)
    assert (package.requirement, package.module, package.use.always) == ("Some.New_Package==2.0",
                                                                          "some_new_package", ())


def test_unreadable_requirements_name_the_file(tmp_path):
    with pytest.raises(InputError, match="requirements.txt: cannot be read"):
        deps.read_requirements(tmp_path / "requirements.txt")


# ------------------------------------------------------------------------------ what is missing
def make_package(site: Path, name: str, version: str) -> None:
    (site / name).mkdir(parents=True)
    (site / name / "__init__.py").write_text(f"VERSION = '{version}'\n")
    info = site / f"{name}-{version}.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {name}\nVersion: {version}\n")


@pytest.fixture
def clean_path(monkeypatch):
    """sys.path and the import caches as they were, whatever a test activates."""
    monkeypatch.setattr(sys, "path", list(sys.path))
    before = set(sys.modules)
    yield
    for name in set(sys.modules) - before:
        if name.startswith("birdseyefake"):
            del sys.modules[name]
    importlib.invalidate_caches()


def test_status_before_and_after_the_folder_is_activated(tmp_path, clean_path):
    folder = tmp_path / "birdseye-dependencies" / "python3.x"
    package = deps.RuntimePackage("birdseyefake-a", "1.0", deps.Use("birdseyefake_a"))
    missing = deps.package_status(package, folder)
    assert (missing.installed_version, missing.in_folder, missing.needs_install) == (None, False, True)

    make_package(folder, "birdseyefake_a", "1.0")
    deps.activate(folder)
    assert sys.path[-1] == str(folder), "the folder goes last: QGIS's own packages win"
    found = deps.package_status(package, folder)
    assert (found.installed_version, found.in_folder, found.needs_install) == ("1.0", True, False)
    newer_pin = deps.RuntimePackage("birdseyefake-a", "2.0", deps.Use("birdseyefake_a"))
    assert deps.package_status(newer_pin, folder).needs_install, "installed by BirdsEye at an old pin: update"


def test_a_version_qgis_ships_is_used_as_it_is(tmp_path, clean_path):
    """QGIS's own copy at another version than the pin is not 'missing' (replacing it could break QGIS)."""
    host = tmp_path / "host-site"
    make_package(host, "birdseyefake_b", "0.9")
    sys.path.insert(0, str(host))
    importlib.invalidate_caches()
    status = deps.package_status(deps.RuntimePackage("birdseyefake-b", "1.0", deps.Use("birdseyefake_b")),
                                 tmp_path / "folder")
    assert (status.installed_version, status.in_folder, status.needs_install) == ("0.9", False, False)


def test_missing_for_lists_only_what_an_algorithm_always_needs(monkeypatch):
    packages = deps.read_requirements()
    monkeypatch.setitem(sys.modules, "onnxruntime", None)  # find_spec and import both see it as absent
    monkeypatch.setitem(sys.modules, "pycolmap", None)
    assert [p.distribution for p in deps.missing_for("detect", packages)] == ["onnxruntime"]
    assert [p.distribution for p in deps.missing_for("refineposes", packages)] == ["pycolmap"]
    assert deps.missing_for("importcameras", packages) == [], "pycolmap is needed only for COLMAP models"
    assert deps.missing_for("selectarms", packages) == []


def test_package_for_module():
    packages = deps.read_requirements()
    assert deps.package_for_module("cv2.dnn", packages).distribution == "opencv-python-headless"
    assert deps.package_for_module("sklearn", packages).distribution == "scikit-learn"
    assert deps.package_for_module("numpy", packages) is None


def test_package_folder_is_per_python_version(tmp_path):
    assert deps.package_folder(tmp_path, (3, 12, 1)) == tmp_path / "python" / "birdseye-dependencies" / "python3.12"


# ------------------------------------------------------------------------------ the interpreter
def test_candidates_on_windows_skip_qgis_bin():
    """OSGeo4W: sys.executable is qgis-bin.exe, Python lives in apps\\Python312 (sys.prefix)."""
    found = deps.python_candidates(r"C:\OSGeo4W\bin\qgis-bin.exe", [r"C:\OSGeo4W\apps\Python312"], "win32",
                                   (3, 12))
    assert found == [r"C:\OSGeo4W\apps\Python312\python.exe", r"C:\OSGeo4W\bin\python3.exe",
                     r"C:\OSGeo4W\bin\python.exe"]


def test_candidates_on_macos_look_in_the_bundle():
    app = "/Applications/QGIS.app/Contents/MacOS"
    found = deps.python_candidates(f"{app}/QGIS", [app], "darwin", (3, 9))
    assert found == [f"{app}/bin/python3.9", f"{app}/bin/python3"]


def test_candidates_on_linux_start_with_sys_executable():
    found = deps.python_candidates("/usr/bin/python3", ["/usr", "/usr"], "linux", (3, 11))
    assert found == ["/usr/bin/python3", "/usr/bin/python3.11"]
    embedded = deps.python_candidates("/usr/bin/qgis", ["/usr"], "linux", (3, 11))
    assert embedded == ["/usr/bin/python3.11", "/usr/bin/python3"]


def fake_python(path: Path, version: str, prefix: str) -> str:
    path.write_text(f"#!/bin/sh\necho {version}\necho {prefix}\n")
    path.chmod(0o755)
    return str(path)


def test_find_python_keeps_the_first_that_is_this_python(tmp_path):
    """Same version and same installation: a pyenv python3.X first on PATH is not QGIS's Python."""
    this = f"{sys.version_info[0]}.{sys.version_info[1]}"
    old = fake_python(tmp_path / "python2", "2.7", sys.base_exec_prefix)
    other = fake_python(tmp_path / "pyenv-python3", this, "/root/.pyenv/versions/other")
    assert deps.find_python([str(tmp_path / "absent"), old, other, sys.executable]) == sys.executable
    with pytest.raises(deps.InstallError) as info:
        deps.find_python([str(tmp_path / "absent"), old, other])
    message = str(info.value)
    assert message.startswith(f"The program of the Python QGIS runs (Python {this} in {sys.base_exec_prefix})")
    assert "absent (not found)" in message and f"python2 (Python 2.7 in {sys.base_exec_prefix})" in message
    assert f"pyenv-python3 (Python {this} in /root/.pyenv/versions/other)" in message


# ------------------------------------------------------------------------------ streaming and cancel
def test_run_streaming_passes_every_line_and_the_status():
    lines = []
    status = deps.run_streaming([sys.executable, "-c", "import sys\nprint('one')\nprint('two', file=sys.stderr)\n"
                                 "sys.exit(3)"], dict(os.environ), lines.append)
    assert (lines, status) == (["one", "two"], 3)


def test_run_streaming_stops_the_process_on_cancel():
    lines = []
    script = "import time\nprint('started', flush=True)\ntime.sleep(60)\nprint('never')"
    start = time.monotonic()
    with pytest.raises(Cancelled):
        deps.run_streaming([sys.executable, "-c", script], dict(os.environ), lines.append,
                           is_canceled=lambda: lines == ["started"])
    assert time.monotonic() - start < 10 and lines == ["started"]
    assert threading.active_count() < 50


# ------------------------------------------------------------------------------ the plan
def report(*items):
    return {"install": [{"metadata": {"name": name, "version": version}} for name, version in items]}


def test_read_plan_installs_what_pip_reports():
    plan = deps.read_plan(report(("onnxruntime", "1.20.1"), ("coloredlogs", "15.0.1")), {"numpy": "1.24.2"})
    assert [p.requirement for p in plan] == ["onnxruntime==1.20.1", "coloredlogs==15.0.1"]


def test_read_plan_refuses_to_replace_a_package_of_qgis():
    with pytest.raises(deps.InstallError) as info:
        deps.read_plan(report(("onnxruntime", "1.20.1"), ("NumPy", "2.1.0")), {"numpy": "1.24.2"})
    assert "numpy" not in str(info.value).split(":")[0]
    assert "NumPy 1.24.2 (needed: 2.1.0)" in str(info.value)


def test_pip_environment_puts_the_folder_last(tmp_path):
    a, b, folder = tmp_path / "a", tmp_path / "b", tmp_path / "folder"
    a.mkdir(), b.mkdir()
    env = deps.pip_environment(folder, [str(a), "", str(tmp_path / "gone"), str(b), str(a), str(folder)],
                               base={"PATH": "/bin"})
    assert env["PYTHONPATH"] == os.pathsep.join([str(a), str(b), str(folder)])
    assert env["PATH"] == "/bin" and env["PIP_DISABLE_PIP_VERSION_CHECK"] == "1"


# ------------------------------------------------------------------------------ pip, for real, offline
@pytest.fixture
def wheelhouse(tmp_path, monkeypatch):
    """A local wheel folder as the only index pip may use (the user's pip.conf is ignored)."""
    house = tmp_path / "wheelhouse"
    house.mkdir()
    make_wheel(house, "birdseyefake_app", "1.0", ("birdseyefake_lib>=2",))
    make_wheel(house, "birdseyefake_lib", "2.1")
    make_wheel(house, "birdseyefake_lib", "1.0")
    make_wheel(house, "birdseyefake_greedy", "1.0", ("birdseyefake_host>=9",))
    make_wheel(house, "birdseyefake_host", "9.0")
    make_wheel(house, "birdseyefake_broken", "1.0", init="raise ImportError('needs a library this system lacks')\n")
    offline_pip(monkeypatch, house)
    return house


def fake_pin(name: str, version: str) -> deps.RuntimePackage:
    return deps.RuntimePackage(name, version, deps.Use(name))


def test_installer_installs_the_pins_and_their_dependencies(tmp_path, wheelhouse, clean_path):
    folder = tmp_path / "profile" / "python" / "birdseye-dependencies" / "python3.x"
    lines, fractions = [], []
    installer = deps.Installer(folder, python=sys.executable, log=lines.append, progress=fractions.append)
    plan = installer.install([fake_pin("birdseyefake_app", "1.0")])
    assert sorted(p.requirement for p in plan) == ["birdseyefake_app==1.0", "birdseyefake_lib==2.1"]
    assert (folder / "birdseyefake_lib" / "__init__.py").read_text() == "VERSION = '2.1'\n"
    assert any(line.startswith("Successfully installed") for line in lines)
    assert "imported birdseyefake_app" in lines
    assert fractions[0] == 0.0 and fractions[-1] == 1.0 and fractions == sorted(fractions)
    assert len(set(fractions)) >= 5, "progress moves while pip fetches each package"
    assert importlib.import_module("birdseyefake_app").VERSION == "1.0", "usable at once, without a restart"

    again = deps.Installer(folder, python=sys.executable).install([fake_pin("birdseyefake_app", "1.0")])
    assert again == [], "what the folder already holds is not installed twice"


def test_installer_refuses_to_shadow_a_host_package(tmp_path, wheelhouse, clean_path):
    host = tmp_path / "host-site"
    make_package(host, "birdseyefake_host", "1.0")
    (host / "birdseyefake_host-1.0.dist-info" / "INSTALLER").write_text("pip\n")
    folder = tmp_path / "folder"
    installer = deps.Installer(folder, python=sys.executable, search_path=[str(host), *sys.path])
    with pytest.raises(deps.InstallError, match=r"birdseyefake_host 1.0 \(needed: 9.0\)"):
        installer.install([fake_pin("birdseyefake_greedy", "1.0")])
    assert not (folder / "birdseyefake_greedy").exists()


def test_installer_reports_a_wheel_that_does_not_load(tmp_path, wheelhouse, clean_path):
    with pytest.raises(deps.InstallError) as info:
        deps.Installer(tmp_path / "folder", python=sys.executable).install([fake_pin("birdseyefake_broken", "1.0")])
    assert "do not load: birdseyefake_broken" in str(info.value)
    assert "needs a library this system lacks" in info.value.log


def test_installer_reports_pip_failures_with_the_log(tmp_path, wheelhouse, clean_path):
    with pytest.raises(deps.InstallError) as info:
        deps.Installer(tmp_path / "folder", python=sys.executable).install([fake_pin("birdseyefake_app", "7.0")])
    assert "pip stopped with exit status" in str(info.value)
    assert "birdseyefake_app==7.0" in info.value.log and "No matching distribution" in info.value.log
