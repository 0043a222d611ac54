"""The shipped IPC corpus (benchmarks/data/ipc): every Fast Downward plan and each of its
mutations gets the verdict VAL gave it (recorded by benchmarks/bench_ipc.py in
val_verdicts.json; judged disagreements take the judged verdict), without VAL. Also
that no domain of the corpus is refused."""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path
from types import ModuleType

import pytest

from verigraph.errors import VeriGraphError
from verigraph.pddl import validate_pddl_dict

BENCH = Path(__file__).parent.parent.parent / "benchmarks" / "bench_ipc.py"


def _bench() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_ipc_for_tests", BENCH)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


bench = _bench()
EXPECTED: dict[str, dict[str, str]] = json.loads(bench.VERDICTS.read_text())
CASES = {"/".join((c.domain, c.instance, c.mutation)): c for c in bench.load_cases(False)}
DOMAINS = sorted({key.split("/")[0] for key in CASES})


def verdict(case: object) -> str:
    texts = [Path(p).read_text() for p in (case.domain_file, case.problem_file)]  # type: ignore[attr-defined]
    try:
        report = validate_pddl_dict(texts[0], texts[1], case.plan)  # type: ignore[attr-defined]
    except VeriGraphError as exc:
        if exc.field in ("domain", "problem"):
            return f"refused: {exc.message}"
        return "invalid"
    return "valid" if report["valid"] else "invalid"


def test_every_case_has_a_recorded_verdict() -> None:
    missing = sorted(set(CASES) - set(EXPECTED))
    # only the cases VAL gave no verdict on (an error other than a refused plan)
    assert len(missing) <= len(CASES) // 20, missing[:10]
    assert not set(EXPECTED) - set(CASES)


@pytest.mark.parametrize("domain", DOMAINS)
def test_domain_agrees_with_val(domain: str) -> None:
    keys = sorted(k for k in EXPECTED if k.startswith(domain + "/") and k in CASES)
    assert keys
    wrong = []
    for key in keys:
        got = verdict(CASES[key])
        if got != EXPECTED[key]["expected"]:
            wrong.append(f"{key}: got {got}, expected {EXPECTED[key]['expected']}")
    assert not wrong, wrong[:5]
    originals = [k for k in keys if k.endswith("/original")]
    assert originals and all(EXPECTED[k]["expected"] == "valid" for k in originals)


def test_every_listed_domain_is_in_the_corpus() -> None:
    """Each domain of the benchmark's table (among them every classical domain of the IPCs
    2008-2023) has cases here unless it is listed, with the reason, as not in the corpus;
    and each folder here has its source in the table."""
    assert not set(bench.DOMAINS) - set(DOMAINS) - set(bench.NOT_IN_CORPUS)
    assert not set(DOMAINS) - set(bench.DOMAINS)
    recent = {name for name, (_, ipc) in bench.DOMAINS.items() if ipc >= "IPC 2008"}
    assert {"cybersec", "labyrinth", "organic-synthesis", "ricochet-robots",
            "slitherlink"} <= recent & set(DOMAINS)
