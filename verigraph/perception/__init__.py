"""Perception: image -> scene graph, SGG(I, R, D, T) of the paper, for sim2d renders.

    >>> from verigraph.sim2d import generate_scene
    >>> scene = generate_scene("kitchen", 7)
    >>> graph = perceive(scene.world.render(), dictionary="kitchen")
    >>> graph.edge_keys() == scene.graph.edge_keys()
    True

`perceive` is the entry point the tools layer calls (`generate_scene_graph`, image
inputs of `load_scene` and `set_goal`); `perceive_image` also returns warnings, the
detected objects and timings. Labellers: the default colour/shape one, or OpenCLIP
(`make_labeller("clip", ClipSource(...))`, optional extra `verigraph-mcp[clip]`). The VLM
path (`VlmClient`) asks an OpenAI-compatible vision model instead.
"""

from verigraph.perception.config import ImageLimits, PerceptionConfig
from verigraph.perception.imageio import ImageInputError, decode_image, read_image
from verigraph.perception.label.clip import ClipSource, make_labeller
from verigraph.perception.label.vlm import VlmClient, VlmConfig, VlmError
from verigraph.perception.metrics import GraphScore, score_graph, summarise
from verigraph.perception.pipeline import perceive, perceive_image
from verigraph.perception.result import DetectedObject, PerceptionResult

__all__ = [
    "ClipSource", "DetectedObject", "GraphScore", "ImageInputError", "ImageLimits",
    "PerceptionConfig", "PerceptionResult", "VlmClient", "VlmConfig", "VlmError",
    "decode_image", "make_labeller", "perceive", "perceive_image", "read_image",
    "score_graph", "summarise",
]
