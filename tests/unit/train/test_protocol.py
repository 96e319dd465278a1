"""The parent's side of the training process protocol, with fake children (tiny Python scripts): no torch."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from birdseye.birdseye_qgis.core.errors import Cancelled, InputError
from birdseye.birdseye_qgis.core.train import protocol
from birdseye.birdseye_qgis.core.train.protocol import TrainingFailed, decode, encode, process_alive, run_child


def child(tmp_path, body: str) -> list[str]:
    script = tmp_path / "child.py"
    script.write_text("import json, os, signal, subprocess, sys, time\n"
                      "def emit(**event):\n    print(json.dumps(event), flush=True)\n" + textwrap.dedent(body))
    return [sys.executable, str(script)]


def test_events_round_trip_and_other_lines_are_messages():
    event = {"type": "progress", "fraction": 0.5, "stage": "fine-tune", "text": "a\nb"}
    assert "\n" not in encode(event) and decode(encode(event) + "\n") == event
    assert decode("Warning: something\n") == {"type": "message", "text": "Warning: something"}
    assert decode('{"no": "type"}')["type"] == "message" and decode("{broken")["type"] == "message"


def test_events_are_relayed_as_they_arrive(tmp_path):
    command = child(tmp_path, """
        emit(type="start", pid=os.getpid())
        for k in range(3):
            emit(type="progress", fraction=k / 3)
            time.sleep(0.3)
        print("a plain line")
        emit(type="result", stopped=False, model="m.onnx")
    """)
    seen = []
    run = run_child(command, lambda e: seen.append((time.perf_counter(), e)))
    kinds = [e["type"] for _, e in seen]
    assert kinds == ["start", "progress", "progress", "progress", "message", "result"]
    assert seen[3][0] - seen[1][0] > 0.4, "progress came while the child ran, not all at its end"
    assert run.result["model"] == "m.onnx" and run.status == 0 and not process_alive(run.pid)
    assert run.first_event_s is not None and run.first_event_s < 5


def test_a_crash_is_reported_with_the_traceback_tail(tmp_path):
    command = child(tmp_path, """
        emit(type="progress", fraction=0.1)
        raise ValueError("the batch norm exploded")
    """)
    with pytest.raises(TrainingFailed, match="exit status 1: ValueError: the batch norm exploded") as caught:
        run_child(command, lambda e: None)
    assert caught.value.cause == "crash" and any("Traceback" in line for line in caught.value.tail)


@pytest.mark.parametrize("body", ["raise MemoryError()",
                                  "sys.stderr.write('RuntimeError: CUDA out of memory. Tried to allocate 2 GiB\\n'); "
                                  "sys.exit(1)"])
def test_out_of_memory_is_named(tmp_path, body):
    with pytest.raises(TrainingFailed, match="ran out of memory") as caught:
        run_child(child(tmp_path, body), lambda e: None)
    assert caught.value.cause == "out_of_memory"


def test_a_kill_by_the_system_reads_as_out_of_memory(tmp_path):
    command = child(tmp_path, """
        emit(type="progress", fraction=0.2)
        os.kill(os.getpid(), signal.SIGKILL)
    """)
    with pytest.raises(TrainingFailed, match="killed \\(SIGKILL\\).*memory") as caught:
        run_child(command, lambda e: None)
    assert caught.value.cause == "out_of_memory" and caught.value.status == -signal.SIGKILL


def test_input_errors_come_back_as_input_errors(tmp_path):
    command = child(tmp_path, """
        emit(type="error", kind="input", text="labels: no tiles in tiles/images")
        sys.exit(2)
    """)
    with pytest.raises(InputError, match="no tiles"):
        run_child(command, lambda e: None)


def test_an_exit_without_result_is_a_failure(tmp_path):
    with pytest.raises(TrainingFailed, match="without a result"):
        run_child(child(tmp_path, "emit(type='progress', fraction=1.0)"), lambda e: None)


def test_cancel_stops_politely_and_keeps_what_the_child_said_while_stopping(tmp_path):
    """SIGTERM: the child writes its checkpoint and goes; its grandchild goes with its process group."""
    marker = tmp_path / "grandchild.pid"
    command = child(tmp_path, f"""
        stop = []
        signal.signal(signal.SIGTERM, lambda *a: stop.append(1))
        grandchild = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
        open({str(marker)!r}, "w").write(str(grandchild.pid))
        k = 0
        while not stop:
            emit(type="progress", fraction=min(0.9, k / 100))
            k += 1
            time.sleep(0.05)
        emit(type="checkpoint", path="ckpt.pt", step=k)
        sys.exit({protocol.EXIT_STOPPED})
    """)
    seen = []
    started = time.perf_counter()
    with pytest.raises(Cancelled):
        run_child(command, seen.append, is_canceled=lambda: len(seen) >= 3, grace_s=10)
    assert time.perf_counter() - started < 8, "the polite stop was not waited out to the grace period"
    assert seen[-1]["type"] == "checkpoint", "the checkpoint written while stopping reached the parent"
    grandchild = int(marker.read_text())
    deadline = time.time() + 5
    while process_alive(grandchild) and time.time() < deadline:
        time.sleep(0.05)
    assert not process_alive(grandchild), "the child's own child outlived the cancel"


def test_cancel_kills_a_child_that_ignores_sigterm(tmp_path):
    command = child(tmp_path, """
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        while True:
            emit(type="progress", fraction=0.1)
            time.sleep(0.05)
    """)
    pids = []
    started = time.perf_counter()
    with pytest.raises(Cancelled):
        run_child(command, lambda e: None, is_canceled=lambda: time.perf_counter() - started > 0.5, grace_s=1.0,
                  on_start=lambda p: pids.append(p.pid))
    assert 1.0 <= time.perf_counter() - started < 6 and not process_alive(pids[0])


def test_process_alive():
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    assert process_alive(os.getpid())
    process.wait()
    assert not process_alive(process.pid)
