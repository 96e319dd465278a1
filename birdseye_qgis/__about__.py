"""Who the plugin is: its folder, name, version, icon and log tag, and ``tr()`` for text outside a class.

One place for what every module of the QGIS side would otherwise repeat. ``core`` does not import it
(``core`` imports nothing outside ``core``).
"""
from __future__ import annotations

import configparser
from pathlib import Path

from qgis.PyQt.QtCore import QCoreApplication

#: The plugin folder (the repository root; installed as ``birdseye``).
PLUGIN_ROOT = Path(__file__).resolve().parents[1]
NAME = "BirdsEye"
#: The tag of BirdsEye's messages in QGIS's log panel.
LOG_TAG = NAME
ICON_PATH = PLUGIN_ROOT / "resources" / "icons" / "birdseye.svg"
HELP_DIR = PLUGIN_ROOT / "resources" / "help"
STYLE_DIR = PLUGIN_ROOT / "resources" / "styles"
#: birdseye_<locale>.qm, compiled from the .ts files by `make translations`.
I18N_DIR = PLUGIN_ROOT / "i18n"
BUNDLED_MODEL = PLUGIN_ROOT / "models" / "birdseye_demo_heatmap.onnx"


def _metadata() -> configparser.SectionProxy:
    parser = configparser.ConfigParser(interpolation=None)
    parser.read(PLUGIN_ROOT / "metadata.txt", encoding="utf-8")
    return parser["general"]


VERSION = _metadata().get("version", "unknown")


def tr(text: str) -> str:
    """Translate ``text`` outside a class's own ``tr``.

    pylupdate5 files calls of a module-level ``tr()`` under the context "@default" (i18n/*.ts), so they
    are looked up there, or their translations would never be found.
    """
    return QCoreApplication.translate("@default", text)
