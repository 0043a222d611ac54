"""The simulator's user-facing error: a scene or action it cannot realise physically."""

from __future__ import annotations

from verigraph.errors import VeriGraphError


class SimError(VeriGraphError):
    """A graph the simulator cannot lay out, or a request it cannot carry out.

    Carries the field, the offending value and a fix like every VeriGraphError, so the
    CLI exits with code 2 and the server answers with a tool error.
    """
