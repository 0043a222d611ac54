"""Image headers read as the decoder reads them: a size checked before decoding is the
size the decoder then allocates, however the file hides another one."""

from __future__ import annotations

import base64
import random
import struct

import cv2
import numpy as np
import pytest

from verigraph.budget import rss_bytes
from verigraph.perception.config import ImageLimits
from verigraph.perception.imageio import (
    MAX_JPEG_SCANS,
    ImageInputError,
    decode_image,
    image_size,
)
from verigraph.tools.errors import ToolArgumentError
from verigraph.tools.images import decode_base64_image

pytestmark = pytest.mark.fast

FAKE_FRAME = (b"\xff\xc0\x00\x11\x08\x00\x10\x00\x10\x03"  # SOF0, 16x16, three components
              b"\x01\x22\x00\x02\x11\x01\x03\x11\x01")


def segment(marker: int, payload: bytes) -> bytes:
    return bytes([0xFF, marker]) + struct.pack(">H", len(payload) + 2) + payload


def jpeg_segments(width: int = 64, height: int = 48) -> list[bytes]:
    """A real JPEG split into its segments: SOI, the tables and frame, the scan to EOI."""
    ok, buf = cv2.imencode(".jpg", np.full((height, width, 3), 128, np.uint8))
    assert ok
    data = buf.tobytes()
    parts, i = [data[:2]], 2
    while data[i + 1] != 0xDA:
        length = struct.unpack(">H", data[i + 2:i + 4])[0]
        parts.append(data[i:i + 2 + length])
        i += 2 + length
    return [*parts, data[i:]]


def with_frame(parts: list[bytes], width: int, height: int) -> list[bytes]:
    """`parts` with the frame header declaring width x height (the scan is unchanged)."""
    out = []
    for part in parts:
        if part[1] in (0xC0, 0xC2):
            part = part[:5] + struct.pack(">HH", height, width) + part[9:]
        out.append(part)
    return out


def hidden_frame_jpeg(width: int, height: int, lead: bytes = b"\xff\x01") -> bytes:
    """A small JPEG whose real frame is width x height, with a 16x16 frame header inside
    an APP1 segment that libjpeg skips. Before the real frame, `lead` (TEM, which has no
    length, or FF 00, which is no marker at all) and two bytes a naive walk takes for
    its length: that walk jumps over the real frame onto the hidden one, while libjpeg
    skips the two bytes as stray data and reads the real frame."""
    soi, *rest = with_frame(jpeg_segments(), width, height)
    frame = next(p for p in rest if p[1] == 0xC0)
    others = [p for p in rest if p is not frame]
    app1 = segment(0xE1, b"Exif\x00\x00" + FAKE_FRAME)
    # a walk that reads a length here goes on 2 + length bytes on: onto FAKE_FRAME
    jump = lead + struct.pack(">H", 2 + len(frame) + 4 + 6)
    return soi + jump + frame + app1 + b"".join(others)


@pytest.mark.parametrize("lead", [b"\xff\x01", b"\xff\x00"], ids=["TEM", "FF00"])
def test_a_frame_hidden_in_a_skipped_segment_is_not_the_size_read(lead: bytes) -> None:
    data = hidden_frame_jpeg(12_000, 12_000, lead)
    assert len(data) < 1024
    # libjpeg's own reading (at 1/8 scale, so nothing large is allocated): 12000x12000
    small = cv2.imdecode(np.frombuffer(data, np.uint8), cv2.IMREAD_REDUCED_COLOR_8)
    assert small is not None and small.shape[:2] == (1500, 1500)
    assert image_size(data) == ("jpeg", 12_000, 12_000)
    before = rss_bytes()
    with pytest.raises(ImageInputError) as err:
        decode_image(data)
    assert "12000x12000" in err.value.message and "40000000 pixels" in err.value.message
    assert err.value.field == "image"
    with pytest.raises(ToolArgumentError) as tool_err:  # generate_scene_graph's intake
        decode_base64_image(base64.b64encode(data).decode())
    assert "12000x12000 pixels, too large" in tool_err.value.message
    assert rss_bytes() - before < 64 * 1024 * 1024  # the pixels (432 MB) never allocated


def test_a_size_opencv_itself_refuses_is_an_error_not_an_exception() -> None:
    """1 x 10,000,000 is under the pixel limit, but OpenCV throws past 2**20 a side."""
    png = bytearray(cv2.imencode(".png", np.zeros((4, 4, 3), np.uint8))[1].tobytes())
    png[16:24] = struct.pack(">II", 1, 10_000_000)
    with pytest.raises(ToolArgumentError, match="1x10000000 pixels, too large"):
        decode_base64_image(base64.b64encode(bytes(png)).decode())
    with pytest.raises(ImageInputError, match="1x10000000"):
        decode_image(bytes(png))


def _libjpeg_size(data: bytes) -> tuple[int, int] | None:
    image = cv2.imdecode(np.frombuffer(data, np.uint8), cv2.IMREAD_COLOR)
    return None if image is None else (image.shape[1], image.shape[0])


def _walk_size(data: bytes) -> tuple[int, int] | None:
    try:
        return image_size(data)[1:]
    except ImageInputError:
        return None


PIECES = {
    "TEM": lambda r: b"\xff\x01",
    "RSTn": lambda r: bytes([0xFF, 0xD0 + r.randrange(8)]),
    "fill": lambda r: b"\xff\xff",
    "stuffed zero and a length-like word": lambda r: b"\xff\x00" + struct.pack(
        ">H", r.randrange(2, 40)),
    "garbage": lambda r: bytes(r.randrange(255) for _ in range(r.randrange(1, 6))),
    "APPn hiding a frame": lambda r: segment(0xE0 + r.randrange(16), b"xx" + FAKE_FRAME),
    "COM hiding a frame": lambda r: segment(0xFE, FAKE_FRAME),
    "a length under 4": lambda r: bytes([0xFF, r.choice([0xE1, 0xFE, 0xEE, 0xDD])])
    + struct.pack(">H", r.randrange(4)) + FAKE_FRAME,
    "any marker": lambda r: bytes([0xFF, r.randrange(256)]) + struct.pack(">H", r.randrange(30)),
}


@pytest.mark.parametrize("piece", sorted(PIECES))
def test_the_header_walk_reads_the_size_libjpeg_decodes(piece: str) -> None:
    """Markers libjpeg reads its own way, put anywhere before the scan: whenever libjpeg
    decodes the file, the walk read the size it decoded (64x48), never the hidden 16x16,
    and it refuses no file libjpeg decodes."""
    rng = random.Random(piece)
    parts = jpeg_segments()
    decoded = 0
    for _ in range(60):
        mixed = list(parts)
        for _ in range(rng.randrange(1, 3)):
            mixed.insert(rng.randrange(1, len(mixed)), PIECES[piece](rng))
        if rng.random() < 0.5:  # and sometimes one of the others too
            mixed.insert(rng.randrange(1, len(mixed)), rng.choice(list(PIECES.values()))(rng))
        data = b"".join(mixed)
        theirs = _libjpeg_size(data)
        if theirs is not None:
            decoded += 1
            assert _walk_size(data) == theirs == (64, 48), data.hex()
    assert decoded  # the case tests something


@pytest.mark.parametrize("marker,name", [(b"\xff\xd8", "a second start of image"),
                                         (b"\xff\xd9", "the end of the image"),
                                         (b"\xff\xda\x00\x02", "the scan")])
def test_a_start_scan_or_end_before_the_frame_is_refused_naming_it(marker: bytes,
                                                                     name: str) -> None:
    soi, *rest = jpeg_segments()
    data = soi + marker + b"".join(rest)
    assert _libjpeg_size(data) is None  # libjpeg finds no frame there either
    with pytest.raises(ImageInputError, match=f"{name} before its frame header"):
        image_size(data)

def test_a_file_that_ends_before_its_frame_is_truncated() -> None:
    soi, *_ = jpeg_segments()
    with pytest.raises(ImageInputError, match="truncated"):
        image_size(soi + segment(0xE0, b"JFIF\x00"))


@pytest.mark.parametrize("width,height,limits,expected", [
    (12_000, 12_000, ImageLimits(), "40000000 pixels"),
    (5_000, 100, ImageLimits(max_side=4000), "4000 px per side")])
def test_a_hidden_size_meets_every_limit(width: int, height: int, limits: ImageLimits,
                                         expected: str) -> None:
    with pytest.raises(ImageInputError, match=f"{width}x{height} pixels.*{expected}"):
        decode_image(hidden_frame_jpeg(width, height), limits)


def test_a_jpeg_of_thousands_of_scans_is_refused_before_decoding() -> None:
    """Each scan is a pass of libjpeg over the whole image: 2,000 copies of a progressive
    JPEG's last scan in 52 KB took 7 s of CPU in one uninterruptible call."""
    ok, buf = cv2.imencode(".jpg", np.full((256, 256, 3), 128, np.uint8),
                           [cv2.IMWRITE_JPEG_PROGRESSIVE, 1])
    data = buf.tobytes()
    assert ok and 1 < data.count(b"\xff\xda") <= MAX_JPEG_SCANS
    assert image_size(data) == ("jpeg", 256, 256)  # an encoder's progressive file is read
    last = data[data.rindex(b"\xff\xda"):-2]
    bomb = data[:-2] + last * 2_000 + b"\xff\xd9"
    with pytest.raises(ImageInputError, match=f"2010 scans, more than the {MAX_JPEG_SCANS}"):
        decode_image(bomb)
    with pytest.raises(ToolArgumentError, match="2010 scans"):
        decode_base64_image(base64.b64encode(bomb).decode())
