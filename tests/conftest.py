"""Test set-up shared by every suite.

The repository root *is* the plugin folder, installed into QGIS as ``birdseye``; tests import it under
that name through a symlink in ``build/pluginpath`` (the same folder serves as ``QGIS_PLUGINPATH`` for
``qgis_process`` and desktop tests). Nothing QGIS-related is constructed at import time.
"""
import os
import sys
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[1]
PLUGIN_PATH = REPO_ROOT / "build" / "pluginpath"


def _ensure_plugin_link() -> None:
    PLUGIN_PATH.mkdir(parents=True, exist_ok=True)
    link = PLUGIN_PATH / "birdseye"
    if not link.is_symlink():
        try:
            link.symlink_to(REPO_ROOT, target_is_directory=True)
        except FileExistsError:  # another xdist worker made it
            pass
    if str(PLUGIN_PATH) not in sys.path:
        sys.path.insert(0, str(PLUGIN_PATH))


_ensure_plugin_link()
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")


def pytest_configure(config):
    """With pytest-qgis active (not under ``-p no:qgis``), every suite gets the QGIS fixtures."""
    if config.pluginmanager.has_plugin("qgis") or config.pluginmanager.has_plugin("pytest_qgis"):
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        import qgis_fixtures

        config.pluginmanager.register(qgis_fixtures, "birdseye_qgis_fixtures")
