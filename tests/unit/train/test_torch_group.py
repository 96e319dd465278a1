"""The PyTorch package group of Install dependencies and how Train detector finds a Python with torch
(birdseye_qgis/dependencies.py), without QGIS and without torch."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from birdseye.birdseye_qgis import dependencies as deps


def test_cpu_build_by_default_cuda_only_with_an_nvidia_driver(tmp_path):
    cpu, cuda = deps.torch_group(cuda=False), deps.torch_group(cuda=True)
    assert cpu.build == "cpu" and cpu.index_url == deps.TORCH_CPU_INDEX
    assert cuda.build == "cuda" and cuda.index_url == deps.TORCH_CUDA_INDEX
    for group in (cpu, cuda):
        pins = {p.distribution: p.specifier for p in group.packages}
        assert pins == {"torch": "==2.13.0", "torchvision": "==0.28.0", "onnx": ">=1.17.0"}, "exact torch pins"
        assert group.pip_options[:2] == ["--index-url", group.index_url] and deps.PYPI_INDEX in group.pip_options
    proc = tmp_path / "version"
    assert not deps.nvidia_driver_present(proc, which=lambda name: None)
    assert deps.nvidia_driver_present(proc, which=lambda name: "/usr/bin/nvidia-smi")
    proc.write_text("NVRM version: NVIDIA UNIX x86_64 Kernel Module  550.54\n")
    assert deps.nvidia_driver_present(proc, which=lambda name: None)


def test_the_group_installs_into_its_own_folder_never_qgis_site_packages(tmp_path):
    folder = deps.torch_folder(tmp_path, (3, 12))
    assert folder == tmp_path / "python" / "birdseye-torch" / "python3.12"
    assert folder != deps.package_folder(tmp_path, (3, 12))
    command = deps.torch_group(cuda=False).pip_command("/usr/bin/python3", folder)
    assert command.startswith('"/usr/bin/python3" -m pip install --target "') and str(folder) in command
    assert '"torch==2.13.0" "torchvision==0.28.0"' in command and deps.TORCH_CPU_INDEX in command


def test_the_installer_passes_the_group_index_to_pip(tmp_path):
    installer = deps.Installer(tmp_path, sys.executable, pip_options=deps.torch_group(cuda=False).pip_options)
    assert installer.pip_options[:2] == ("--index-url", deps.TORCH_CPU_INDEX)


def fake_distribution(folder: Path, name: str, version: str) -> None:
    info = folder / f"{name}-{version}.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {name}\nVersion: {version}\n")


def test_group_status_reads_the_folder_without_importing(tmp_path):
    folder = tmp_path / "torch-folder"
    fake_distribution(folder, "torch", "2.13.0")
    states = {s.package.distribution: s for s in deps.group_statuses(deps.torch_group(cuda=False), folder)}
    assert states["torch"].installed_version == "2.13.0" and states["torch"].in_folder
    assert not states["torch"].needs_install
    # In a fresh interpreter (the unit suite's own process imports torch in the recipe tests): reading the
    # group's state imports nothing of it, as the dependencies dialog in QGIS's process needs.
    script = ("import sys; sys.path.insert(0, sys.argv[1]); from birdseye.birdseye_qgis import dependencies as d; "
              "from pathlib import Path; d.group_statuses(d.torch_group(cuda=False), Path(sys.argv[2])); "
              "assert 'torch' not in sys.modules, 'reading the state imported torch'")
    plugin_path = Path(deps.__file__).resolve().parents[1] / "build" / "pluginpath"
    subprocess.run([sys.executable, "-c", script, str(plugin_path), str(folder)], check=True, timeout=60)


def test_finding_the_training_python(tmp_path):
    profile = tmp_path / "profile"
    deps.torch_folder(profile).mkdir(parents=True)
    everything = dict.fromkeys(deps.TRAINING_MODULES, "1.0")

    def probe(executable, pythonpath):
        return {"/venv/python": everything, "/qgis/python": {**everything, "torch": None}}.get(executable)

    found, tried = deps.find_training_python("/venv/python", profile, probe=probe)
    assert found.executable == "/venv/python" and found.origin == "the Python given" and not tried
    found, tried = deps.find_training_python("/bad/python", profile, qgis_python=lambda: "/venv/python", probe=probe)
    assert found is None and tried == ["/bad/python (the Python given): does not run"], "a named Python is not replaced"
    found, _ = deps.find_training_python(None, profile, qgis_python=lambda: "/venv/python", environ={}, probe=probe)
    assert found.pythonpath == (str(deps.torch_folder(profile)), str(deps.package_folder(profile)))
    found, tried = deps.find_training_python(None, profile, qgis_python=lambda: "/qgis/python",
                                             environ={deps.TRAINING_PYTHON_VARIABLE: "/nowhere"}, probe=probe)
    assert found is None and len(tried) == 2 and "no torch" in tried[1]


def test_the_training_environment_puts_the_plugin_first(tmp_path):
    python = deps.TrainingPython("/p", ("/torch",), "x", {})
    env = python.environment(Path("/plugin"), base={"PYTHONPATH": "/user"})
    assert env["PYTHONPATH"].split(":") == ["/plugin", "/torch", "/user"] and env["PYTHONUNBUFFERED"] == "1"


def test_probe_finds_modules_without_importing_them():
    versions = deps.probe_training_python(sys.executable)
    assert versions is not None and versions["numpy"] and set(versions) == set(deps.TRAINING_MODULES)
    assert deps.probe_training_python("/no/such/python") is None
