"""The Python packages BirdsEye needs at run time: which are missing, and installing them with pip.

QGIS runs its own Python (on Windows and macOS a copy shipped inside QGIS) with numpy, GDAL and often
scipy and matplotlib, but without onnxruntime, OpenCV and the rest of ``requirements.txt``. This module
knows those packages — the version ranges come from the plugin's ``requirements.txt``, shipped in the
zip (lower bounds the tests ran with, environment markers for a package that has no release for some
Python); :data:`USES` says which algorithms need each — and installs the missing ones with QGIS's own
interpreter::

    python -m pip install --target <profile>/python/birdseye-dependencies/python3.X --no-deps name==version …

into a folder of the QGIS profile (it survives plugin updates, which replace the plugin folder). The
plugin adds that folder at the *end* of ``sys.path`` when it starts (:func:`activate`), so a package
QGIS already has is never shadowed. The rules:

* only what is missing is installed: a package importable at a version inside its range stays, and
  one QGIS itself ships is used as it is even outside the range (replacing it could break QGIS);
* pip first resolves the missing requirements against what QGIS's Python already has
  (``--dry-run --report``), so the versions suit that Python and its numpy (1.x or 2.x);
* of pip's plan only BirdsEye's own closure counts (:func:`read_plan`): a conflict among packages QGIS
  ships that no BirdsEye package needs is not ours to fix;
* when that closure would replace one of QGIS's packages (numpy above all: GDAL's bindings are built
  against it), pip resolves again with QGIS's version held, which picks older releases of ours that
  work with it; only when none exists does the installer refuse, naming the package.

No QGIS and no Qt here: the dialog (``gui/dependencies.py``) and the Processing algorithms
(``processing/algorithms/base.py``) use it, and it is tested without QGIS.
"""
from __future__ import annotations

import importlib
import importlib.metadata
import importlib.util
import json
import operator
import os
import queue
import re
import site
import subprocess
import sys
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path, PurePosixPath, PureWindowsPath
from typing import Callable, Iterable, Sequence

from .core.errors import Cancelled, InputError
from .core.train.protocol import relay_lines

#: The plugin folder; ``requirements.txt`` sits at its top, in the repository and in the zip.
PLUGIN_ROOT = Path(__file__).resolve().parents[1]
REQUIREMENTS_FILE = PLUGIN_ROOT / "requirements.txt"
#: pip's ``--dry-run --report`` (the resolution against the packages QGIS already has) needs pip 22.2.
MIN_PIP = (22, 2)
MENU_PATH = "BirdsEye › Install dependencies…"


@dataclass(frozen=True)
class Use:
    """What imports a distribution and which algorithms (ids without ``birdseye:``) need it:
    ``always`` on every run, ``sometimes`` only for some inputs or options (they are not refused
    upfront; the run says so when it gets there)."""

    module: str
    always: tuple[str, ...] = ()
    sometimes: tuple[str, ...] = ()


#: Every distribution of ``requirements.txt`` (tests check both lists agree). Found by recording, while
#: the QGIS test suites ran each algorithm, which of these packages its run imported, and reading the
#: code behind each import: ``always`` when the algorithm's main path imports it, ``sometimes`` when only
#: an option does (a DEM, a calibration YAML file, an HTML report or plot, a COLMAP model, …).
USES: dict[str, Use] = {
    "onnxruntime": Use("onnxruntime", always=("detect", "screencheckpoints"), sometimes=("sweepoperatingpoints",)),
    "opencv-python-headless": Use("cv2", always=("detect", "screencheckpoints", "simulatecampaign"),
                                  sometimes=("sweepoperatingpoints", "writelabels")),
    "scipy": Use("scipy", always=("clusterdetections", "comparedetectors", "evaluatedetections", "importgeotags",
                                  "montecarlobound", "planflight", "screencheckpoints", "sensorbound",
                                  "simulatecampaign", "sweepoperatingpoints", "writelabels"),
                 sometimes=("detect", "importcameras", "importdjiimages", "importflightlog")),
    "fast-tsp": Use("fast_tsp", always=("planflight",)),
    "PyYAML": Use("yaml", always=("simulatecampaign",),
                  sometimes=("importdjiimages", "importflightlog", "montecarlobound", "planflight", "sensorbound",
                             "terrainslope")),
    "matplotlib": Use("matplotlib", always=("montecarlobound", "sensorbound", "terrainslope"),
                      sometimes=("evaluatedetections", "screencheckpoints", "sweepoperatingpoints")),
    "pycolmap": Use("pycolmap", always=("refineposes",), sometimes=("importcameras",)),
    "pyodm": Use("pyodm", always=("processodm",)),
}


@dataclass(frozen=True)
class RuntimePackage:
    """A package of ``requirements.txt`` with what the plugin knows about it: the versions it accepts
    (``specifier``, such as ``>=1.13.1``) and whether requirements.txt offers it to the running Python
    at all (``available``: False where its environment markers leave it out, for want of wheels)."""

    distribution: str
    specifier: str
    use: Use
    available: bool = True

    @property
    def requirement(self) -> str:
        return f"{self.distribution}{self.specifier}"

    @property
    def module(self) -> str:
        return self.use.module

    def allows(self, version: str) -> bool:
        """Whether ``version`` is inside the range (a version that cannot be read is taken as inside:
        there is no telling, and reinstalling would not help)."""
        key = version_key(version)
        return key is None or all(_COMPARE[op](key, version_key(bound)) for op, bound in _clauses(self.specifier))


@dataclass(frozen=True)
class PackageStatus:
    """Where a package stands in the running Python.

    ``installed_version`` is None when the module cannot be found. ``in_folder`` says it was found in
    BirdsEye's package folder (installed by this installer), else QGIS's Python has it itself.
    """

    package: RuntimePackage
    installed_version: str | None
    in_folder: bool

    @property
    def needs_install(self) -> bool:
        """Missing, or installed by BirdsEye at a version outside the range (a plugin update moved it).
        A version QGIS itself ships is used as it is: replacing it could break QGIS. A package with no
        release for this Python cannot be installed."""
        if not self.package.available:
            return False
        if self.installed_version is None:
            return True
        return self.in_folder and not self.package.allows(self.installed_version)

    @property
    def in_range(self) -> bool:
        return self.installed_version is not None and self.package.allows(self.installed_version)


def normalized(name: str) -> str:
    """A distribution name as pip compares them (PEP 503)."""
    return re.sub(r"[-_.]+", "-", name).lower()


# requirements.txt is read here without `packaging` (QGIS's Python may lack it), so its lines keep to
# a subset of PEP 508 that this module fully understands: a name, comma-separated version clauses, and
# optionally `; python_version <op> "X.Y"` conditions joined by `and`.
_NAME = re.compile(r"^([A-Za-z0-9][A-Za-z0-9._-]*)\s*(.*)$")
_CLAUSE = re.compile(r"^(==|!=|>=|<=|<|>)\s*([0-9][A-Za-z0-9.+!_-]*)$")
_PYTHON_CONDITION = re.compile(r"""^python_version\s*(==|!=|>=|<=|<|>)\s*["']([0-9.]+)["']$""")
_COMPARE = {"==": operator.eq, "!=": operator.ne, ">=": operator.ge, "<=": operator.le, "<": operator.lt,
            ">": operator.gt}
_VERSION = re.compile(r"^v?(\d+(?:\.\d+)*)(?:[-_.]?(a|b|c|rc|alpha|beta|pre|preview|dev|post|rev|r)[-_.]?(\d*))?",
                      re.IGNORECASE)


def version_key(version: str) -> tuple | None:
    """A PEP 440 version as a comparable key: the release numbers (trailing zeros dropped, 1.13 = 1.13.0),
    then pre- and dev-releases before the release and post-releases after it; local labels (Debian's
    ``+dfsg``) ignored. None when ``version`` is not one."""
    match = _VERSION.match(version.strip())
    if match is None:
        return None
    release = tuple(int(part) for part in match.group(1).split("."))
    while len(release) > 1 and release[-1] == 0:
        release = release[:-1]
    tag = (match.group(2) or "").lower()
    phase = 1 if not tag else 2 if tag in ("post", "rev", "r") else 0
    return release, phase, int(match.group(3) or 0)


def _clauses(specifier: str) -> list[tuple[str, str]]:
    return [_CLAUSE.match(clause.strip()).groups() for clause in specifier.split(",")]


def _python_holds(marker: str, python: Sequence[int]) -> bool:
    here = version_key(f"{python[0]}.{python[1]}")
    return all(_COMPARE[op](here, version_key(bound))
               for op, bound in (_PYTHON_CONDITION.match(part.strip()).groups() for part in marker.split(" and ")))


def _parse_requirement(text: str) -> tuple[str, str, str] | None:
    """(name, specifier, marker) of a requirements.txt line in the subset this module reads, else None."""
    requirement, _, marker = text.partition(";")
    match = _NAME.match(requirement.strip())
    if match is None:
        return None
    name, specifier = match.group(1), re.sub(r"\s+", "", match.group(2))
    if not specifier or not all(_CLAUSE.match(c) for c in specifier.split(",")):
        return None
    marker = marker.strip()
    if marker and not all(_PYTHON_CONDITION.match(part.strip()) for part in marker.split(" and ")):
        return None
    return name, specifier, marker


def read_requirements(path: Path = REQUIREMENTS_FILE, python: Sequence[int] = sys.version_info) -> list[RuntimePackage]:
    """The packages of ``requirements.txt`` for Python ``python``: lines ``name<clauses>[; python_version
    conditions]`` and ``#`` comments; per package the first line whose conditions hold, or, when none does,
    the package marked not available."""
    path = Path(path)
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except OSError as exc:
        raise InputError(f"cannot be read ({exc.strerror})", source=str(path)) from exc
    uses = {normalized(name): (name, use) for name, use in USES.items()}
    chosen: dict[str, RuntimePackage] = {}
    # A package USES does not know yet (tests/unit/test_dependencies.py fails on it) is still installed;
    # its module is guessed from its name and no algorithm is refused for it.
    for row, line in enumerate(lines, start=1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        parsed = _parse_requirement(text)
        if parsed is None:
            raise InputError(f"'{text}' is not a requirement 'name>=version' with optional "
                             "'; python_version >= \"3.X\"' conditions", source=str(path), row=row)
        name, specifier, marker = parsed
        known_name, use = uses.get(normalized(name), (name, Use(normalized(name).replace("-", "_"))))
        holds = not marker or _python_holds(marker, python)
        previous = chosen.get(normalized(name))
        if previous is None or (holds and not previous.available):
            chosen[normalized(name)] = RuntimePackage(known_name, specifier, use, holds)
    return list(chosen.values())


def package_folder(profile_dir: Path | str, version: Sequence[int] = sys.version_info) -> Path:
    """BirdsEye's package folder in a QGIS profile; one per Python version, since compiled wheels
    only load in the Python they were built for (a QGIS upgrade to a new Python starts afresh)."""
    return Path(profile_dir) / "python" / "birdseye-dependencies" / f"python{version[0]}.{version[1]}"


def activate(folder: Path | str) -> None:
    """Make the packages in ``folder`` importable: append it to ``sys.path`` (``.pth`` files
    included, as in any site folder) and forget what the import system cached about it, so packages
    installed a moment ago are found without restarting QGIS."""
    folder = str(folder)
    if folder not in sys.path:
        site.addsitedir(folder)
    sys.path_importer_cache.pop(folder, None)
    importlib.invalidate_caches()


def _in_folder(path: str | None, folder: Path | None) -> bool:
    if not path or folder is None:
        return False
    try:
        Path(path).resolve().relative_to(Path(folder).resolve())
    except ValueError:
        return False
    return True


def package_status(package: RuntimePackage, folder: Path | None = None) -> PackageStatus:
    """Whether ``package`` is importable, without importing it (``find_spec``), and which version."""
    try:
        spec = importlib.util.find_spec(package.module)
    except (ImportError, ValueError):
        spec = None
    if spec is None:
        return PackageStatus(package, None, False)
    location = spec.origin if spec.has_location else next(iter(spec.submodule_search_locations or []), None)
    in_folder = _in_folder(location, folder)
    search = [str(folder)] if in_folder else [p for p in sys.path if not _in_folder(p, folder)]
    found = next(iter(importlib.metadata.distributions(name=package.distribution, path=search)), None)
    return PackageStatus(package, found.version if found is not None else "unknown", in_folder)


def statuses(packages: Iterable[RuntimePackage] | None = None, folder: Path | None = None) -> list[PackageStatus]:
    return [package_status(p, folder) for p in (read_requirements() if packages is None else packages)]


def missing_for(algorithm_id: str, packages: Iterable[RuntimePackage] | None = None) -> list[RuntimePackage]:
    """The packages ``algorithm_id`` needs on every run that cannot be imported (those with no release
    for this Python included: the message says so)."""
    needed = [p for p in (read_requirements() if packages is None else packages) if algorithm_id in p.use.always]
    return [p for p in needed if package_status(p).installed_version is None]


def package_for_module(module_name: str, packages: Iterable[RuntimePackage] | None = None) -> RuntimePackage | None:
    """The runtime package that provides ``module_name`` (``cv2.dnn`` → opencv-python-headless)."""
    top = module_name.split(".")[0]
    return next((p for p in (read_requirements() if packages is None else packages) if p.module == top), None)


# ---------------------------------------------------------------------------------------- the interpreter
class InstallError(RuntimeError):
    """The installation failed; ``log`` holds pip's output for the user."""

    def __init__(self, message: str, log: str = ""):
        super().__init__(message)
        self.log = log


def python_candidates(executable: str | None = sys.executable,
                      prefixes: Sequence[str] = (sys.exec_prefix, sys.base_exec_prefix, sys.prefix),
                      platform: str = sys.platform, version: Sequence[int] = sys.version_info) -> list[str]:
    """Where the interpreter of the running Python may be, most likely first.

    ``sys.executable`` is that interpreter in Debian's and Ubuntu's QGIS, but in QGIS for Windows it
    is ``qgis-bin.exe`` and on macOS the QGIS app itself (qgis/QGIS#45646, #66672), and running it
    with ``-m pip`` would start another QGIS. So, as Deepness, qpip and QGIS's own proposed fix do,
    look where QGIS keeps its Python: ``<prefix>\\python.exe`` on Windows (OSGeo4W, the standalone
    installer and conda keep it in ``sys.prefix``, ``apps\\Python3X``), ``bin\\python3.exe`` beside
    ``qgis-bin.exe`` (OSGeo4W's launcher); ``<prefix>/bin/python3.X`` elsewhere and
    ``QGIS.app/Contents/MacOS/bin/python3`` in the macOS bundle. :func:`find_python` then keeps the
    first that is this very Python. The ``python`` on ``PATH`` is never asked for: it may be another
    installation, whose packages QGIS does not see and whose wheels its Python may not load.
    """
    windows = platform == "win32"
    pure = PureWindowsPath if windows else PurePosixPath
    versioned = f"python{version[0]}.{version[1]}"
    found: list[str] = []
    exe = pure(executable) if executable else None
    if exe is not None and exe.name.lower().startswith("python"):
        found.append(str(exe))
    for prefix in prefixes:
        if not prefix:
            continue
        if windows:
            found.append(str(pure(prefix) / "python.exe"))
        else:
            found += [str(pure(prefix) / "bin" / versioned), str(pure(prefix) / "bin" / "python3")]
    if exe is not None and windows:
        found += [str(exe.parent / "python3.exe"), str(exe.parent / "python.exe")]
    elif exe is not None and platform == "darwin":
        found += [str(exe.parent / "bin" / versioned), str(exe.parent / "bin" / "python3")]
    return list(dict.fromkeys(found))


def _hidden_window() -> dict:
    """On Windows, keep pip from flashing a console window over QGIS."""
    return {"creationflags": getattr(subprocess, "CREATE_NO_WINDOW", 0)} if sys.platform == "win32" else {}


def _same_path(a: str, b: str) -> bool:
    return os.path.normcase(os.path.realpath(a)) == os.path.normcase(os.path.realpath(b))


def find_python(candidates: Sequence[str] | None = None, version: Sequence[int] = sys.version_info,
                base_prefix: str = sys.base_exec_prefix) -> str:
    """The first candidate interpreter that runs and is *this* Python: the same major.minor version and
    the same installation (``sys.base_exec_prefix``). The version alone is not enough: Debian's QGIS
    finds its ``sys.executable`` on ``PATH``, where a pyenv or conda ``python3`` of the same version
    may come first, and its packages are not QGIS's."""
    candidates = python_candidates() if candidates is None else candidates
    wanted = f"{version[0]}.{version[1]}"
    tried = []
    for candidate in candidates:
        if not Path(candidate).is_file():
            tried.append(f"{candidate} (not found)")
            continue
        try:
            result = subprocess.run(
                [candidate, "-c", "import sys; print('%d.%d' % sys.version_info[:2]); print(sys.base_exec_prefix)"],
                capture_output=True, text=True, timeout=60, check=False, **_hidden_window())
        except (OSError, subprocess.TimeoutExpired) as exc:
            tried.append(f"{candidate} ({exc})")
            continue
        reported = result.stdout.splitlines() if result.returncode == 0 else []
        if len(reported) == 2 and reported[0] == wanted and _same_path(reported[1], base_prefix):
            return candidate
        tried.append(f"{candidate} (" + (f"Python {reported[0]} in {reported[1]}" if len(reported) == 2
                                         else "did not start") + ")")
    raise InstallError(f"The program of the Python QGIS runs (Python {wanted} in {base_prefix}) was not found; "
                       "looked at:\n  " + "\n  ".join(tried))


def pip_environment(folder: Path, search_path: Sequence[str] = tuple(sys.path),
                    base: dict | None = None) -> dict[str, str]:
    """The environment pip runs in: QGIS's own search path, BirdsEye's folder last (as at run time),
    so pip resolves against exactly the packages QGIS imports."""
    env = dict(os.environ if base is None else base)
    entries = [p for p in search_path if p and Path(p).is_dir() and not _in_folder(p, folder)]
    env["PYTHONPATH"] = os.pathsep.join(list(dict.fromkeys(entries)) + [str(folder)])
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    env["PYTHONIOENCODING"] = "utf-8"
    return env


def run_streaming(command: Sequence[str], env: dict[str, str], log: Callable[[str], None],
                  is_canceled: Callable[[], bool] = lambda: False, poll_s: float = 0.1, cwd: Path | None = None) -> int:
    """Run ``command`` (in ``cwd``), passing each output line (stdout and stderr) to ``log`` as it
    comes; stop it and raise :class:`Cancelled` as soon as ``is_canceled()`` says so. Returns the exit
    status."""
    process = subprocess.Popen(list(command), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                               stdin=subprocess.DEVNULL, text=True, encoding="utf-8", errors="replace",
                               bufsize=1, cwd=cwd, **_hidden_window())
    lines: queue.Queue = queue.Queue()

    def read() -> None:
        for line in process.stdout:
            lines.put(line.rstrip("\r\n"))
        lines.put(None)

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        if relay_lines(lines, log, is_canceled, poll_s):
            raise Cancelled()
        return process.wait()
    finally:
        if process.poll() is None:
            process.terminate()
            try:
                process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        reader.join(timeout=5)
        process.stdout.close()


def _pip_version(python: str, env: dict[str, str], cwd: Path) -> tuple[int, ...]:
    result = subprocess.run([python, "-m", "pip", "--version"], capture_output=True, text=True, env=env,
                            cwd=cwd, timeout=120, check=False, **_hidden_window())
    match = re.match(r"pip (\d+)\.(\d+)", result.stdout)
    if result.returncode != 0 or match is None:
        raise InstallError(f"pip is not available in the Python QGIS runs ({python}). Install it first "
                           "(Debian/Ubuntu: sudo apt install python3-pip; elsewhere: "
                           f"{python} -m ensurepip), then try again.", result.stdout + result.stderr)
    return tuple(int(g) for g in match.groups())


@dataclass(frozen=True)
class Planned:
    """A distribution pip will put in BirdsEye's folder (one of ours or one they depend on)."""

    name: str
    version: str

    @property
    def requirement(self) -> str:
        return f"{self.name}=={self.version}"


def host_distributions(folder: Path, search_path: Sequence[str] = tuple(sys.path)) -> dict[str, str]:
    """{normalized name: version} of what QGIS's Python has outside BirdsEye's folder."""
    path = [p for p in search_path if p and not _in_folder(p, folder)]
    return {normalized(d.metadata["Name"] or ""): d.version for d in importlib.metadata.distributions(path=path)}


def _requirement_class():
    """PEP 508 parsing for the dependencies pip reports: `packaging` where QGIS's Python has it, else
    the copy inside pip (which the installer needs anyway)."""
    try:
        from packaging.requirements import Requirement
    except ImportError:
        from pip._vendor.packaging.requirements import Requirement
    return Requirement


def read_plan(report: dict) -> list[Planned]:
    """What pip's installation report plans for BirdsEye: the requested packages and, through the
    packages the plan installs, what they depend on (in the running Python's environment, no extras).

    A dependency that is already installed ends the walk there. So a downgrade pip plans only because
    of packages QGIS ships — Debian's sympy 1.14 wants mpmath < 1.4 and Debian has mpmath 1.4.1 — is
    not BirdsEye's to make: nothing we install needs it, and the folder, last on ``sys.path``, could not
    change what sympy loads anyway."""
    requirement = _requirement_class()
    environment = report.get("environment", {})
    items = {normalized(item["metadata"]["name"]): item for item in report.get("install", [])}
    todo = [name for name, item in items.items() if item.get("requested")]
    needed: set[str] = set()
    while todo:
        name = todo.pop()
        if name in needed or name not in items:
            continue
        needed.add(name)
        for line in items[name]["metadata"].get("requires_dist", []):
            dependency = requirement(line)
            if dependency.marker is None or dependency.marker.evaluate({**environment, "extra": ""}):
                todo.append(normalized(dependency.name))
    return [Planned(item["metadata"]["name"], item["metadata"]["version"]) for name, item in items.items()
            if name in needed]


def clash_message(clashes: dict[str, tuple[str, str]]) -> str:
    """``clashes``: {name: (QGIS's version, the version BirdsEye's packages need)}."""
    named = ", ".join(f"{name} {have} (needed: {want})" for name, (have, want) in clashes.items())
    return (f"Installing would replace packages of the Python QGIS runs: {named}; no release of BirdsEye's "
            "packages works with QGIS's version. BirdsEye does not change QGIS's own packages; update QGIS, "
            "or install the versions BirdsEye needs with your Python's package manager.")


class Installer:
    """Installs runtime packages into BirdsEye's folder with the interpreter QGIS runs.

    ``log(line)`` receives every line pip writes; ``progress(fraction)`` goes from 0 to 1;
    ``is_canceled()`` is polled while pip runs (cancelling stops pip and raises :class:`Cancelled`;
    pip writes into the folder only at the very end, so a cancelled download leaves it as it was).
    """

    def __init__(self, folder: Path, python: str | None = None, search_path: Sequence[str] | None = None,
                 log: Callable[[str], None] = lambda line: None,
                 progress: Callable[[float], None] = lambda fraction: None,
                 is_canceled: Callable[[], bool] = lambda: False, pip_options: Sequence[str] = ()):
        self.folder = Path(folder)
        self.python = python
        # Extra pip options for both resolution and installation (a package group's index, e.g. PyTorch's).
        self.pip_options = tuple(pip_options)
        self.search_path = tuple(sys.path) if search_path is None else tuple(search_path)
        self.log, self.progress, self.is_canceled = log, progress, is_canceled
        self.output: list[str] = []
        # Every command runs in an empty scratch folder: `python -m` puts the working folder first on
        # sys.path, where whatever QGIS was started from could shadow pip's own modules.
        self.scratch: Path | None = None

    def _log(self, line: str) -> None:
        self.output.append(line)
        self.log(line)

    def _pip(self, arguments: Sequence[str], env: dict[str, str], on_line=None) -> None:
        command = [self.python, "-m", "pip", *arguments]
        self._log("$ " + " ".join(command))

        def line(text: str) -> None:
            self._log(text)
            if on_line is not None:
                on_line(text)

        status = run_streaming(command, env, line, self.is_canceled, cwd=self.scratch)
        if status != 0:
            raise InstallError(f"pip stopped with exit status {status}.", "\n".join(self.output))

    def install(self, packages: Sequence[RuntimePackage]) -> list[Planned]:
        """Install ``packages`` (those with a release for this Python) with what they depend on, at
        versions that keep QGIS's own packages; returns what was installed."""
        packages = [p for p in packages if p.available]
        self.progress(0.0)
        if self.python is None:
            self.python = find_python()
        self._log(f"Python: {self.python}")
        self._log(f"Folder: {self.folder}")
        self.folder.mkdir(parents=True, exist_ok=True)
        env = pip_environment(self.folder, self.search_path)
        with tempfile.TemporaryDirectory(prefix="birdseye-pip-") as scratch:
            self.scratch = Path(scratch)
            pip = _pip_version(self.python, env, self.scratch)
            if pip < MIN_PIP:
                raise InstallError(f"pip {'.'.join(map(str, pip))} in {self.python} is too old; BirdsEye needs "
                                   f"pip {'.'.join(map(str, MIN_PIP))} or newer ({self.python} -m pip install "
                                   "--upgrade pip).")
            plan = self._resolve(packages, env)
            self.progress(0.1)
            if plan:
                self._install_plan(plan, env)
            self.progress(0.95)
            self._verify(packages, env)
        activate(self.folder)
        self.progress(1.0)
        return plan

    def _resolve(self, packages: Sequence[RuntimePackage], env: dict[str, str]) -> list[Planned]:
        """pip's plan for ``packages`` (:func:`read_plan`), resolved again with QGIS's version of each
        package the plan would replace held by a constraint, until the plan replaces none or pip finds
        no versions that keep them all (a held package is never planned again, so each round holds one
        more and this ends)."""
        host = host_distributions(self.folder, self.search_path)
        held: dict[str, str] = {}
        clashes: dict[str, tuple[str, str]] = {}
        while True:
            constraints = self.scratch / "qgis-packages.txt"
            constraints.write_text("".join(f"{name}=={version}\n" for name, version in held.items()),
                                   encoding="utf-8")
            report_path = self.scratch / "report.json"
            try:
                self._pip(["install", "--dry-run", "--no-input", "--only-binary=:all:", "--report", str(report_path),
                           *self.pip_options, "-c", str(constraints), *(p.requirement for p in packages)], env)
            except InstallError as exc:
                if not clashes:
                    raise
                raise InstallError(clash_message(clashes), exc.log) from None
            plan = read_plan(json.loads(report_path.read_text(encoding="utf-8")))
            replaced = {normalized(p.name): p for p in plan if normalized(p.name) in host}
            if not replaced:
                return plan
            clashes.update({p.name: (host[name], p.version) for name, p in replaced.items()})
            self._log("Holding QGIS's " + ", ".join(f"{name} {host[name]}" for name in replaced)
                      + ": resolving again")
            held.update({name: host[name] for name in replaced})

    def _install_plan(self, plan: list[Planned], env: dict[str, str]) -> None:
        fetched = 0

        def follow(line: str) -> None:
            nonlocal fetched
            if line.startswith(("Collecting ", "Processing ")):
                fetched += 1
                self.progress(0.1 + 0.75 * min(fetched, len(plan)) / len(plan))
            elif line.startswith("Installing collected packages"):
                self.progress(0.85)

        self._pip(["install", "--no-deps", "--no-input", "--only-binary=:all:", "--progress-bar", "off",
                   *self.pip_options, "--upgrade", "--target", str(self.folder), *(p.requirement for p in plan)], env,
                  follow)

    def _verify(self, packages: Sequence[RuntimePackage], env: dict[str, str]) -> None:
        """Import each package in a separate Python: a wheel that does not load on this system fails
        here, with its error in the log, instead of inside QGIS."""
        modules = [p.module for p in packages]
        script = ("import importlib, sys\n"
                  "for name in sys.argv[1:]:\n"
                  "    importlib.import_module(name)\n"
                  "    print('imported', name)\n")
        command = [self.python, "-c", script, *modules]
        self._log("$ " + " ".join([self.python, "-c", "<import each package>", *modules]))
        status = run_streaming(command, env, self._log, self.is_canceled, cwd=self.scratch)
        if status != 0:
            raise InstallError("The packages were installed but do not load: " + ", ".join(modules) + ".",
                               "\n".join(self.output))


# ---------------------------------------------------------------------------------------- PyTorch, for training
# Train detector (birdseye:traindetector) trains in a separate Python process; QGIS's own Python never
# imports torch. PyTorch is an optional package group that Install dependencies installs on request into
# its own folder of the profile (never QGIS's site-packages, nor BirdsEye's runtime folder): the training
# process is QGIS's Python with that folder and BirdsEye's folder on its PYTHONPATH. A Python that already
# has torch (a venv, conda) can be named instead (the algorithm's PYTHON parameter or the environment
# variable below); tests and the repository use .venv's.
TORCH_VERSION = "2.13.0"
TORCHVISION_VERSION = "0.28.0"
ONNX_SPECIFIER = ">=1.17.0"
#: PyTorch's own package index for the CPU build (PyPI's Linux wheels are the CUDA build, gigabytes);
#: the CUDA build's index matches the CUDA runtime of PyPI's torch 2.13 wheels.
TORCH_CPU_INDEX = "https://download.pytorch.org/whl/cpu"
TORCH_CUDA_INDEX = "https://download.pytorch.org/whl/cu130"
PYPI_INDEX = "https://pypi.org/simple"
TRAINING_PYTHON_VARIABLE = "BIRDSEYE_TRAINING_PYTHON"
#: Modules the training process imports: torch, onnx (export), cv2 and numpy (tiles); torchvision only
#: for a pretrained backbone, matplotlib only for the loss plot.
TRAINING_MODULES = {"torch": "torch", "onnx": "onnx", "cv2": "opencv-python-headless", "numpy": "numpy",
                    "torchvision": "torchvision", "matplotlib": "matplotlib"}
TRAINING_REQUIRED = ("torch", "onnx", "cv2", "numpy")


@dataclass(frozen=True)
class PackageGroup:
    """An optional group of packages installed together into their own folder, from ``index_url``
    (PyPI stays the extra index for their dependencies)."""

    name: str
    title: str
    build: str
    packages: tuple[RuntimePackage, ...]
    index_url: str | None = None

    @property
    def pip_options(self) -> list[str]:
        return [] if self.index_url is None else ["--index-url", self.index_url, "--extra-index-url", PYPI_INDEX]

    def pip_command(self, python: str, folder: Path | str) -> str:
        """The command that installs the group by hand (what the installer does, in one line)."""
        return " ".join([f'"{python}"', "-m", "pip", "install", "--target", f'"{folder}"', *self.pip_options,
                         *(f'"{p.requirement}"' for p in self.packages)])


def nvidia_driver_present(proc_version: Path = Path("/proc/driver/nvidia/version"),
                          which: Callable[[str], str | None] | None = None) -> bool:
    """Whether an NVIDIA driver is installed: Linux's ``/proc/driver/nvidia/version``, or ``nvidia-smi``
    on the PATH (Windows and Linux; the driver installs it)."""
    import shutil

    which = shutil.which if which is None else which
    try:
        if Path(proc_version).is_file():
            return True
    except OSError:
        pass
    return which("nvidia-smi") is not None


def torch_group(cuda: bool | None = None) -> PackageGroup:
    """PyTorch for Train detector: the CPU build, or the CUDA build where an NVIDIA driver is present
    (``cuda=None``: detect it). Exactly these torch and torchvision versions (a looser request would
    let pip pick another build); onnx for the export."""
    cuda = nvidia_driver_present() if cuda is None else cuda
    use = Use("torch", always=("traindetector",))
    packages = (RuntimePackage("torch", f"=={TORCH_VERSION}", use),
                RuntimePackage("torchvision", f"=={TORCHVISION_VERSION}",
                               Use("torchvision", sometimes=("traindetector",))),
                RuntimePackage("onnx", ONNX_SPECIFIER, Use("onnx", always=("traindetector",))))
    return PackageGroup("torch", "PyTorch (training)", "cuda" if cuda else "cpu", packages,
                        TORCH_CUDA_INDEX if cuda else TORCH_CPU_INDEX)


def torch_folder(profile_dir: Path | str, version: Sequence[int] = sys.version_info) -> Path:
    """The PyTorch group's folder in a QGIS profile, one per Python version (next to BirdsEye's own)."""
    return Path(profile_dir) / "python" / "birdseye-torch" / f"python{version[0]}.{version[1]}"


def group_statuses(group: PackageGroup, folder: Path | None) -> list[PackageStatus]:
    """Each package of ``group`` as found in its folder (from the distributions' metadata: nothing is
    imported, so torch never enters QGIS's process), else in QGIS's Python."""
    out = []
    for package in group.packages:
        found = None
        if folder is not None and Path(folder).is_dir():
            found = next(iter(importlib.metadata.distributions(name=package.distribution, path=[str(folder)])), None)
        if found is not None:
            out.append(PackageStatus(package, found.version, True))
            continue
        host = next(iter(importlib.metadata.distributions(
            name=package.distribution, path=[p for p in sys.path if not _in_folder(p, folder)])), None)
        out.append(PackageStatus(package, None if host is None else host.version, False))
    return out


@dataclass(frozen=True)
class TrainingPython:
    """A Python the training process can run in: the interpreter, what goes first on its PYTHONPATH,
    where it came from (for the log) and the versions of :data:`TRAINING_MODULES` it has (None: missing)."""

    executable: str
    pythonpath: tuple[str, ...]
    origin: str
    versions: dict

    @property
    def missing(self) -> list[str]:
        return [m for m in TRAINING_REQUIRED if not self.versions.get(m)]

    def environment(self, plugin_root: Path = PLUGIN_ROOT, base: dict | None = None) -> dict[str, str]:
        """The child's environment: the plugin folder (``birdseye_qgis`` importable), then this Python's
        own entries, then any PYTHONPATH already set; unbuffered UTF-8 output."""
        env = dict(os.environ if base is None else base)
        entries = [str(plugin_root), *self.pythonpath] + ([env["PYTHONPATH"]] if env.get("PYTHONPATH") else [])
        env["PYTHONPATH"] = os.pathsep.join(entries)
        env["PYTHONIOENCODING"] = "utf-8"
        env["PYTHONUNBUFFERED"] = "1"
        return env


_PROBE = ("import importlib.metadata as m, importlib.util as u, json, sys\n"
          "out = {}\n"
          "for module, dist in json.loads(sys.argv[1]).items():\n"
          "    try:\n"
          "        out[module] = m.version(dist) if u.find_spec(module) else None\n"
          "    except Exception:\n"
          "        out[module] = 'unknown' if u.find_spec(module) else None\n"
          "print(json.dumps(out))\n")


def probe_training_python(executable: str, pythonpath: Sequence[str] = (), timeout: float = 60) -> dict | None:
    """{module: version or None} of :data:`TRAINING_MODULES` in ``executable`` with ``pythonpath`` first,
    found without importing them (quick: no torch start-up); None when the interpreter does not run."""
    env = TrainingPython(executable, tuple(pythonpath), "", {}).environment()
    try:
        result = subprocess.run([executable, "-c", _PROBE, json.dumps(TRAINING_MODULES)], capture_output=True,
                                text=True, timeout=timeout, env=env, cwd=tempfile.gettempdir(), check=False,
                                **_hidden_window())
    except (OSError, subprocess.TimeoutExpired):
        return None
    try:
        return json.loads(result.stdout.strip().splitlines()[-1]) if result.returncode == 0 else None
    except (ValueError, IndexError):
        return None


def training_python_candidates(configured: str | None, profile_dir: Path | str | None,
                               qgis_python: Callable[[], str] | None = None,
                               environ: dict | None = None) -> list[tuple[str, tuple[str, ...], str]]:
    """(interpreter, PYTHONPATH entries, origin) to try, in order: the Python the user named, the one in
    ``BIRDSEYE_TRAINING_PYTHON``, then QGIS's Python with the profile's PyTorch folder (and BirdsEye's
    package folder) when Install dependencies created it."""
    environ = os.environ if environ is None else environ
    found = []
    if configured:
        found.append((configured, (), "the Python given"))
    if environ.get(TRAINING_PYTHON_VARIABLE):
        found.append((environ[TRAINING_PYTHON_VARIABLE], (), TRAINING_PYTHON_VARIABLE))
    if profile_dir is not None:
        folder = torch_folder(profile_dir)
        if folder.is_dir():
            try:
                python = (qgis_python or find_python)()
            except InstallError:
                python = None
            if python:
                found.append((python, (str(folder), str(package_folder(profile_dir))),
                              f"QGIS's Python with {folder}"))
    return found


def find_training_python(configured: str | None = None, profile_dir: Path | str | None = None,
                         qgis_python: Callable[[], str] | None = None, environ: dict | None = None,
                         probe: Callable[..., dict | None] = probe_training_python
                         ) -> tuple[TrainingPython | None, list[str]]:
    """The first candidate (:func:`training_python_candidates`) that has torch, onnx, OpenCV and numpy,
    and what was tried (for the message when none does). A Python the user named is the only one
    tried: a mistake there is reported, not silently replaced."""
    tried = []
    candidates = training_python_candidates(configured, profile_dir, qgis_python, environ)
    if configured:
        candidates = candidates[:1]
    for executable, pythonpath, origin in candidates:
        versions = probe(executable, pythonpath)
        if versions is None:
            tried.append(f"{executable} ({origin}): does not run")
            continue
        candidate = TrainingPython(executable, tuple(pythonpath), origin, versions)
        if not candidate.missing:
            return candidate, tried
        tried.append(f"{executable} ({origin}): no {', '.join(TRAINING_MODULES[m] for m in candidate.missing)}")
    return None, tried
