"""Processing a flight on an OpenDroneMap node (NodeODM, ClusterODM, or WebODM's processing node).

The node runs OpenDroneMap's full structure from motion on its own hardware; BirdsEye uploads the
images, waits, and downloads only the reconstruction (``opensfm/reconstruction*.json`` and
``reference_lla.json``), which :func:`.solutions.import_camera_solution` reads like any OpenSfM result.
Talks to the node through ``pyodm``, the NodeODM API's Python client.
"""
from __future__ import annotations

import threading
import uuid
from pathlib import Path

from ..errors import Cancelled, InputError
from .solutions import IMAGE_SUFFIXES

#: What the node is asked to put in the task's archive: the camera solution and its geographic reference.
RECONSTRUCTION_OUTPUTS = ["opensfm/reconstruction.json", "opensfm/reconstruction.topocentric.json",
                          "opensfm/reference_lla.json"]


def parse_options(text: str) -> dict:
    """ODM options from ``name=value`` pairs separated by commas, semicolons or new lines."""
    options = {}
    for k, item in enumerate(part.strip() for part in text.replace(";", ",").replace("\n", ",").split(",")):
        if not item:
            continue
        if "=" not in item:
            raise InputError(f"option {k + 1} ({item!r}) is not name=value, e.g. feature-quality=high",
                             field="ODM_OPTIONS")
        name, value = (v.strip() for v in item.split("=", 1))
        low = value.lower()
        options[name] = True if low == "true" else False if low == "false" else _number_or_text(value)
    return options


def _number_or_text(value: str):
    for kind in (int, float):
        try:
            return kind(value)
        except ValueError:
            continue
    return value


def process_on_node(images_folder, node_url: str, destination, options: dict | None = None, token: str = "",
                    progress=None, is_canceled=None, log=None) -> Path:
    """Upload the folder's images to the node, wait for OpenDroneMap, download the reconstruction.

    Returns the downloaded ``opensfm/reconstruction.json``. Progress: upload 0–20 %, processing
    20–90 % (the node's own estimate), download 90–100 %. Cancel, at any stage, removes the task from
    the node (:func:`_discard`) and raises :class:`Cancelled`; during the upload it does not wait for the
    images in flight.
    """
    from pyodm import Node
    from pyodm.exceptions import NodeConnectionError, NodeResponseError, TaskFailedError

    images = sorted(str(p) for p in Path(images_folder).iterdir() if p.suffix.lower() in IMAGE_SUFFIXES)
    if len(images) < 2:
        raise InputError(f"holds {len(images)} image(s); OpenDroneMap needs at least two", source=str(images_folder))

    def report(fraction):
        if progress is not None:
            progress(fraction)

    def canceled():
        return is_canceled is not None and is_canceled()

    destination = Path(destination)
    # Our own task id: the node knows the task by it from the first upload on, so cancel can remove it.
    task_uuid = str(uuid.uuid4())
    task = None
    try:
        node = Node.from_url(node_url)
        if token:
            node.token = token
        info = node.info()
        if log is not None:
            log(f"node {node_url}: {info.engine} {info.engine_version}, {info.task_queue_count} task(s) queued")
        task = _upload(node, images, options or {}, f"BirdsEye {Path(images_folder).name}", task_uuid, report,
                       canceled)

        def status(task_info):
            report(0.2 + 0.7 * float(task_info.progress or 0) / 100.0)
            if canceled():
                raise Cancelled()

        def downloaded(percent):
            if canceled():
                raise Cancelled()
            report(0.9 + 0.1 * percent / 100.0)

        task.wait_for_completion(status_callback=status, interval=2)
        task.download_assets(str(destination), progress_callback=downloaded)
    except Cancelled:
        if task is not None:  # else the upload's thread removes it once the images in flight are up
            _discard(node, task_uuid, committed=True)
        for partial in destination.glob(f"{task_uuid}_*_all.zip*"):
            partial.unlink()
        if log is not None:
            log(f"cancelled: task {task_uuid} is being removed from the node")
        raise
    except (NodeConnectionError, NodeResponseError) as exc:
        raise InputError(f"the OpenDroneMap node did not answer as expected ({exc})", source=node_url) from exc
    except TaskFailedError as exc:
        raise InputError(f"OpenDroneMap failed on the node ({exc}); see the task's console output there",
                         source=node_url) from exc
    report(1.0)
    found = destination / "opensfm" / "reconstruction.json"
    if not found.is_file():
        raise InputError("the task's archive holds no opensfm/reconstruction.json", source=node_url)
    return found


def _upload(node, images, options, name, task_uuid, report, canceled):
    """pyodm's upload in a thread, so that cancel returns at once instead of after the images in flight.

    pyodm consults its progress callback only when an image has gone up and others are still queued;
    once cancelled, the callback raises there and no further image is sent. Whatever happened to the
    upload, the thread then removes the task, committed or not, from the node (:func:`_discard`).
    """
    stop, lock = threading.Event(), threading.Lock()
    outcome = {"percent": 0.0}

    def uploaded(percent):
        if stop.is_set():
            raise Cancelled()
        outcome["percent"] = percent

    def run():
        try:
            outcome["task"] = node.create_task(images, options, name=name, outputs=RECONSTRUCTION_OUTPUTS,
                                               skip_post_processing=True, progress_callback=uploaded,
                                               task_uuid=task_uuid)
        except Exception as exc:  # noqa: BLE001 — handed to the caller's thread, which re-raises it
            outcome["error"] = exc
        with lock:  # a cancel either reaches this thread before it finishes, or the caller sees it finished
            outcome["done"] = True
            cancelled = stop.is_set()
        if cancelled:
            _discard(node, task_uuid, committed="task" in outcome)

    thread = threading.Thread(target=run, name=f"odm-upload-{task_uuid}", daemon=True)
    thread.start()
    while thread.is_alive():
        thread.join(0.2)
        report(0.2 * outcome["percent"] / 100.0)
        if canceled():
            with lock:
                handed_over = "done" not in outcome
                if handed_over:
                    stop.set()
            if handed_over:
                raise Cancelled()
    if "error" in outcome:
        raise outcome["error"]
    return outcome["task"]


def _discard(node, task_uuid: str, committed: bool) -> None:
    """Cancel and remove the task on the node, as far as the node lets us (it may be unreachable).

    NodeODM keeps an uncommitted upload in its temporary folder with no call to remove it, so a
    cancelled upload is committed first: the node then knows the task, and cancel + remove delete it.
    """
    from pyodm.api import Task
    from pyodm.exceptions import OdmError

    try:
        if not committed:
            node.post(f"/task/new/commit/{task_uuid}")
        task = Task(node, task_uuid)
        task.cancel()
        task.remove()
    except (OdmError, OSError):
        pass  # an uncommitted upload without images is refused by commit and deleted by the node itself
