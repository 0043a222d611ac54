"""Image payloads at the tool boundary: base64 in, BGR arrays inside, PNG out.

Agents send images as base64 text (optionally a `data:` URL). Decoding checks the size
before and after decompression, so a small file that inflates to a huge bitmap is
refused with a message rather than exhausting memory.
"""

from __future__ import annotations

import base64
import binascii
import re
from dataclasses import dataclass

import cv2
import numpy as np

from verigraph.perception.imageio import ImageInputError, image_size
from verigraph.sim2d.render import encode_png
from verigraph.tools.errors import ToolArgumentError

MAX_IMAGE_BYTES = 12 * 1024 * 1024
MAX_IMAGE_PIXELS = 16_000_000  # e.g. 4000 x 4000; 48 MB once decoded
MAX_IMAGE_SIDE = 16_384  # as perception's ImageLimits; OpenCV itself throws past 2**20
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
JPEG_MAGIC = b"\xff\xd8\xff"
_DATA_URL = re.compile(r"^data:image/[A-Za-z0-9.+-]+;base64,", re.IGNORECASE)
_FIX = "send a PNG or JPEG file encoded as base64 text (a data:image/...;base64, prefix is fine)"


def decode_base64_image(text: str, *, field: str = "image") -> np.ndarray:
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
    if not raw.startswith((PNG_MAGIC, JPEG_MAGIC)):
        raise ToolArgumentError("the bytes are not a PNG or JPEG file", field=field,
                                value=raw[:8].hex(), fix=_FIX)
    try:  # the size OpenCV's decoder will allocate, read from the header as it reads it
        _, width, height = image_size(raw)
    except ImageInputError as exc:
        raise ToolArgumentError(f"the image header is damaged: {exc.message}", field=field,
                                value=raw[:8].hex(), fix=_FIX) from None
    if width * height > MAX_IMAGE_PIXELS or max(width, height) > MAX_IMAGE_SIDE:
        raise ToolArgumentError(f"image is {width}x{height} pixels, too large to decode",
                                field=field, value=f"{width}x{height}",
                                fix=f"downscale it below 16 megapixels and {MAX_IMAGE_SIDE} px "
                                    "a side (1024 px is plenty)")
    try:
        image = cv2.imdecode(np.frombuffer(raw, dtype=np.uint8), cv2.IMREAD_COLOR)
    except cv2.error:  # a check of OpenCV's own refused the file
        image = None
    if image is None or image.size == 0:
        raise ToolArgumentError("the bytes are not a PNG or JPEG image OpenCV can decode",
                                field=field, value=raw[:8].hex(), fix=_FIX)
    return image


MAX_PHOTO_SIDE = 1600  # photos are sent back at most this large (vision models downscale anyway)


def fit(image: np.ndarray, longest: int) -> np.ndarray:
    """The image scaled down (never up) so that its longer side is at most `longest`."""
    height, width = image.shape[:2]
    scale = longest / max(height, width)
    if scale >= 1:
        return image
    size = (max(1, round(width * scale)), max(1, round(height * scale)))
    return cv2.resize(image, size, interpolation=cv2.INTER_AREA)


@dataclass(frozen=True)
class KeptImage:
    """An episode's photo as PNG bytes, at most MAX_PHOTO_SIDE on its long side.

    A decoded photo costs width x height x 3 bytes for the episode's whole life (51 MiB
    for a 62 KB JPEG of a large scene); kept encoded and at the size it is ever served,
    it costs its PNG size, and is decoded only while a tool draws it.
    """

    png: bytes
    width: int
    height: int

    @classmethod
    def of(cls, image: np.ndarray) -> KeptImage:
        fitted = fit(image, MAX_PHOTO_SIDE)
        return cls(encode_png(fitted), int(fitted.shape[1]), int(fitted.shape[0]))

    def array(self) -> np.ndarray:
        image = cv2.imdecode(np.frombuffer(self.png, dtype=np.uint8), cv2.IMREAD_COLOR)
        assert image is not None, "a kept image is always a valid PNG"
        return image


def png_base64(png: bytes) -> str:
    return base64.b64encode(png).decode("ascii")
