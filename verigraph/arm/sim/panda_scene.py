"""A headless PyBullet cell: a Franka Panda on a table (the ground plane) with objects.

The scene is the physics behind the `pybullet` driver and behind the loopback
rosbridge server used in tests. It executes joint trajectories and gripper commands
by stepping the simulation, and it can be built from a scene graph so the simulated
cell starts in exactly the state the episode describes.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import pybullet as pb
import pybullet_data

from verigraph.arm.config import PyBulletOptions
from verigraph.arm.errors import MotionCancelledError
from verigraph.arm.models import Pose
from verigraph.arm.sim.kinematics import PANDA_REST, JointTrajectory, sample
from verigraph.graph.dictionary import SUPPORT_RELATIONS, load_dictionary
from verigraph.graph.model import SceneGraph
from verigraph.graph.wellformed import resolve_properties

PANDA_URDF = "franka_panda/panda.urdf"
ARM_JOINTS = tuple(range(7))
FINGER_JOINTS = (9, 10)
TCP_LINK = 11
ARM_FORCES = (87.0,) * 4 + (12.0,) * 3
FINGER_OPEN = 0.04  # per finger, metres
SETTLE_TOLERANCE = 0.002  # rad

COLOURS: dict[str, tuple[float, float, float, float]] = {
    "red": (0.85, 0.1, 0.1, 1), "green": (0.1, 0.7, 0.2, 1), "blue": (0.1, 0.3, 0.9, 1),
    "yellow": (0.95, 0.85, 0.1, 1), "orange": (1.0, 0.5, 0.0, 1),
    "purple": (0.5, 0.2, 0.7, 1), "white": (0.95, 0.95, 0.95, 1),
    "black": (0.1, 0.1, 0.1, 1), "brown": (0.5, 0.3, 0.1, 1), "grey": (0.5, 0.5, 0.5, 1),
    "gray": (0.5, 0.5, 0.5, 1), "pink": (1.0, 0.6, 0.7, 1), "tan": (0.8, 0.7, 0.5, 1),
}
_PALETTE = [COLOURS[c] for c in ("red", "green", "blue", "yellow", "orange", "purple")]


@dataclass(frozen=True, slots=True)
class SceneBody:
    """One graph object in the physics: its body id and box size (metres)."""

    object_id: str
    body: int
    size: tuple[float, float, float]
    fixed: bool


class PandaScene:
    """A Panda, a ground-plane table and boxes; every PyBullet call holds `lock`."""

    def __init__(self, options: PyBulletOptions | None = None) -> None:
        self.options = options or PyBulletOptions()
        self.lock = threading.RLock()
        self.client = pb.connect(pb.DIRECT)
        c = self.client
        pb.setAdditionalSearchPath(pybullet_data.getDataPath(), physicsClientId=c)
        pb.setGravity(0, 0, -9.81, physicsClientId=c)
        pb.setTimeStep(self.options.time_step_s, physicsClientId=c)
        self.plane = pb.loadURDF("plane.urdf", physicsClientId=c)
        self.robot = pb.loadURDF(PANDA_URDF, useFixedBase=True, physicsClientId=c)
        for j, q in zip(ARM_JOINTS, PANDA_REST, strict=True):
            pb.resetJointState(self.robot, j, q, physicsClientId=c)
        for j in FINGER_JOINTS:
            pb.resetJointState(self.robot, j, FINGER_OPEN, physicsClientId=c)
            pb.changeDynamics(self.robot, j, lateralFriction=1.5, physicsClientId=c)
        self.bodies: dict[str, SceneBody] = {}
        self.sim_time = 0.0
        self._arm_target = np.asarray(PANDA_REST)
        self._finger_target, self._finger_force = FINGER_OPEN, 20.0
        self._listeners: list[tuple[int, Callable[[PandaScene], None]]] = []
        self._steps = 0

    # -- building ----------------------------------------------------------------------------
    def add_ground(self, object_id: str) -> None:
        """Let the ground plane stand for a fixed surface of the graph (the table)."""
        self.bodies[object_id] = SceneBody(object_id, self.plane, (10.0, 10.0, 0.0), True)

    def add_box(self, object_id: str, size: Sequence[float], centre: Sequence[float],
                colour: tuple[float, float, float, float], *, yaw: float = 0.0,
                mass: float = 0.1, fixed: bool = False) -> int:
        half = [s / 2 for s in size]
        with self.lock:
            c = self.client
            shape = pb.createCollisionShape(pb.GEOM_BOX, halfExtents=half, physicsClientId=c)
            visual = pb.createVisualShape(pb.GEOM_BOX, halfExtents=half, rgbaColor=colour,
                                          physicsClientId=c)
            body = pb.createMultiBody(0.0 if fixed else mass, shape, visual, list(centre),
                                      pb.getQuaternionFromEuler([0, 0, yaw]),
                                      physicsClientId=c)
            pb.changeDynamics(body, -1, lateralFriction=1.0, spinningFriction=0.001,
                              physicsClientId=c)
        self.bodies[object_id] = SceneBody(object_id, body, (size[0], size[1], size[2]), fixed)
        return body

    def add_container(self, object_id: str, size: Sequence[float], centre: Sequence[float],
                      colour: tuple[float, float, float, float], *, wall: float = 0.006,
                      mass: float = 0.3) -> int:
        """An open-top box: a floor and four walls in one rigid body."""
        sx, sy, sz = size
        parts = [((sx / 2, sy / 2, wall / 2), (0, 0, -sz / 2 + wall / 2)),
                 ((wall / 2, sy / 2, sz / 2), (sx / 2 - wall / 2, 0, 0)),
                 ((wall / 2, sy / 2, sz / 2), (-sx / 2 + wall / 2, 0, 0)),
                 ((sx / 2, wall / 2, sz / 2), (0, sy / 2 - wall / 2, 0)),
                 ((sx / 2, wall / 2, sz / 2), (0, -sy / 2 + wall / 2, 0))]
        with self.lock:
            c = self.client
            shape = pb.createCollisionShapeArray(
                [pb.GEOM_BOX] * 5, halfExtents=[h for h, _ in parts],
                collisionFramePositions=[o for _, o in parts], physicsClientId=c)
            visual = pb.createVisualShapeArray(
                [pb.GEOM_BOX] * 5, halfExtents=[h for h, _ in parts],
                visualFramePositions=[o for _, o in parts], rgbaColors=[colour] * 5,
                physicsClientId=c)
            body = pb.createMultiBody(mass, shape, visual, list(centre), physicsClientId=c)
            pb.changeDynamics(body, -1, lateralFriction=1.0, physicsClientId=c)
        self.bodies[object_id] = SceneBody(object_id, body, (sx, sy, sz), False)
        return body

    # -- stepping --------------------------------------------------------------------------
    def on_step(self, every: int, listener: Callable[[PandaScene], None]) -> None:
        """Call `listener(scene)` every `every` physics steps (camera frames, logging)."""
        self._listeners.append((every, listener))

    def step(self, n: int = 1) -> None:
        dt = self.options.time_step_s
        pace = self.options.real_time_factor
        for _ in range(n):
            started = time.monotonic()
            with self.lock:
                self._drive()
                pb.stepSimulation(physicsClientId=self.client)
                self.sim_time += dt
                self._steps += 1
            for every, listener in self._listeners:
                if self._steps % every == 0:
                    listener(self)
            if pace is not None:
                time.sleep(max(0.0, dt / pace - (time.monotonic() - started)))

    def settle(self, seconds: float = 0.3) -> None:
        self.step(max(1, round(seconds / self.options.time_step_s)))

    def _drive(self) -> None:
        pb.setJointMotorControlArray(self.robot, ARM_JOINTS, pb.POSITION_CONTROL,
                                     targetPositions=self._arm_target.tolist(),
                                     forces=ARM_FORCES, physicsClientId=self.client)
        pb.setJointMotorControlArray(self.robot, FINGER_JOINTS, pb.POSITION_CONTROL,
                                     targetPositions=[self._finger_target] * 2,
                                     forces=[self._finger_force] * 2, physicsClientId=self.client)

    # -- the arm ---------------------------------------------------------------------------
    def arm_positions(self) -> tuple[float, ...]:
        with self.lock:
            return tuple(s[0] for s in pb.getJointStates(self.robot, ARM_JOINTS,
                                                         physicsClientId=self.client))

    def finger_positions(self) -> tuple[float, float]:
        with self.lock:
            a, b = pb.getJointStates(self.robot, FINGER_JOINTS, physicsClientId=self.client)
        return a[0], b[0]

    def tcp_pose(self) -> Pose:
        with self.lock:
            state = pb.getLinkState(self.robot, TCP_LINK, computeForwardKinematics=True,
                                    physicsClientId=self.client)
        m = pb.getMatrixFromQuaternion(state[5])
        return Pose(x=state[4][0], y=state[4][1], z=state[4][2], yaw=math.atan2(m[3], m[0]))

    def hold(self) -> None:
        """Keep the arm where it is now (after a stop)."""
        self._arm_target = np.asarray(self.arm_positions())

    def follow(self, trajectory: JointTrajectory, cancel: threading.Event) -> None:
        """Track a joint trajectory in simulated time; raises MotionCancelledError on cancel."""
        dt = self.options.time_step_s
        t = 0.0
        while t < trajectory.duration:
            if cancel.is_set():
                self.hold()
                raise MotionCancelledError("the trajectory was cancelled")
            t += dt
            self._arm_target = sample(trajectory, t)
            self.step()
        target = np.asarray(trajectory.final)
        for _ in range(round(0.5 / dt)):  # let the joints catch up with the last point
            if np.max(np.abs(np.asarray(self.arm_positions()) - target)) < SETTLE_TOLERANCE:
                break
            if cancel.is_set():
                self.hold()
                raise MotionCancelledError("the trajectory was cancelled")
            self.step()

    def grip(self, per_finger: float, force_n: float, cancel: threading.Event,
             seconds: float = 0.6) -> None:
        """Move both fingers to `per_finger` (metres) with `force_n` each; stop when still."""
        self._finger_target = max(0.0, min(FINGER_OPEN, per_finger))
        self._finger_force = force_n
        last = self.finger_positions()
        for k in range(round(seconds / self.options.time_step_s)):
            if cancel.is_set():
                raise MotionCancelledError("the gripper command was cancelled")
            self.step()
            if k % 12 == 11:
                now = self.finger_positions()
                if max(abs(a - b) for a, b in zip(now, last, strict=True)) < 1e-4:
                    break
                last = now

    # -- ground truth (tests and examples; the adapter itself only uses the camera) --------
    def body_position(self, object_id: str) -> tuple[float, float, float]:
        with self.lock:
            pos, _ = pb.getBasePositionAndOrientation(self.bodies[object_id].body,
                                                      physicsClientId=self.client)
        return pos

    def in_contact(self, a: str, b: str) -> bool:
        with self.lock:
            return bool(pb.getContactPoints(self.bodies[a].body, self.bodies[b].body,
                                            physicsClientId=self.client))

    def close(self) -> None:
        with self.lock:
            if pb.isConnected(self.client):
                pb.disconnect(self.client)

    # -- from a scene graph ----------------------------------------------------------------
    @classmethod
    def from_graph(cls, graph: SceneGraph, options: PyBulletOptions | None = None
                   ) -> PandaScene:
        """A cell whose objects stand as the graph says, laid out in front of the arm.

        The first fixed surface is the ground plane; other fixed surfaces become low
        slabs; movable objects are boxes sized from the dictionary (cm -> m), containers
        are open boxes; stacks are built bottom-up and left to settle.
        """
        scene = cls(options)
        dictionary = load_dictionary(graph.dictionary)
        props = resolve_properties(graph, dictionary, [])
        support = {e.source: (e.relation, e.target) for e in graph.edges
                   if e.relation in SUPPORT_RELATIONS}
        fixed = [n.id for n in graph.nodes if n.id in props and not props[n.id][1].movable]
        ground = next((i for i in fixed if props[i][0] == "table"), fixed[0] if fixed else None)
        if ground is not None:
            scene.add_ground(ground)

        def size_of(node_id: str) -> tuple[float, float, float]:
            p = props[node_id][1]
            width = (p.width or 5.0) / 100
            height = (p.height or 5.0) / 100
            if not p.movable:
                return (min(width, 0.25), min(width, 0.25), 0.03)
            return (width, width, height)

        def colour_of(index: int, node_id: str) -> tuple[float, float, float, float]:
            node = graph.node(node_id)
            named = [str(node.attrs.get("color", "")) if node is not None else ""]
            named += node_id.lower().split("_") + [props[node_id][1].color or ""]
            return next((COLOURS[n] for n in named if n in COLOURS),
                        _PALETTE[index % len(_PALETTE)])

        # Objects standing on the ground (and the other fixed surfaces) get a slot each.
        roots = [i for i in fixed if i != ground] + [
            n.id for n in graph.nodes if n.id in props and props[n.id][1].movable
            and (n.id not in support or support[n.id][1] == ground)]
        widths = [size_of(i)[1] for i in roots]
        gap = 0.06
        total = sum(widths) + gap * max(0, len(roots) - 1)
        y = -total / 2
        placed: dict[str, tuple[float, float, float]] = {}  # id -> (x, y, top z)
        for index, (node_id, width) in enumerate(zip(roots, widths, strict=True)):
            sx, sy, sz = size_of(node_id)
            centre = (0.5, y + width / 2, sz / 2 + 0.001)
            y += width + gap
            scene._add(node_id, (sx, sy, sz), centre, colour_of(index, node_id),
                       container=props[node_id][1].container, fixed=node_id in fixed)
            placed[node_id] = (centre[0], centre[1], sz + 0.001)
        pending = [n.id for n in graph.nodes if n.id in support and n.id not in placed]
        index = len(roots)
        while pending:
            ready = [i for i in pending if support[i][1] in placed]
            if not ready:
                break  # the graph was well formed, so this only drops unsupported leftovers
            for node_id in ready:
                relation, target = support[node_id]
                tx, ty, top = placed[target]
                sx, sy, sz = size_of(node_id)
                bottom = top + 0.001 if relation == "on" else top - size_of(target)[2] + 0.008
                scene._add(node_id, (sx, sy, sz), (tx, ty, bottom + sz / 2),
                           colour_of(index, node_id), container=props[node_id][1].container)
                placed[node_id] = (tx, ty, bottom + sz)
                pending.remove(node_id)
                index += 1
        scene.settle(0.5)
        return scene

    def _add(self, node_id: str, size: tuple[float, float, float],
             centre: tuple[float, float, float], colour: tuple[float, float, float, float], *,
             container: bool, fixed: bool = False) -> None:
        if container and not fixed:
            self.add_container(node_id, size, centre, colour)
        else:
            self.add_box(node_id, size, centre, colour, fixed=fixed)
