"""Make the plugin importable as ``birdseye`` when a benchmark runs as a script."""
import sys
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[1]
PLUGIN_PATH = REPO_ROOT / "build" / "pluginpath"
PLUGIN_PATH.mkdir(parents=True, exist_ok=True)
if not (PLUGIN_PATH / "birdseye").is_symlink():
    (PLUGIN_PATH / "birdseye").symlink_to(REPO_ROOT, target_is_directory=True)
if str(PLUGIN_PATH) not in sys.path:
    sys.path.insert(0, str(PLUGIN_PATH))
