"""A PNG encoder for sparse 8-bit rasters (soft-label rasters are ~99 % zeros).

General encoders deflate every byte of a 1920×1200 raster (≈ 45 ms with OpenCV, ≈ 11 ms with raw
zlib); here each run of all-zero rows reuses one pre-compressed deflate block and only the rows
that hold humps are compressed. Deflate blocks from independent compressors concatenate into one
valid stream when each ends on a byte boundary (``Z_SYNC_FLUSH``), so the output is an ordinary
PNG (greyscale, 8 bit, filter 0) that any decoder reads.
"""
from __future__ import annotations

import functools
import struct
import zlib

import numpy as np

_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def _deflate_raw(data: bytes, level: int = 1) -> bytes:
    comp = zlib.compressobj(level, zlib.DEFLATED, -15)
    return comp.compress(data) + comp.flush(zlib.Z_SYNC_FLUSH)


@functools.lru_cache(maxsize=16)
def _zero_rows_block(row_bytes: int, n_rows: int) -> bytes:
    return _deflate_raw(bytes(row_bytes * n_rows), level=6)


_FINAL_EMPTY_BLOCK = zlib.compressobj(6, zlib.DEFLATED, -15).flush(zlib.Z_FINISH)
_ZERO_RUN = 64  # zero rows per cached block: long runs cost a handful of bytes each


def _adler32_zeros(adler: int, n_bytes: int) -> int:
    """Adler-32 continued over ``n_bytes`` zero bytes, in closed form (a is unchanged, b grows by n·a)."""
    a, b = adler & 0xFFFF, adler >> 16
    return (((b + n_bytes * a) % 65521) << 16) | a


def encode_gray_png(raster: np.ndarray) -> bytes:
    """PNG bytes of a 2-D uint8 array; fast when most rows are entirely zero."""
    raster = np.ascontiguousarray(raster, dtype=np.uint8)
    height, width = raster.shape
    row_bytes = width + 1  # a filter byte 0 ("None") starts every scanline
    nonzero = raster.any(axis=1)
    # Runs of equal "row has data" state, as [start, end) pairs.
    edges = np.flatnonzero(np.diff(nonzero.astype(np.int8))) + 1
    starts = np.concatenate([[0], edges])
    ends = np.concatenate([edges, [height]])
    parts, adler = [], 1
    for start, end in zip(starts, ends):
        if nonzero[start]:
            band = np.zeros((end - start, row_bytes), dtype=np.uint8)
            band[:, 1:] = raster[start:end]
            data = band.tobytes()
            parts.append(_deflate_raw(data))
            adler = zlib.adler32(data, adler)
            continue
        full, rest = divmod(end - start, _ZERO_RUN)
        parts.extend([_zero_rows_block(row_bytes, _ZERO_RUN)] * full)
        parts.extend([_zero_rows_block(row_bytes, 1)] * rest)
        adler = _adler32_zeros(adler, (end - start) * row_bytes)
    parts.append(_FINAL_EMPTY_BLOCK)
    stream = b"\x78\x01" + b"".join(parts) + struct.pack(">I", adler & 0xFFFFFFFF)
    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    return _SIGNATURE + _chunk(b"IHDR", header) + _chunk(b"IDAT", stream) + _chunk(b"IEND", b"")
