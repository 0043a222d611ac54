"""VeriGraph task planning as an OpenEnv environment (openenv 0.10).

`VeriGraphEnv` is the client (OpenEnv's `EnvClient`), `VeriGraphAction` the model's text
reply, `VeriGraphObservation` the next planner prompt with the verifier's verdict. The
server (`verigraph_openenv.server.app`) forwards each session to a VeriGraph environment
server over OpenEnv's WebSocket protocol.
"""

from verigraph_openenv.client import VeriGraphEnv
from verigraph_openenv.models import VeriGraphAction, VeriGraphObservation

__all__ = ["VeriGraphAction", "VeriGraphEnv", "VeriGraphObservation"]
