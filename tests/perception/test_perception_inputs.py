"""Bad input never crashes perception: clear errors naming the field and the fix."""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import cv2
import numpy as np
import pytest

from verigraph.cli import main
from verigraph.errors import VeriGraphError
from verigraph.perception import perceive_image
from verigraph.perception.config import ImageLimits, PerceptionConfig
from verigraph.perception.imageio import (
    ImageInputError,
    as_bgr,
    decode_image,
    image_size,
    read_image,
)
from verigraph.sim2d.generator import generate_scene


def png_chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(
        ">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def bomb_png(width: int, height: int) -> bytes:
    """A tiny, valid-looking PNG whose header declares a huge image (all zeros inflate)."""
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    body = zlib.compress(b"\x00" * 1024)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + png_chunk(b"IDAT", body)
            + png_chunk(b"IEND", b""))


@pytest.fixture(scope="module")
def render() -> np.ndarray:
    return generate_scene("kitchen", 2).world.render(640, 480)


def encoded(image: np.ndarray, ext: str) -> bytes:
    ok, buf = cv2.imencode(ext, image)
    assert ok
    return buf.tobytes()


@pytest.mark.parametrize("ext,fmt", [(".png", "png"), (".jpg", "jpeg"), (".bmp", "bmp"),
                                     (".webp", "webp")])
def test_header_sizes_match_the_decoded_image(render: np.ndarray, ext: str, fmt: str) -> None:
    data = encoded(render, ext)
    assert image_size(data) == (fmt, 640, 480)
    assert decode_image(data).shape == (480, 640, 3)


def test_decompression_bomb_is_refused_before_decoding() -> None:
    data = bomb_png(60_000, 60_000)
    assert len(data) < 200
    with pytest.raises(ImageInputError) as err:
        decode_image(data)
    assert err.value.field == "image" and "60000x60000" in str(err.value)
    assert "downscale" in (err.value.fix or "")


def test_limits_are_configurable(render: np.ndarray) -> None:
    small = ImageLimits(max_pixels=100_000)
    with pytest.raises(ImageInputError, match="640x480"):
        decode_image(encoded(render, ".png"), small)
    with pytest.raises(ImageInputError, match="640x480"):
        perceive_image(render, config=PerceptionConfig(limits=small))
    with pytest.raises(ImageInputError, match="bytes"):
        decode_image(encoded(render, ".png"), ImageLimits(max_bytes=1000))
    tiny = perceive_image(np.zeros((8, 8, 3), np.uint8))
    assert tiny.graph.nodes == [] and "too small" in tiny.warnings[0]


@pytest.mark.parametrize("ext", [".png", ".jpg"])
def test_truncated_files_are_refused(render: np.ndarray, ext: str) -> None:
    data = encoded(render, ext)
    with pytest.raises(ImageInputError, match="truncated"):
        decode_image(data[: len(data) // 2])


@pytest.mark.parametrize("data", [b"", b"hello world, not an image", b"\x89PNG\r\n\x1a\n",
                                  b"GIF89a" + b"\x00" * 20, b"\xff\xd8\xff\xe0\x00\x10"])
def test_non_images_are_refused_with_a_fix(data: bytes) -> None:
    with pytest.raises(ImageInputError) as err:
        decode_image(data)
    assert err.value.fix and err.value.field == "image"


def test_corrupt_png_body_is_refused() -> None:
    ihdr = struct.pack(">IIBBBBB", 64, 64, 8, 2, 0, 0, 0)
    data = (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr)
            + png_chunk(b"IDAT", b"not zlib data at all") + png_chunk(b"IEND", b""))
    with pytest.raises(ImageInputError, match="corrupt"):
        decode_image(data)


@pytest.mark.parametrize("array,message", [
    (np.zeros((480, 640, 3), np.float32), "float32"),
    (np.zeros((480, 640, 2), np.uint8), "shape"),
    (42, "int"),
    ("not a file.png", "no image file"),
])
def test_bad_arrays_are_refused(array: object, message: str) -> None:
    with pytest.raises(ImageInputError, match=message):
        perceive_image(array)


def test_grey_and_bgra_arrays_and_bytes_and_paths_are_accepted(render: np.ndarray,
                                                               tmp_path: Path) -> None:
    grey = cv2.cvtColor(render, cv2.COLOR_BGR2GRAY)
    assert as_bgr(grey).shape == (480, 640, 3)
    bgra = cv2.cvtColor(render, cv2.COLOR_BGR2BGRA)
    reference = perceive_image(render, dictionary="kitchen").graph
    assert perceive_image(bgra, dictionary="kitchen").graph == reference
    assert perceive_image(encoded(render, ".png"), dictionary="kitchen").graph == reference
    path = tmp_path / "scene.png"
    path.write_bytes(encoded(render, ".png"))
    assert perceive_image(path, dictionary="kitchen").graph == reference
    assert perceive_image(str(path), dictionary="kitchen").graph == reference


def test_missing_file_names_the_path(tmp_path: Path) -> None:
    with pytest.raises(ImageInputError, match="no image file"):
        read_image(tmp_path / "nope.png")


def test_errors_are_verigraph_errors_with_a_dict_form() -> None:
    with pytest.raises(VeriGraphError) as err:
        decode_image(b"junk")
    data = err.value.to_dict()
    assert data["field"] == "image" and data["fix"]


# -- the command line -----------------------------------------------------------------
def test_cli_prints_sentences_and_json(render: np.ndarray, tmp_path: Path,
                                       capsys: pytest.CaptureFixture[str]) -> None:
    import json

    path = tmp_path / "k.png"
    path.write_bytes(encoded(render, ".png"))
    truth = generate_scene("kitchen", 2).graph
    assert main(["perceive", str(path), "--family", "kitchen"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("# tabletop view") and all(s in out for s in truth.sentences())
    assert main(["perceive", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["family"] == "kitchen" and data["view"] == "tabletop"
    assert {tuple(e.values()) for e in data["graph"]["edges"]} >= {
        (e.source, e.relation, e.target, None, None) for e in truth.edges}
    assert len(data["objects"]) == len(truth.nodes)


@pytest.mark.parametrize("content,message", [
    (b"plain text", "not an image format"),
    (bomb_png(50_000, 50_000), "50000x50000"),
])
def test_cli_exits_2_on_bad_images(tmp_path: Path, content: bytes, message: str,
                                   capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "bad.png"
    path.write_bytes(content)
    assert main(["perceive", str(path)]) == 2
    assert message in capsys.readouterr().err


def test_cli_max_pixels_flag(render: np.ndarray, tmp_path: Path,
                             capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "k.png"
    path.write_bytes(encoded(render, ".png"))
    assert main(["perceive", str(path), "--max-pixels", "1000"]) == 2
    assert "640x480" in capsys.readouterr().err


def test_cli_empty_scene_warns(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "blank.png"
    path.write_bytes(encoded(np.full((240, 320, 3), 250, np.uint8), ".png"))
    assert main(["perceive", str(path), "--family", "tangram"]) == 0
    captured = capsys.readouterr()
    assert "0 objects" in captured.out and "warning: no tangram pieces" in captured.err


def test_pure_noise_gives_an_empty_graph_not_hallucinated_pieces() -> None:
    import numpy as np

    from verigraph.perception import perceive_image

    noise = np.random.default_rng(0).integers(0, 256, (800, 800, 3), dtype=np.uint8)
    result = perceive_image(noise)
    assert result.graph.nodes == [] and result.warnings
