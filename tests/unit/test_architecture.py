"""The dependency rules of docs/design.md ("Architecture"), checked on the source's imports.

- ``birdseye_qgis/core`` imports no QGIS and no Qt, and nothing of the plugin outside ``core``;
- no Processing algorithm imports another algorithm (shared code lives in ``qgis_io``, ``core`` or
  ``processing/parameters``);
- nothing under ``birdseye_qgis`` imports this plugin's ``processing/`` (the provider is handed to the
  plugin object); QGIS's own ``processing`` framework, imported absolutely, is fine.
"""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
LIBRARY = REPO_ROOT / "birdseye_qgis"
CORE = LIBRARY / "core"
ALGORITHMS = REPO_ROOT / "processing" / "algorithms"
QT_OR_QGIS = ("qgis", "PyQt5", "PyQt6", "sip")


def imported_modules(path: Path) -> list[tuple[int, list[str]]]:
    """(line, absolute dotted names it may import, rooted at the repository as package ``birdseye``) per
    import statement: ``from a import b`` may import module ``a.b`` or name ``b`` of ``a``."""
    package = ["birdseye", *path.relative_to(REPO_ROOT).with_suffix("").parts[:-1]]
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
        if isinstance(node, ast.Import):
            out.extend((node.lineno, [alias.name]) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            out.append((node.lineno, [module] + [f"{module}.{alias.name}" for alias in node.names]))
    return out


def violations(files, rule) -> list[str]:
    found = []
    for path in files:
        for line, candidates in imported_modules(path):
            for module in candidates:
                reason = rule(path, module)
                if reason:
                    found.append(f"{path.relative_to(REPO_ROOT)}:{line}: imports {module} ({reason})")
                    break
    return found


def core_rule(path, module):
    top = module.split(".")[0]
    if top in QT_OR_QGIS:
        return "core must not import QGIS or Qt"
    if module.startswith("birdseye.") and not module.startswith("birdseye.birdseye_qgis.core"):
        return "core must not import the plugin outside core"
    return None


def algorithm_rule(path, module):
    if module.startswith("birdseye.processing.algorithms."):
        name = module.split(".")[3]
        if name not in ("base", path.stem):
            return "an algorithm must not import another algorithm"
    return None


def library_rule(path, module):
    if module == "birdseye.processing" or module.startswith("birdseye.processing."):
        return "birdseye_qgis must not import processing/"
    return None


def python_files(folder: Path) -> list[Path]:
    return sorted(p for p in folder.rglob("*.py") if "__pycache__" not in p.parts)


def test_core_imports_neither_qgis_nor_qt_nor_the_rest_of_the_plugin():
    assert violations(python_files(CORE), core_rule) == []


def test_no_algorithm_imports_another():
    assert violations(python_files(ALGORITHMS), algorithm_rule) == []


def test_the_library_never_imports_processing():
    assert violations(python_files(LIBRARY), library_rule) == []


@pytest.mark.parametrize("folder, source, rule, expected", [
    ("birdseye_qgis/core/geometry", "from qgis.core import QgsPointXY\n", core_rule, "QGIS or Qt"),
    ("birdseye_qgis/core/geometry", "from ...qgis_io import layers\n", core_rule, "outside core"),
    ("birdseye_qgis/core/geometry", "from ..errors import InputError\n", core_rule, None),
    ("processing/algorithms", "from .clusterdetections import read_geotags\n", algorithm_rule, "another algorithm"),
    ("processing/algorithms", "from .base import BirdsEyeAlgorithm\n", algorithm_rule, None),
    ("processing/algorithms", "from ..parameters.dem import DemParametersMixin\n", algorithm_rule, None),
    ("birdseye_qgis/gui", "from ...processing.provider import BirdsEyeProvider\n", library_rule, "processing/"),
    ("birdseye_qgis/gui", "import processing  # QGIS's framework\n", library_rule, None),
    ("birdseye_qgis/qgis_io", "from . import layers\n", library_rule, None),
])
def test_the_rules_catch_a_violation(tmp_path, monkeypatch, folder, source, rule, expected):
    """Each rule, fed one import in a file placed where it would live, flags exactly the bad ones."""
    fake_root = tmp_path / "repo"
    target = fake_root / folder / "probe.py"
    target.parent.mkdir(parents=True)
    target.write_text(source)
    monkeypatch.setattr(__import__(__name__), "REPO_ROOT", fake_root)
    found = violations([target], rule)
    if expected is None:
        assert found == []
    else:
        assert len(found) == 1 and expected in found[0], found
