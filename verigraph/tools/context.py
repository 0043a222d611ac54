"""What every tool function receives: the episode store, the arm cells and the limits."""

from __future__ import annotations

from dataclasses import dataclass, field

from verigraph.tools.executors import DEFAULT_MAX_ARM_WORLDS, ArmCells, ArmSetup
from verigraph.tools.store import (
    DEFAULT_IDLE_TIMEOUT_S,
    DEFAULT_MAX_EPISODES,
    Episode,
    EpisodeStore,
)


@dataclass(frozen=True)
class ToolConfig:
    """Limits and switches; the defaults suit a local server for one or a few agents.

    `executor` is where load_scene episodes run unless the call picks another; `arm`
    is the server's arm (from --arm-config), used by `arm:<driver>` episodes.
    """

    max_episodes: int = DEFAULT_MAX_EPISODES
    idle_timeout_s: float = DEFAULT_IDLE_TIMEOUT_S
    enable_solve: bool = True
    max_actions_per_episode: int = 10_000
    executor: str = "graph"
    arm: ArmSetup | None = None
    max_arm_worlds: int = DEFAULT_MAX_ARM_WORLDS


@dataclass
class ToolContext:
    """The shared state of one tool host (a server process, a CLI run, a test)."""

    config: ToolConfig = field(default_factory=ToolConfig)
    store: EpisodeStore = field(init=False)
    arms: ArmCells = field(init=False)

    def __post_init__(self) -> None:
        self.arms = ArmCells(self.config.max_arm_worlds)
        self.store = EpisodeStore(self.config.max_episodes, self.config.idle_timeout_s,
                                  on_drop=self._drop)

    def _drop(self, episode: Episode) -> None:
        """An ended or evicted episode lets go of its arm (disconnects, frees the cell)."""
        self.arms.close(episode.world)
