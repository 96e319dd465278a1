"""A local stand-in for a NodeODM node: the API endpoints pyodm calls (NodeODM's REST API: /info,
/task/new/init, /task/new/upload/<uuid>, /task/new/commit/<uuid>, /task/<uuid>/info,
/task/<uuid>/download/all.zip, /task/cancel, /task/remove), answering with a prepared OpenSfM
reconstruction instead of running OpenDroneMap. Like NodeODM, it takes the task id a client proposes
(header ``set-uuid``) and refuses to commit an upload without images. It records what it received, so
tests can check the upload; ``upload_delay_s`` makes each image's upload take that long."""
from __future__ import annotations

import io
import json
import re
import threading
import time
import uuid as uuidlib
import zipfile
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from urllib.parse import parse_qs

QUEUED, RUNNING, FAILED, COMPLETED, CANCELED = 10, 20, 30, 40, 50


class NodeOdmStub:
    def __init__(self, archive_files: dict, polls_until_done: int = 2, fail: bool = False,
                 upload_delay_s: float = 0.0):
        self.archive_files = archive_files  # path inside all.zip -> bytes
        self.polls_until_done = polls_until_done
        self.fail = fail
        self.upload_delay_s = upload_delay_s
        self.tasks: dict[str, dict] = {}
        self.cancelled: list[str] = []
        self.removed: list[str] = []
        self.downloads = 0
        self.uploaded: list[str] = []
        self.init_fields = b""
        stub = self

        class Handler(BaseHTTPRequestHandler):
            def log_message(self, *args):
                pass

            def _json(self, payload, code=200):
                body = json.dumps(payload).encode()
                self.send_response(code)
                self.send_header("Content-Type", "application/json")
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)

            def _body(self) -> bytes:
                return self.rfile.read(int(self.headers.get("Content-Length") or 0))

            def do_GET(self):
                path = self.path.split("?", 1)[0]
                if path == "/info":
                    return self._json({"version": "2.2.1", "taskQueueCount": 0, "maxImages": None,
                                       "engine": "odm", "engineVersion": "3.5.0", "maxParallelTasks": 1})
                m = re.fullmatch(r"/task/([\w-]+)/info", path)
                if m and m.group(1) in stub.tasks:
                    task = stub.tasks[m.group(1)]
                    task["polls"] += 1
                    if task["code"] == RUNNING and task["polls"] >= stub.polls_until_done:
                        task["code"] = FAILED if stub.fail else COMPLETED
                    return self._json({"uuid": m.group(1), "name": "t", "dateCreated": 1700000000000,
                                       "processingTime": 1000, "status": {"code": task["code"]}, "options": [],
                                       "imagesCount": len(stub.uploaded),
                                       "progress": 100 if task["code"] == COMPLETED else 50})
                m = re.fullmatch(r"/task/([\w-]+)/download/all.zip", path)
                if m and m.group(1) in stub.tasks:
                    stub.downloads += 1
                    buffer = io.BytesIO()
                    with zipfile.ZipFile(buffer, "w") as archive:
                        for name, data in stub.archive_files.items():
                            archive.writestr(name, data)
                    body = buffer.getvalue()
                    self.send_response(200)
                    self.send_header("Content-Type", "application/zip")
                    self.send_header("Content-Length", str(len(body)))
                    self.end_headers()
                    self.wfile.write(body)
                    return None
                return self._json({"error": f"no route {path}"}, 404)

            def do_POST(self):
                path = self.path.split("?", 1)[0]
                body = self._body()
                if path == "/task/new/init":
                    stub.init_fields = body
                    task_id = self.headers.get("set-uuid") or str(uuidlib.uuid4())
                    stub.tasks[task_id] = {"code": None, "polls": 0, "images": 0}
                    return self._json({"uuid": task_id})
                m = re.fullmatch(r"/task/new/upload/([\w-]+)", path)
                if m:
                    time.sleep(stub.upload_delay_s)
                    names = re.findall(rb'filename="([^"]+)"', body)
                    stub.uploaded += names
                    stub.tasks[m.group(1)]["images"] += len(names)
                    return self._json({"success": True})
                m = re.fullmatch(r"/task/new/commit/([\w-]+)", path)
                if m:
                    task = stub.tasks[m.group(1)]
                    if not task["images"]:
                        del stub.tasks[m.group(1)]
                        return self._json({"error": "Need at least 1 file."})
                    task["code"] = RUNNING
                    return self._json({"uuid": m.group(1)})
                if path in ("/task/cancel", "/task/remove"):
                    task_id = parse_qs(body.decode()).get("uuid", [""])[0]
                    if stub.tasks.get(task_id, {}).get("code") is None:
                        return self._json({"error": "Invalid uuid"})
                    if path == "/task/cancel":
                        stub.tasks[task_id]["code"] = CANCELED
                        stub.cancelled.append(task_id)
                    else:
                        stub.removed.append(task_id)
                        del stub.tasks[task_id]
                    return self._json({"success": True})
                return self._json({"error": f"no route {path}"}, 404)

        self.server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.url = f"http://127.0.0.1:{self.server.server_address[1]}"
        self.thread = threading.Thread(target=self.server.serve_forever, daemon=True)

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self.server.shutdown()
        self.server.server_close()
