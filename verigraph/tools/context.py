"""What every tool function receives: the episode store, the arm cells and the limits."""

from __future__ import annotations

from dataclasses import dataclass, field

from verigraph.tools.executors import (
    DEFAULT_MAX_ARM_WORLDS,
    ArmCells,
    ArmSetup,
    arm_setup_for,
)
from verigraph.tools.records import WorldExtras
from verigraph.tools.store import (
    DEFAULT_IDLE_TIMEOUT_S,
    DEFAULT_MAX_EPISODES,
    DEFAULT_RECLAIM_IDLE_S,
    EpisodeStore,
    LiveEpisode,
)
from verigraph.tools.store_durable import DurableStore
from verigraph.tools.stores import open_store


@dataclass(frozen=True)
class ToolConfig:
    """Limits and switches; the defaults suit a local server for one or a few agents.

    `executor` is where load_scene episodes run unless the call picks another; `arm`
    is the server's arm (from --arm-config), used by `arm:<driver>` episodes. `store`
    is where episodes live (see `tools.stores`): memory unless the host picks a durable one.
    `episodes_per_caller` is one caller's share of `max_episodes` (None: all of it, for
    a host with one caller); a full store replaces episodes idle `reclaim_idle_s`.
    """

    max_episodes: int = DEFAULT_MAX_EPISODES
    episodes_per_caller: int | None = None
    reclaim_idle_s: float = DEFAULT_RECLAIM_IDLE_S
    idle_timeout_s: float = DEFAULT_IDLE_TIMEOUT_S
    enable_solve: bool = True
    max_actions_per_episode: int = 10_000
    executor: str = "graph"
    arm: ArmSetup | None = None
    max_arm_worlds: int = DEFAULT_MAX_ARM_WORLDS
    store: str = "memory://"


@dataclass
class ToolContext:
    """The shared state of one tool host (a server process, a CLI run, a test)."""

    config: ToolConfig = field(default_factory=ToolConfig)
    store: EpisodeStore = field(init=False)
    arms: ArmCells = field(init=False)

    def __post_init__(self) -> None:
        self.arms = ArmCells(self.config.max_arm_worlds)
        self.store = open_store(self.config.store, self.config.max_episodes,
                                self.config.idle_timeout_s, on_drop=self._drop,
                                share=self.config.episodes_per_caller,
                                reclaim_after=self.config.reclaim_idle_s)
        if isinstance(self.store, DurableStore):
            self.store.revive = self._revive

    def _drop(self, episode: LiveEpisode) -> None:
        """An ended or evicted episode lets go of its arm (disconnects, frees the cell)."""
        self.arms.close(episode.world)

    def _revive(self, episode: LiveEpisode) -> None:
        """A stored arm episode gets a fresh driver connection in this process.

        The connection is never assumed to survive; a stop latched before the record
        was written is latched again on the new connection.
        """
        if not episode.executor.startswith("arm:") or episode.state is None:
            return
        setup = arm_setup_for(episode.executor, self.config.arm)
        world, _ = self.arms.open(setup, episode.state, self.store.evict_idle)
        object.__setattr__(episode, "world", world)
        if isinstance(world, WorldExtras):
            world.restore_extras(episode.extras)  # e.g. latch a stop latched before
