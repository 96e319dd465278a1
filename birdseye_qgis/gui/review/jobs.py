"""Work the review dock hands to its thread pool: chips and scores, reported back through signals."""
from __future__ import annotations

from collections import OrderedDict

from qgis.PyQt.QtCore import QObject, QRunnable, pyqtSignal

from ...core.review.chips import ImageCache, load_chips
from ...core.scoring.evaluation import evaluate_flights


class JobSignals(QObject):
    """Carries worker results to the UI thread (parentless: workers keep it alive)."""

    chips_ready = pyqtSignal(int, str, object)
    scores_ready = pyqtSignal(int, object)


class ChipJob(QRunnable):
    """Plans and renders one unit's chips off the UI thread; the result carries the dock's generation."""

    def __init__(self, signals, generation, key, plan_fn, out_px, pixels):
        super().__init__()
        self.signals, self.generation, self.key = signals, generation, key
        self.plan_fn, self.out_px, self.pixels = plan_fn, out_px, pixels

    def run(self):
        try:
            plans, n_frames = self.plan_fn(self.key)
            images = load_chips(plans, self.out_px, self.pixels)
            payload = (plans, images, n_frames, None)
        except Exception as exc:  # noqa: BLE001 — report in the dock, never kill the worker thread
            payload = ([], [], 0, str(exc))
        self.signals.chips_ready.emit(self.generation, self.key, payload)


class ScoreJob(QRunnable):
    """Scores every flight (PRE and POST, all conventions) off the UI thread."""

    def __init__(self, signals, generation, flights, geotags, op, log):
        super().__init__()
        self.signals, self.generation = signals, generation
        self.flights, self.geotags, self.op, self.log = flights, geotags, op, log

    def run(self):
        try:
            result = {f.name: evaluate_flights([f], self.geotags, self.op, self.log).to_dict() for f in self.flights}
        except Exception as exc:  # noqa: BLE001
            result = exc
        self.signals.scores_ready.emit(self.generation, result)


class ChipLoader(QObject):
    """Chips of the units: loaded in the thread pool, the current unit first and its neighbours ahead of
    the reviewer, kept for the last :data:`CACHE_UNITS` units. ``loaded(key)`` says a unit's chips arrived;
    :meth:`reset` drops what was loaded or is in flight (new inputs, another window size). ``pixels`` is where
    the chips' pixels come from (``window(plan)``, see :func:`..core.review.chips.load_chips`): the frames'
    image cache (``frame_images``), or the reader of the raster the detections were found on."""

    CACHE_UNITS = 64
    PREFETCH_AHEAD = 3
    loaded = pyqtSignal(str)

    def __init__(self, pool, out_px: int):
        super().__init__()
        self.pool, self.out_px = pool, out_px
        self.chips: OrderedDict = OrderedDict()
        self.pending: set = set()
        self.frame_images = ImageCache(24)
        self.pixels = self.frame_images
        self.generation = 0
        self._signals = JobSignals()
        self._signals.chips_ready.connect(self._on_chips)

    def reset(self) -> None:
        self.generation += 1
        self.chips.clear()
        self.pending.clear()

    def get(self, key):
        """(plans, images, n_frames, error) of a loaded unit, now the most recently used."""
        self.chips.move_to_end(key)
        return self.chips[key]

    def request(self, key, planner, priority: int = 0) -> None:
        """Load ``key``'s chips with ``planner(key) -> (plans, n_frames)`` unless loaded or under way."""
        if key in self.chips or key in self.pending:
            return
        self.pending.add(key)
        self.pool.start(ChipJob(self._signals, self.generation, key, planner, self.out_px, self.pixels),
                        priority)

    def prefetch(self, shown, key, planner_for) -> None:
        """The next few shown units after ``key`` and the one before it."""
        if key not in shown:
            return
        p = shown.index(key)
        for k in shown[p + 1:p + 1 + self.PREFETCH_AHEAD] + shown[max(0, p - 1):p]:
            self.request(k, planner_for(k))

    def _on_chips(self, generation, key, payload):
        if generation != self.generation:
            return
        self.pending.discard(key)
        self.chips[key] = payload
        while len(self.chips) > self.CACHE_UNITS:
            self.chips.popitem(last=False)
        self.loaded.emit(key)
