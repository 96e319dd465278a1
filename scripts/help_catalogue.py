"""Put the help texts into a Qt translation catalogue: ``python3 scripts/help_catalogue.py i18n/birdseye_en.ts``.

`make translations` runs it after pylupdate5, which only sees ``tr()`` calls in Python. Every block of
``resources/help/<alg_id>.md`` (``help_blocks``, the unit the algorithm translates at run time) becomes
one message of the context ``help_context(alg_id)``, with the file and line it starts at; contexts of
help files from an earlier run are replaced, everything else in the catalogue is left as it is.
Needs QGIS's Python (it reads the split from ``processing/algorithms/base.py``).
"""
from __future__ import annotations

import argparse
import importlib
import importlib.util
import os
import re
import sys
from pathlib import Path
from xml.sax.saxutils import escape

REPO_ROOT = Path(__file__).resolve().parents[1]
HELP_DIR = REPO_ROOT / "resources" / "help"
ENTITIES = {"'": "&apos;", '"': "&quot;"}


def plugin_base():
    """``processing.algorithms.base`` of this working tree, imported as the plugin ``birdseye`` would be."""
    if "birdseye" not in sys.modules:
        spec = importlib.util.spec_from_file_location("birdseye", REPO_ROOT / "__init__.py",
                                                      submodule_search_locations=[str(REPO_ROOT)])
        package = importlib.util.module_from_spec(spec)
        sys.modules["birdseye"] = package
        spec.loader.exec_module(package)
    return importlib.import_module("birdseye.processing.algorithms.base")


def help_contexts(ts_dir: Path) -> str:
    """The ``<context>`` elements of every help file, as pylupdate5 writes contexts."""
    base = plugin_base()
    contexts = []
    for path in sorted(HELP_DIR.glob("*.md")):
        text = path.read_text(encoding="utf-8")
        location = Path(os.path.relpath(path, ts_dir)).as_posix()
        messages, offset = [], 0
        for block in base.help_blocks(text):
            offset = text.index(block, offset)
            line = text.count("\n", 0, offset) + 1
            messages.append(f'    <message>\n        <location filename="{location}" line="{line}"/>\n'
                            f"        <source>{escape(block, ENTITIES)}</source>\n"
                            '        <translation type="unfinished"></translation>\n    </message>\n')
        contexts.append(f"<context>\n    <name>{escape(base.help_context(path.stem))}</name>\n"
                        + "".join(messages) + "</context>\n")
    return "".join(contexts)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("ts", type=Path, help="the catalogue to update, e.g. i18n/birdseye_en.ts")
    ts = parser.parse_args(argv).ts
    catalogue = ts.read_text(encoding="utf-8")
    earlier = rf"<context>\n    <name>{re.escape(plugin_base().help_context(''))}[^<]*</name>\n.*?</context>\n"
    catalogue = re.sub(earlier, "", catalogue, flags=re.S)
    if "</TS>" not in catalogue:
        sys.exit(f"help_catalogue: {ts} is not a Qt .ts file")
    catalogue = catalogue.replace("</TS>", help_contexts(ts.resolve().parent) + "</TS>")
    ts.write_text(catalogue, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
