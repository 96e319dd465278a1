"""The training process of ``birdseye:traindetector``: ``python -m birdseye_qgis.core.train.child JOB.json``.

Started by the algorithm (:func:`.protocol.run_child`) with the plugin folder on ``PYTHONPATH``, in a
Python that has torch. Reads the job (:class:`.job.TrainJob`), runs it (:func:`.job.run_job`) and
writes the events of :mod:`.protocol` on stdout, one JSON object per line. SIGTERM (CTRL_BREAK on
Windows) ends training at the next step: the checkpoint is written and the process exits with
:data:`.protocol.EXIT_STOPPED`. Input the user can fix exits with :data:`.protocol.EXIT_INPUT` and an
``error`` event; any other failure prints its traceback on stderr and exits 1.
"""
from __future__ import annotations

import signal
import sys
import traceback
from pathlib import Path

from ..errors import InputError
from .protocol import EXIT_INPUT, EXIT_STOPPED, encode


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1:
        print("usage: python -m birdseye_qgis.core.train.child JOB.json", file=sys.stderr)
        return EXIT_INPUT
    try:
        sys.stdout.reconfigure(line_buffering=True, encoding="utf-8")
    except (AttributeError, ValueError):
        pass
    stop = {"requested": False}

    def request_stop(signum, frame) -> None:
        stop["requested"] = True

    for name in ("SIGTERM", "SIGBREAK", "SIGINT"):
        if hasattr(signal, name):
            signal.signal(getattr(signal, name), request_stop)

    def emit(event: dict) -> None:
        sys.stdout.write(encode(event) + "\n")
        sys.stdout.flush()

    try:
        from .job import TrainJob, run_job

        job = TrainJob.from_json(Path(argv[0]).read_text(encoding="utf-8"))
        result = run_job(job, emit, should_stop=lambda: stop["requested"])
    except InputError as exc:
        emit({"type": "error", "kind": "input", "text": str(exc)})
        return EXIT_INPUT
    except BaseException as exc:  # noqa: BLE001 — every failure is reported to the parent
        traceback.print_exc(file=sys.stderr)
        sys.stderr.flush()
        emit({"type": "error", "kind": "crash", "text": f"{type(exc).__name__}: {exc}"})
        return 1
    return EXIT_STOPPED if result.get("stopped") else 0


if __name__ == "__main__":
    sys.exit(main())
