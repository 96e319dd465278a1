"""Running BirdsEye algorithms through the Processing registry, as the toolbox does, for the QGIS tests."""
import csv


def run(alg_id, params, feedback=None):
    """``birdseye:<alg_id>`` with ``params``; its results."""
    import processing

    return processing.run(f"birdseye:{alg_id}", params, feedback=feedback)


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
