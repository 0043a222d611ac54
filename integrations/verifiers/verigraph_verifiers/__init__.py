"""VeriGraph as a verifiers taskset (`--env.taskset.id verigraph-verifiers`).

`load_environment(base_url=..., family=..., level=..., size=...)` gives the verifiers
`Env`; verifiers finds the same classes itself from the taskset id.
"""

from verigraph_verifiers.taskset import (
    VeriGraphConfig,
    VeriGraphData,
    VeriGraphEnv,
    VeriGraphEnvConfig,
    VeriGraphTask,
    VeriGraphTaskset,
    load_environment,
)

__all__ = [
    "VeriGraphConfig",
    "VeriGraphData",
    "VeriGraphEnv",
    "VeriGraphEnvConfig",
    "VeriGraphTask",
    "VeriGraphTaskset",
    "load_environment",
]
