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
