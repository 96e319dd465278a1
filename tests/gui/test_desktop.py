"""The real QGIS desktop, under its own Xvfb, with the plugin enabled in a fresh profile.

QGIS is started once for the module with ``--code desktop_probe.py``; the probe inspects the running
application, saves build/screenshots/desktop.png, writes a JSON report and quits. The tests below
read that report. A Python error while QGIS loads the plugin opens a modal dialog that nobody
clicks: QGIS then never quits, and the test fails after a timeout with a screenshot of the screen.
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import sysconfig
from contextlib import contextmanager
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
PLUGIN_PATH = REPO_ROOT / "build" / "pluginpath"
SCREENSHOTS = REPO_ROOT / "build" / "screenshots"
PROBE_DIR = Path(__file__).parent  # the probes and probe_session.py, their shared driver
PROBE = PROBE_DIR / "desktop_probe.py"
QGIS_BIN = Path("/usr/bin/qgis.bin")  # Debian's /usr/bin/qgis only adds $QGIS_OPTS from /etc/default
ALGORITHM_DIR = REPO_ROOT / "processing" / "algorithms"
ALGORITHM_IDS = sorted(f"birdseye:{p.stem}" for p in ALGORITHM_DIR.glob("*.py")
                       if p.stem not in {"__init__", "base"})
DESKTOP_TIMEOUT_S = 90
# For a desktop without network: no news feed, and no download of a missing font that a style or QGIS's
# own defaults name (3.40 fetches Open Sans, and its failure is a warning in the message bar).
OFFLINE_SETTINGS = "[core]\nNewsFeed\\httpsfeedqgisorg\\disabled=true\n\n[fonts]\ndownloadMissingFonts=false\n"

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(not QGIS_BIN.exists() or shutil.which("Xvfb") is None,
                       reason="needs Debian's qgis and xvfb (make setup installs them)"),
]


@contextmanager
def xvfb_display(screen: str = "1600x1000x24"):
    """A private X server; Xvfb picks a free display number itself and reports it (-displayfd)."""
    read_end, write_end = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write_end), "-screen", "0", screen,
                               "-nolisten", "tcp"], pass_fds=(write_end,),
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    os.close(write_end)
    with os.fdopen(read_end) as reader:
        number = reader.readline().strip()  # written once the server accepts connections
    try:
        if not number:
            server.kill()
            pytest.fail(f"Xvfb did not start: {server.communicate()[1].decode(errors='replace')}")
        yield f":{number}"
    finally:
        server.terminate()
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            server.kill()


def grab_screen(display: str, path: Path) -> None:
    """Screenshot of the whole X screen, taken from outside QGIS (QGIS may be stuck in a dialog)."""
    code = ("import sys; from qgis.PyQt.QtWidgets import QApplication; app = QApplication([]); "
            "app.primaryScreen().grabWindow(0).save(sys.argv[1])")
    subprocess.run([sys.executable, "-c", code, str(path)],
                   env={**os.environ, "DISPLAY": display, "QT_QPA_PLATFORM": "xcb"},
                   timeout=30, check=False, capture_output=True)


def fresh_profile(root: Path) -> Path:
    """A profiles folder whose default profile enables BirdsEye and Processing, offline."""
    ini = root / "profiles" / "default" / "QGIS" / "QGIS3.ini"
    ini.parent.mkdir(parents=True)
    ini.write_text("[PythonPlugins]\nbirdseye=true\nprocessing=true\n\n" + OFFLINE_SETTINGS)
    return root


def desktop_env(display: str, runtime_dir: Path, **extra: str) -> dict[str, str]:
    """QGIS's environment: the X display, the plugin, the test venv's packages, and ``BIRDSEYE_PROBE_DIR`` (a
    ``--code`` script has no ``__file__``: the probes import probe_session.py from there)."""
    env = {k: v for k, v in os.environ.items() if k not in {"QGIS_CUSTOM_CONFIG_PATH", "PYTHONPATH"}}
    # The test venv's packages (the host's .venv, or the chroot's): QGIS embeds the bare system Python.
    site_packages = [sysconfig.get_path("purelib")]
    env.update(DISPLAY=display, QT_QPA_PLATFORM="xcb", QGIS_PLUGINPATH=str(PLUGIN_PATH),
               XDG_RUNTIME_DIR=str(runtime_dir), PYTHONPATH=os.pathsep.join(map(str, site_packages)),
               BIRDSEYE_PROBE_DIR=str(PROBE_DIR), **extra)
    return env


def screenshot_folder(folder: Path, old: str = "*.png") -> Path:
    """``folder``, made if need be, without the screenshots (``old``) of an earlier run."""
    folder.mkdir(parents=True, exist_ok=True)
    for path in folder.glob(old):
        path.unlink()
    return folder


def run_probe(probe: Path, work: Path, timeout_s: float, stuck_screenshot: Path, output_copy: Path | None = None,
              report_copy: Path | None = None, screen: str = "1600x1000x24", **env: str) -> dict:
    """Start the real QGIS desktop under Xvfb (a screen of ``screen``, "WxHxDepth") with a fresh profile, let
    ``probe`` (a ``--code`` script) play its session and write ``work/report.json``, and return the report plus
    QGIS's output and exit code. ``env`` goes to QGIS's environment (``desktop_env``).

    A QGIS that has not quit after ``timeout_s`` is almost always stuck in a modal dialog (a Python
    error while loading a plugin): the screen is saved to ``stuck_screenshot`` and the test fails.
    ``output_copy`` keeps QGIS's output in a file, for a look after a failure; ``report_copy`` the report
    (beside the screenshots, say).
    """
    runtime_dir = work / "runtime"
    runtime_dir.mkdir(mode=0o700)
    report_path = work / "report.json"
    command = [str(QGIS_BIN), "--nologo", "--noversioncheck", "--profiles-path",
               str(fresh_profile(work / "profiles")), "--code", str(probe)]
    with xvfb_display(screen) as display:
        qgis = subprocess.Popen(command, env=desktop_env(display, runtime_dir, BIRDSEYE_PROBE_RESULT=str(report_path),
                                                         **env),
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        try:
            output, _ = qgis.communicate(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            grab_screen(display, stuck_screenshot)
            qgis.kill()
            output, _ = qgis.communicate()
            pytest.fail(f"QGIS did not quit within {timeout_s} s — most likely a modal dialog "
                        f"(a Python error while loading a plugin?); screen saved to {stuck_screenshot}.\n{output}")
    if output_copy is not None:
        output_copy.write_text(output, encoding="utf-8")
    assert report_path.is_file(), f"the probe wrote no report (QGIS exit {qgis.returncode}):\n{output}"
    if report_copy is not None:
        shutil.copy(report_path, report_copy)
    return {"report": json.loads(report_path.read_text(encoding="utf-8")), "output": output,
            "returncode": qgis.returncode}


@pytest.fixture(scope="module")
def desktop(tmp_path_factory) -> dict:
    """Start QGIS once, let the probe inspect it, and return its report plus QGIS's output."""
    screenshot = screenshot_folder(SCREENSHOTS, old="desktop.png") / "desktop.png"
    result = run_probe(PROBE, tmp_path_factory.mktemp("desktop"), DESKTOP_TIMEOUT_S,
                       SCREENSHOTS / "desktop-timeout.png", BIRDSEYE_PROBE_SCREENSHOT=str(screenshot))
    return {**result, "screenshot": screenshot}


def test_probe_ran_cleanly(desktop):
    assert desktop["report"]["errors"] == []
    assert desktop["returncode"] == 0, desktop["output"]


def test_plugin_and_provider_loaded(desktop):
    report = desktop["report"]
    assert "birdseye" in report["plugins"]
    assert "Loaded BirdsEye (package: birdseye)" in report["message_log"].get("Plugins", "")
    assert report["provider_algorithms"] == ALGORITHM_IDS


def test_no_python_error(desktop):
    log = desktop["report"]["message_log"]
    assert "Python error" not in log, log.get("Python error")
    ours = [line for line in log.get("BirdsEye", "").splitlines() if "WARNING" in line or "CRITICAL" in line]
    assert ours == []
    assert "Traceback" not in desktop["output"], desktop["output"]
    assert not any("error" in title.lower() for title, _ in desktop["report"]["message_bar"])


def test_menu_toolbar_toolbox_and_docks(desktop):
    report = desktop["report"]
    menus = report["menu_bar"]
    assert "mBirdsEyeMenu" in menus and menus.index("mBirdsEyeMenu") < menus.index("mHelpMenu")
    assert report["toolbar_actions"] and report["toolbar_actions"][0] == "BirdsEye algorithms…"
    assert report["toolbox"]["visible"] and report["toolbox"]["filter"] == "birdseye"
    assert report["toolbox"]["algorithms"] == ALGORITHM_IDS, "the filtered toolbox shows other algorithms"
    assert all(report["docks"].values()), report["docks"]


def test_screenshot_saved(desktop):
    from qgis.PyQt.QtGui import QImage

    assert desktop["report"]["screenshot_saved"]
    image = QImage(str(desktop["screenshot"]))
    assert image.width() >= 1024 and image.height() >= 700
