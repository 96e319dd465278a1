"""Peak extraction at several thresholds on one heatmap: the same as separate runs, not the score filter."""
import cv2
import numpy as np
import pytest
from test_detector import campaign, conv_model, gaussian_image

from birdseye.birdseye_qgis.core.detect.detector import (
    DetectRequest,
    HeatmapModel,
    detect_frames,
    detect_frames_at_thresholds,
)
from birdseye.birdseye_qgis.core.errors import InputError


def test_a_blob_that_splits_at_a_higher_threshold_splits_as_in_a_separate_run(tmp_path):
    poses, local = campaign(n=2, dist=(0, 0, 0, 0, 0))
    path = tmp_path / "f.png"
    # Two humps of 0.9 (σ 4 px) 12 px apart: between them the image is 0.9·exp(−6²/(2·4²)) = 0.29, so the
    # smoothed heatmap is one blob above 0.2 and two above 0.5 (peaks 0.9·16/17 = 0.85 after the σ = 1 px blur).
    cv2.imwrite(str(path), gaussian_image(200, 150, [[94, 75], [106, 75]], 4.0, 0.9))
    model = HeatmapModel(conv_model(tmp_path / "m.onnx"))
    runs = []
    model_run = model.run
    model.run = lambda tiles: runs.append(len(tiles)) or model_run(tiles)
    ladder = list(detect_frames_at_thresholds(model, poses, [path, path], [0.2, 0.5], local=local))
    tiles_per_frame = sum(runs) / 2
    assert [len(found) for found in ladder[0]] == [1, 2]
    for k, per_threshold in enumerate(ladder):
        for threshold, found in zip((0.2, 0.5), per_threshold):
            alone = list(detect_frames(model, poses, [path, path], DetectRequest(threshold=threshold), local=local))[k]
            np.testing.assert_array_equal(found.uv, alone.uv)
            np.testing.assert_array_equal(found.score, alone.score)
            np.testing.assert_array_equal(found.ground_local, alone.ground_local)
    # one heatmap per frame serves both thresholds
    runs.clear()
    list(detect_frames(model, poses, [path, path], local=local))
    assert sum(runs) / 2 == tiles_per_frame
    # keeping the 0.2 run's detections scored ≥ 0.5 is not a run at 0.5: one detection, not two
    low = ladder[0][0]
    assert int((low.score >= 0.5).sum()) == 1


def test_every_threshold_is_checked_and_skipped_frames_repeat_per_threshold(tmp_path):
    poses, local = campaign(n=1, dist=(0, 0, 0, 0, 0))
    model = HeatmapModel(conv_model(tmp_path / "m.onnx"))
    with pytest.raises(InputError, match="between 0 and 1"):
        next(detect_frames_at_thresholds(model, poses, [tmp_path / "f.png"], [0.3, 1.0], local=local))
    (skipped_low, skipped_high), = detect_frames_at_thresholds(model, poses, [tmp_path / "missing.png"], [0.3, 0.6],
                                                               local=local)
    assert "cannot be read" in skipped_low.skipped and skipped_high.skipped == skipped_low.skipped
