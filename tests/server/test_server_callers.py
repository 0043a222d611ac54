"""How the server tells callers apart (verigraph.server.callers): a token by a stable
fingerprint that never shows the token, an address by itself, an IPv6 address by its /64
(so one host cannot take a share per address it can choose)."""

from __future__ import annotations

import pytest

from verigraph.server.callers import CALLER_KEY, TokenGate, caller_of, token_caller

pytestmark = pytest.mark.fast


def test_a_token_caller_is_a_stable_fingerprint_that_hides_the_token() -> None:
    one, two = token_caller("s3cret-one"), token_caller("s3cret-two")
    assert one == token_caller("s3cret-one") and one != two
    assert one.startswith("token ") and len(one) == len("token ") + 12
    assert "s3cret" not in one


@pytest.mark.parametrize(("peer", "caller"), [
    ("127.0.0.1", "address 127.0.0.1"),
    ("::1", "address ::1"),
    ("::ffff:10.1.2.3", "address 10.1.2.3"),
    ("2001:db8:1:2::5", "address 2001:db8:1:2::/64"),
    ("2001:db8:1:2:ffff:1:2:3", "address 2001:db8:1:2::/64"),
    ("2001:db8:1:3::5", "address 2001:db8:1:3::/64"),
    ("fe80::1%eth0", "address fe80::/64"),
    ("not-an-ip", "address not-an-ip"),
])
def test_an_address_caller_groups_an_ipv6_host_by_its_64(peer: str, caller: str) -> None:
    assert caller_of({"client": (peer, 50000)}) == caller


def test_a_named_caller_wins_and_no_peer_is_unknown() -> None:
    assert caller_of({"client": ("127.0.0.1", 1), CALLER_KEY: "token abc"}) == "token abc"
    assert caller_of({}) == "address unknown"


def _scope(*authorization: bytes) -> dict[str, object]:
    return {"type": "http", "headers": [(b"Authorization", a) for a in authorization]}


def test_the_token_gate_admits_a_token_and_says_why_it_refuses() -> None:
    gate = TokenGate(["one"])
    admitted = _scope(b"Bearer one")
    assert gate.check(admitted) is None
    assert CALLER_KEY not in admitted  # one token: every holder is alike
    assert gate.check(_scope()) == "missing_token"
    assert gate.check(_scope(b"  ")) == "missing_token"
    assert gate.check(_scope(b"Bearer two")) == "wrong_token"
    assert gate.check(_scope(b"one")) == "wrong_token"
    assert gate.check(_scope(b"Bearer two", b"Bearer one")) == "wrong_token"  # the first


def test_with_several_tokens_the_gate_names_the_caller_of_the_one_matched() -> None:
    gate = TokenGate(["one", "two"])
    scope = _scope(b"Bearer two")
    assert gate.check(scope) is None
    assert scope[CALLER_KEY] == token_caller("two") == caller_of(scope)
