"""`verigraph val` and `verigraph-val`: a drop-in for VAL's `Validate` on classical plans.

    verigraph-val [-v] [-s | -S] [-a] [-t N] DOMAIN PROBLEM PLAN [PLAN ...]

The arguments, exit status and key output lines are those of VAL 4's `Validate`
(KCL-Planning/VAL, applications/Validate/src/main.cpp), so a script that calls
`Validate` can call this instead:

* each plan: `Checking plan: PLAN`, then `Plan executed successfully - checking goal`,
  `Plan valid` and `Final value: N ` (the plan's total cost under a `:metric`, else its
  length, as VAL), or `Goal not satisfied` / `Plan invalid`, or `Plan failed to execute`;
  then `Successful plans:` with each plan's value and `Failed plans:` with the names;
* `-v`: VAL's trace (`Plan to validate:`, `Checking next happening (time N)`, `Deleting`
  / `Adding` for every atom a step changes) and, for a failed plan, `Plan Repair
  Advice:` in VAL's words (`(pick-up a) has an unsatisfied precondition at time 3`,
  `(Set (clear a) to true)`, `(Follow each of: ... and ...)`, `The goal is not
  satisfied`), each followed by VeriGraph's reason (what last made the atom false, the
  actions that achieve it) and fix, indented; `-a` leaves the advice out;
* `-s` prints only what fails, `-S` only each plan's value (or `failed`); `-t N` (VAL's
  tolerance for temporal plans) is accepted and has no effect on classical plans;
* exit status: 0 when every plan is valid, else the number of plans that are not
  (at most 254, so it never wraps to 0); 255 when the domain, the problem or the
  arguments cannot be used, with VAL's line (`Bad domain file!`, `Problem in domain
  definition!`, `Bad problem file!`, `Type problem in problem specification!`,
  `Unrecognised command line switch: -x`) and the reason on standard error.

Where VeriGraph differs from VAL, by design: a step VAL cannot execute at all (an action
of the wrong arity, where VAL crashes; an unknown action or object, where VAL prints
`Bad plan description!` and still exits 0) is judged by the PDDL engine with the reason
(a failed plan, counted in the exit status); a plan file that cannot be read is counted
as failed too (`Bad plan file!` and the reason), and so is a plan the validator itself
fails on (VAL's `Error occurred in validation attempt:` and `Queries (validator
failed):`; the next plan is still checked). VAL's other switches (robustness,
LaTeX, `-c`/`-e` continuing past a failure, `-g`, `-m`, `-L`, ...) are refused by name.
The `time N` of the trace and the advice is the step's number. Each plan may use
$VERIGRAPH_CPU_SECONDS of CPU (default 60, verigraph.budget.command_line_budget); a
plan over it is one the validator failed on. See docs/validator.md.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, field
from typing import Any

from verigraph.budget import CPU_SECONDS_ENV, BudgetExceeded, command_line_budget
from verigraph.cli.exits import EXIT_FATAL, EXIT_OK, MAX_FAILED_STATUS
from verigraph.errors import InputFileError, VeriGraphError

UNSUPPORTED = {
    "r": "robustness analysis", "j": "robustness analysis of events", "g": "graphplan length",
    "c": "continuing past an unsatisfied precondition", "e": "the full error report and "
    "plan repair", "d": "turning off the derived predicate check", "i": "invariant warnings",
    "l": "LaTeX reports", "p": "LaTeX Gantt charts", "q": "LaTeX graphs", "o": "LaTeX Gantt "
    "objects", "m": "makespan as the metric", "L": "step length as the metric",
    "f": "LaTeX report files",
}
USAGE = """VeriGraph's drop-in for VAL's Validate (classical PDDL plans)

Usage: verigraph-val [options] domainFile problemFile planFile1 ...
Options:
    -v         -- Verbose reporting of plan check progress.
    -a         -- Do not output plan repair advice when Verbose is on.
    -s         -- Silent mode: output is generated only when errors occur
    -S         -- Silent mode with values: outputs only plan values in order (failed for bad plan)
    -t <n>     -- Set tolerance to (float) value of n (no effect on classical plans).
    -h         -- Print this message.
Multiple plan file arguments can be appended for checking.
Exit status: 0 every plan valid, N plans not valid (at most 254), 255 unusable input.
Each plan may use $VERIGRAPH_CPU_SECONDS of CPU (default 60; 0: no limit).
"""


class UsageError(Exception):
    """Arguments this entry point cannot run, with VAL's line for them."""


@dataclass
class Options:
    verbose: bool = False
    silent: int = 0  # VAL's Silent: 0 normal, 1 `-s`, 2 `-S`
    advice: bool = True
    help: bool = False
    files: list[str] = field(default_factory=list)


def parse_args(argv: list[str]) -> Options:
    """VAL's switch loop: leading arguments that start with '-' are switches, read by
    their second character; the rest are files."""
    opts = Options()
    i = 0
    while i < len(argv) and argv[i].startswith("-") and len(argv[i]) > 1:
        arg = argv[i]
        key = arg[1]
        if arg == "--help" or key == "h":
            opts.help = True
        elif key == "v":
            opts.verbose = True
        elif key == "s":
            opts.silent = 1
        elif key == "S":
            opts.silent = 2
        elif key == "a":
            opts.advice = False
        elif key == "t":
            i += 1
            if i >= len(argv):
                raise UsageError("-t needs a tolerance value")
            try:
                float(argv[i])
            except ValueError:
                raise UsageError(f"-t needs a number, got '{argv[i]}'") from None
        elif key in UNSUPPORTED:
            raise UsageError(f"Unrecognised command line switch: {arg}\n"
                             f"error: {arg} ({UNSUPPORTED[key]}) is VAL's and not supported "
                             "here (classical plans: -v -s -S -a -t)")
        else:
            raise UsageError(f"Unrecognised command line switch: {arg}")
        i += 1
    opts.files = argv[i:]
    return opts


def _value_text(value: float) -> str:
    """A number as VAL's stream prints it (precision 10, no trailing zeros)."""
    return f"{value:.10g}"


def _atom_and_value(literal: str, expected: Any) -> tuple[str, bool]:
    """`(not (p a))` -> (`(p a)`, False); `(p a)` with expected True -> (`(p a)`, True)."""
    text = literal.strip()
    if text.startswith("(not ") and text.endswith(")"):
        return text[5:-1].strip(), False
    return text, expected is not False


def _set_advice(literals: list[tuple[str, bool]]) -> list[str]:
    """VAL's AdvicePropositionLiteral/Conj display: one `(Set ...)` or `(Follow each of:`."""
    sets = [f"(Set {atom} to {'true' if value else 'false'})" for atom, value in literals]
    if not sets:
        return []
    if len(sets) == 1:
        return sets
    return ["(Follow each of:", f"    {sets[0]}", *(f"    and {s}" for s in sets[1:]), ")"]


def _reason_lines(items: list[dict[str, Any]]) -> list[str]:
    """VeriGraph's why for each unmet atom: its history and the actions that achieve it,
    as every report text says it (`reporting.explained_text`)."""
    from verigraph.reporting import explained_text

    return [f"    {explained_text(item)}" for item in items]


@dataclass
class PlanResult:
    """One plan's outcome: VAL's lines for it, and its value when it is valid."""
    lines: list[str]
    value: float | None  # None: the plan is not valid


_METRIC = re.compile(r"\(\s*:metric\b", re.IGNORECASE)
_COMMENT = re.compile(r";[^\n]*")


def has_metric(problem_text: str) -> bool:
    """Whether the problem declares a `(:metric ...)` (the PDDL reader accepts only
    `minimize (total-cost)`, and refuses any other by name)."""
    return bool(_METRIC.search(_COMMENT.sub("", problem_text)))


def final_value(data: dict[str, Any], metric: bool) -> float:
    """VAL's `Final value`: under a metric, the plan's total cost (0 when no action has a
    cost); without one, the plan's length (VAL's default), even if actions have costs."""
    if metric:
        value = data.get("total_cost", 0)
        return float(value) if isinstance(value, int | float) else 0.0
    return float(len(data["steps"]))


def plan_lines(data: dict[str, Any], opts: Options, metric: bool = False) -> PlanResult:
    """VAL's output for one report (after `Checking plan:`), in VAL's order."""
    out: list[str] = []
    steps = data["steps"]
    if opts.verbose:
        later = int(data.get("not_checked") or 0)
        out += ["Plan to validate:", "", f"Plan size: {len(steps) + later}"]
        for s in steps:
            out += [f"{s['step']}:", s["text"], " "]
        if later:  # the report holds the steps up to the first failure
            out += [f"({later} later step(s), not executed)", " "]
        out.append("")
        if steps:
            out += ["Plan Validation details", "-----------------------"]
        for s in steps:
            out += ["", f"Checking next happening (time {s['step']})"]
            if s["ok"]:
                edit = s.get("edit") or {}
                out += [f"Deleting {a}" for a in edit.get("removed", []) if isinstance(a, str)]
                out += [f"Adding {a}" for a in edit.get("added", []) if isinstance(a, str)]
            elif (s.get("violation") or {}).get("unsatisfied"):
                out += ["Plan failed because of unsatisfied precondition in:", s["text"]]
            else:
                out.append(f"Plan failed: {s['text']} cannot be executed: "
                           f"{(s.get('violation') or {}).get('message', '')}")
    value: float | None = None
    advice: list[str] = []
    if data["plan_valid"]:
        if not opts.silent:
            out.append("Plan executed successfully - checking goal")
        if data.get("goal_reached") is not False:
            value = final_value(data, metric)
            if not opts.silent:
                out += ["Plan valid", f"Final value: {_value_text(value)} "]
            elif opts.silent > 1:
                out.append(f"{_value_text(value)} ")
        else:
            if opts.silent < 2:
                out.append("Goal not satisfied")
            else:
                out.append("failed")
            if opts.silent < 2:
                out.append("Plan invalid")
            missing = [_atom_and_value(x, True)
                       for x in (data.get("goal_diff") or {}).get("missing_atoms", [])]
            advice += ["", "The goal is not satisfied", *_set_advice(missing),
                       *_reason_lines(data.get("unmet_goals") or [])]
    else:
        out.append("failed" if opts.silent > 1 else "\nPlan failed to execute")
        v = data["violations"][0]
        unsatisfied = v.get("unsatisfied") or []
        time = v.get("step")
        text = next((s["text"] for s in steps if s["step"] == time), "")
        if unsatisfied:
            advice += ["", f"{text} has an unsatisfied precondition at time {time}",
                       *_set_advice([_atom_and_value(u["literal"], u.get("expected", True))
                                     for u in unsatisfied]),
                       *_reason_lines(unsatisfied)]
        else:
            advice += ["", f"{text} cannot be executed at time {time}: {v.get('message', '')}"]
        if v.get("suggestion"):
            advice.append(f"    fix: {v['suggestion']}")
    if opts.verbose and opts.advice and advice:
        out += ["", "Plan Repair Advice:", *advice]
    return PlanResult(out, value)


def _read(path: str, what: str) -> str:
    from verigraph.cli.validating import read_text_file

    return read_text_file(path, what)


def _fatal(line: str, exc: VeriGraphError | None = None) -> int:
    print(line, file=sys.stderr)
    if exc is not None:
        print(f"error: {exc}", file=sys.stderr)
    return EXIT_FATAL


def _input_failure(exc: VeriGraphError) -> int:
    """VAL's line for a domain or problem that cannot be used, and the reason."""
    problem = str(exc.field or "").startswith("problem")
    if isinstance(exc, InputFileError):
        return _fatal("Bad problem file!" if problem else "Bad domain file!", exc)
    return _fatal("Type problem in problem specification!" if problem
                  else "Problem in domain definition!", exc)


def _is_plan_error(exc: VeriGraphError) -> bool:
    return str(exc.field or "").startswith("plan")


def run(argv: list[str]) -> int:
    """VAL's Validate on `argv` (the arguments after the program name)."""
    try:
        opts = parse_args(argv)
    except UsageError as exc:
        print(str(exc), file=sys.stderr)
        return EXIT_FATAL
    if opts.help or not opts.files:
        print(USAGE, end="")
        return EXIT_OK
    try:  # each plan's CPU budget, refused here when $VERIGRAPH_CPU_SECONDS is no number
        command_line_budget(None)
    except VeriGraphError as exc:
        return _fatal(f"Bad {CPU_SECONDS_ENV}!", exc)
    try:
        domain_text = _read(opts.files[0], "domain")
        if len(opts.files) == 1:  # VAL: a domain alone is checked, and that is all
            from verigraph.cli.validating import within_cpu_budget
            from verigraph.pddl.reader import read_domain

            within_cpu_budget(lambda: read_domain(domain_text), "val")
            return EXIT_OK
        problem_text = _read(opts.files[1], "problem")
    except VeriGraphError as exc:
        return _input_failure(exc)
    checker = _Checker(domain_text, problem_text, opts)
    for name in opts.files[2:]:
        lines = checker.check(name)
        if lines is None:
            return checker.fatal
        if lines:
            print("\n".join(lines))
    if not checker.inputs_checked:  # no plan could be read: VAL still reads the problem
        try:
            checker.validate("")
        except VeriGraphError as exc:
            return _input_failure(exc)
    _summary(checker.valued, checker.failed, checker.queries, opts, minimize=checker.metric)
    return min(len(checker.failed) + len(checker.queries), MAX_FAILED_STATUS)


class _Checker:
    """The plans of one run against one domain and problem, and VAL's tallies of them."""

    def __init__(self, domain_text: str, problem_text: str, opts: Options) -> None:
        self.domain_text, self.problem_text, self.opts = domain_text, problem_text, opts
        self.engine = "strips" if opts.verbose else "auto"  # -v traces atoms, as VAL does
        self.metric = has_metric(problem_text)  # also: values listed ascending (VAL)
        self.failed: list[str] = []
        self.queries: list[str] = []  # plans the validator itself failed on
        self.valued: list[tuple[float, str]] = []
        self.inputs_checked = False  # the domain and problem have been read without error
        self.fatal = 0

    def validate(self, plan_text: str) -> dict[str, Any]:
        from verigraph.cli.validating import within_cpu_budget
        from verigraph.pddl.validate import validate_pddl_dict

        def check(engine: str) -> dict[str, Any]:
            return within_cpu_budget(lambda: validate_pddl_dict(
                self.domain_text, self.problem_text, plan_text, engine=engine), "val")

        try:
            data = check(self.engine)
        except BudgetExceeded:
            raise
        except VeriGraphError:
            if self.engine == "auto":
                raise
            data = check("auto")
        self.inputs_checked = True
        return data

    def check(self, name: str) -> list[str] | None:
        """VAL's lines for one plan, or None when the domain or problem cannot be used
        (VAL's message is then on stderr and `fatal` is the exit status). The plan is
        judged before anything is printed, so a bad domain prints no plan lines (VAL
        reads the domain and problem before any plan)."""
        opts = self.opts
        head = [] if opts.silent else [f"Checking plan: {name}"]
        try:
            plan_text = _read(name, "plan")
        except VeriGraphError as exc:
            if not self.inputs_checked:
                try:
                    self.validate("")
                except VeriGraphError as bad_input:
                    self.fatal = _input_failure(bad_input)
                    return None
            self.failed.append(name)
            return [*head, "Bad plan file!", *([f"    why: {exc}"] if opts.silent < 2 else [])]
        try:
            data = self.validate(plan_text)
        except BudgetExceeded as exc:  # VAL's "validator failed": the next plan goes on
            self.queries.append(name)
            return [*head, *([] if opts.silent > 1 else [
                f"Error occurred in validation attempt:\n  {exc}"])]
        except VeriGraphError as exc:
            if not _is_plan_error(exc):
                self.fatal = _input_failure(exc)
                return None
            self.failed.append(name)
            return [*head, "failed" if opts.silent > 1
                    else f"Bad plan description!\n    why: {exc}"]
        except Exception as exc:  # noqa: BLE001 - VAL's "validator failed": the next plan
            self.queries.append(name)
            return [*head, *([] if opts.silent > 1 else [
                f"Error occurred in validation attempt:\n  {type(exc).__name__}: "
                f"{str(exc)[:200]}"])]
        result = plan_lines(data, opts, self.metric)
        if result.value is None:
            self.failed.append(name)
        else:
            self.valued.append((result.value, name))
        return [*head, *result.lines]


def _summary(valued: list[tuple[float, str]], failed: list[str], queries: list[str],
             opts: Options, *, minimize: bool) -> None:
    """VAL's closing lists: the successful plans by value, then the failed plans."""
    if valued and not opts.silent:
        lines = ["", "Successful plans:"]
        groups: dict[float, list[str]] = {}
        for value, name in valued:
            groups.setdefault(value, []).append(name)
        for value in sorted(groups, reverse=not minimize):
            lines.append(f"Value: {_value_text(value)}")
            lines += [(" " if k == 0 else "") + f"{name} {_value_text(value)} "
                      for k, name in enumerate(groups[value])]
        print("\n".join(lines) + "\n")
    if failed and opts.silent < 2:
        print("\n\nFailed plans:\n " + "".join(f"{name} " for name in failed))
    if queries and opts.silent < 2:
        print("\n\nQueries (validator failed):\n " + "".join(f"{name} " for name in queries))


def register(sub: Any) -> None:
    """`verigraph val ARGS...`: VAL's own arguments, passed through untouched."""
    p = sub.add_parser("val", help="VAL's Validate interface: [-v] domain problem plan...",
                       description="A drop-in for VAL's Validate: same arguments, exit "
                                   "status and key lines (verigraph val -h for VAL's "
                                   "options).", add_help=False, prefix_chars="+")
    p.add_argument("args", nargs="*", metavar="ARG",
                   help="VAL's arguments: [-v] [-s|-S] [-a] [-t N] domain problem plan...")
    p.set_defaults(handler=lambda args: run(list(args.args)))


def main(argv: list[str] | None = None) -> int:
    """The `verigraph-val` console script."""
    from verigraph.cli import run_guarded

    args = list(sys.argv[1:] if argv is None else argv)
    return run_guarded(lambda: run(args), process_ends=argv is None)


if __name__ == "__main__":
    sys.exit(main())
