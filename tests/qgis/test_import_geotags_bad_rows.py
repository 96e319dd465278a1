"""Import geotags with bad rows into a GeoPackage, as the toolbox dialog runs it: the run succeeds, says which rows
it left out as a warning (not an error), and its output loads into the project.

The bad rows used to keep the output open: each bad row was kept as the exception the reader raised, with its
traceback, whose frames reach back to the algorithm's and its output sink; that reference cycle lived until the
garbage collector ran, so the GeoPackage was still uncommitted when Processing loaded it ("The following layers
were not correctly generated", OGR: Cannot open). The garbage collector is off during each run here, as it may
well be in QGIS between the run and the loading, so the test sees what a user saw.
"""
from __future__ import annotations

import gc

import pytest
from qgis.core import QgsProcessingContext, QgsProcessingOutputLayerDefinition, QgsProject, QgsVectorLayer
from registry import Recorder

N_ROWS = 20
BAD = {5: "lon", 10: "lat"}  # row → the field made unreadable


def rover_csv(path):
    """A BirdsEye rover CSV of N_ROWS rows, rows 5 and 10 with a word where a coordinate belongs."""
    rows = []
    for row in range(1, N_ROWS + 1):
        lat, lon = f"{-27.55 + row * 1e-5:.7f}", f"{151.95 + row * 1e-5:.7f}"
        if BAD.get(row) == "lat":
            lat = "oops"
        if BAD.get(row) == "lon":
            lon = "north"
        rows.append(f"{lat},{lon},400.0,360.0,4,burrow")
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return path


def header_csv(path):
    """The same survey as a CSV with a header (row 1), so the bad rows are 6 and 11."""
    lines = ["name,latitude,longitude,ellipsoidal height"]
    for row in range(1, N_ROWS + 1):
        lat, lon = f"{-27.55 + row * 1e-5:.7f}", f"{151.95 + row * 1e-5:.7f}"
        lines.append(f"T{row},{'oops' if BAD.get(row) == 'lat' else lat},{'north' if BAD.get(row) == 'lon' else lon},"
                     "400.0")
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


@pytest.fixture(params=[rover_csv, header_csv], ids=["rover_csv", "header_csv"])
def bad_survey(request, tmp_path):
    return request.param(tmp_path / "survey.csv")


def run_as_the_dialog_does(params):
    """``birdseye:importgeotags`` through Processing's own executor and result handling (what the toolbox dialog
    calls), loading its outputs into the project; (ok, results, handled, feedback)."""
    from processing.gui.AlgorithmExecutor import execute
    from processing.gui.Postprocessing import handleAlgorithmResults
    from qgis.core import QgsApplication

    algorithm = QgsApplication.processingRegistry().createAlgorithmById("birdseye:importgeotags")
    context = QgsProcessingContext()
    context.setProject(QgsProject.instance())
    feedback = Recorder()
    collecting = gc.isenabled()
    gc.disable()
    try:
        ok, results = execute(algorithm, params, context, feedback)
        handled = handleAlgorithmResults(algorithm, context, feedback, parameters=params)
    finally:
        if collecting:
            gc.enable()
    return ok, results, handled, feedback


def test_bad_rows_are_a_warning_and_the_output_loads(birdseye_provider, bad_survey, tmp_path):
    project = QgsProject.instance()
    before = set(project.mapLayers())
    output = tmp_path / "geotags.gpkg"
    ok, results, handled, feedback = run_as_the_dialog_does({
        "INPUT": str(bad_survey), "OUTPUT": QgsProcessingOutputLayerDefinition(str(output), project)})
    added = [project.mapLayer(i) for i in set(project.mapLayers()) - before]
    try:
        assert ok and results["GEOTAG_COUNT"] == N_ROWS - len(BAD) and results["BAD_ROWS"] == len(BAD)
        assert handled, feedback.errors
        assert feedback.errors == [], "bad rows left out are a warning, not an error"
        assert len(added) == 1 and added[0].isValid() and added[0].featureCount() == N_ROWS - len(BAD)
        left_out = [w for w in feedback.warnings if "bad row(s) left out" in w]
        assert len(left_out) == 1 and left_out[0].startswith(f"{len(BAD)} bad row(s)")
        first_bad = min(BAD) + (1 if bad_survey.read_text(encoding="utf-8").startswith("name,") else 0)
        assert f"row {first_bad}, field" in left_out[0], left_out[0]
    finally:
        project.removeMapLayers([layer.id() for layer in added])


def test_the_geopackage_is_complete_when_the_run_returns(birdseye_provider, bad_survey, tmp_path):
    """Without the dialog: the file is written and closed by the time processing.run returns."""
    import processing

    output = tmp_path / "geotags.gpkg"
    collecting = gc.isenabled()
    gc.disable()
    try:
        processing.run("birdseye:importgeotags", {"INPUT": str(bad_survey), "OUTPUT": str(output)},
                       feedback=Recorder())
        journal = output.with_name(output.name + "-journal")
        assert not journal.exists(), "the GeoPackage's transaction is still open after the run"
        layer = QgsVectorLayer(str(output), "geotags", "ogr")
        assert layer.isValid() and layer.featureCount() == N_ROWS - len(BAD)
    finally:
        if collecting:
            gc.enable()
