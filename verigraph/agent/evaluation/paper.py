"""The paper's published numbers (Ekpo et al., "VeriGraph: Scene Graphs for Execution
Verifiable Robot Planning"): Table 1 (scene graph generation) and Table 2 (planning).

This module is the one place they live. They are printed as published, in tables of
their own beside ours (never as rows among ours: the paper's planner is GPT-4 with
GPT-4V scene graphs on its own scenes, ours are offline planners on generated suites).
Table 2's columns are the methods SayCan, VILA, Ours (Direct) and Ours (iterative
planning with constraint validation); "-" is a cell the paper leaves empty (SayCan
receives only object names, so it is not evaluated on image goals). The test of this
module parses the paper's LaTeX tables and checks every value printed here.
"""

from __future__ import annotations

from typing import NamedTuple

from verigraph.agent.evaluation.markdown import table
from verigraph.tasks.groups import GroupName

GROUP_TITLES: dict[GroupName, str] = {
    "stacking": "Stacking",
    "language": "Language instr.",
    "ref_image_kitchen": "Ref. image (kitchen)",
    "ref_image_blocks": "Ref. image (blocks)",
    "tangram": "Tangram",
}
# Table 2's column order in the paper (tasks are its rows there).
PAPER_GROUPS: tuple[GroupName, ...] = ("stacking", "language", "ref_image_blocks",
                                       "ref_image_kitchen", "tangram")
# Success rates as fractions, exactly as Table 2 prints them; None is the paper's "-".
TABLE2: dict[str, dict[GroupName, float | None]] = {
    "SayCan": {"stacking": 0.07, "language": 0.17, "ref_image_blocks": None,
               "ref_image_kitchen": 0.00, "tangram": None},
    "VILA": {"stacking": 0.62, "language": 0.43, "ref_image_blocks": 0.27,
             "ref_image_kitchen": 0.05, "tangram": 0.16},
    "Ours (Direct)": {"stacking": 0.35, "language": 0.73, "ref_image_blocks": 0.67,
                      "ref_image_kitchen": 0.50, "tangram": 0.72},
    "Ours (iterative)": {"stacking": 0.65, "language": 0.65, "ref_image_blocks": 0.86,
                         "ref_image_kitchen": 0.55, "tangram": 0.72},
}
ITERATIVE = "Ours (iterative)"


class SggRow(NamedTuple):
    """One row of Table 1: a scene family, the VLM, node and edge F1, exact graphs."""

    scene: str
    method: str
    nodes_f1: float
    edges_f1: float
    exact: float


TABLE1: tuple[SggRow, ...] = (
    SggRow("Blocks", "LLaVA", 0.30, 0.07, 0.00),
    SggRow("Blocks", "Gemini", 1.00, 0.93, 0.73),
    SggRow("Blocks", "GPT-4V", 1.00, 1.00, 1.00),
    SggRow("Kitchen", "LLaVA", 0.50, 0.05, 0.00),
    SggRow("Kitchen", "Gemini", 0.78, 0.59, 0.04),
    SggRow("Kitchen", "GPT-4V", 0.98, 0.87, 0.65),
    SggRow("Tableware", "LLaVA", 0.52, 0.16, 0.00),
    SggRow("Tableware", "Gemini", 0.95, 0.90, 0.39),
    SggRow("Tableware", "GPT-4V", 0.99, 0.95, 0.89),
)

PAPER_MARGINS = ("The paper's abstract: VeriGraph is ahead of its baseline methods by 58 "
                 "points on language tasks, 56 on tangram and 30 on image-based tasks.")
COMPARABILITY = (
    "Not comparable in value: the paper's planner is GPT-4 on its own scenes, images and "
    "instructions; the rows above are offline planners (a privileged solver, a translator, "
    "a greedy heuristic, a solver with injected errors) on this project's generated suites. "
    "What carries over is the shape of the effects (iterative vs direct, feedback vs none, "
    "the threshold t); only an LLM backend row (`--planners openai` or `anthropic` with a "
    "key) has the same kind of planner, still on different tasks."
)
SGG_COMPARABILITY = (
    "The paper's VLMs read its own photographs without in-context examples; `bench sgg` "
    "measures this project's detectors on generated scenes, so only the metrics (node and "
    "edge F1, exact graph accuracy) are shared, not the images."
)


def _cell(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f}"


def table2_rows() -> list[list[str]]:
    """Table 2 as printed: one row per method, the paper's column order, two decimals."""
    return [[method, *[_cell(cells[g]) for g in PAPER_GROUPS]]
            for method, cells in TABLE2.items()]


def paper_table() -> list[str]:
    """The paper's Table 2 (all four methods) and what is and is not comparable."""
    header = ["paper (Table 2), success rate", *[GROUP_TITLES[g] for g in PAPER_GROUPS]]
    return [*table(header, table2_rows()), "", PAPER_MARGINS, "", COMPARABILITY]


def sgg_paper_table() -> list[str]:
    """The paper's Table 1 (scene graph generation), for printing beside `bench sgg`."""
    header = ["paper (Table 1): scene", "method", "node F1", "edge F1",
              "exact graph accuracy"]
    rows = [[r.scene, r.method, f"{r.nodes_f1:.2f}", f"{r.edges_f1:.2f}", f"{r.exact:.2f}"]
            for r in TABLE1]
    return [*table(header, rows), "", SGG_COMPARABILITY]


def paper_value(group: GroupName, method: str = ITERATIVE) -> float | None:
    """One published cell of Table 2 (None where the paper prints '-')."""
    return TABLE2[method][group]
