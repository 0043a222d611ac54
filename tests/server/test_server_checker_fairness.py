"""The large-body checker over real HTTP: a stopped child (SIGSTOP) is killed and replaced
after its deadline, bodies near the body limit never queue in front of smaller ones, and
within one lane bodies are taken round-robin over clients, each client's queue capped.

The fair-queue tests run the server on a thread of this process, so that `checker_spy`
can hold the check of one body (its turn held) while the others queue behind it; the
clients are told apart by the loopback address they connect from (127.0.0.1, 127.0.0.2).
"""

from __future__ import annotations

import json
import os
import signal
import socket
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Any
from urllib.parse import urlsplit

import anyio
import anyio.lowlevel
import httpx2
import pytest
from mcp_helpers import (
    JSON_HEADERS,
    CheckerSpy,
    checker_spy,
    checking_processes,
    free_port,
    http_in_thread,
    http_server,
    process_gone,
    rpc,
    tower_graph,
    wait_until,
)

from verigraph.server.http import HttpOptions
from verigraph.server.http.argument_process import (
    DEFAULT_QUEUED_PER_CLIENT,
    QUEUE_FULL_REASON,
    FairTurns,
    QueueFull,
)
from verigraph.tools.registry import TOOLS, Toolbox, parse_arguments

__all__ = ["checker_spy"]  # the fixture, imported for the tests below
TOKEN = "checker-token"
HEADERS = {**JSON_HEADERS, "Authorization": f"Bearer {TOKEN}",
           "MCP-Protocol-Version": "2025-11-25"}
FLOODER, OTHER = "127.0.0.1", "127.0.0.2"  # two clients: two loopback addresses

PLAN = {"graph": tower_graph(1500),
        "plan": [f"move(b{i}, on, table)" for i in range(1498, 1398, -1)]}
# Far beyond the node limit and above 4 MiB: the other child checks (and refuses) it.
HUGE = {"graph": {"nodes": [{"id": f"n{i}", "label": "block"} for i in range(150_000)],
                  "edges": []}, "plan": "done"}
# Above the 1 KiB threshold of the in-process servers below: checked in the child.
SMALL = {"graph": tower_graph(40), "plan": [f"move(b{i}, on, table)" for i in range(38, 30, -1)]}


def body(arguments: dict[str, Any], request_id: int) -> bytes:
    return rpc("tools/call", {"name": "validate_plan", "arguments": arguments}, request_id)


def post(url: str, arguments: dict[str, Any], request_id: int = 1) -> httpx2.Response:
    return httpx2.post(url, content=body(arguments, request_id), headers=HEADERS, timeout=40)


def post_from(address: str, url: str, request_id: int, token: str = TOKEN
              ) -> httpx2.Response:
    """SMALL posted on a connection of its own from loopback `address`."""
    transport = httpx2.HTTPTransport(local_address=address)
    headers = {**HEADERS, "Authorization": f"Bearer {token}"}
    with httpx2.Client(transport=transport, headers=headers, timeout=60) as http:
        return http.post(url, content=body(SMALL, request_id))


def library_answer(arguments: dict[str, Any]) -> dict[str, Any]:
    spec = TOOLS["validate_plan"]
    return json.loads(Toolbox().run(spec, parse_arguments(spec, arguments)).model_dump_json())


def in_process_options(**changes: Any) -> HttpOptions:
    """A server whose checker takes every body above 1 KiB (SMALL is about 3 KiB)."""
    return HttpOptions(**{"port": free_port(), "tokens": (TOKEN,), "large_call_bytes": 1024,
                          **changes})


def test_a_stopped_checker_is_killed_and_replaced_after_its_deadline() -> None:
    with http_server(token=TOKEN, extra=["--check-seconds", "2"]) as running:
        assert post(running.url, PLAN).status_code == 200
        [child] = checking_processes(running.proc.pid)
        os.kill(child, signal.SIGSTOP)
        try:
            response = post(running.url, PLAN, request_id=41)
        finally:
            if not process_gone(child):
                os.kill(child, signal.SIGCONT)
        assert response.status_code == 503
        assert response.headers["retry-after"] == "1"
        error = response.json()["error"]
        assert response.json()["id"] == 41
        assert "within 2 s" in error["message"] and "send the request again" in error["message"]
        wait_until(lambda: process_gone(child), "the stopped checking process was not killed")
        reply = post(running.url, PLAN).json()
        assert reply["result"]["structuredContent"] == library_answer(PLAN)
        assert set(checking_processes(running.proc.pid)) - {child}


def test_a_smaller_large_call_does_not_wait_for_a_huge_one() -> None:
    """With the child for huge bodies stopped, a 100 KB call is still answered, well
    before that child's deadline would have let it through."""
    with http_server(token=TOKEN, extra=["--check-seconds", "120"]) as running:
        refused = post(running.url, HUGE).json()["result"]
        assert refused["isError"] is True and "at most 5000 nodes" in refused["content"][0]["text"]
        [huge_child] = checking_processes(running.proc.pid)
        assert post(running.url, PLAN).status_code == 200
        assert len(checking_processes(running.proc.pid)) == 2
        os.kill(huge_child, signal.SIGSTOP)
        try:
            reply = post(running.url, PLAN).json()  # the client gives up after 40 s
        finally:
            os.kill(huge_child, signal.SIGCONT)
        assert reply["result"]["structuredContent"] == library_answer(PLAN)
        assert post(running.url, HUGE).json()["result"]["isError"] is True


def queue_behind_a_held_body(spy: CheckerSpy, pool: ThreadPoolExecutor, url: str,
                             queued: int) -> list[Future[httpx2.Response]]:
    """FLOODER's body 10 held in its check, then its bodies 11, 12, ... waiting behind it
    (each on a connection of its own, as a client posting many at once sends them)."""
    spy.hold.add(10)
    posts = [pool.submit(post_from, FLOODER, url, 10)]
    assert spy.entered.wait(30), "the first body never reached the checker"
    posts += [pool.submit(post_from, FLOODER, url, 11 + i) for i in range(queued)]
    wait_until(lambda: spy.waiting() == queued, f"{queued} bodies did not queue")
    return posts


def answered(posts: list[Future[httpx2.Response]]) -> list[dict[str, Any]]:
    replies = [future.result(timeout=60) for future in posts]
    assert all(reply.status_code == 200 for reply in replies), [r.text[:200] for r in replies]
    return [reply.json() for reply in replies]


def test_another_client_s_body_waits_for_at_most_one_of_a_flooding_client_s(
        checker_spy: CheckerSpy) -> None:
    """One client has a body being checked and 5 more queued; another client's single
    body, posted last, is checked next, before any of the 5."""
    with http_in_thread(Toolbox(), in_process_options()) as url, ThreadPoolExecutor(8) as pool:
        flood = queue_behind_a_held_body(checker_spy, pool, url, 5)
        other = pool.submit(post_from, OTHER, url, 20)
        wait_until(lambda: checker_spy.waiting() == 6, "the other client's body did not queue")
        checker_spy.release.set()
        replies = answered([*flood, other])
    assert checker_spy.order[:2] == [10, 20]
    assert sorted(checker_spy.order[2:]) == [11, 12, 13, 14, 15]
    expected = library_answer(SMALL)
    assert all(reply["result"]["structuredContent"] == expected for reply in replies)
    assert [reply["id"] for reply in replies] == [10, 11, 12, 13, 14, 15, 20]


def test_bodies_from_one_address_are_one_client_s_and_keep_their_order(
        checker_spy: CheckerSpy) -> None:
    """The peer of the test above: the same last body from the flooding client's own
    address is that client's, so it waits for all of its bodies before it."""
    with http_in_thread(Toolbox(), in_process_options()) as url, ThreadPoolExecutor(8) as pool:
        flood = queue_behind_a_held_body(checker_spy, pool, url, 5)
        same = pool.submit(post_from, FLOODER, url, 20)
        wait_until(lambda: checker_spy.waiting() == 6, "the last body did not queue")
        checker_spy.release.set()
        answered([*flood, same])
    assert checker_spy.order[0] == 10 and checker_spy.order[-1] == 20


def test_clients_on_one_address_with_tokens_of_their_own_take_turns(
        checker_spy: CheckerSpy) -> None:
    """With a token per client (`serve --token A --token B`), two clients on one host are
    two clients: the second's body is checked next, as if it came from elsewhere."""
    own = "other-client-token"
    options = in_process_options(tokens=(TOKEN, own))
    with http_in_thread(Toolbox(), options) as url, ThreadPoolExecutor(8) as pool:
        flood = queue_behind_a_held_body(checker_spy, pool, url, 5)
        other = pool.submit(post_from, FLOODER, url, 20, own)
        wait_until(lambda: checker_spy.waiting() == 6, "the other client's body did not queue")
        checker_spy.release.set()
        answered([*flood, other])
    assert checker_spy.order[:2] == [10, 20]


def test_a_client_beyond_its_queue_cap_is_refused_with_the_limit(
        checker_spy: CheckerSpy) -> None:
    cap = DEFAULT_QUEUED_PER_CLIENT
    with http_in_thread(Toolbox(), in_process_options()) as url, \
            ThreadPoolExecutor(cap + 3) as pool:
        flood = queue_behind_a_held_body(checker_spy, pool, url, cap)
        refused = post_from(FLOODER, url, 99)  # answered at once, its turn never comes
        other = pool.submit(post_from, OTHER, url, 20)  # another client still queues
        wait_until(lambda: checker_spy.waiting() == cap + 1, "the other client was refused")
        checker_spy.release.set()
        replies = answered([*flood, other])
        assert post_from(FLOODER, url, 100).status_code == 200  # its queue has drained
    assert refused.status_code == 503 and refused.headers["retry-after"] == "1"
    reply = refused.json()
    assert reply["id"] == 99 and reply["error"]["data"] == {"reason": QUEUE_FULL_REASON}
    message = reply["error"]["message"]
    assert f"{cap} of its bodies already wait" in message, message
    assert f"at most {cap} per client" in message and "wait for their answers" in message
    assert 99 not in checker_spy.order and checker_spy.order[:2] == [10, 20]
    assert len(replies) == cap + 2


def raw_post(address: str, url: str, request_id: int) -> socket.socket:
    """SMALL sent from `address` on a raw connection, left open (no reply is read)."""
    parts = urlsplit(url)
    data = body(SMALL, request_id)
    head = "".join(f"{k}: {v}\r\n" for k, v in HEADERS.items())
    sock = socket.create_connection((parts.hostname, parts.port), source_address=(address, 0))
    sock.sendall(f"POST {parts.path} HTTP/1.1\r\nHost: {parts.netloc}\r\n{head}"
                 f"Content-Length: {len(data)}\r\n\r\n".encode() + data)
    return sock


def test_a_queued_body_whose_client_leaves_gives_up_its_place(
        checker_spy: CheckerSpy) -> None:
    with http_in_thread(Toolbox(), in_process_options()) as url, ThreadPoolExecutor(4) as pool:
        first = queue_behind_a_held_body(checker_spy, pool, url, 0)
        leaving = raw_post(OTHER, url, 30)
        wait_until(lambda: checker_spy.waiting() == 1, "the body did not queue")
        leaving.close()
        wait_until(lambda: checker_spy.waiting() == 0, "the body kept its place")
        later = pool.submit(post_from, OTHER, url, 31)
        wait_until(lambda: checker_spy.waiting() == 1, "the later body did not queue")
        checker_spy.release.set()
        answered([*first, later])
    assert checker_spy.order == [10, 31]


def test_a_body_abandoned_in_the_child_keeps_the_turn_until_the_child_is_done(
        checker_spy: CheckerSpy) -> None:
    """A client that posts and leaves at once cannot stack bodies in the child past
    other clients' turns: with the child stopped while it checks a left client's body,
    the next client's body waits for its turn, and is checked by the same child once
    that one has resumed and finished."""
    options = in_process_options(large_call_deadline_s=60)
    with http_in_thread(Toolbox(), options) as url, ThreadPoolExecutor(2) as pool:
        assert post_from(FLOODER, url, 1).status_code == 200  # the child is up
        [child] = checker_spy.lanes[0].children()
        os.kill(child.pid, signal.SIGSTOP)
        try:
            leaving = raw_post(FLOODER, url, 30)
            wait_until(lambda: 30 in checker_spy.order, "the body never reached the child")
            leaving.close()
            assert checker_spy.abandoned.wait(30), "the server did not see the client leave"
            other = pool.submit(post_from, OTHER, url, 31)
            wait_until(lambda: checker_spy.waiting() == 1, "the next body did not wait")
            assert 31 not in checker_spy.order
        finally:
            os.kill(child.pid, signal.SIGCONT)
        reply = other.result(timeout=60)
        assert reply.status_code == 200
        assert reply.json()["result"]["structuredContent"] == library_answer(SMALL)
        assert checker_spy.lanes[0].children() == [child]
    assert checker_spy.order == [1, 30, 31]


async def queued_in_turn(turns: FairTurns, arrivals: list[str]) -> tuple[list[str], FairTurns]:
    """The order in which `arrivals` (client names, in order of arrival) get their turn
    behind a body of client "a" that holds it; each releases its turn at once."""
    order: list[str] = []

    async def one(client: str) -> None:
        await turns.acquire(client)
        order.append(client)
        turns.release(client)

    await turns.acquire("a")
    async with anyio.create_task_group() as tg:
        for client in arrivals:
            tg.start_soon(one, client)
            await anyio.wait_all_tasks_blocked()  # it waits: the next arrives after it
        turns.release("a")
    return order, turns


def test_turns_go_round_robin_over_clients_oldest_turn_first() -> None:
    order, turns = anyio.run(queued_in_turn, FairTurns(), ["a", "a", "a", "b", "b", "c"])
    assert order == ["b", "c", "a", "b", "a", "a"]
    assert turns.waiting() == 0 and not turns._clients  # every client forgotten


def test_a_client_over_its_cap_is_refused_and_others_are_not() -> None:
    async def scenario() -> list[str]:
        turns = FairTurns(queued_per_client=2)
        await turns.acquire("a")
        async with anyio.create_task_group() as tg:
            for _ in range(2):
                tg.start_soon(turns.acquire, "a")
            await anyio.wait_all_tasks_blocked()
            with pytest.raises(QueueFull) as refused:
                await turns.acquire("a")
            assert refused.value.waiting == 2 and turns.waiting() == 2
            tg.start_soon(turns.acquire, "b")
            await anyio.wait_all_tasks_blocked()
            assert turns.waiting() == 3
            tg.cancel_scope.cancel()  # the waiting callers give up
        assert turns.waiting() == 0
        turns.release("a")
        return list(turns._clients)

    assert anyio.run(scenario) == []


def test_a_turn_given_to_a_caller_cancelled_meanwhile_goes_to_the_next() -> None:
    async def scenario() -> list[str]:
        turns = FairTurns()
        order: list[str] = []
        await turns.acquire("a")
        async with anyio.create_task_group() as tg:
            cancelled = anyio.CancelScope()

            async def leaving() -> None:  # as _Lane.prepare takes and ends its turn
                with cancelled:
                    await turns.acquire("b")
                    try:
                        await anyio.lowlevel.checkpoint_if_cancelled()
                        order.append("b")  # never: cancelled as its turn came
                    finally:
                        turns.release("b")

            async def staying() -> None:
                await turns.acquire("c")
                order.append("c")
                turns.release("c")

            tg.start_soon(leaving)
            await anyio.wait_all_tasks_blocked()
            tg.start_soon(staying)
            await anyio.wait_all_tasks_blocked()
            turns.release("a")  # the turn goes to b ...
            cancelled.cancel()  # ... which is cancelled before it runs
        assert turns.waiting() == 0 and not turns._held
        return order

    assert anyio.run(scenario) == ["c"]
