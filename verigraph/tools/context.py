"""What every tool function receives: the episode store and the server's limits."""

from __future__ import annotations

from dataclasses import dataclass, field

from verigraph.tools.store import DEFAULT_IDLE_TIMEOUT_S, DEFAULT_MAX_EPISODES, EpisodeStore


@dataclass(frozen=True)
class ToolConfig:
    """Limits and switches; the defaults suit a local server for one or a few agents."""

    max_episodes: int = DEFAULT_MAX_EPISODES
    idle_timeout_s: float = DEFAULT_IDLE_TIMEOUT_S
    enable_solve: bool = True
    max_actions_per_episode: int = 10_000


@dataclass
class ToolContext:
    """The shared state of one tool host (a server process, a CLI run, a test)."""

    config: ToolConfig = field(default_factory=ToolConfig)
    store: EpisodeStore = field(init=False)

    def __post_init__(self) -> None:
        self.store = EpisodeStore(self.config.max_episodes, self.config.idle_timeout_s)
