"""Killing a review in the middle loses no committed verdict and leaves a consistent log.

A child process runs a scripted review through the same session code the dock uses
(``review_store.ReviewSession``: verdicts with and without propagation, undos, added targets; each
action committed with the cursor before the next) and prints each action's number once it returned,
i.e. once committed. The test kills it with SIGKILL three times: once while it holds an open
transaction (the action's rows inserted, COMMIT not yet issued — the child announces it), once in
full flight wherever it is, and once more while holding; fresh processes resume from the log each
time, and a last one finishes. After each kill:

* ``PRAGMA integrity_check`` is ok and every row is complete (required fields, JSON, geometry);
* every action the child reported is in the log, and the log is *exactly* the script's first M
  actions replayed from scratch (same rows, in order, no partial action): nothing lost, nothing torn;
* the saved cursor belongs to the last committed action (written in its transaction).

Run for the GeoPackage in rollback-journal mode and in WAL mode (QGIS switches GeoPackages to WAL).
"""
from __future__ import annotations

import json
import os
import signal
import sqlite3
import struct
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
PLUGIN_PATH = REPO_ROOT / "build" / "pluginpath"

SCRIPT = textwrap.dedent(f'''
    import json
    import sys
    import time

    sys.path.insert(0, {str(PLUGIN_PATH)!r})
    import numpy as np

    from birdseye.birdseye_qgis.core.review.actions import Ledger
    from birdseye.birdseye_qgis.core.review.units import ReviewLayer, ReviewParameters, build_units
    from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
    from birdseye.birdseye_qgis.core.field.geotags import Geotags
    from birdseye.birdseye_qgis.core.scoring.evaluation import Detections
    from birdseye.birdseye_qgis.qgis_io.review_store import ReviewSession, VerdictStore

    SITE = LocalFrame(-27.55, 151.95, 400.0)
    VERDICTS = ("confirmed_real", "hard_negative", "uncertain")
    DIGESTS = {{"detections:model": "d" * 64, "frames:frames": "f" * 64, "geotags:geotags": "g" * 64}}


    def scripted_units():
        """24 spots of 9 detections; spots come in pairs 0.18 m apart (separate units with DBSCAN's
        EPS 0.10 m, one propagation group within EPS_PRED 0.20 m), pairs 2 m apart."""
        centres = [(2.0 * (k // 2), 0.18 * (k % 2)) for k in range(24)]
        xy = np.array([(cx + dx, cy + dy) for cx, cy in centres for dx in (-0.03, 0, 0.03) for dy in (-0.03, 0, 0.03)])
        lat, lon, h = SITE.to_geodetic(np.column_stack([xy, np.zeros(len(xy))]))
        det = Detections(lat, lon, h, np.arange(len(xy)) % 5, np.full(len(xy), 0.8), name="model")
        empty = Geotags(np.array([], dtype=object), [], [], [])
        return build_units([ReviewLayer(det, np.zeros(len(xy)), np.zeros(len(xy)))], SITE, empty, [],
                           ReviewParameters(eps_m=0.10, min_samples=3, eps_pred_m=0.20))


    def action(k, ledger, units):
        """The k-th action (from 1) of the scripted review, given the log so far."""
        if k % 7 == 0:
            return ("undo",)
        if k % 11 == 0:
            return ("add", -27.55 - 1e-5 * k, 151.95 + 1e-5 * k)
        key = units.keys[units.order[k % len(units)]]
        current = ledger.direct(key)
        verdict = next(v for v in VERDICTS[k % 3:] + VERDICTS[:k % 3] if v != current)
        return ("verdict", key, verdict, k % 2 == 0)


    def planned(step, ledger, units):
        """(rows, undoes) the step appends, planned by the same core the session uses."""
        if step[0] == "undo":
            undoes, rows = ledger.plan_undo()
            return rows, undoes
        if step[0] == "add":
            return ledger.plan_add(step[1], step[2]), None
        _, key, verdict, propagate = step
        i = units.index[key]
        return ledger.plan_verdict(units.ref(i), verdict, [units.ref(j) for j in units.neighbours(i)],
                                   propagate), None


    def hold_commit(at_action, current):
        """Test hook: before committing action ``at_action``, announce it and wait to be killed."""
        commit = VerdictStore._Txn.__exit__

        def exit_(self, kind, value, tb):
            if kind is None and current[0] == at_action:
                rows = self.c.execute("SELECT COUNT(*) FROM birdseye_verdicts WHERE action_id = ?",
                                      (at_action,)).fetchone()[0]
                print(f"holding {{at_action}} {{rows}}", flush=True)
                time.sleep(120)
            return commit(self, kind, value, tb)

        VerdictStore._Txn.__exit__ = exit_


    def main(path, limit, hold):
        current = [0]
        if hold:
            hold_commit(hold, current)
        units = scripted_units()
        session = ReviewSession(VerdictStore(path), units, "crash-bot", DIGESTS)
        k = max((r["action_id"] for r in session.ledger.rows), default=0)
        while k < limit:
            k += 1
            current[0] = k
            step = action(k, session.ledger, units)
            cursor = {{"unit_key": units.keys[units.order[(k + 1) % len(units)]], "k": k}}
            if step[0] == "undo":
                session.undo(cursor_for=lambda key: dict(cursor, unit_key=key))
            elif step[0] == "add":
                session.add_target(step[1], step[2], cursor=cursor)
            else:
                session.set_verdict(step[1], step[2], step[3], cursor=cursor)
            print(k, flush=True)


    if __name__ == "__main__":
        main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
''')

LIMIT = 400


@pytest.fixture(scope="module")
def script(tmp_path_factory):
    path = tmp_path_factory.mktemp("crash") / "scripted_review.py"
    path.write_text(SCRIPT)
    namespace = {"__name__": "scripted_review"}
    exec(compile(SCRIPT, str(path), "exec"), namespace)   # the parent replays the same script
    return path, namespace


def run_and_kill(script_path, store, after_lines=None, hold=0):
    """Start the scripted review and SIGKILL it once it reported ``after_lines`` committed actions,
    or while it holds action ``hold``'s transaction open; let it finish when neither is given.
    Returns the action numbers it reported committed, and the rows it held uncommitted."""
    child = subprocess.Popen([sys.executable, str(script_path), str(store), str(LIMIT), str(hold)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    reported, held = [], 0
    try:
        for line in child.stdout:
            if line.startswith("holding"):
                _, action, held = line.split()
                held = int(held)
                assert int(action) == hold
                os.kill(child.pid, signal.SIGKILL)
                break
            reported.append(int(line))
            if after_lines is not None and len(reported) >= after_lines:
                os.kill(child.pid, signal.SIGKILL)
                break
        child.wait(timeout=60)
        # What the child printed before the kill landed but the loop had not read yet: the child runs on
        # while the parent reads, so the last line read is not the last action the child reported.
        reported.extend(int(line) for line in child.stdout if not line.startswith("holding"))
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
    stderr = child.stderr.read()
    if after_lines is None and not hold:
        assert child.returncode == 0, stderr
    else:
        assert child.returncode == -signal.SIGKILL, stderr
    return reported, held


def check_log(store, namespace, reported):
    """Integrity, complete rows, the exact replay of the script's first M actions, the cursor."""
    from birdseye.birdseye_qgis.core.review.actions import Ledger
    from birdseye.birdseye_qgis.qgis_io.review_store import STATE_TABLE, VERDICT_FIELD_NAMES, VERDICT_TABLE

    c = sqlite3.connect(store)
    try:
        assert c.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
        rows = [dict(zip(VERDICT_FIELD_NAMES + ["geom"], r)) for r in
                c.execute(f"SELECT {', '.join(VERDICT_FIELD_NAMES)}, geom FROM {VERDICT_TABLE} ORDER BY fid")]
        state = dict(c.execute(f"SELECT key, value FROM {STATE_TABLE}").fetchall())
    finally:
        c.close()
    for r in rows:
        for name in ("unit_key", "verdict", "provenance", "action_id", "action", "time", "reviewer", "lat", "lon",
                     "layers_fired", "matching_parameters", "postprocessing", "input_digests"):
            assert r[name] is not None, (name, r)
        for name in ("layers_fired", "matching_parameters", "postprocessing", "input_digests"):
            json.loads(r[name])
        assert r["geom"][:2] == b"GP" and struct.unpack("<dd", r["geom"][13:29]) == (r["lon"], r["lat"])
    # Nothing reported is missing; at most the one action committed before it could be reported.
    actions = sorted({r["action_id"] for r in rows})
    m = len(actions)
    assert actions == list(range(1, m + 1))
    assert not reported or reported[-1] <= m <= reported[-1] + 1
    # The log is the script replayed: every action whole, in order.
    units = namespace["scripted_units"]()
    ledger = Ledger()
    for k in range(1, m + 1):
        step = namespace["action"](k, ledger, units)
        expected, undoes = namespace["planned"](step, ledger, units)
        got = [r for r in rows if r["action_id"] == k]
        assert [(p.unit_key, p.verdict, p.provenance, p.lat, p.lon) for p in expected] == \
            [(r["unit_key"], r["verdict"], r["provenance"], r["lat"], r["lon"]) for r in got], f"action {k}"
        assert {r["action"] for r in got} == {"undo" if step[0] == "undo" else step[0]}
        assert {r["undoes"] for r in got} == {undoes}
        ledger.extend(got)
    # The cursor was written with the last committed action.
    (cursor,) = [json.loads(v) for k, v in state.items() if k.startswith("cursor/")]
    assert cursor["k"] == m
    return m


@pytest.mark.parametrize("journal", ["delete", "wal"])
def test_killing_a_review_loses_no_committed_verdict(script, tmp_path, journal):
    from birdseye.birdseye_qgis.qgis_io.review_store import VerdictStore

    script_path, namespace = script
    store = tmp_path / "review.gpkg"
    VerdictStore(store).close()                          # a fresh GeoPackage with the log's tables
    c = sqlite3.connect(store)
    assert c.execute(f"PRAGMA journal_mode={journal}").fetchone()[0] == journal
    c.close()

    # Killed inside a transaction: the action's rows were inserted, none may survive.
    first, held = run_and_kill(script_path, store, hold=32)   # action 32: a verdict propagated to a neighbour
    assert held == 2 and first[-1] == 31
    assert check_log(store, namespace, first) == 31
    # Killed wherever it happens to be.
    second, _ = run_and_kill(script_path, store, after_lines=40)
    assert second[0] == 32                               # resumed exactly after the last committed action
    m2 = check_log(store, namespace, second)
    assert m2 >= 71
    third, held = run_and_kill(script_path, store, hold=m2 + 30)
    assert held >= 1 and third[0] == m2 + 1
    assert check_log(store, namespace, third) == m2 + 29
    last, _ = run_and_kill(script_path, store)
    assert last[0] == m2 + 30 and last[-1] == LIMIT
    assert check_log(store, namespace, last) == LIMIT
    # The GeoPackage is still one: OGR lists the verdict layer with every row.
    from osgeo import ogr

    ds = ogr.Open(str(store))
    layer = ds.GetLayerByName("birdseye_verdicts")
    assert layer is not None and layer.GetFeatureCount() == sum(1 for _ in sqlite3.connect(store).execute(
        "SELECT fid FROM birdseye_verdicts"))
    ds = None
