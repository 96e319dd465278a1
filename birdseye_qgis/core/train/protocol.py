"""The line protocol between ``birdseye:traindetector`` and its training process, and the parent's side.

Training runs in a separate Python process (PyTorch is never imported into QGIS's own Python). The
child (:mod:`.child`) writes one JSON object per line on stdout; any other stdout line is a plain
message, and stderr is kept for the error report. Events (``type``):

* ``start`` — torch version, ``device`` (``cpu``/``cuda``), threads, backbone, pid;
* ``data`` — tiles, positives, negatives, the split, provenance counts;
* ``progress`` — ``fraction`` (0–1 of the whole run), ``stage``, and while training ``step``, ``loss``,
  ``tiles_per_s`` (at most twice a second);
* ``point`` — a point of the loss history: ``stage``, ``step``, ``loss``, ``val_loss``, ``seconds``;
* ``checkpoint`` — the last good checkpoint was written (atomically) to ``path``;
* ``message`` — ``text`` for the log (``level`` ``warning``: a warning, e.g. a threshold not validated);
* ``error`` — ``kind`` (``input`` for input the user can fix, else ``crash``) and ``text``;
* ``result`` — the run's outcome: files, figures, history (``stopped`` after a cancel).

:func:`run_child` starts the command in its own process group, relays events as they arrive, and on
cancel stops the whole group: SIGTERM (on Windows CTRL_BREAK), on which the child ends training at the
next step and writes its checkpoint, then SIGKILL after a grace period. A non-zero exit raises
:class:`TrainingFailed` with its cause read from the exit status and the last lines of stderr.
Pure standard library: tested with fake children, no torch.
"""
from __future__ import annotations

import collections
import json
import os
import queue
import signal
import subprocess
import sys
import threading
import time
from typing import Callable, Sequence

from ..errors import Cancelled, InputError

OUT_OF_MEMORY_MARKERS = ("MemoryError", "CUDA out of memory", "OutOfMemoryError", "DefaultCPUAllocator: can't allocate",
                         "std::bad_alloc")
#: Exit status of the child when training ends on SIGTERM/CTRL_BREAK (cancel) after writing its checkpoint.
EXIT_STOPPED = 3
#: Exit status of the child for input the user can fix (its ``error`` event says what).
EXIT_INPUT = 2


def encode(event: dict) -> str:
    """One event as a line (no newline inside: JSON escapes them)."""
    return json.dumps(event, separators=(",", ":"), default=str)


def decode(line: str) -> dict:
    """An event from a line: a JSON object with a ``type``, or a ``message`` holding the raw line."""
    text = line.strip()
    if text.startswith("{"):
        try:
            event = json.loads(text)
        except json.JSONDecodeError:
            event = None
        if isinstance(event, dict) and isinstance(event.get("type"), str):
            return event
    return {"type": "message", "text": line.rstrip("\r\n")}


class TrainingFailed(RuntimeError):
    """The training process ended badly; ``cause`` is ``out_of_memory``, ``killed`` or ``crash``,
    ``tail`` the last lines of its stderr, ``status`` its exit status."""

    def __init__(self, message: str, cause: str, status: int | None, tail: Sequence[str] = ()):
        super().__init__(message)
        self.cause, self.status, self.tail = cause, status, list(tail)


def failure(status: int | None, stderr_tail: Sequence[str], error_event: dict | None = None) -> TrainingFailed:
    """What a non-zero exit means: out of memory (a MemoryError or CUDA's message on stderr, or SIGKILL
    from the system, which is how Linux's OOM killer ends a process), another signal, or a crash."""
    tail = [line for line in stderr_tail if line.strip()]
    text = "\n".join(tail)
    last = tail[-1] if tail else ""
    if error_event is not None and error_event.get("text"):
        last = error_event["text"]
    if any(marker in text or marker in last for marker in OUT_OF_MEMORY_MARKERS):
        return TrainingFailed(f"The training process ran out of memory ({last}). Train with a smaller batch or "
                              "network, or close other programs.", "out_of_memory", status, tail)
    if status is not None and status < 0 and os.name != "nt":
        try:
            name = signal.Signals(-status).name
        except ValueError:
            name = f"signal {-status}"
        if -status == getattr(signal, "SIGKILL", 9):
            return TrainingFailed("The training process was killed (SIGKILL) by the system, most likely because "
                                  "memory ran out. Train with a smaller batch or network, or close other programs."
                                  + (f" Last output: {last}" if last else ""), "out_of_memory", status, tail)
        return TrainingFailed(f"The training process was ended by {name}." + (f" Last output: {last}" if last else ""),
                              "killed", status, tail)
    return TrainingFailed(f"The training process stopped with exit status {status}: {last or 'no error message'}",
                          "crash", status, tail)


def _group_kwargs() -> dict:
    if sys.platform == "win32":
        return {"creationflags": getattr(subprocess, "CREATE_NEW_PROCESS_GROUP", 0)
                | getattr(subprocess, "CREATE_NO_WINDOW", 0)}
    return {"start_new_session": True}  # its own process group: a stop reaches whatever it started


def _signal_group(process: subprocess.Popen, hard: bool) -> None:
    """SIGTERM (hard: SIGKILL) to the child's process group; on Windows CTRL_BREAK, then TerminateProcess."""
    if process.poll() is not None and not hard:
        return
    try:
        if sys.platform == "win32":
            if hard:
                process.kill()
            else:
                process.send_signal(signal.CTRL_BREAK_EVENT)
        else:
            os.killpg(process.pid, signal.SIGKILL if hard else signal.SIGTERM)
    except (ProcessLookupError, PermissionError, OSError):
        pass


def stop_group(process: subprocess.Popen, grace_s: float) -> None:
    """End the child and its group: a polite stop, then a kill after ``grace_s``; wait for it."""
    _signal_group(process, hard=False)
    try:
        process.wait(timeout=grace_s)
    except subprocess.TimeoutExpired:
        pass
    _signal_group(process, hard=True)  # whatever of the group is still there (the child's own children)
    if process.poll() is None:
        process.kill()
    process.wait()


class ChildRun:
    """What came back from a child: its events by type, the last ``result`` and ``error``, the pid."""

    def __init__(self):
        self.pid: int | None = None
        self.events: list[dict] = []
        self.result: dict | None = None
        self.error: dict | None = None
        self.stderr_tail: collections.deque = collections.deque(maxlen=40)
        self.started = time.perf_counter()
        self.first_event_s: float | None = None
        self.status: int | None = None


def run_child(command: Sequence[str], on_event: Callable[[dict], None], is_canceled: Callable[[], bool] = lambda: False,
              env: dict | None = None, cwd=None, grace_s: float = 10.0, poll_s: float = 0.1,
              on_start: Callable[[subprocess.Popen], None] | None = None) -> ChildRun:
    """Run ``command`` and pass each event to ``on_event`` as it arrives (in the caller's thread).

    Raises :class:`Cancelled` after stopping the child (and its group) when ``is_canceled()`` turns true,
    :class:`~..errors.InputError` when the child reports input the user can fix, and
    :class:`TrainingFailed` for any other non-zero exit. Returns the run on a clean exit.
    """
    run = ChildRun()
    process = subprocess.Popen(list(command), stdout=subprocess.PIPE, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
                               env=env, cwd=None if cwd is None else str(cwd), text=True, encoding="utf-8",
                               errors="replace", bufsize=1, **_group_kwargs())
    run.pid = process.pid
    if on_start is not None:
        on_start(process)
    lines: queue.Queue = queue.Queue()

    def read_stdout() -> None:
        for line in process.stdout:
            lines.put(line)
        lines.put(None)

    def read_stderr() -> None:
        for line in process.stderr:
            run.stderr_tail.append(line.rstrip("\r\n"))

    readers = [threading.Thread(target=read_stdout, daemon=True), threading.Thread(target=read_stderr, daemon=True)]
    for reader in readers:
        reader.start()
    def receive(line: str) -> None:
        event = decode(line)
        if run.first_event_s is None:
            run.first_event_s = time.perf_counter() - run.started
        run.events.append(event)
        if event["type"] == "result":
            run.result = event
        elif event["type"] == "error":
            run.error = event
        on_event(event)

    try:
        if relay_lines(lines, receive, is_canceled, poll_s):
            stop_group(process, grace_s)
            # what the child said while it stopped (its last checkpoint) still counts
            while True:
                try:
                    line = lines.get(timeout=1.0)
                except queue.Empty:
                    break
                if line is None:
                    break
                event = decode(line)
                run.events.append(event)
                if event["type"] in ("checkpoint", "result"):
                    on_event(event)
            raise Cancelled()
        run.status = process.wait()
    finally:
        if process.poll() is None:
            stop_group(process, grace_s)
        for reader in readers:
            reader.join(timeout=5)
        process.stdout.close()
        process.stderr.close()
    run.status = process.returncode
    if run.status == EXIT_INPUT and run.error is not None and run.error.get("kind") == "input":
        raise InputError(run.error.get("text", "bad input"))
    if run.status != 0:
        raise failure(run.status, list(run.stderr_tail), run.error)
    if run.result is None:
        raise failure(run.status, list(run.stderr_tail) + ["the training process ended without a result"], run.error)
    return run


def relay_lines(lines: queue.Queue, handle: Callable[[str], None], is_canceled: Callable[[], bool],
                poll_s: float) -> bool:
    """Pass each line a reader thread puts on ``lines`` to ``handle`` (in the caller's thread) until the
    reader's closing None; True when ``is_canceled()`` turned true first (checked every ``poll_s``)."""
    while True:
        if is_canceled():
            return True
        try:
            line = lines.get(timeout=poll_s)
        except queue.Empty:
            continue
        if line is None:
            return False
        handle(line)


def process_alive(pid: int) -> bool:
    """Whether a process with ``pid`` still exists (and is not a zombie); POSIX (on Windows
    ``os.kill`` would end the process)."""
    try:
        with open(f"/proc/{pid}/stat", encoding="utf-8") as f:
            return f.read().split(")")[-1].split()[0] != "Z"
    except OSError:
        pass
    try:
        os.kill(pid, 0)
    except OSError:
        return False
    return True
