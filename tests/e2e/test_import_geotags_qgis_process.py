"""Import geotags with bad rows from ``qgis_process``: the run exits 0, says which rows it left out as a WARNING
(not an ERROR) and leaves a complete GeoPackage of the good rows."""
from __future__ import annotations

import pytest
from test_qgis_process import qgis_process

pytestmark = pytest.mark.slow


def test_bad_rows_are_a_warning(qgis_app, tmp_path):
    survey = tmp_path / "survey.csv"
    rows = []
    for row in range(1, 21):
        lat, lon = f"{-27.55 + row * 1e-5:.7f}", f"{151.95 + row * 1e-5:.7f}"
        rows.append(f"{'oops' if row == 10 else lat},{'north' if row == 5 else lon},400.0,360.0,4,burrow")
    survey.write_text("\n".join(rows) + "\n", encoding="utf-8")
    output = tmp_path / "geotags.gpkg"
    result = qgis_process("run", "birdseye:importgeotags", "--", f"INPUT={survey}", f"OUTPUT={output}",
                          config_dir=tmp_path / "config", timeout=180)
    printed = result.stdout + result.stderr
    assert result.returncode == 0, printed
    assert "ERROR" not in printed, printed
    warnings = [line for line in printed.splitlines() if line.startswith("WARNING")]
    assert len(warnings) == 1, printed
    assert "2 bad row(s) left out" in warnings[0] and "row 5, field 'lon'" in warnings[0], warnings[0]
    assert "GEOTAG_COUNT:\t18" in printed and "BAD_ROWS:\t2" in printed, printed
    from qgis.core import QgsVectorLayer

    layer = QgsVectorLayer(str(output), "geotags", "ogr")
    assert layer.isValid() and layer.featureCount() == 18
