"""Perception: image -> scene graph (OpenCV detectors, OpenCLIP labeller, VLM prompt path)."""

from verigraph.perception.pipeline import PerceptionResult, perceive, perceive_image

__all__ = ["PerceptionResult", "perceive", "perceive_image"]
