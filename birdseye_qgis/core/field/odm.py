"""Processing a flight on an OpenDroneMap node (NodeODM, ClusterODM, or WebODM's processing node).

The node runs OpenDroneMap's full structure from motion on its own hardware; BirdsEye uploads the
images, waits, and downloads only the reconstruction (``opensfm/reconstruction*.json`` and
``reference_lla.json``), which :func:`.solutions.import_camera_solution` reads like any OpenSfM result.
Talks to the node through ``pyodm``, the NodeODM API's Python client.
"""
from __future__ import annotations

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
    20–90 % (the node's own estimate), download 90–100 %. Cancel stops waiting and cancels the task
    on the node.
    """
    from pyodm import Node
    from pyodm.exceptions import NodeConnectionError, NodeResponseError, TaskFailedError

    images = sorted(str(p) for p in Path(images_folder).iterdir() if p.suffix.lower() in IMAGE_SUFFIXES)
    if len(images) < 2:
        raise InputError(f"holds {len(images)} image(s); OpenDroneMap needs at least two", source=str(images_folder))

    def report(fraction):
        if progress is not None:
            progress(fraction)

    def check_cancel():
        if is_canceled is not None and is_canceled():
            raise Cancelled()

    try:
        node = Node.from_url(node_url)
        if token:
            node.token = token
        info = node.info()
        if log is not None:
            log(f"node {node_url}: {info.engine} {info.engine_version}, {info.task_queue_count} task(s) queued")
        task = node.create_task(images, options or {}, name=f"BirdsEye {Path(images_folder).name}",
                                outputs=RECONSTRUCTION_OUTPUTS, skip_post_processing=True,
                                progress_callback=lambda percent: report(0.2 * percent / 100.0))
        check_cancel()

        def status(task_info):
            report(0.2 + 0.7 * float(task_info.progress or 0) / 100.0)
            if is_canceled is not None and is_canceled():
                task.cancel()
                raise Cancelled()

        task.wait_for_completion(status_callback=status, interval=2)
        task.download_assets(str(destination))
    except (NodeConnectionError, NodeResponseError) as exc:
        raise InputError(f"the OpenDroneMap node did not answer as expected ({exc})", source=node_url) from exc
    except TaskFailedError as exc:
        raise InputError(f"OpenDroneMap failed on the node ({exc}); see the task's console output there",
                         source=node_url) from exc
    report(1.0)
    found = Path(destination) / "opensfm" / "reconstruction.json"
    if not found.is_file():
        raise InputError("the task's archive holds no opensfm/reconstruction.json", source=node_url)
    return found
