"""`verigraph perceive IMAGE`: built-in perception (or a VLM endpoint) from the command line.

Prints the scene graph's sentences, or with --json the graph together with the view,
the family, the detected objects and any warnings. Exit 0 with a graph (warnings go to
stderr), 2 for input that cannot be perceived (not an image, truncated, too large).
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

from verigraph.cli.exits import EXIT_OK

FAMILIES = ("all", "blocks", "kitchen", "tableware", "tangram")


def register(sub: Any) -> None:
    p = sub.add_parser("perceive", help="image -> scene graph (built-in perception)",
                       description=__doc__)
    p.add_argument("image", help="PNG, JPEG, BMP or WebP file")
    p.add_argument("--family", default="all", help="dictionary D: blocks, kitchen, tableware, "
                                                   "tangram, all (default) or a file path")
    p.add_argument("--json", action="store_true", help="print the result as JSON")
    p.add_argument("--view", choices=("auto", "tabletop", "tangram"), default="auto")
    p.add_argument("--labeller", choices=("default", "clip"), default="default",
                   help="clip: OpenCLIP zero-shot labels (needs verigraph-mcp[clip] and local "
                        "weights; falls back to default with a message)")
    p.add_argument("--clip-model", default=None,
                   help="open_clip architecture or local-dir:/path folder (default ViT-B-32)")
    p.add_argument("--clip-pretrained", default=None,
                   help="pretrained tag in your cache (default openai) or a checkpoint file")
    p.add_argument("--max-pixels", type=int, default=None,
                   help="refuse larger images (default 40000000)")
    p.add_argument("--task", default=None, help="task T for the VLM prompt")
    p.add_argument("--vlm-model", default=None, help="use an OpenAI-compatible vision model "
                                                     "instead of the built-in detectors")
    p.add_argument("--vlm-base-url", default=None, help="e.g. http://127.0.0.1:11434/v1")
    p.add_argument("--vlm-response-format", default="json_schema",
                   choices=("json_schema", "json_object_schema", "json_object", "none"))
    p.set_defaults(handler=run_perceive)


def run_perceive(args: argparse.Namespace) -> int:
    from verigraph.perception.config import ImageLimits, PerceptionConfig
    from verigraph.perception.imageio import read_image
    from verigraph.perception.pipeline import perceive_image

    limits = ImageLimits(**({"max_pixels": args.max_pixels} if args.max_pixels else {}))
    dictionary = None if args.family == "all" else args.family
    image = read_image(args.image, limits)
    notes: list[str] = []
    if args.vlm_model:
        from verigraph.perception import VlmClient, VlmConfig

        client = VlmClient(VlmConfig.from_env(model=args.vlm_model, base_url=args.vlm_base_url,
                                              response_format=args.vlm_response_format))
        try:
            result = client.perceive(image, dictionary, task=args.task, limits=limits)
        finally:
            client.close()
    else:
        from verigraph.perception import ClipSource, make_labeller

        source = ClipSource(**{k: v for k, v in (("model", args.clip_model),
                                                 ("pretrained", args.clip_pretrained))
                               if v is not None})
        labeller, note = make_labeller(args.labeller, source)
        if note:
            notes.append(note)
        config = PerceptionConfig(limits=limits, view=args.view)
        result = perceive_image(image, dictionary=dictionary, config=config, labeller=labeller)
    result.warnings[:0] = notes
    if args.json:
        print(json.dumps(result.model_dump(mode="json"), indent=2))
    else:
        lines = result.graph.sentences() or ["(no relations)"]
        print(f"# {result.view} view, {len(result.graph.nodes)} objects"
              + (f", {result.family}" if result.family else ""))
        print("\n".join(lines))
    if result.family_reason and not args.json:
        print(f"family: {result.family_reason}", file=sys.stderr)
    for warning in result.warnings:
        print(f"warning: {warning}", file=sys.stderr)
    for item in result.uncertain:
        print(f"uncertain: {item.item} ({item.confidence:.2f}): {item.reason}", file=sys.stderr)
    return EXIT_OK
