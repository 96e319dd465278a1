"""Build the plugin zip a user installs with QGIS's "Install from ZIP": build/birdseye-<version>.zip.

The zip holds one top folder, ``birdseye/`` (the name QGIS installs the plugin under), with only what
the plugin needs at run time: the files and folders in :data:`INCLUDED`. Tests, benchmarks, scripts,
the venv, build output, caches and hidden files stay out. Runs with Debian's python3 (no QGIS needed).

    /usr/bin/python3 scripts/package.py [--out build]
"""
from __future__ import annotations

import argparse
import configparser
import sys
import zipfile
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[1]
PLUGIN_FOLDER = "birdseye"
INCLUDED = ["__init__.py", "metadata.txt", "LICENSE", "README.md",
            "birdseye_qgis", "processing", "models", "resources"]
EXCLUDED_DIR_NAMES = {"__pycache__", ".pytest_cache", ".hypothesis", ".mypy_cache", ".ruff_cache"}
EXCLUDED_SUFFIXES = {".pyc", ".pyo", ".orig", ".rej", ".swp"}


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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=REPO_ROOT / "build", help="output folder")
    args = parser.parse_args()
    archive = build(args.out)
    with zipfile.ZipFile(archive) as zf:
        count = len(zf.namelist())
    print(f"{archive} ({count} files, {archive.stat().st_size / 1e6:.1f} MB)")


if __name__ == "__main__":
    main()
