"""Where the QGIS suites can train: the Python running them, when it has the training extra.

On the host, `make setup` installs requirements-train.txt into .venv, so a missing torch is a failed
install and the training tests must fail. The QGIS chroots (scripts/qgis_chroot.sh, which sets
BIRDSEYE_VENV) install requirements.txt and requirements-test.txt only: PyTorch has no CPU wheel for
their Python 3.13/3.14 from the package registry (only CUDA builds of several GB), so there is no
Python to train in there and those tests are skipped, saying so. Only ``find_spec`` looks: torch is
never imported into the tests' (QGIS's) process.
"""
import importlib.util
import os
import sys

import pytest

TRAINING_PYTHON = sys.executable
IN_QGIS_CHROOT = bool(os.environ.get("BIRDSEYE_VENV"))
needs_training_python = pytest.mark.skipif(
    IN_QGIS_CHROOT and importlib.util.find_spec("torch") is None,
    reason="no Python with torch in the QGIS chroot (only the host's .venv has requirements-train.txt)")
