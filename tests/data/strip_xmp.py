"""Copies of real drone JPEGs without their XMP packet: what a drone that writes only EXIF produces."""
from pathlib import Path

XMP_HEADER = b"http://ns.adobe.com/xap/1.0/\x00"


def strip_xmp(src, dst) -> Path:
    """Copy the JPEG ``src`` to ``dst`` without the APP1 segment(s) holding XMP; EXIF and pixels stay.

    Walks the marker segments up to the start of scan; every segment but an XMP APP1 (payload starting
    with the Adobe XMP namespace) is copied byte for byte.
    """
    data = Path(src).read_bytes()
    if data[:2] != b"\xff\xd8":
        raise ValueError(f"{src} is not a JPEG file")
    out, pos, dropped = bytearray(data[:2]), 2, 0
    while pos < len(data) and data[pos] == 0xFF:
        marker = data[pos + 1]
        if marker == 0xDA:  # start of scan: the rest is image data
            break
        size = int.from_bytes(data[pos + 2:pos + 4], "big")
        segment = data[pos:pos + 2 + size]
        if marker == 0xE1 and segment[4:4 + len(XMP_HEADER)] == XMP_HEADER:
            dropped += 1
        else:
            out += segment
        pos += 2 + size
    if not dropped:
        raise ValueError(f"{src} holds no XMP packet")
    out += data[pos:]
    Path(dst).write_bytes(bytes(out))
    return Path(dst)
