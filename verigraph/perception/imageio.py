"""Reading images safely: sizes from the header before decoding, truncation detected.

A 100 kB PNG can declare 50000x50000 pixels and take 7 GB to decode, so the width and
height are read from the file header (PNG, JPEG, BMP, WebP) and checked against the
limits first; formats whose header we cannot read are refused rather than trusted.
A truncated PNG or JPEG decodes silently to a half-grey picture in OpenCV, so the end
marker is checked too. Every failure is an `ImageInputError` naming the fix.
"""

from __future__ import annotations

import struct
from pathlib import Path

import cv2
import numpy as np

from verigraph.errors import VeriGraphError
from verigraph.perception.config import ImageLimits

SUPPORTED = "PNG, JPEG, BMP or WebP"


class ImageInputError(VeriGraphError):
    """An image that cannot or may not be decoded (format, size, truncation)."""


def image_size(data: bytes) -> tuple[str, int, int]:
    """(format, width, height) from the header; ImageInputError if unreadable."""
    if data[:8] == b"\x89PNG\r\n\x1a\n":
        if len(data) < 24 or data[12:16] != b"IHDR":
            raise _truncated("PNG")
        w, h = struct.unpack(">II", data[16:24])
        return "png", w, h
    if data[:3] == b"\xff\xd8\xff":
        return ("jpeg", *_jpeg_size(data))
    if data[:2] == b"BM":
        if len(data) < 26:
            raise _truncated("BMP")
        w, h = struct.unpack("<ii", data[18:26])
        return "bmp", abs(w), abs(h)
    if data[:4] == b"RIFF" and data[8:12] == b"WEBP":
        return ("webp", *_webp_size(data))
    raise ImageInputError(
        "the data is not an image format perception reads", field="image",
        value=data[:8].hex(), fix=f"give a {SUPPORTED} file")


def _truncated(fmt: str) -> ImageInputError:
    return ImageInputError(f"the {fmt} file is truncated (it ends before the image does)",
                           field="image", value=fmt,
                           fix="send the complete file; re-export it if it was cut off")


# Frame headers libjpeg reads (SOF0-3, 5-7, 9-11, 13-15); C4 (DHT), C8 (JPG) and CC (DAC)
# share the range but are not frames.
_SOF = frozenset({*range(0xC0, 0xD0)} - {0xC4, 0xC8, 0xCC})
_STANDALONE = frozenset({0x01, *range(0xD0, 0xD8)})  # TEM and RST0-7: no length word
# Scans a JPEG may have: encoders write about 10 (progressive) or 1. libjpeg runs every
# scan over the whole image, so 2,000 repeated scans in a 52 KB file cost 7 s of CPU in
# one call nothing can interrupt; FF DA (a scan) never occurs inside coded data.
MAX_JPEG_SCANS = 100


def _jpeg_size(data: bytes) -> tuple[int, int]:
    """The frame size libjpeg will decode, read as libjpeg reads the markers
    (jdmarker.c `next_marker`, `read_markers`): bytes up to an 0xFF are skipped, then fill
    0xFF bytes; FF 00 is stuffed data, not a marker; TEM and RSTn stand alone; every
    other marker has a length word, and a length under 2 skips nothing more (libjpeg
    reads on right after it). The first SOFn on that walk is the frame; an SOI, EOI or
    SOS before it means libjpeg finds no frame there, so the file is refused. Reading
    any other way (a TEM with a length, a length under 2 taken as is, FF 00 as a marker)
    lets a file show this walk a small frame hidden in a segment libjpeg skips while
    libjpeg decodes a huge one."""
    n = len(data)
    i = 2
    while True:
        i = data.find(b"\xff", i)
        if i < 0:
            break
        while i < n and data[i] == 0xFF:
            i += 1
        if i >= n:
            break
        marker = data[i]
        i += 1
        if marker == 0x00 or marker in _STANDALONE:
            continue
        if marker in _SOF:
            if i + 7 > n:
                break
            h, w = struct.unpack(">HH", data[i + 3:i + 7])
            scans = data.count(b"\xff\xda", i)
            if scans > MAX_JPEG_SCANS:
                raise ImageInputError(
                    f"the JPEG has {scans} scans, more than the {MAX_JPEG_SCANS} perception "
                    "decodes (each scan is a pass over the whole image)", field="image",
                    value=scans, fix="re-encode it (any encoder writes at most a few dozen)")
            return w, h
        if marker in (0xD8, 0xD9, 0xDA):
            name = {0xD8: "a second start of image", 0xD9: "the end of the image",
                    0xDA: "the scan"}[marker]
            raise ImageInputError(f"the JPEG has {name} before its frame header",
                                  field="image", value=f"marker FF{marker:02X} at byte {i - 2}",
                                  fix="re-export the image and send it again")
        if i + 2 > n:
            break
        i += max(struct.unpack(">H", data[i:i + 2])[0], 2)
    raise _truncated("JPEG")


def _webp_size(data: bytes) -> tuple[int, int]:
    chunk = data[12:16]
    if chunk == b"VP8 " and len(data) >= 30:
        w, h = struct.unpack("<HH", data[26:30])
        return w & 0x3FFF, h & 0x3FFF
    if chunk == b"VP8L" and len(data) >= 25:
        bits = int.from_bytes(data[21:25], "little")
        return (bits & 0x3FFF) + 1, ((bits >> 14) & 0x3FFF) + 1
    if chunk == b"VP8X" and len(data) >= 30:
        return (int.from_bytes(data[24:27], "little") + 1,
                int.from_bytes(data[27:30], "little") + 1)
    raise _truncated("WebP")


def check_size(width: int, height: int, limits: ImageLimits) -> None:
    """Refuse images outside the configured limits (before any pixel is decoded)."""
    if width <= 0 or height <= 0:
        raise ImageInputError(f"the image header declares {width}x{height} pixels",
                              field="image", value=f"{width}x{height}",
                              fix="give an image with a valid header")
    if width * height > limits.max_pixels or max(width, height) > limits.max_side:
        raise ImageInputError(
            f"the image is {width}x{height} pixels, more than perception accepts "
            f"({limits.max_pixels} pixels, {limits.max_side} px per side)", field="image",
            value=f"{width}x{height}",
            fix="downscale it (1024 px on the long side is plenty), or raise "
                "ImageLimits.max_pixels / max_side if you trust the source")


def _check_complete(fmt: str, data: bytes) -> None:
    if fmt == "png" and b"IEND" not in data[-64:]:
        raise _truncated("PNG")
    if fmt == "jpeg" and b"\xff\xd9" not in data[-64:]:
        raise _truncated("JPEG")


def decode_image(data: bytes, limits: ImageLimits | None = None) -> np.ndarray:
    """BGR uint8 pixels of an encoded image, checked against the limits first."""
    limits = limits or ImageLimits()
    if not data:
        raise ImageInputError("the image is empty (0 bytes)", field="image", value="",
                              fix=f"give a {SUPPORTED} file")
    if len(data) > limits.max_bytes:
        raise ImageInputError(
            f"the image file is {len(data)} bytes, more than {limits.max_bytes}",
            field="image", value=len(data),
            fix="compress or downscale it, or raise ImageLimits.max_bytes")
    fmt, width, height = image_size(data)
    check_size(width, height, limits)
    _check_complete(fmt, data)
    try:
        image = cv2.imdecode(np.frombuffer(data, dtype=np.uint8), cv2.IMREAD_COLOR)
    except cv2.error:  # a check of OpenCV's own refused the file
        image = None
    if image is None or image.size == 0:
        raise ImageInputError(f"the {fmt.upper()} data is corrupt and cannot be decoded",
                              field="image", value=data[:8].hex(),
                              fix="re-export the image and send it again")
    return np.asarray(image, dtype=np.uint8)


def read_image(path: str | Path, limits: ImageLimits | None = None) -> np.ndarray:
    """Decode an image file (size-checked before it is read in full)."""
    limits = limits or ImageLimits()
    p = Path(path)
    if not p.is_file():
        raise ImageInputError(f"no image file at {p}", field="image", value=str(p),
                              fix="check the path")
    size = p.stat().st_size
    if size > limits.max_bytes:
        raise ImageInputError(f"{p.name} is {size} bytes, more than {limits.max_bytes}",
                              field="image", value=str(p),
                              fix="compress or downscale it, or raise ImageLimits.max_bytes")
    return decode_image(p.read_bytes(), limits)


def as_bgr(image: object, limits: ImageLimits | None = None) -> np.ndarray:
    """A BGR uint8 array from an array (grey, BGR or BGRA), encoded bytes or a path."""
    limits = limits or ImageLimits()
    if isinstance(image, bytes | bytearray | memoryview):
        return decode_image(bytes(image), limits)
    if isinstance(image, str | Path):
        return read_image(image, limits)
    if not isinstance(image, np.ndarray):
        raise ImageInputError(f"cannot perceive a {type(image).__name__}", field="image",
                              value=type(image).__name__,
                              fix="pass a BGR uint8 array, encoded image bytes or a path")
    if image.dtype != np.uint8:
        raise ImageInputError(f"image pixels are {image.dtype}, not uint8", field="image",
                              value=str(image.dtype),
                              fix="convert with image.astype(numpy.uint8) after scaling to "
                                  "0-255")
    if image.ndim == 2:
        image = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR)
    elif image.ndim == 3 and image.shape[2] == 4:
        image = cv2.cvtColor(image, cv2.COLOR_BGRA2BGR)
    elif image.ndim != 3 or image.shape[2] != 3:
        raise ImageInputError(f"image array has shape {image.shape}", field="image",
                              value=str(image.shape),
                              fix="pass an (height, width, 3) BGR array")
    check_size(image.shape[1], image.shape[0], limits)
    return np.ascontiguousarray(image)
