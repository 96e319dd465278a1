"""A tiny writelabels-like folder made in the tests: tiles of a textured ground with dark round
"burrows", their soft labels (Gaussian, 255 at each centre), labels.csv with provenance, summary.json."""
from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np


def make_label_folder(folder, n_frames: int = 8, tiles_per_frame: int = 2, tile: int = 96, seed: int = 0,
                      sigma_px: float = 3.0, centre_offset_px: float = 0.0, class_name: str = "burrow") -> Path:
    """``centre_offset_px`` moves every label centre off the pixel grid (u, v = pixel + offset);
    ``class_name`` is the class of every row of labels.csv."""
    import cv2

    folder = Path(folder)
    (folder / "tiles" / "images").mkdir(parents=True, exist_ok=True)
    (folder / "tiles" / "labels").mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:tile, 0:tile]
    rows, geotag = [], 0
    for frame in range(1, n_frames + 1):
        for k in range(tiles_per_frame):
            base = rng.normal(120, 12, (tile, tile, 1)) + np.array([0, 10, 25])
            img = cv2.GaussianBlur(base.astype(np.float32), (5, 5), 1.5)
            label = np.zeros((tile, tile), np.float32)
            if k == 0:  # the first tile of a frame holds targets, the others none
                for _ in range(int(rng.integers(1, 3))):
                    cy, cx = rng.integers(12, tile - 12, 2) + centre_offset_px
                    img[(yy - cy) ** 2 + (xx - cx) ** 2 <= 16] = (40, 45, 50)
                    label = np.maximum(label, np.exp(-((yy - cy) ** 2 + (xx - cx) ** 2) / (2 * sigma_px ** 2)))
                    geotag += 1
                    rows.append([frame, f"frame_{frame}.jpg", geotag, class_name, cx, cy, sigma_px, 20.0,
                                 "review" if geotag % 3 == 0 else "survey"])
            name = f"{frame}_{k * tile}_0.png"
            cv2.imwrite(str(folder / "tiles" / "images" / name), np.clip(img, 0, 255).astype(np.uint8))
            cv2.imwrite(str(folder / "tiles" / "labels" / name), np.round(label * 255).astype(np.uint8))
    with open(folder / "labels.csv", "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(["frame_id", "image", "geotag_id", "label", "u", "v", "sigma_px", "margin_px", "provenance"])
        writer.writerows(rows)
    (folder / "summary.json").write_text(json.dumps({"sigma_px": sigma_px, "tiles": {
        "size": tile, "positive": n_frames, "negative": n_frames * (tiles_per_frame - 1), "hard_negative": 0}}))
    return folder
