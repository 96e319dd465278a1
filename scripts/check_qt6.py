"""Check that the plugin's Qt usage exists in PyQt6 (QGIS 4), without QGIS 4.

Run with a Python that has PyQt6 (``make setup`` makes ``.venv-qt6``):

    .venv-qt6/bin/python scripts/check_qt6.py [--fix] [FILE_OR_FOLDER ...]

For every name imported from ``qgis.PyQt.<module>`` (``Qt``, ``QMessageBox``, …) each attribute chain the
code spells (``Qt.AlignmentFlag.AlignLeft``, ``QMessageBox.StandardButton.Yes``,
``QCoreApplication.translate``) must resolve in ``PyQt6.<module>`` under that exact name: PyQt6 dropped
the unscoped enum aliases (``Qt.AlignLeft``) and ``exec_()``. Also refused: importing PyQt5 or PyQt6
directly (only ``qgis.PyQt`` picks the right one), any ``.exec_`` attribute, importing a name from a
``qgis.PyQt`` module whose PyQt6 counterpart lacks it (``QAction`` moved from QtWidgets to QtGui), and the
QGIS enum names QGIS 3.30–3.36 deprecated when the enums moved into ``Qgis`` (``QgsProcessing.TypeVectorPoint``,
``QgsWkbTypes.PointZ`` …; QGIS 4 keeps them only as aliases): those values come from
``birdseye_qgis/qgis_enums.py``, or take the scoped spelling QGIS 3.22 already has. The new spellings,
``Qgis.<Enum>.<Member>``, must exist in the QGIS API of ``qgis-stubs`` (PyPI; a recent QGIS 3 release,
whose enums QGIS 4 keeps). Code for old releases is left alone where it says so: the ``else`` of
``if Qgis.QGIS_VERSION_INT >= N``, the body of ``if … QGIS_VERSION_INT < N``, and the ``except ImportError``
fallback of a ``try`` import — that is where APIs that moved keep their QGIS 3.22 spelling.

Prints one line per problem (``file:line: message``) and exits 1 if there is any. ``--fix`` rewrites
the unscoped enum members that belong to exactly one enum of their class to the scoped spelling, which
PyQt5 5.15 (QGIS 3.22) understands too, and reports what it could not fix.
"""
from __future__ import annotations

import ast
import importlib
import re
import sys
import sysconfig
from functools import lru_cache
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[1]
DEFAULT_ROOTS = ("__init__.py", "birdseye_qgis", "processing")
#: qgis.PyQt sub-modules that have a PyQt6 counterpart of the same name.
QT_MODULES = {"QtCore", "QtGui", "QtWidgets", "QtSvg", "QtXml", "QtNetwork", "QtPrintSupport", "QtSql",
              "QtTest"}
ENUM_MODULE = "birdseye_qgis/qgis_enums.py"
#: Deprecated QGIS enum names, by class: the members (a regular expression) and what to use instead.
DEPRECATED_QGIS_NAMES = {
    "QgsProcessing": (r"Type\w*|SourceType", f"SOURCE_… of {ENUM_MODULE} (Qgis.ProcessingSourceType, QGIS 3.36)"),
    "QgsProcessingParameterNumber": (r"Double|Integer|Type",
                                     f"NUMBER_… of {ENUM_MODULE} (Qgis.ProcessingNumberParameterType, QGIS 3.36)"),
    "QgsProcessingParameterFile": (r"File|Folder|Behavior",
                                   f"FILE_BEHAVIOR_… of {ENUM_MODULE} (Qgis.ProcessingFileParameterBehavior, 3.36)"),
    "QgsProcessingParameterDefinition": (r"Flag\w*", f"PARAMETER_… of {ENUM_MODULE} (Qgis.ProcessingParameterFlag)"),
    "QgsFeatureRequest": (r"NoGeometry|SubsetOfAttributes|ExactIntersect|Flag",
                          f"REQUEST_… of {ENUM_MODULE} (Qgis.FeatureRequestFlag, QGIS 3.36)"),
    "QgsCoordinateReferenceSystem": (r"WKT\w*|WktVariant", f"CRS_WKT… of {ENUM_MODULE} (Qgis.CrsWktVariant, 3.36)"),
    "QgsWkbTypes": (r"[A-Z]\w*", f"WKB_… or GEOMETRY_… of {ENUM_MODULE} (Qgis.WkbType, Qgis.GeometryType, 3.30)"),
    "QgsUnitTypes": (r"[A-Z]\w*", f"DISTANCE_… of {ENUM_MODULE} (Qgis.DistanceUnit, QGIS 3.30)"),
    "QgsMapLayerType": (r"[A-Z]\w*", f"LAYER_… of {ENUM_MODULE} (Qgis.LayerType, QGIS 3.30)"),
    "QgsMapLayerProxyModel": (r"[A-Z]\w*", f"FILTER_… of {ENUM_MODULE} (Qgis.LayerFilter, QGIS 3.34)"),
    "QgsFeatureSink": (r"FastInsert|RollBackOnErrors", "QgsFeatureSink.Flag.<name> (QGIS 3.22 has it too)"),
    "QgsVertexMarker": (r"ICON_\w+", "QgsVertexMarker.IconType.<name> (QGIS 3.22 has it too)"),
    "QgsFileWidget": (r"GetFile|GetDirectory|GetMultipleFiles|SaveFile",
                      "QgsFileWidget.StorageMode.<name> (QGIS 3.22 has it too)"),
    "Qgis": (r"Info|Warning|Critical|Success|NoLevel", "Qgis.MessageLevel.<name> (QGIS 3.22 has it too)"),
}


@lru_cache(maxsize=None)
def qgis_stub_enums() -> dict[str, set[str]]:
    """``{'ProcessingSourceType': {'VectorPoint', …}, '': {members of Qgis itself}}`` from qgis-stubs."""
    stub = Path(sysconfig.get_paths()["purelib"]) / "qgis-stubs" / "_core.pyi"
    if not stub.is_file():
        sys.exit(f"check_qt6: {stub} is missing: run `make setup` (requirements-qt6.txt installs qgis-stubs)")
    qgis = next(node for node in ast.parse(stub.read_text(encoding="utf-8")).body
                if isinstance(node, ast.ClassDef) and node.name == "Qgis")
    enums = {"": set()}
    for node in qgis.body:
        if isinstance(node, ast.ClassDef):
            enums[node.name] = {target.id for item in node.body if isinstance(item, ast.Assign)
                                for target in item.targets if isinstance(target, ast.Name)}
        names = [t.id for t in node.targets if isinstance(t, ast.Name)] if isinstance(node, ast.Assign) else []
        enums[""].update(names + [getattr(node, "name", "")])
    return enums


def python_files(paths) -> list[Path]:
    files = []
    for path in paths:
        path = Path(path)
        if path.is_dir():
            files.extend(p for p in sorted(path.rglob("*.py")) if "__pycache__" not in p.parts)
        else:
            files.append(path)
    return files


def attribute_chain(node: ast.Attribute) -> list[str] | None:
    """['Qt', 'AlignmentFlag', 'AlignLeft'] for ``Qt.AlignmentFlag.AlignLeft``; None if not a plain chain."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if not isinstance(node, ast.Name):
        return None
    parts.append(node.id)
    return parts[::-1]


def _mentions_qgis_version(test: ast.expr) -> bool:
    return any(isinstance(n, (ast.Name, ast.Attribute)) and "QGIS_VERSION_INT" in ast.unparse(n)
               for n in ast.walk(test))


def _old_qgis_branch(test: ast.expr) -> str | None:
    """'orelse' for ``QGIS_VERSION_INT >= N`` (the old release runs the else), 'body' for ``< N``."""
    if not (isinstance(test, ast.Compare) and len(test.ops) == 1 and _mentions_qgis_version(test.left)):
        return None
    if isinstance(test.ops[0], (ast.GtE, ast.Gt)):
        return "orelse"
    if isinstance(test.ops[0], (ast.Lt, ast.LtE)):
        return "body"
    return None


class Checker(ast.NodeVisitor):
    def __init__(self, path: Path):
        self.path = path
        self.qt_names: dict[str, str] = {}  # local name -> "PyQt6.QtCore.Qt"-style dotted origin
        self.qgis_names: dict[str, str] = {}  # local name -> class name in qgis.core / qgis.gui
        self.problems: list[str] = []
        self.fixes: list[tuple[ast.Attribute, str]] = []  # (node, scoped spelling of the whole chain)

    def report(self, node: ast.AST, message: str) -> None:
        self.problems.append(f"{self.path}:{node.lineno}: {message}")

    def visit_Import(self, node: ast.Import) -> None:
        for alias in node.names:
            if alias.name.split(".")[0] in ("PyQt5", "PyQt6"):
                self.report(node, f"imports {alias.name} directly; import it from qgis.PyQt")

    def visit_ImportFrom(self, node: ast.ImportFrom) -> None:
        module = node.module or ""
        if module.split(".")[0] in ("PyQt5", "PyQt6"):
            self.report(node, f"imports from {module} directly; import from qgis.PyQt")
        if module in ("qgis.core", "qgis.gui"):
            self.qgis_names.update({alias.asname or alias.name: alias.name for alias in node.names})
        parts = module.split(".")
        if parts[:2] == ["qgis", "PyQt"] and len(parts) == 3 and parts[2] in QT_MODULES:
            qt6_module = importlib.import_module(f"PyQt6.{parts[2]}")
            for alias in node.names:
                if not hasattr(qt6_module, alias.name):
                    self.report(node, f"{alias.name} is not in PyQt6.{parts[2]}{moved_hint(alias.name)}")
                    continue
                self.qt_names[alias.asname or alias.name] = f"PyQt6.{parts[2]}.{alias.name}"

    def visit_Try(self, node: ast.Try) -> None:
        for child in node.body + node.orelse + node.finalbody:
            self.visit(child)
        for handler in node.handlers:
            if handler.type is None or "ImportError" not in ast.unparse(handler.type):
                self.visit(handler)

    def visit_If(self, node: ast.If) -> None:
        self._visit_guarded(node)

    def visit_IfExp(self, node: ast.IfExp) -> None:
        self._visit_guarded(node)

    def _visit_guarded(self, node) -> None:
        skip = _old_qgis_branch(node.test)
        self.visit(node.test)
        for branch in ("body", "orelse"):
            if branch == skip:
                continue
            value = getattr(node, branch)
            for child in value if isinstance(value, list) else [value]:
                self.visit(child)

    def visit_Attribute(self, node: ast.Attribute) -> None:
        if node.attr == "exec_":
            self.report(node, "exec_() is gone in PyQt6; call exec()")
        chain = attribute_chain(node)
        if chain and len(chain) > 1 and chain[0] in self.qgis_names:
            deprecated = DEPRECATED_QGIS_NAMES.get(self.qgis_names[chain[0]])
            if deprecated and re.fullmatch(deprecated[0], chain[1]):
                self.report(node, f"{'.'.join(chain)} is deprecated (QGIS 4 keeps it only as an alias): "
                                  f"use {deprecated[1]}")
            elif self.qgis_names[chain[0]] == "Qgis" and chain[1][:1].isupper() and not chain[1].isupper():
                self.check_qgis_enum(node, chain)
            return  # the whole chain is checked; its inner Attribute nodes are prefixes of it
        if chain and chain[0] in self.qt_names:
            self.check_chain(node, chain)
            return  # the whole chain is checked; its inner Attribute nodes are prefixes of it
        self.generic_visit(node)

    def check_qgis_enum(self, node: ast.Attribute, chain: list[str]) -> None:
        """``Qgis.<Enum>.<Member>`` (or ``Qgis.<Member>``) must be in the QGIS API of qgis-stubs."""
        enums = qgis_stub_enums()
        if chain[1] not in enums and chain[1] not in enums[""]:
            self.report(node, f"{'.'.join(chain[:2])} is not in the QGIS API (qgis-stubs)")
        elif len(chain) > 2 and chain[1] in enums and chain[2] not in enums[chain[1]]:
            self.report(node, f"{'.'.join(chain[:3])} is not in the QGIS API (qgis-stubs)")

    def check_chain(self, node: ast.Attribute, chain: list[str]) -> None:
        module_name, _, class_name = self.qt_names[chain[0]].rpartition(".")
        try:
            obj = getattr(importlib.import_module(module_name), class_name)
        except (ImportError, AttributeError):
            self.report(node, f"{chain[0]} does not exist in {module_name}")
            return
        for depth, attr in enumerate(chain[1:], start=1):
            if not hasattr(obj, attr):
                spelled = ".".join(chain[:depth + 1])
                enums = enums_with_member(obj, attr)
                if len(enums) == 1 and depth == len(chain) - 1:
                    self.fixes.append((node, ".".join(chain[:depth] + [enums[0], attr])))
                hint = f" (use {'.'.join(chain[:depth])}.{enums[0]}.{attr})" if enums else ""
                self.report(node, f"{spelled} does not exist in PyQt6{hint}")
                return
            obj = getattr(obj, attr)


def moved_hint(name: str) -> str:
    """' (it is in PyQt6.QtGui)' for a class Qt 6 moved to another module."""
    for module in sorted(QT_MODULES):
        try:
            if hasattr(importlib.import_module(f"PyQt6.{module}"), name):
                return f" (it is in PyQt6.{module})"
        except ImportError:
            continue
    return ""


def enums_with_member(owner, member: str) -> list[str]:
    """Names of ``owner``'s enum classes that have ``member`` (``['AlignmentFlag']`` for Qt, AlignLeft)."""
    import enum

    return [name for name in dir(owner)
            if isinstance(getattr(owner, name, None), type) and issubclass(getattr(owner, name), enum.Enum)
            and member in getattr(owner, name).__members__]


def check(paths, fix: bool = False) -> list[str]:
    problems = []
    for path in python_files(paths):
        source = path.read_text(encoding="utf-8")
        checker = Checker(path)
        checker.visit(ast.parse(source, filename=str(path)))
        if fix and checker.fixes:
            path.write_text(apply_fixes(source, checker.fixes), encoding="utf-8")
            checker = Checker(path)
            checker.visit(ast.parse(path.read_text(encoding="utf-8"), filename=str(path)))
        problems.extend(checker.problems)
    return problems


def apply_fixes(source: str, fixes) -> str:
    lines = source.splitlines(keepends=True)
    # Right to left within a line, so earlier column offsets stay valid.
    for node, text in sorted(fixes, key=lambda f: (f[0].lineno, f[0].col_offset), reverse=True):
        if node.lineno != node.end_lineno:
            continue
        line = lines[node.lineno - 1].encode("utf-8")
        lines[node.lineno - 1] = (line[:node.col_offset] + text.encode("utf-8")
                                  + line[node.end_col_offset:]).decode("utf-8")
    return "".join(lines)


def main(argv: list[str]) -> int:
    fix = "--fix" in argv
    paths = [a for a in argv if a != "--fix"] or [REPO_ROOT / p for p in DEFAULT_ROOTS]
    problems = check(paths, fix=fix)
    for line in problems:
        print(line)
    files = len(python_files(paths))
    print(f"check_qt6: {len(problems)} problem(s) in {files} file(s)", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
