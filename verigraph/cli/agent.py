"""`verigraph agent`: run Algorithm 1 as a real MCP client of a VeriGraph server.

It spawns `verigraph serve` over stdio (default) or connects to a streamable-HTTP URL,
then does everything through the tools (load_scene, set_goal, get_state,
execute_actions, end_episode), printing each iteration and the verdict.
Exit codes: 0 goal reached, 1 goal missed, 2 bad input, 3 the planner raised (the
episode is closed and --trace is still written).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from verigraph.cli.exits import EXIT_NEGATIVE, EXIT_OK, EXIT_PLANNER_FAILED
from verigraph.cli.scenes import scene_argument
from verigraph.errors import VeriGraphError


def register(sub: Any) -> None:
    from verigraph.llm.formats import RESPONSE_FORMATS
    from verigraph.planning.factory import PLANNER_NAMES
    from verigraph.planning.iteration import DEFAULT_K, DEFAULT_THRESHOLD
    from verigraph.planning.noisy import MISTAKE_KINDS

    p = sub.add_parser(
        "agent", help="plan with an LLM (or the solver) through the MCP tools, Algorithm 1",
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    task = p.add_argument_group("task")
    task.add_argument("--scene", required=True,
                      help="built-in scene id (cup_on_book, three_blocks, kitchen_pan), a scene "
                           "file (.json/.yaml), or a generated scene FAMILY:SEED[:N] "
                           "(e.g. blocks:3, needs sim2d)")
    task.add_argument("--goal", help="goal file (graph, {graph, partial}, {predicate}, "
                                     "{formula} or a formula as text), a predicate name "
                                     "(single_stack) or a formula '(forall ...)'; default: "
                                     "the scene's own")
    task.add_argument("--instruction", help="the task in words, shown to the planner")
    task.add_argument("--hide-goal-graph", action="store_true",
                      help="show the planner only the instruction; the verifier still checks "
                           "the goal graph")
    task.add_argument("--simulate", action="store_true",
                      help="also execute actions in the 2D simulator (needs sim2d)")
    loop = p.add_argument_group("loop (Algorithm 1)")
    loop.add_argument("--planner", choices=PLANNER_NAMES, default="oracle")
    loop.add_argument("--mode", choices=("iterative", "direct"), default="iterative")
    loop.add_argument("--k", type=int, default=DEFAULT_K,
                      help=f"actions per iteration (default {DEFAULT_K})")
    loop.add_argument("--threshold", "-t", type=int, default=DEFAULT_THRESHOLD,
                      help="the error threshold: stop after this many consecutive failed "
                           f"iterations (default {DEFAULT_THRESHOLD})")
    loop.add_argument("--done-policy", choices=("verify", "trust"), default="verify",
                      help="verify: refuse done while the goal does not hold (default); "
                           "trust: the end token always stops (the paper's literal rule)")
    loop.add_argument("--stop-on-goal", action=argparse.BooleanOptionalAction, default=True,
                      help="stop as soon as the goal holds (default); --no-stop-on-goal "
                           "waits for the end token, the paper's literal rule")
    loop.add_argument("--no-progress", type=int, default=15, metavar="N",
                      help="stop after N iterations without a new lowest distance to the "
                           "goal, e.g. valid moves back and forth (default 15; 0 = never)")
    loop.add_argument("--max-iterations", type=int, default=60, metavar="N",
                      help="stop after N planner calls whatever tau is (default 60): the "
                           "last safety stop for planners that never finish")
    loop.add_argument("--feedback", choices=("full", "constraint", "none"), default="full",
                      help="what the planner is told of a failure: the verifier's full "
                           "report (default), the constraint id only, or nothing")
    server = p.add_argument_group("server")
    server.add_argument("--transport", choices=("stdio", "http"), default="stdio",
                        help="stdio: spawn `verigraph serve`; http: connect to --url")
    server.add_argument("--url", help="MCP endpoint for --transport http, e.g. "
                                      "http://127.0.0.1:8000/mcp")
    server.add_argument("--token", help="bearer token for --transport http "
                                        "(default: $VERIGRAPH_TOKEN)")
    llm = p.add_argument_group("planner backends")
    llm.add_argument("--noise", type=float, default=0.3, help="noisy: mistake rate per call")
    llm.add_argument("--seed", type=int, default=0, help="noisy: RNG seed")
    llm.add_argument("--mistakes", default=",".join(MISTAKE_KINDS),
                     help=f"noisy: comma-separated kinds ({', '.join(MISTAKE_KINDS)})")
    llm.add_argument("--base-url", help="openai/anthropic endpoint (default: $OPENAI_BASE_URL "
                                        "or $ANTHROPIC_BASE_URL, else the public API)")
    llm.add_argument("--model", help="model name (default: $OPENAI_MODEL / $ANTHROPIC_MODEL)")
    llm.add_argument("--api-key", help="API key (default: $OPENAI_API_KEY / "
                                       "$ANTHROPIC_API_KEY); prefer the variable")
    llm.add_argument("--response-format", choices=RESPONSE_FORMATS,
                     help="openai: how to ask for JSON (json_schema for OpenAI/vLLM/Ollama, "
                          "json_object_schema for llama.cpp's server)")
    llm.add_argument("--free-ids", action="store_true",
                     help="do not enumerate object ids in the JSON schema")
    llm.add_argument("--temperature", type=float)
    llm.add_argument("--max-tokens", type=int)
    llm.add_argument("--timeout", type=float, help="seconds per LLM request")
    llm.add_argument("--retries", type=int, help="retries on transient HTTP errors")
    out = p.add_argument_group("output")
    out.add_argument("--trace", help="write the episode trace (JSON) to this file")
    out.add_argument("--trace-prompts", action="store_true", help="keep prompts in the trace")
    out.add_argument("--quiet", "-q", action="store_true", help="print only the verdict")
    out.add_argument("--record", metavar="DIR",
                     help="write the planner transcript (each prompt and reply) to "
                          "DIR/<scene>__<mode>.jsonl")
    out.add_argument("--replay", metavar="DIR",
                     help="answer from a transcript recorded with --record instead of "
                          "calling the planner (no key, no network); a prompt that differs "
                          "from the recorded one stops the episode as a planner error")
    p.set_defaults(handler=run_agent)


def _scene_spec(args: argparse.Namespace) -> dict[str, Any]:
    resolved = scene_argument(args.scene)
    load: dict[str, Any] = {}
    if resolved.graph is not None:
        load["graph"] = resolved.graph.model_dump(mode="json", exclude_none=True)
    elif resolved.builtin is not None:
        load["scene_id"] = resolved.builtin
    else:
        load["generator"] = resolved.generator
    if args.simulate:
        load["simulate"] = True
    return load


def _goal_spec(args: argparse.Namespace) -> dict[str, Any] | None:
    from verigraph.graph.goal import PREDICATES
    from verigraph.graph.io import load_goal

    goal: dict[str, Any] = {}
    if args.goal:
        if args.goal in PREDICATES:
            goal["predicate"] = args.goal
        elif args.goal.lstrip().startswith("("):  # a formula as text
            goal["formula"] = args.goal.strip()
        elif Path(args.goal).is_file():
            g = load_goal(args.goal)
            if g.graph is not None:
                goal["graph"] = g.graph.model_dump(mode="json", exclude_none=True)
                goal["partial"] = g.partial
            if g.predicate is not None:
                goal["predicate"] = g.predicate
            if g.formula is not None:
                goal["formula"] = g.formula
            if g.instruction and not args.instruction:
                goal["instruction"] = g.instruction
        else:
            raise VeriGraphError(f"goal '{args.goal}' is neither a file, a predicate nor a "
                                 "formula",
                                 field="--goal", value=args.goal,
                                 fix=f"give a goal file or one of {', '.join(PREDICATES)}")
    if args.instruction:
        goal["instruction"] = args.instruction
    return goal or None


def _planner_options(args: argparse.Namespace) -> Any:
    from verigraph.planning.factory import PlannerOptions

    kinds = tuple(k.strip() for k in args.mistakes.split(",") if k.strip())
    try:
        return PlannerOptions(
            noise=args.noise, seed=args.seed, mistakes=kinds, base_url=args.base_url,
            model=args.model, api_key=args.api_key, response_format=args.response_format,
            constrain_ids=not args.free_ids, temperature=args.temperature,
            max_tokens=args.max_tokens, timeout_s=args.timeout, retries=args.retries)
    except ValueError as exc:
        raise VeriGraphError(f"bad planner option: {exc}", field="planner options",
                             fix="see `verigraph agent --help`") from None


def _planner(args: argparse.Namespace) -> Any:
    from verigraph.agent.transcripts import RecordingPlanner, ReplayingPlanner
    from verigraph.planning.factory import make_planner

    if args.record and args.replay:
        raise VeriGraphError("--record and --replay exclude each other", field="--replay",
                             value=args.replay, fix="record once, then replay in another run")
    key = f"{Path(args.scene).stem if Path(args.scene).is_file() else args.scene}__{args.mode}"
    if args.replay:
        return ReplayingPlanner(args.replay, key)
    planner = make_planner(args.planner, _planner_options(args))
    return RecordingPlanner(planner, args.record, key) if args.record else planner


def _environment(args: argparse.Namespace) -> Any:
    import os

    from verigraph.agent.environment import McpTools

    if args.transport == "http":
        if not args.url:
            raise VeriGraphError("--transport http needs --url", field="--url",
                                 fix="pass e.g. --url http://127.0.0.1:8000/mcp")
        return McpTools.http(args.url, token=args.token or os.environ.get("VERIGRAPH_TOKEN"))
    return McpTools.stdio()


def run_agent(args: argparse.Namespace) -> int:
    from pydantic import ValidationError

    from verigraph.agent.console import header_lines, print_iteration, verdict_line
    from verigraph.agent.loop import LoopConfig, run_episode
    from verigraph.tasks.task import EpisodeSpec

    try:
        config = LoopConfig(mode=args.mode, k=args.k, threshold=args.threshold,
                            done_policy=args.done_policy, max_iterations=args.max_iterations,
                            stop_on_goal=args.stop_on_goal, no_progress=args.no_progress,
                            feedback=args.feedback, record_prompts=args.trace_prompts)
    except ValidationError as exc:
        err = exc.errors()[0]
        name = str(err["loc"][0]) if err["loc"] else "options"
        raise VeriGraphError(f"{err['msg']}", field=f"--{name.replace('_', '-')}",
                             value=err.get("input"), fix="see `verigraph agent --help`"
                             ) from None
    spec = EpisodeSpec(load=_scene_spec(args), set_goal=_goal_spec(args),
                       show_goal_graph=not args.hide_goal_graph)
    planner = _planner(args)
    out = sys.stdout

    def on_start(trace: Any) -> None:
        if not args.quiet:
            out.write("\n".join(header_lines(trace)) + "\n")

    def on_iteration(record: Any) -> None:
        if not args.quiet:
            print_iteration(record, out)

    try:
        env = _environment(args)
        try:
            trace = run_episode(env, planner, spec, config, on_iteration=on_iteration,
                                on_start=on_start)
        finally:
            env.close()
    finally:
        planner.close()
    out.write(verdict_line(trace) + "\n")
    if trace.planner_error:
        sys.stderr.write(f"error: the planner failed: {trace.planner_error}\n")
    if args.trace:
        Path(args.trace).write_text(json.dumps(trace.model_dump(mode="json"), indent=2) + "\n")
        if not args.quiet:
            out.write(f"trace written to {args.trace}\n")
    if trace.planner_error:
        return EXIT_PLANNER_FAILED
    return EXIT_OK if trace.success else EXIT_NEGATIVE
