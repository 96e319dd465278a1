"""birdseye_qgis/dependencies.py without QGIS: the ranges, what is missing, the interpreter, pip.

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
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from fake_wheels import make_wheel, offline_pip  # noqa: E402

from birdseye.birdseye_qgis import dependencies as deps
from birdseye.birdseye_qgis.core.errors import Cancelled, InputError

REPO_ROOT = Path(__file__).resolve().parents[2]
ALGORITHM_IDS = {p.stem for p in (REPO_ROOT / "processing" / "algorithms").glob("*.py")} - {"__init__", "base"}


# ------------------------------------------------------------------------------ the ranges and their uses
def test_requirements_and_uses_list_the_same_packages():
    """requirements.txt is the one list of packages; USES must say something about each, and nothing else."""
    listed = {deps.normalized(p.distribution) for p in deps.read_requirements()}
    assert listed == {deps.normalized(name) for name in deps.USES}


@pytest.mark.parametrize("minor", range(9, 15))
def test_requirements_give_every_python_from_3_9_to_3_14_a_tested_lower_bound(minor):
    """Ranges with a lower bound and no exact pin, for every Python QGIS runs; only pycolmap (no wheels
    for 3.9) is left out anywhere (the wheels themselves: docs/developers.md, "Dependencies")."""
    packages = deps.read_requirements(python=(3, minor))
    assert all(">=" in p.specifier and "==" not in p.specifier for p in packages)
    unavailable = {p.distribution for p in packages if not p.available}
    assert unavailable == ({"pycolmap"} if minor == 9 else set())
    onnxruntime = next(p for p in packages if p.distribution == "onnxruntime")
    assert onnxruntime.specifier == (">=1.19.2" if minor == 9 else ">=1.20.1")


def test_constraints_hold_the_development_venv_at_the_lower_bounds():
    """.venv (make test) runs the versions requirements.txt names as tested: each range's lower bound."""
    pins = dict(line.split("==") for line in (REPO_ROOT / "constraints.txt").read_text().splitlines()
                if "==" in line and not line.startswith("#"))
    for package in deps.read_requirements(python=(3, 11)):
        assert package.specifier == ">=" + pins[package.distribution], package.distribution


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
    # The scan finds what an algorithm imports and not everything: Detect reaches ONNX Runtime, not the structure
    # from motion of Refine frame poses nor the training process's torch.
    detect = reachable_packages("detect")
    assert "onnxruntime" in detect and "pycolmap" not in detect and "torch" not in detect


def write(path: Path, text: str) -> Path:
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


def test_read_requirements_keeps_ranges_and_the_line_for_this_python(tmp_path):
    path = write(tmp_path / "requirements.txt", """\
        # runtime
        onnxruntime >= 1.20.1 ; python_version >= "3.10"   # the detector
        onnxruntime>=1.19.2; python_version < '3.10'

        scipy>=1.13.1,<3,!=1.14.0
        pycolmap>=4.2.1; python_version >= "3.10" and python_version < "3.15"
        """)
    packages = deps.read_requirements(path, python=(3, 12))
    assert [(p.distribution, p.specifier, p.module, p.available) for p in packages] == [
        ("onnxruntime", ">=1.20.1", "onnxruntime", True), ("scipy", ">=1.13.1,<3,!=1.14.0", "scipy", True),
        ("pycolmap", ">=4.2.1", "pycolmap", True)]
    assert packages[1].requirement == "scipy>=1.13.1,<3,!=1.14.0"
    old = deps.read_requirements(path, python=(3, 9))
    assert [(p.distribution, p.specifier, p.available) for p in old] == [
        ("onnxruntime", ">=1.19.2", True), ("scipy", ">=1.13.1,<3,!=1.14.0", True), ("pycolmap", ">=4.2.1", False)]
    assert not deps.read_requirements(path, python=(3, 15))[2].available


@pytest.mark.parametrize("line", [
    "onnxruntime",                                   # no range: every release, untested ones included
    "onnxruntime>=1.20; sys_platform == 'linux'",    # only python_version conditions are read here
    "onnxruntime>=1.20; python_version >= '3.10' or python_version < '3'",
    "onnxruntime[cuda]>=1.20",
    "onnxruntime~=1.20",
])
def test_read_requirements_names_the_bad_row(tmp_path, line):
    path = write(tmp_path / "requirements.txt", f"# ranges\nscipy>=1.13.1\n{line}\n")
    with pytest.raises(InputError) as info:
        deps.read_requirements(path)
    assert str(info.value).startswith(f"{path}, row 3: ") and "is not a requirement 'name>=version'" in str(info.value)


def test_a_package_uses_does_not_know_is_still_installed(tmp_path):
    path = write(tmp_path / "requirements.txt", "Some.New_Package>=2.0\n")
    [package] = deps.read_requirements(path)
    assert (package.requirement, package.module, package.use.always) == ("Some.New_Package>=2.0",
                                                                          "some_new_package", ())


def test_versions_compare_as_pip_compares_them():
    ordered = ["1.9", "1.13.0rc1", "1.13", "1.13.1.dev0", "1.13.1", "1.13.1.post1", "2.0.0", "10.0"]
    keys = [deps.version_key(v) for v in ordered]
    assert keys == sorted(keys) and len(set(keys)) == len(keys)
    assert deps.version_key("1.13") == deps.version_key("1.13.0") == deps.version_key("1.13.0+dfsg")
    package = deps.RuntimePackage("scipy", ">=1.13.1,<2,!=1.14.0", deps.Use("scipy"))
    assert [package.allows(v) for v in ("1.13.0", "1.13.1", "1.14.0", "1.15.2", "2.0", "unknown")] == [
        False, True, False, True, False, True]


def test_unreadable_requirements_name_the_file(tmp_path):
    with pytest.raises(InputError, match="requirements.txt: cannot be read"):
        deps.read_requirements(tmp_path / "requirements.txt")


# ------------------------------------------------------------------------------ what is missing
def make_package(site: Path, name: str, version: str, requires: tuple[str, ...] = ()) -> None:
    (site / name).mkdir(parents=True)
    (site / name / "__init__.py").write_text(f"VERSION = '{version}'\n")
    info = site / f"{name}-{version}.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {name}\nVersion: {version}\n"
                                   + "".join(f"Requires-Dist: {r}\n" for r in requires))


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
    package = deps.RuntimePackage("birdseyefake-a", ">=1.0", deps.Use("birdseyefake_a"))
    missing = deps.package_status(package, folder)
    assert (missing.installed_version, missing.in_folder, missing.needs_install) == (None, False, True)

    make_package(folder, "birdseyefake_a", "1.2")
    deps.activate(folder)
    assert sys.path[-1] == str(folder), "the folder goes last: QGIS's own packages win"
    found = deps.package_status(package, folder)
    assert (found.installed_version, found.in_folder, found.needs_install) == ("1.2", True, False)
    assert not deps.package_status(deps.RuntimePackage("birdseyefake-a", ">=1.1,<2", deps.Use("birdseyefake_a")),
                                   folder).needs_install, "inside the range: not installed again"
    raised = deps.RuntimePackage("birdseyefake-a", ">=2.0", deps.Use("birdseyefake_a"))
    assert deps.package_status(raised, folder).needs_install, "installed by BirdsEye below a raised bound: update"


def test_a_version_qgis_ships_is_used_as_it_is(tmp_path, clean_path):
    """QGIS's own copy, inside the range or not, is not 'missing' (replacing it could break QGIS)."""
    host = tmp_path / "host-site"
    make_package(host, "birdseyefake_b", "0.9")
    sys.path.insert(0, str(host))
    importlib.invalidate_caches()
    status = deps.package_status(deps.RuntimePackage("birdseyefake-b", ">=1.0", deps.Use("birdseyefake_b")),
                                 tmp_path / "folder")
    assert (status.installed_version, status.in_folder, status.needs_install, status.in_range) == (
        "0.9", False, False, False)
    inside = deps.package_status(deps.RuntimePackage("birdseyefake-b", ">=0.8", deps.Use("birdseyefake_b")),
                                 tmp_path / "folder")
    assert (inside.needs_install, inside.in_range) == (False, True)


def test_a_package_with_no_release_for_this_python_is_not_offered(tmp_path):
    package = deps.RuntimePackage("birdseyefake-c", ">=4.2", deps.Use("birdseyefake_c", always=("refineposes",)),
                                  available=False)
    status = deps.package_status(package, tmp_path)
    assert (status.installed_version, status.needs_install) == (None, False)
    assert deps.missing_for("refineposes", [package]) == [package], "the algorithm still says it lacks it"


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
    assert deps.package_for_module("scipy.spatial", packages).distribution == "scipy"
    assert deps.package_for_module("numpy", packages) is None
    assert deps.package_for_module("sklearn", packages) is None, "clustering does without scikit-learn"


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
    # flush: a child's stdout into a pipe is block-buffered, and 'one' would arrive after 'two'
    # (unless PYTHONUNBUFFERED is set, as it is on some machines).
    status = deps.run_streaming([sys.executable, "-c", "import sys\nprint('one', flush=True)\n"
                                 "print('two', file=sys.stderr)\nsys.exit(3)"], dict(os.environ), lines.append)
    assert (lines, status) == (["one", "two"], 3)


def test_run_streaming_stops_the_process_on_cancel(tmp_path):
    """Cancelled, the child is stopped, not waited for: when run_streaming returns, the child is gone and
    never reached the marker it writes after its 60 s sleep (waiting for it would have let it write it)."""
    lines = []
    marker = tmp_path / "slept_to_the_end"
    script = ("import os, sys, time\nprint('started', os.getpid(), flush=True)\ntime.sleep(60)\n"
              "open(sys.argv[1], 'w').close()\nprint('never')")
    with pytest.raises(Cancelled):
        deps.run_streaming([sys.executable, "-c", script, str(marker)], dict(os.environ), lines.append,
                           is_canceled=lambda: bool(lines))
    assert len(lines) == 1 and lines[0].startswith("started ")
    pid = int(lines[0].split()[1])
    assert not Path(f"/proc/{pid}").exists(), f"the child {pid} still runs (or was never reaped)"
    assert not marker.exists(), "run_streaming waited for the child to finish instead of stopping it"
    assert threading.active_count() < 50


# ------------------------------------------------------------------------------ the plan
def report(*items, environment=None):
    """A pip installation report: items (name, version, requested, requires_dist)."""
    return {"environment": environment or {"python_version": "3.11", "sys_platform": "linux"},
            "install": [{"metadata": {"name": name, "version": version, "requires_dist": list(requires)},
                         "requested": requested} for name, version, requested, requires in items]}


def test_read_plan_installs_what_our_packages_need():
    plan = deps.read_plan(report(("onnxruntime", "1.20.1", True, ["coloredlogs", "numpy>=1.21.6"]),
                                 ("coloredlogs", "15.0.1", False, ["humanfriendly>=9.1"]),
                                 ("humanfriendly", "10.0", False, [])))
    assert [p.requirement for p in plan] == ["onnxruntime==1.20.1", "coloredlogs==15.0.1", "humanfriendly==10.0"]


def test_read_plan_leaves_out_what_only_qgis_packages_ask_for():
    """Debian unstable: onnxruntime needs sympy, which Debian ships (1.14, wanting mpmath < 1.4) beside
    mpmath 1.4.1; pip plans an older mpmath for sympy's sake. sympy is installed, so the walk ends there."""
    plan = deps.read_plan(report(("onnxruntime", "1.20.1", True, ["sympy", "numpy>=1.21.6"]),
                                 ("mpmath", "1.3.0", False, [])))
    assert [p.requirement for p in plan] == ["onnxruntime==1.20.1"]


def test_read_plan_follows_only_dependencies_whose_markers_hold():
    plan = deps.read_plan(report(
        ("matplotlib", "3.9.2", True, ['importlib-resources>=3.2.0; python_version < "3.10"', "pillow>=8",
                                       'pytest; extra == "dev"']),
        ("importlib-resources", "6.4.0", False, []), ("pillow", "11.0.0", False, []), ("pytest", "8.3.3", False, [])))
    assert [p.name for p in plan] == ["matplotlib", "pillow"]


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
    return deps.RuntimePackage(name, f"=={version}", deps.Use(name))


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
    lines = []
    installer = deps.Installer(folder, python=sys.executable, search_path=[str(host), *sys.path], log=lines.append)
    with pytest.raises(deps.InstallError, match=r"birdseyefake_host 1.0 \(needed: 9.0\); no release") as info:
        installer.install([fake_pin("birdseyefake_greedy", "1.0")])
    assert "Holding QGIS's birdseyefake-host 1.0: resolving again" in lines
    assert "ResolutionImpossible" in info.value.log or "conflict" in info.value.log
    assert not (folder / "birdseyefake_greedy").exists()


def test_installer_picks_a_release_that_keeps_the_host_package(tmp_path, wheelhouse, clean_path):
    """The newest release wants a newer version of a package QGIS ships (OpenCV 4.12 wants numpy 2 beside
    QGIS's numpy 1.x); an older one in the range works with QGIS's: that one is installed."""
    make_wheel(wheelhouse, "birdseyefake_picky", "2.0", ("birdseyefake_host>=9",))
    make_wheel(wheelhouse, "birdseyefake_picky", "1.5", ("birdseyefake_host>=1",))
    host = tmp_path / "host-site"
    make_package(host, "birdseyefake_host", "1.0")
    folder = tmp_path / "folder"
    installer = deps.Installer(folder, python=sys.executable, search_path=[str(host), *sys.path])
    plan = installer.install([deps.RuntimePackage("birdseyefake_picky", ">=1.0", deps.Use("birdseyefake_picky"))])
    assert [p.requirement for p in plan] == ["birdseyefake_picky==1.5"]
    assert not (folder / "birdseyefake_host").exists()


def test_installer_ignores_a_conflict_among_host_packages_we_do_not_need(tmp_path, wheelhouse, clean_path):
    """The Debian-unstable case with fake wheels: our app needs hostlib (installed, wanting dep < 1.4)
    and the host has dep 1.4.1; pip plans dep 1.3.0 for hostlib's sake. We neither need nor install it."""
    make_wheel(wheelhouse, "birdseyefake_app2", "1.0", ("birdseyefake_hostlib",))
    make_wheel(wheelhouse, "birdseyefake_dep", "1.3.0")
    host = tmp_path / "host-site"
    make_package(host, "birdseyefake_hostlib", "1.14", ("birdseyefake_dep<1.4",))
    make_package(host, "birdseyefake_dep", "1.4.1")
    folder = tmp_path / "folder"
    lines = []
    installer = deps.Installer(folder, python=sys.executable, search_path=[str(host), *sys.path], log=lines.append)
    plan = installer.install([deps.RuntimePackage("birdseyefake_app2", ">=1.0", deps.Use("birdseyefake_app2"))])
    assert [p.requirement for p in plan] == ["birdseyefake_app2==1.0"]
    assert any("birdseyefake_dep-1.3.0" in line or "birdseyefake_dep 1.3.0" in line for line in lines), \
        "pip did plan the downgrade: the test covers the case"
    assert (folder / "birdseyefake_app2").is_dir() and not (folder / "birdseyefake_dep").exists()


def test_installer_installs_only_what_is_missing(tmp_path, wheelhouse, clean_path):
    """A dependency already there in range (here: in the folder) is neither planned nor replaced."""
    folder = tmp_path / "folder"
    deps.Installer(folder, python=sys.executable).install([fake_pin("birdseyefake_lib", "2.1")])
    plan = deps.Installer(folder, python=sys.executable).install(
        [deps.RuntimePackage("birdseyefake_app", ">=1.0", deps.Use("birdseyefake_app"))])
    assert [p.requirement for p in plan] == ["birdseyefake_app==1.0"]


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
