"""The arm's carry in unverified mode: lift the grasped object and swing it over the target.

A verified move only ever grasps a clear object, so the path does not matter and the
object is put down directly. Without the verifier the grasped object may carry others:
here it is moved kinematically (straight up above everything, then across, with a
fast arm's acceleration of 12 m/s^2) while the physics runs, so whatever rests on it
rides, slides or topples as physics dictates. The arm holds only the grasped object.
"""

from __future__ import annotations

import math

import pymunk

from verigraph.sim2d import physics
from verigraph.sim2d.scene import TabletopScene

LIFT_SPEED = 40.0
CARRY_SPEED = 120.0
CLEARANCE = 4.0
ACCELERATION = 1200.0
MAX_STEPS = 5000


def _glide(scene: TabletopScene, body: pymunk.Body, dx: float, dy: float, speed: float) -> None:
    """Move a kinematic body by (dx, dy): accelerate, cruise, brake (trapezoidal speed)."""
    distance = math.hypot(dx, dy)
    if distance < 1e-9:
        return
    ux, uy = dx / distance, dy / distance
    ramp = min(speed * speed / ACCELERATION, distance) / 2  # distance spent accelerating
    peak = math.sqrt(2 * ACCELERATION * ramp)
    travelled, v = 0.0, 0.0
    for _ in range(MAX_STEPS):
        remaining = distance - travelled
        if remaining <= 1e-6:
            break
        braking = v * v / (2 * ACCELERATION) >= remaining
        v = max(ACCELERATION * physics.DT, v - ACCELERATION * physics.DT) if braking else \
            min(peak, v + ACCELERATION * physics.DT)
        v = min(v, remaining / physics.DT)
        body.velocity = (ux * v, uy * v)
        scene.space.step(physics.DT)
        travelled += v * physics.DT
    body.velocity = (0.0, 0.0)


def carry_over(scene: TabletopScene, obj: str, target: str) -> None:
    """Lift `obj` above everything and carry it over `target`, with physics running."""
    thing = scene.things[obj]
    body = thing.body
    others = [t.bounds()[3] for t in scene.things.values()
              if t.id != obj and t.body.space is not None]
    left, bottom, right, _ = thing.bounds()
    rise = max(others + [bottom]) + CLEARANCE - bottom
    body.body_type = pymunk.Body.KINEMATIC
    try:
        _glide(scene, body, 0.0, rise, LIFT_SPEED)
        _glide(scene, body, scene.things[target].com()[0] - (left + right) / 2, 0.0,
               CARRY_SPEED)
    finally:
        body.body_type = pymunk.Body.DYNAMIC
