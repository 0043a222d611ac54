"""Random tangram aligns, drawn the same way by the agreement benchmark and its test."""

from __future__ import annotations

import random
from collections.abc import Sequence

from verigraph.actions.model import AlignAction
from verigraph.sim2d.tangram_geometry import piece_model


def random_align(rng: random.Random, ids: Sequence[str]) -> AlignAction:
    """An align of one random piece's random side to a random side of another piece.

    Not checked: the caller validates it, so refused draws can be counted or skipped.
    """
    piece, target = rng.sample(ids, 2)
    return AlignAction(object=piece, side=rng.randrange(len(piece_model(piece))), target=target,
                       target_side=rng.randrange(len(piece_model(target))))
