"""The degradation suite at a small size: mild camera changes keep graphs exact, and a
wrong graph never comes without a warning (the silent-wrong rate), strong levels too.

The full-size numbers are `verigraph bench sgg` (benchmarks/results/sgg_robustness.md).
"""

from __future__ import annotations

from functools import cache

import pytest

from verigraph.perception import perceive_image, score_graph
from verigraph.perception.robustness import FAMILIES, SUITE, CellResult, run_suite
from verigraph.sim2d.generator import generate_scene

N = 3  # scenes per family; 4 families x 11 degradations x 2 levels x 3 = 264 images
SEED = 31_000  # apart from the benchmark's seeds


@cache
def cells() -> tuple[CellResult, ...]:
    return tuple(run_suite(FAMILIES, N, first_seed=SEED))


@cache
def clean_exact(family: str) -> float:
    """Exact accuracy on the same scenes undegraded."""
    hits = 0
    for seed in range(SEED, SEED + N):
        scene = generate_scene(family, seed)
        result = perceive_image(scene.world.render(), dictionary=family)
        hits += score_graph(result.graph, scene.graph, family).exact
    return hits / N


@pytest.mark.parametrize("family", FAMILIES)
def test_mild_degradations_keep_graphs_exact(family: str) -> None:
    """Mild exact >= 0.95 of what clean perception gets on the same scenes (a sample of
    three cannot measure 0.95 absolutely when clean tangram is 0.99; the benchmark
    reports the absolute rate)."""
    mild = [c for c in cells() if c.family == family and c.level == "mild"]
    assert len(mild) == len(SUITE)
    exact = sum(c.exact for c in mild) / sum(c.images for c in mild)
    wrong = [f"{c.degradation}: {c.images - c.exact}/{c.images}" for c in mild
             if c.exact < c.images]
    assert clean_exact(family) >= 2 / 3
    assert exact >= 0.95 * clean_exact(family), wrong


def test_wrong_graphs_are_never_silent() -> None:
    everything = cells()
    images = sum(c.images for c in everything)
    silent = [f"{c.family}/{c.degradation}/{c.level}: {c.silent_wrong}" for c in everything
              if c.silent_wrong]
    assert images == len(FAMILIES) * len(SUITE) * 2 * N
    assert sum(c.silent_wrong for c in everything) <= 0.01 * images, silent


def test_strong_degradations_are_flagged_not_trusted() -> None:
    """Being wrong is forgivable: at the strong levels most wrong graphs exist, and
    every one of them must be flagged (the test above); here, that flagging is not a
    blanket: clean-looking mild images mostly pass unflagged."""
    mild = [c for c in cells() if c.level == "mild"]
    unflagged = sum(c.images - c.flagged for c in mild) / sum(c.images for c in mild)
    assert unflagged >= 0.5
