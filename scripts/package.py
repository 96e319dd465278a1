"""Build the plugin zip a user installs with QGIS's "Install from ZIP": build/birdseye-<version>.zip.

The zip holds one top folder, ``birdseye/`` (the name QGIS installs the plugin under), with only what
the plugin needs at run time: the files and folders in :data:`INCLUDED` (the bundled ONNX model and
the ranges of ``requirements.txt`` included) and the compiled translations ``i18n/*.qm``. Tests,
benchmarks, scripts, the venv, build output, caches and hidden files stay out. The zip is then checked
as plugins.qgis.org's upload validator checks it (:func:`repository_problems`); any problem fails the
build. Runs with Debian's python3 (no QGIS needed).

    /usr/bin/python3 scripts/package.py [--out build]
"""
from __future__ import annotations

import argparse
import configparser
import io
import re
import sys
import zipfile
from pathlib import Path
from urllib.parse import urlparse

REPO_ROOT = Path(__file__).resolve().parents[1]
PLUGIN_FOLDER = "birdseye"
# requirements.txt: the ranges BirdsEye › Install dependencies… installs from (birdseye_qgis/dependencies.py)
INCLUDED = ["__init__.py", "metadata.txt", "LICENSE", "README.md", "requirements.txt",
            "birdseye_qgis", "processing", "models", "resources"]
INCLUDED_PATTERNS = ["i18n/*.qm"]  # translations the plugin loads; the .ts sources stay in the repository
EXCLUDED_DIR_NAMES = {"__pycache__", ".pytest_cache", ".hypothesis", ".mypy_cache", ".ruff_cache"}
EXCLUDED_SUFFIXES = {".pyc", ".pyo", ".orig", ".rej", ".swp"}

# plugins.qgis.org's upload validator (QGIS-Django, plugins/validator.py): its size limit, the metadata
# it requires, the folders it refuses anywhere in the zip.
MAX_UPLOAD_BYTES = 25_000_000
REQUIRED_METADATA = ("name", "description", "version", "qgisMinimumVersion", "author", "email", "about",
                     "tracker", "repository")
URL_METADATA = ("tracker", "repository", "homepage")
FORBIDDEN_DIRS = ("__MACOSX", ".git", "__pycache__")


def plugin_version(root: Path = REPO_ROOT) -> str:
    metadata = configparser.ConfigParser(interpolation=None)
    metadata.read(root / "metadata.txt", encoding="utf-8")
    return metadata["general"]["version"]


def packaged_files(root: Path = REPO_ROOT) -> list[Path]:
    """Every file the zip holds, relative to ``root``, sorted."""
    files = []
    for name in INCLUDED:
        path = root / name
        if not path.exists():
            sys.exit(f"package: {path} is missing")
        candidates = [path] if path.is_file() else sorted(p for p in path.rglob("*") if p.is_file())
        for candidate in candidates:
            relative = candidate.relative_to(root)
            if any(part.startswith(".") or part in EXCLUDED_DIR_NAMES for part in relative.parts):
                continue
            if candidate.suffix in EXCLUDED_SUFFIXES:
                continue
            files.append(relative)
    for pattern in INCLUDED_PATTERNS:
        files += [p.relative_to(root) for p in root.glob(pattern) if p.is_file()]
    return sorted(files)


def build(out_dir: Path, root: Path = REPO_ROOT) -> Path:
    out_dir.mkdir(parents=True, exist_ok=True)
    archive = out_dir / f"{PLUGIN_FOLDER}-{plugin_version(root)}.zip"
    tmp = archive.with_suffix(".zip.part")
    with zipfile.ZipFile(tmp, "w", compression=zipfile.ZIP_DEFLATED) as zf:
        for relative in packaged_files(root):
            zf.write(root / relative, f"{PLUGIN_FOLDER}/{relative.as_posix()}")
    tmp.replace(archive)  # never leave a half-written zip under the final name
    return archive


def repository_problems(archive: Path, new_plugin: bool = True) -> list[str]:
    """What plugins.qgis.org's upload validator would refuse in ``archive`` (empty: it passes).

    The same checks, in the same terms: size, member paths, forbidden folders and .pyc files, a sound
    zip, one top folder with a valid (PEP 8 for a new plugin) name holding ``__init__.py``,
    ``metadata.txt`` with a ``[general]`` section and every required key, the icon it names, a
    LICENSE, an author without slashes and well-formed tracker/repository/homepage URLs (the site
    also fetches those URLs; that needs the network and is left to the upload) — and one trap of
    QGIS's own installer, an empty ``plugin_dependencies``.
    """
    problems = []
    size = archive.stat().st_size
    if size > MAX_UPLOAD_BYTES:
        problems.append(f"the zip is {size / 1e6:.1f} MB; plugins.qgis.org accepts at most "
                        f"{MAX_UPLOAD_BYTES / 1e6:g} MB")
    try:
        zf = zipfile.ZipFile(archive)
    except zipfile.BadZipFile:
        return problems + ["the file cannot be unzipped"]
    with zf:
        names = zf.namelist()
        for name in names:
            parts = name.split("/")
            if ".." in name or name.startswith("/"):
                problems.append(f"{name}: member paths must not contain '..' or start with '/'")
            if ".pyc" in name:
                problems.append(f"{name}: .pyc files are refused")
            for forbidden in FORBIDDEN_DIRS:
                if forbidden in parts[:-1] or (forbidden == parts[-1] and name.endswith("/")):
                    problems.append(f"{name}: a '{forbidden}' folder is refused")
        bad = zf.testzip()
        if bad:
            problems.append(f"{bad}: bad CRC, the zip is damaged")
        tops = sorted({name.split("/")[0] for name in names})
        if not names or "/" not in names[0]:
            return problems + ["the zip holds no top folder (it must hold <plugin folder>/__init__.py …)"]
        if len(tops) > 1:
            problems.append(f"the zip holds several top folders ({', '.join(tops)}); it must hold exactly one")
        package = names[0].split("/")[0]
        if new_plugin and not re.match(r"^[a-z_][a-z0-9_]*$", package):
            problems.append(f"top folder '{package}': a new plugin's folder must be PEP 8 (lowercase, digits, _)")
        if not re.match(r"^[A-Za-z][A-Za-z0-9-_]+$", package):
            problems.append(f"top folder '{package}': only ASCII letters, digits, '-' and '_', starting with a letter")
        for required in ("__init__.py", "metadata.txt", "LICENSE"):
            if f"{package}/{required}" not in names:
                problems.append(f"{package}/{required} is missing")
        if f"{package}/metadata.txt" not in names:
            return problems
        parser = configparser.ConfigParser(interpolation=None)
        parser.optionxform = str  # keys are case-sensitive (qgisMinimumVersion)
        try:
            parser.read_file(io.StringIO(zf.read(f"{package}/metadata.txt").decode("utf-8")))
        except (configparser.Error, UnicodeDecodeError) as exc:
            return problems + [f"metadata.txt cannot be parsed: {exc}"]
        if not parser.has_section("general"):
            return problems + ["metadata.txt has no [general] section"]
        general = parser["general"]
        missing = [key for key in REQUIRED_METADATA if not general.get(key, "").strip()]
        if missing:
            problems.append(f"metadata.txt lacks {', '.join(missing)}")
        icon = general.get("icon", "").strip()
        if icon and f"{package}/{icon.removeprefix('./')}" not in names:
            problems.append(f"metadata.txt names the icon {icon}, which is not in the zip")
        if "/" in general.get("author", ""):
            problems.append("metadata.txt: the author must not contain '/'")
        if "plugin_dependencies" in general and not general["plugin_dependencies"].strip():
            # Not the site's rule but QGIS's installer: it splits the empty value into one dependency
            # named "" and greets every Install from ZIP with a dialog asking to install it.
            problems.append("metadata.txt: plugin_dependencies is empty; leave the key out")
        for key in URL_METADATA:
            url = general.get(key, "").strip()
            if key in REQUIRED_METADATA or url:
                parsed = urlparse(url)
                if not (parsed.scheme and parsed.netloc):
                    problems.append(f"metadata.txt: {key} = '{url}' is not a URL")
    return problems


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=REPO_ROOT / "build", help="output folder")
    args = parser.parse_args()
    archive = build(args.out)
    with zipfile.ZipFile(archive) as zf:
        count = len(zf.namelist())
    print(f"{archive} ({count} files, {archive.stat().st_size / 1e6:.1f} MB of plugins.qgis.org's "
          f"{MAX_UPLOAD_BYTES / 1e6:g} MB)")
    problems = repository_problems(archive)
    if problems:
        sys.exit("package: plugins.qgis.org would refuse it:\n  - " + "\n  - ".join(problems))
    print("package: passes plugins.qgis.org's upload checks (size, paths, folders, metadata, icon, LICENSE)")


if __name__ == "__main__":
    main()
