"""``--scheduler`` at an address where no Dask scheduler listens fails fast (issue 46, fault 5).

The servers are local (127.0.0.1), run in threads and stop by themselves: one that accepts
and says nothing, an HTTP server, one that replies garbage (a length of 3 EiB, the crash of
the issue) and one whose reply has a plausible length but is not a handshake.
"""

from __future__ import annotations

import contextlib
import http.server
import socket
import subprocess
import sys
import threading
import time

import pytest

from test_evaluate_cli import _env
from test_runner import make_otb_dataset

FAST_S = 15  # a wrong endpoint must be refused well within this (the probe waits 5 s at most)


@contextlib.contextmanager
def tcp_server(greeting: bytes | None, lifetime: float = 60.0):
    """``tcp://127.0.0.1:PORT`` of a server that sends ``greeting`` (None: nothing) to each
    connection and keeps it open; it stops at the end of the block or after ``lifetime`` s."""
    listener = socket.create_server(("127.0.0.1", 0))
    listener.settimeout(0.2)
    stop, held = threading.Event(), []
    deadline = time.monotonic() + lifetime

    def serve() -> None:
        while not stop.is_set() and time.monotonic() < deadline:
            try:
                conn, _ = listener.accept()
            except TimeoutError:
                continue
            if greeting:
                conn.sendall(greeting)
            held.append(conn)
        for conn in held:
            conn.close()
        listener.close()

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield f"tcp://127.0.0.1:{listener.getsockname()[1]}"
    finally:
        stop.set()
        thread.join(5)


@contextlib.contextmanager
def http_server():
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), http.server.SimpleHTTPRequestHandler)
    thread = threading.Thread(target=server.serve_forever, kwargs={"poll_interval": 0.1}, daemon=True)
    thread.start()
    try:
        yield f"tcp://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()
        thread.join(5)


@contextlib.contextmanager
def closed_port():
    with socket.socket() as s:  # a free port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    yield f"tcp://127.0.0.1:{port}"


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return make_otb_dataset(tmp_path_factory.mktemp("otb"), n_frames=4)


@pytest.mark.parametrize(
    ("endpoint", "expected"),
    [
        (lambda: tcp_server(None), "no Dask handshake within 5 s"),
        (http_server, "no Dask handshake within 5 s"),
        (lambda: tcp_server(b"\x00\x00\x00\x00\x00\x00\x00\x30" + b"x" * 64), "the reply is not a Dask handshake"),
        (lambda: tcp_server((100).to_bytes(8, "little") + b"HTTP/1.0 400 Bad request\r\n" * 4), "not a Dask"),
        (lambda: tcp_server(b"SSH-2.0-OpenSSH_9.6\r\n"), "not a Dask handshake"),
        (closed_port, "cannot connect to the Dask scheduler at"),
    ],
    ids=["silent", "http", "garbage-3EiB", "garbage-short", "ssh", "closed"],
)
def test_a_wrong_scheduler_address_fails_fast_with_a_clear_error(dataset, tmp_path, endpoint, expected):
    run_dir = tmp_path / "run"
    with endpoint() as address:
        cmd = [sys.executable, "-m", "smtmvt.cli", "evaluate", "--dataset", str(dataset), "--trackers", "opencv-kcf"]
        t0 = time.monotonic()
        proc = subprocess.run(
            [*cmd, "--out", str(run_dir), "--scheduler", address, "--quiet"],
            capture_output=True,
            text=True,
            env=_env(),
            timeout=120,
        )
        seconds = time.monotonic() - t0
    assert proc.returncode == 2, proc.stderr
    (line,) = proc.stderr.strip().splitlines()  # one line, no traceback
    assert line.startswith("smtmvt evaluate: error: ") and address in line and expected in line, line
    assert seconds < FAST_S, seconds
    assert not run_dir.exists()  # refused before the run folder is touched
