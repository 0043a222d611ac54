"""Image payloads at the tool boundary: base64 in, BGR arrays inside, PNG out.

Agents send images as base64 text (optionally a `data:` URL). Decoding checks the size
before and after decompression, so a small file that inflates to a huge bitmap is
refused with a message rather than exhausting memory.
"""

from __future__ import annotations

import base64
import binascii
import re

import cv2
import numpy as np

from verigraph.tools.errors import ToolArgumentError

MAX_IMAGE_BYTES = 12 * 1024 * 1024
MAX_IMAGE_PIXELS = 40_000_000
_DATA_URL = re.compile(r"^data:image/[A-Za-z0-9.+-]+;base64,", re.IGNORECASE)
_FIX = "send a PNG or JPEG file encoded as base64 text (a data:image/...;base64, prefix is fine)"


def decode_image(text: str, *, field: str = "image") -> np.ndarray:
    """A BGR uint8 image from base64 PNG/JPEG text; ToolArgumentError names what is wrong."""
    payload = _DATA_URL.sub("", text.strip(), count=1)
    if len(payload) > MAX_IMAGE_BYTES * 4 // 3 + 8:
        raise ToolArgumentError(
            f"image is larger than {MAX_IMAGE_BYTES // (1024 * 1024)} MiB", field=field,
            value=f"{len(payload)} base64 characters",
            fix="downscale it (1024 px on the long side is plenty) or compress it as JPEG")
    try:
        raw = base64.b64decode(payload, validate=True)
    except (binascii.Error, ValueError):
        raise ToolArgumentError("image is not valid base64", field=field,
                                value=payload[:32], fix=_FIX) from None
    if not raw:
        raise ToolArgumentError("image is empty", field=field, value="", fix=_FIX)
    header = _probe_size(raw)
    if header is not None and header[0] * header[1] > MAX_IMAGE_PIXELS:
        raise ToolArgumentError(f"image is {header[0]}x{header[1]} pixels, too large to decode",
                                field=field, value=f"{header[0]}x{header[1]}",
                                fix="downscale it below 40 megapixels")
    image = cv2.imdecode(np.frombuffer(raw, dtype=np.uint8), cv2.IMREAD_COLOR)
    if image is None or image.size == 0:
        raise ToolArgumentError("the bytes are not a PNG or JPEG image OpenCV can decode",
                                field=field, value=raw[:8].hex(), fix=_FIX)
    return image


def _probe_size(raw: bytes) -> tuple[int, int] | None:
    """Width and height from a PNG header (decompression-bomb guard), else None."""
    if raw[:8] == b"\x89PNG\r\n\x1a\n" and len(raw) >= 24:
        return int.from_bytes(raw[16:20], "big"), int.from_bytes(raw[20:24], "big")
    return None


def encode_png(image: np.ndarray) -> bytes:
    """PNG bytes of a BGR (or grey) uint8 image."""
    ok, buffer = cv2.imencode(".png", image)
    if not ok:  # pragma: no cover - only for impossible shapes
        raise ValueError("OpenCV could not encode the image as PNG")
    return bytes(buffer.tobytes())


def png_base64(png: bytes) -> str:
    return base64.b64encode(png).decode("ascii")
