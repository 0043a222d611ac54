"""Errors the tool layer adds to the core ones: episodes, limits and missing subsystems.

They are VeriGraphError subclasses, so every transport reports them the same way:
the field that was wrong, the value seen, and what to do instead.
"""

from __future__ import annotations

from verigraph.errors import VeriGraphError


class ToolArgumentError(VeriGraphError):
    """Arguments that do not match a tool's input model (wrong type, unknown name...)."""


class UnknownEpisodeError(VeriGraphError):
    """An episode id that is not (or no longer) in the store."""

    def __init__(self, episode_id: str) -> None:
        shown = episode_id if len(episode_id) <= 48 else episode_id[:45] + "..."
        super().__init__(f"no open episode with id '{shown}'", field="episode_id", value=shown,
                         fix="pass the episode_id returned by load_scene; ended or expired "
                             "episodes are gone, so call load_scene again to start a new one")


class EpisodeLimitError(VeriGraphError):
    """The store already holds its maximum number of open episodes."""


class EpisodeShareError(EpisodeLimitError):
    """The caller already holds its share of the store's episodes (others may open more)."""


class EpisodeStateError(VeriGraphError):
    """A call that the episode's current phase does not allow (e.g. executing after t)."""


class FeatureUnavailableError(VeriGraphError):
    """A tool this server's configuration disables (e.g. solve)."""


class InvalidArgumentsError(ToolArgumentError):
    """Several argument problems at once; the message already names each field."""

    def __str__(self) -> str:
        return self.message if not self.fix else f"{self.message} (fix: {self.fix})"


class StaleEpisodeError(VeriGraphError):
    """Another process changed the episode while this call ran on an older version.

    Nothing of this call was stored; the tool host runs the call again on the new state.
    """


class StoreError(VeriGraphError):
    """The episode store cannot be opened or reached (bad --store URL, server down)."""
