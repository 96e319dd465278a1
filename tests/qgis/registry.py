"""Running BirdsEye algorithms through the Processing registry, as the toolbox does, for the QGIS tests."""
import csv

from qgis.core import QgsProcessingFeedback


class Recorder(QgsProcessingFeedback):
    """Feedback that keeps what an algorithm reported (``errors``, ``warnings``, ``infos``), so tests can read
    the log; it still goes to QGIS's own log too."""

    def __init__(self):
        super().__init__()
        self.errors, self.warnings, self.infos = [], [], []

    def reportError(self, error, fatalError=False):  # noqa: N802, N803 — QGIS's names
        self.errors.append(error)
        super().reportError(error, fatalError)

    def pushWarning(self, warning):  # noqa: N802 — QGIS's name
        self.warnings.append(warning)
        super().pushWarning(warning)

    def pushInfo(self, info):  # noqa: N802 — QGIS's name
        self.infos.append(info)
        super().pushInfo(info)


def run(alg_id, params, feedback=None):
    """``birdseye:<alg_id>`` with ``params``; its results."""
    import processing

    return processing.run(f"birdseye:{alg_id}", params, feedback=feedback)


def imported_campaign(folder, config):
    """A simulated campaign (``core.sim.campaign.CampaignConfig``) written to ``folder`` and imported as the
    toolbox imports one: (its geotags layer, its frame layer), both temporary."""
    from birdseye.birdseye_qgis.core.sim.campaign import simulate_campaign

    simulate_campaign(config, folder)
    geotags = run("importgeotags", {"INPUT": str(folder / "geotags.csv"), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    frames = run("importflightlog", {"POSE_LOG": str(folder / "poses.csv"), "IMAGES": str(folder / "frames"),
                                     "CALIBRATION": str(folder / "calibration.yaml"),
                                     "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    return geotags, frames


def rows(path):
    """The rows of a CSV file an algorithm wrote, as dicts."""
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def simulated_terrain_campaign(folder, campaign: dict) -> dict:
    """``simulatecampaign`` with ``campaign`` into ``folder``, then its geotags and flight log imported, the
    frames placed on the simulated DEM (ellipsoidal heights). Returns the simulation's results with the
    ``dem`` layer, ``geotags`` and ``frames``."""
    from qgis.core import QgsRasterLayer

    sim = run("simulatecampaign", {**campaign, "OUTPUT_FOLDER": str(folder)})
    dem = QgsRasterLayer(sim["DEM"], "terrain")
    assert dem.isValid(), sim["DEM"]
    geotags = run("importgeotags", {"INPUT": sim["GEOTAGS"], "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    frames = run("importflightlog", {"POSE_LOG": sim["POSES"], "IMAGES": str(folder / "frames"),
                                     "CALIBRATION": sim["CALIBRATION"], "DEM": dem, "DEM_VERTICAL_DATUM": 0,
                                     "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    return {**sim, "dem": dem, "geotags": geotags, "frames": frames}
