"""The PyBullet camera as an ObjectLocator: segmentation mask -> 3D points -> box.

This stands in for the paper's LangSAM + depth step with the same geometry: pixels
of one object are unprojected through the depth buffer into the robot base frame;
the highest points give the top height, the lowest visible ones the bottom, and the
minimum-area rectangle of their footprint gives centre, size and yaw. The camera
looks obliquely, so the sides of a covered block still show its footprint.
"""

from __future__ import annotations

import math
import time
from collections.abc import Collection
from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np
import pybullet as pb

from verigraph.arm.config import CameraView
from verigraph.arm.models import ObjectLocation
from verigraph.arm.sim.panda_scene import PandaScene

NEAR, FAR = 0.05, 4.0


@dataclass(frozen=True, slots=True)
class Frame:
    """One camera image: RGB, depth buffer, segmentation, and the inverse projection."""

    rgb: np.ndarray  # (H, W, 3) uint8
    depth: np.ndarray  # (H, W) float32, OpenGL depth buffer in [0, 1]
    segmentation: np.ndarray  # (H, W) int32 body ids, -1 for background
    inverse_view_projection: np.ndarray  # (4, 4)
    timestamp: float

    def points(self, mask: np.ndarray) -> np.ndarray:
        """World coordinates (N, 3) of the masked pixels."""
        height, width = self.depth.shape
        v, u = np.nonzero(mask)
        ndc = np.stack([(2 * u + 1) / width - 1, 1 - (2 * v + 1) / height,
                        2 * self.depth[v, u] - 1, np.ones(len(u))], axis=1)
        world = ndc @ self.inverse_view_projection.T
        return np.asarray(world[:, :3] / world[:, 3:4])

    def save_png(self, path: str | Path) -> Path:
        target = Path(path)
        target.parent.mkdir(parents=True, exist_ok=True)
        cv2.imwrite(str(target), cv2.cvtColor(self.rgb, cv2.COLOR_RGB2BGR))
        return target


def capture(scene: PandaScene, camera: CameraView | None = None) -> Frame:
    """Render the scene from `camera` (default: the first configured), headless."""
    o = camera or scene.options.cameras[0]
    view = pb.computeViewMatrix(o.eye, o.target, [0, 0, 1])
    projection = pb.computeProjectionMatrixFOV(o.fov_deg, o.width / o.height, NEAR, FAR)
    with scene.lock:
        _, _, rgba, depth, seg = pb.getCameraImage(
            o.width, o.height, view, projection, renderer=pb.ER_TINY_RENDERER,
            physicsClientId=scene.client)
        stamp = time.time()
    shape = (o.height, o.width)
    v = np.asarray(view, dtype=float).reshape(4, 4).T  # PyBullet matrices are column-major
    p = np.asarray(projection, dtype=float).reshape(4, 4).T
    return Frame(rgb=np.asarray(rgba, dtype=np.uint8).reshape(*shape, 4)[:, :, :3].copy(),
                 depth=np.asarray(depth, dtype=np.float32).reshape(shape),
                 segmentation=np.asarray(seg, dtype=np.int32).reshape(shape),
                 inverse_view_projection=np.linalg.inv(p @ v), timestamp=stamp)


def location_from_points(object_id: str, points: np.ndarray, timestamp: float,
                         source: str) -> ObjectLocation:
    """Box estimate from an object's visible 3D points."""
    z = points[:, 2]
    top, bottom = float(np.percentile(z, 99)), float(np.percentile(z, 1))
    (cx, cy), (w, h), angle = cv2.minAreaRect(points[:, :2].astype(np.float32))
    return ObjectLocation(object_id=object_id, centre=(float(cx), float(cy), (top + bottom) / 2),
                          size=(float(w), float(h), max(0.0, top - bottom)),
                          yaw=math.radians(angle), timestamp=timestamp, source=source)


class PyBulletCameraLocator:
    """Locates the scene's objects through its cameras; `last_frames` keeps the images."""

    def __init__(self, scene: PandaScene, cameras: list[CameraView] | None = None, *,
                 min_pixels: int = 20) -> None:
        self.scene = scene
        self.cameras = cameras or scene.options.cameras
        self.min_pixels = min_pixels
        self.last_frames: list[Frame] = []

    def locate(self, object_ids: Collection[str]) -> dict[str, ObjectLocation]:
        frames = [capture(self.scene, camera) for camera in self.cameras]
        self.last_frames = frames
        stamp = min(f.timestamp for f in frames)
        found: dict[str, ObjectLocation] = {}
        for object_id in object_ids:
            body = self.scene.bodies.get(object_id)
            if body is None:
                continue
            points = np.concatenate([f.points(f.segmentation == body.body) for f in frames])
            if len(points) < self.min_pixels:
                continue
            found[object_id] = location_from_points(object_id, points, stamp,
                                                    "pybullet camera")
        return found
