"""Tiny pure-Python wheels and a pip set-up that uses only them: the installer's tests run pip for real,
offline, against a folder of these."""
from __future__ import annotations

import os
import zipfile
from pathlib import Path


def make_wheel(wheelhouse: Path, name: str, version: str, requires: tuple[str, ...] = (),
               init: str | None = None) -> Path:
    """A wheel (PEP 427 layout) holding one package ``name`` whose ``__init__`` is ``init``
    (default: ``VERSION = '<version>'``), depending on ``requires``."""
    info = f"{name}-{version}.dist-info"
    files = {
        f"{name}/__init__.py": f"VERSION = '{version}'\n" if init is None else init,
        f"{info}/METADATA": "Metadata-Version: 2.1\nName: {}\nVersion: {}\n{}".format(
            name, version, "".join(f"Requires-Dist: {r}\n" for r in requires)),
        f"{info}/WHEEL": "Wheel-Version: 1.0\nGenerator: birdseye-tests\nRoot-Is-Purelib: true\nTag: py3-none-any\n",
    }
    files[f"{info}/RECORD"] = "".join(f"{path},,\n" for path in files) + f"{info}/RECORD,,\n"
    wheel = wheelhouse / f"{name}-{version}-py3-none-any.whl"
    with zipfile.ZipFile(wheel, "w") as zf:
        for path, text in files.items():
            zf.writestr(path, text)
    return wheel


def offline_pip(monkeypatch, wheelhouse: Path) -> None:
    """Let pip (run by the code under test, which inherits os.environ) see only ``wheelhouse``: no
    index, no pip.conf, no PIP_* settings of the machine."""
    for key in [k for k in os.environ if k.startswith("PIP_")]:
        monkeypatch.delenv(key)
    monkeypatch.setenv("PIP_CONFIG_FILE", os.devnull)
    monkeypatch.setenv("PIP_NO_INDEX", "1")
    monkeypatch.setenv("PIP_FIND_LINKS", str(wheelhouse))
