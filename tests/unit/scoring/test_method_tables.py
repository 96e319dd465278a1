"""A table as the method prints it, recomputed with the code's formulas to the printed digits: the F1
column from the recall and GMCF columns (harmonic mean), the review-load column from the detections-per-
frame column (relative to the lightest row). Expectations computed by hand."""
import pytest

from birdseye.birdseye_qgis.core.scoring.screening import relative_to_lightest
from birdseye.birdseye_qgis.core.scoring.sweep import f1_geo

# recall, GMCF, detections per frame | F1 = 2rg/(r+g), review load = dpf / 2.40 (by hand)
TABLE = [
    ("0.800", "0.600", "3.10", "0.686", "1.29"),    # 0.96 / 1.40 = 0.68571; 3.10 / 2.40 = 1.29167
    ("0.750", "0.500", "2.40", "0.600", "1.00"),    # 0.75 / 1.25 = 0.6; the lightest row
    ("0.900", "0.300", "5.00", "0.450", "2.08"),    # 0.54 / 1.20 = 0.45; 5.00 / 2.40 = 2.08333
    ("0.625", "0.875", "7.20", "0.729", "3.00"),    # 1.09375 / 1.50 = 0.72917; 7.20 / 2.40 = 3
    ("0.000", "0.000", "2.64", "0.000", "1.10"),    # F1 of nothing found is 0; 2.64 / 2.40 = 1.1
]


@pytest.mark.parametrize("row", range(len(TABLE)))
def test_f1_column_from_the_recall_and_gmcf_columns(row):
    recall, gmcf, _, f1, _ = TABLE[row]
    assert f"{float(f1_geo(float(recall), float(gmcf))):.3f}" == f1


def test_review_load_column_from_the_detections_per_frame_column():
    loads = relative_to_lightest([float(r[2]) for r in TABLE])
    assert [f"{v:.2f}" for v in loads] == [r[4] for r in TABLE]
