"""Where an episode's actions run: the graph only, the 2D simulator, or a robot arm.

`graph` verifies only; `sim2d` also runs every action in the pymunk world; `arm:<driver>`
sends it through the arm adapter (verigraph.arm), the only path to a robot. The arm's
configuration belongs to the server (`verigraph serve --arm-config`): a client may
choose an executor per episode but never the arm's mode or limits, so `real` stays the
operator's explicit opt-in in the config file. `runs_on` words where an episode's
actions run for every text that says it.
"""

from __future__ import annotations

import contextlib
import ctypes
import ctypes.util
import functools
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from pydantic import BaseModel, Field

from verigraph.arm import (
    ArmConfig,
    ArmConfigError,
    ArmWorld,
    driver_from_executor,
    load_arm_config,
    open_arm_world,
    parse_arm_config,
    probe_arm,
    scoped_confirm,
)
from verigraph.arm.models import RunMode
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.sim2d import world_for_graph
from verigraph.tools.errors import EpisodeLimitError, ToolArgumentError

EXECUTOR_HELP = "graph (verify only), sim2d or arm:<pybullet|rosbridge|xarm>"
DEFAULT_MAX_ARM_WORLDS = 8

ArmOpener = Callable[[ArmConfig, SceneGraph], ArmWorld]


def open_with_elicitation(config: ArmConfig, graph: SceneGraph) -> ArmWorld:
    """The server's arm world: real motions ask whichever hook the tool call installed."""
    return open_arm_world(config, graph, confirm=scoped_confirm)


@dataclass(frozen=True)
class ArmSetup:
    """The server's arm: its validated configuration and how to open a world on it.

    `opener` is the seam for hardware that cannot run here (tests pass a driver around
    a stand-in for the vendor SDK); the server uses `open_with_elicitation`.
    """

    config: ArmConfig
    opener: ArmOpener = open_with_elicitation

    @property
    def executor(self) -> str:
        return f"arm:{self.config.driver}"


def arm_mode_of(world: object) -> RunMode | None:
    """An arm episode's mode (dry-run, sim, real); None for graph and sim2d episodes."""
    return world.config.mode if isinstance(world, ArmWorld) else None


def runs_on(executor: str, arm_mode: str | None = None) -> str:
    """Where the actions run, worded so that no reader takes a check for a motion.

    `graph` and `sim2d` never move anything physical; an arm episode says its mode, and
    only `real` means a robot moved.
    """
    if executor == "graph":
        return "graph (verified only, nothing physical moved)"
    if executor == "sim2d":
        return "sim2d (simulated in the 2D simulator, nothing physical moved)"
    what = {"real": "real arm: validated actions move the robot after the user approves",
            "sim": "simulated arm, nothing physical moved",
            "dry-run": "dry-run: motions recorded, nothing moved"}.get(
                arm_mode or "", "robot arm")
    return f"{executor} ({what})"


def executor_line(executor: str, arm_mode: str | None = None) -> str:
    """`executor: graph (verified only, nothing physical moved)`"""
    return f"executor: {runs_on(executor, arm_mode)}"


def enabled_executors(default: str, arm: ArmSetup | None) -> str:
    """The executors this server runs, its default marked: what a client may pick.

    `graph (verified only, default), sim2d (simulated), arm:xarm (real arm)`; shown in the
    server's instructions and in every refusal of an executor, so no client has to find
    the configured arm by trial and error.
    """
    names = {"graph": "verified only", "sim2d": "simulated"}
    if arm is not None:
        names[arm.executor] = {"real": "real arm", "sim": "simulated arm",
                               "dry-run": "arm dry-run, nothing moves"}[arm.config.mode]
    return ", ".join(f"{n} ({what}{', default' if n == default else ''})"
                     for n, what in names.items())


def executors_text(default: str, arm: ArmSetup | None) -> str:
    """`executors on this server: graph (verified only, default), sim2d (simulated); no
    robot connected: ...`: said when a scene loads, so whether a robot is there is never
    learnt by a refused call."""
    text = f"executors on this server: {enabled_executors(default, arm)}"
    if arm is None:
        return (text + "; no robot connected: no executor here moves a real robot (a plan "
                "runs on the graph or in the simulator only)")
    if arm.config.mode != "real":
        return text + f"; {arm.executor} is an arm in {arm.config.mode} mode: no real robot moves"
    return text + f"; {arm.executor} reaches a real robot (arm_status: its connection)"


def check_executor(name: str, *, field: str = "executor", enabled: str | None = None) -> str:
    """`graph`, `sim2d` or a known `arm:<driver>`; anything else names the choices
    (`enabled`: the server's own, see enabled_executors)."""
    if name in ("graph", "sim2d"):
        return name
    if not name.startswith("arm:"):
        choices = f"this server runs {enabled}" if enabled else f"use {EXECUTOR_HELP}"
        raise ToolArgumentError(f"unknown executor '{name[:64]}'", field=field,
                                value=name[:64], fix=choices)
    try:
        driver_from_executor(name)
    except ArmConfigError as exc:
        raise ToolArgumentError(exc.message, field=field, value=name[:64],
                                fix=exc.fix) from None
    return name


def arm_setup_for(executor: str, server_arm: ArmSetup | None) -> ArmSetup:
    """The arm an `arm:<driver>` episode runs on: the server's, and only the server's.

    Arms are the operator's choice (`verigraph serve --executor arm:<driver>` or
    `--arm-config`), never a client's: on a server without an arm every arm executor
    is refused, so no client can make it open PyBullet worlds or connect to hardware.
    """
    driver_from_executor(executor)
    if server_arm is None:
        raise ToolArgumentError(
            f"this server has no arm, so executor {executor} is not available",
            field="executor", value=executor,
            fix="this server runs graph (verified only) and sim2d (simulated); arm episodes "
                "need a server started with --executor arm:<driver> or --arm-config")
    if server_arm.executor != executor:
        raise ToolArgumentError(
            f"this server's arm is {server_arm.executor}, not {executor}", field="executor",
            value=executor, fix=f"use executor {server_arm.executor}, graph or sim2d; another "
                                "arm needs a server started with its own --arm-config")
    return server_arm


def server_executor(executor: str | None, arm_config: str | Path | None
                    ) -> tuple[str, ArmSetup | None]:
    """`verigraph serve --executor/--arm-config`, checked before the server starts.

    The default executor is the config's arm when a config is given, else `graph`. A
    hardware arm must have a locator (a `layout` in its config) and, unless in
    dry-run, answer a TCP connection within its connect timeout.
    """
    config = load_arm_config(arm_config) if arm_config is not None else None
    name = check_executor(executor or (f"arm:{config.driver}" if config else "graph"),
                          field="--executor")
    if not name.startswith("arm:"):
        return name, ArmSetup(config) if config else None
    driver = driver_from_executor(name)
    if config is not None and config.driver != driver:
        raise ToolArgumentError(f"--executor {name} but the arm config's driver is "
                                f"{config.driver}", field="--arm-config", value=str(arm_config),
                                fix=f"use --executor arm:{config.driver}, or a config with "
                                    f"driver: {driver}")
    config = config or parse_arm_config({"driver": driver})
    if driver != "pybullet" and not config.layout:
        raise ArmConfigError(f"the {driver} driver has no camera of its own and the config "
                             "gives no layout", field="layout", value=None,
                             fix="add a layout (object id -> measured centre and size) to "
                                 "the arm config, or use --executor arm:pybullet")
    probe_arm(config)
    return name, ArmSetup(config)


class SceneCheck(BaseModel):
    """How the scene the arm observes compares with the episode's graph at the start."""

    matches: bool
    not_observed: list[str] = Field(description="edges of the graph the arm does not see")
    observed_instead: list[str] = Field(description="edges the arm sees that the graph lacks")

    def summary(self) -> str:
        if self.matches:
            return "the arm observes the scene as the graph says"
        parts = []
        if self.not_observed:
            parts.append("not observed: " + "; ".join(self.not_observed))
        if self.observed_instead:
            parts.append("observed instead: " + "; ".join(self.observed_instead))
        return ("WARNING: the arm observes a different scene (" + " | ".join(parts) + "); it "
                "validates every action on what it observes, so fix the graph or the cell "
                "and load the scene again")


def check_scene(world: ArmWorld, graph: SceneGraph) -> SceneCheck:
    found = world.verify_scene(graph)
    return SceneCheck(matches=found.satisfied,
                      not_observed=found.missing_edges + [f"object {n}" for n in
                                                          found.missing_nodes],
                      observed_instead=found.extra_edges + [f"object {n}" for n in
                                                            found.extra_nodes])


@dataclass
class ArmCells:
    """The open arm worlds of one tool host: a bounded number, one per hardware arm.

    Two episodes must never drive the same physical arm (each would believe it runs
    the only motion), so a connected hardware arm belongs to one episode until it
    ends. Simulated cells and dry runs are only bounded by `limit`.
    """

    limit: int = DEFAULT_MAX_ARM_WORLDS
    _lock: threading.Lock = field(default_factory=threading.Lock)
    # open worlds and reservations (a plain object while connecting) -> hardware key
    _slots: dict[object, str | None] = field(default_factory=dict)

    def __len__(self) -> int:
        with self._lock:
            return len(self._slots)

    def open(self, setup: ArmSetup, state: WorldState,
             evict_idle: Callable[[], None]) -> tuple[ArmWorld, SceneCheck]:
        """Open (and connect) a world for `state`, and check the scene it observes."""
        if state.dictionary.name == "tangram":
            raise ToolArgumentError("the arm adapter carries out move actions only, and "
                                    "tangram scenes need align", field="executor",
                                    value=setup.executor, fix="use executor sim2d or graph")
        if len(self) >= self.limit:
            evict_idle()
        token = self._reserve(setup)
        try:
            graph = state.to_graph()
            world = setup.opener(setup.config, graph)
            try:
                check = check_scene(world, graph)
            except BaseException:
                world.close()
                raise
        except BaseException:
            self._release(token)
            raise
        with self._lock:
            self._slots[world] = self._slots.pop(token)
        return world, check

    def close(self, world: object) -> None:
        """Close an arm world (disconnecting it) and free its slot; others are ignored."""
        if isinstance(world, ArmWorld):
            try:
                world.close()
            finally:
                self._release(world)
                return_freed_memory()

    def _reserve(self, setup: ArmSetup) -> object:
        key = _hardware_key(setup.config)
        with self._lock:
            if len(self._slots) >= self.limit:
                raise EpisodeLimitError(
                    f"the server already runs {self.limit} arm cells", field="executor",
                    value=setup.executor, fix="call end_episode on arm episodes you no "
                                              "longer need, or use executor graph")
            if key is not None and key in self._slots.values():
                raise EpisodeLimitError(
                    f"the {setup.config.driver} arm at {setup.config.host} is in use by "
                    "another episode", field="executor", value=setup.executor,
                    fix="call end_episode on that episode first; one episode drives a "
                        "physical arm at a time")
            token = object()
            self._slots[token] = key
            return token

    def _release(self, slot: object) -> None:
        with self._lock:
            self._slots.pop(slot, None)


def return_freed_memory() -> None:
    """Hand memory freed by a closed arm world (meshes, simulator state) back to the OS.

    glibc keeps freed heap pages in its arenas, so the process would stay as large as
    its peak after every closed PyBullet world; malloc_trim releases them.
    """
    with contextlib.suppress(OSError, AttributeError):  # not glibc: nothing to trim
        _libc().malloc_trim(0)


@functools.cache
def _libc() -> ctypes.CDLL:
    """The C library, looked up once (find_library runs `ldconfig -p` in a subprocess)."""
    return ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")


def _hardware_key(config: ArmConfig) -> str | None:
    """The physical arm a config connects to, or None for simulators and dry runs."""
    if config.mode == "dry-run" or config.driver == "pybullet":
        return None
    return f"{config.driver}@{config.host}"


def check_tangram_start(state: WorldState) -> None:
    """The one rule of a valid tangram start, whatever the executor: the pieces can lie
    as align lays them with exactly the listed contacts and no overlap, as the
    simulator lays them out (`sim2d.tangram.build_tangram`, whose SimError names the
    piece, each contact tried and what went wrong). Anything but tangram passes."""
    if state.objects and all(o.props.sides is not None for o in state.objects.values()):
        world_for_graph(state.to_graph())
