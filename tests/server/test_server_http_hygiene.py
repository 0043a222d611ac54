"""HTTP connection hygiene against a real `verigraph serve --transport http` on loopback:
header deadline, connection cap, Host matching per RFC 9110 (raw sockets throughout)."""

from __future__ import annotations

import socket
from collections.abc import Iterator
from urllib.parse import urlsplit

import pytest
from mcp_helpers import http_server, rpc

SAFETY_S = 60  # a socket timeout only so that a broken server fails the test, never a measure


@pytest.fixture(scope="module")
def port() -> Iterator[int]:
    with http_server(extra=["--header-timeout", "1", "--max-connections", "4"]) as running:
        yield int(urlsplit(running.url).port or 0)


def connect(port: int) -> socket.socket:
    sock = socket.create_connection(("127.0.0.1", port), timeout=SAFETY_S)
    return sock


def read_all(sock: socket.socket) -> bytes:
    data = b""
    while chunk := sock.recv(65536):
        data += chunk
    return data


def post(port: int, host: str, origin: str | None = None) -> int:
    body = rpc("ping")
    extra = f"Origin: {origin}\r\n" if origin else ""
    request = (f"POST /mcp HTTP/1.1\r\nHost: {host}\r\n{extra}Content-Type: application/json\r\n"
               "Accept: application/json, text/event-stream\r\nConnection: close\r\n"
               f"Content-Length: {len(body)}\r\n\r\n").encode() + body
    with connect(port) as sock:
        sock.sendall(request)
        status_line = read_all(sock).split(b"\r\n", 1)[0]
    return int(status_line.split()[1])


def test_unfinished_headers_get_408_and_the_connection_closes(port: int) -> None:
    with connect(port) as sock:
        sock.sendall(b"POST /mcp HTTP/1.1\r\nHost: 127.0.0.1\r\n")  # ...and never the rest
        reply = read_all(sock)  # returns once the server closes the connection
    assert reply.startswith(b"HTTP/1.1 408")
    assert b"request headers not received within 1 s" in reply


def test_a_silent_connection_is_closed_too(port: int) -> None:
    with connect(port) as sock:
        assert read_all(sock).startswith(b"HTTP/1.1 408")


def test_connections_beyond_the_cap_get_a_clean_503(port: int) -> None:
    busy: list[socket.socket] = []
    try:
        for _ in range(4):  # headers complete, the body promised and never sent: busy
            busy.append(sock := connect(port))
            sock.sendall(b"POST /mcp HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: 100\r\n"
                         b"Expect: 100-continue\r\n\r\n")
            got = sock.recv(300)
            assert got.startswith(b"HTTP/1.1 100"), got  # the app waits for the body
        with connect(port) as extra:
            reply = read_all(extra)
        assert reply.startswith(b"HTTP/1.1 503")
        assert b"4 open connections with requests in progress" in reply
    finally:
        for sock in busy:
            sock.close()


def test_waiting_connections_make_room_for_a_new_one(port: int) -> None:
    """With 4 slots, one may wait for its headers; an older waiting one is closed."""
    with connect(port) as old:
        old.sendall(b"POST /mcp HTTP/1.1\r\n")
        assert post(port, "127.0.0.1") == 200  # a new connection evicts the waiting one
        try:  # closed: with a 503 that says why, or reset if it came before its bytes were read
            reply = read_all(old)
        except ConnectionResetError:
            reply = b"reset"
        assert reply == b"reset" or b"waiting for their request headers" in reply, reply


@pytest.mark.parametrize("host,expected", [
    ("127.0.0.1:{port}", 200),
    ("LOCALHOST:{port}", 200),
    ("LocalHost", 200),
    ("[::1]:{port}", 200),
    ("127.0.0.1:{port}@evil.example", 421),
    ("127.0.0.1:{port}.evil.example", 421),
    ("127.0.0.1:1", 421),
    ("localhost:0{port}x", 421),
    ("evil.example:{port}", 421),
    ("", 421),
])
def test_host_header_is_matched_per_rfc_9110(port: int, host: str, expected: int) -> None:
    assert post(port, host.format(port=port)) == expected


@pytest.mark.parametrize("origin,expected", [
    ("http://localhost:6274", 200),
    ("http://LOCALHOST", 200),
    ("http://127.0.0.1:{port}@evil.example", 403),
    ("http://evil.example", 403),
    ("file://localhost", 403),
])
def test_origin_is_matched_by_its_parsed_host(port: int, origin: str, expected: int) -> None:
    assert post(port, f"127.0.0.1:{port}", origin.format(port=port)) == expected
