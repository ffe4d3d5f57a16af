"""Where pairs run: this process, a pool of local worker processes, a Dask cluster, and a
fresh process for each pair of a tracker registered with ``fresh_process=True``.

Guarantees
----------
* **No orphans.** Every process started here watches its parent (:func:`exit_with_parent`):
  when the driver dies, even by SIGKILL, its workers exit within half a second instead of
  waiting forever for work. When the driver stops on an exception (Ctrl-C, SIGTERM turned
  into :class:`KeyboardInterrupt` by the CLI), the pool terminates its workers before the
  exception goes on.
* **The same boxes wherever a pair runs.** Workers use one OpenCV/BLAS thread each (like
  Dask's) and one thread for the tracker's per-candidate work unless a tracker option sets
  ``threads`` (the boxes are the same for any number); a ``fresh_process`` pair runs in a new interpreter started with
  ``subprocess`` (which Dask's daemonic workers may also start), so state a tracker keeps
  outside its seed cannot leak from one pair to the next.
* Only the driver writes to the run folder: workers return :class:`~.pairs.PairOutcome`.
"""

from __future__ import annotations

import collections
import contextlib
import multiprocessing
import os
import pickle
import signal
import socket
import struct
import subprocess
import sys
import threading
import time
import uuid
from collections.abc import Callable, Iterator
from multiprocessing.connection import wait

from .pairs import PairOutcome, PairTask, describe, run_pair

__all__ = ["execute", "run_tasks", "exit_with_parent", "probe_scheduler", "WORKER_ENV"]

#: Thread caps for worker processes (the same as Dask's nanny sets for its workers), and
#: one thread for the tracker's per-candidate work (``TrackerConfig.threads=None``,
#: :mod:`smtmvt.threads`): workers and threads do not oversubscribe the cores.
WORKER_ENV = {"OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "SMTMVT_THREADS": "1"}
_FRAME_REPORT_S = 0.5  # a pool worker reports frames done at most this often
#: seconds a Dask scheduler's address has to accept a connection and greet it
SCHEDULER_PROBE_S = 5.0
_HANDSHAKE_MAX = 1 << 16  # bytes: a scheduler's greeting is about 60

Finish = Callable[[PairTask, "PairOutcome | None", "str | None"], None]


def exit_with_parent(parent_pid: int, interval: float = 0.5) -> None:
    """Start a daemon thread that ends this process (``os._exit(1)``) once ``parent_pid`` is
    no longer its parent, i.e. the parent died and the process was adopted."""

    def watch() -> None:
        while os.getppid() == parent_pid:
            time.sleep(interval)
        os._exit(1)

    threading.Thread(target=watch, name="smtmvt-exit-with-parent", daemon=True).start()


def _killed_with_parent() -> None:
    """Linux: ask the kernel to SIGKILL this process when its parent dies (immediate; the
    :func:`exit_with_parent` thread stays as the portable fallback). Only for processes the
    driver's main thread starts: the signal follows the thread that started the process."""
    if not sys.platform.startswith("linux"):
        return
    try:
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, 9)  # PR_SET_PDEATHSIG, SIGKILL
    except (OSError, AttributeError):
        pass


def execute(task: PairTask, on_frame: Callable[[int], None] | None = None) -> PairOutcome:
    """Run ``task`` here, or in a fresh process when ``task.fresh_process``."""
    if not task.fresh_process:
        return run_pair(task, on_frame)
    return run_in_fresh_process(task)


def run_in_fresh_process(task: PairTask) -> PairOutcome:
    """:func:`run_pair` in a new interpreter (``python -m smtmvt.evaluation.isolated``):
    the task goes in pickled on stdin, the outcome comes back pickled on stdout. One
    OpenCV/BLAS thread, as in pool workers, so every place gives the same boxes."""
    env = dict(os.environ, **WORKER_ENV, SMTMVT_PARENT_PID=str(os.getpid()))
    env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)  # registered test trackers too
    proc = subprocess.run(
        [sys.executable, "-m", "smtmvt.evaluation.isolated"], input=pickle.dumps(task), capture_output=True, env=env
    )
    if proc.returncode == 0:
        try:
            return pickle.loads(proc.stdout)
        except (pickle.UnpicklingError, EOFError, AttributeError, ImportError) as exc:
            reason = f"unreadable outcome ({describe(exc)})"
    else:
        reason = f"exit code {proc.returncode}"
    tail = proc.stderr.decode("utf-8", "replace").strip().splitlines()[-3:]
    error = f"{task.tracker} on {task.sequence.name}: fresh process failed ({reason})" + (
        f": {' | '.join(tail)}" if tail else ""
    )
    return PairOutcome(task.tracker, task.sequence.name, task.n_frames, error=error)


def run_tasks(tasks: list[PairTask], finish: Finish, bars, workers: int = 1, scheduler=None) -> None:
    """Run every task and call ``finish(task, outcome, None)`` for each as it completes, or
    ``finish(task, None, message)`` when its worker died. ``bars``: a
    :class:`~.progress.Progress`."""
    if not tasks:
        return
    if scheduler is not None:
        _run_dask(tasks, scheduler, finish)
    elif workers > 1:
        _Pool(min(workers, len(tasks)), bars).run(tasks, finish)
    else:
        for task in tasks:
            bars.start(task)
            finish(task, execute(task, bars.frame_counter(task)), None)


# --------------------------------------------------------------------------- local pool


@contextlib.contextmanager
def _worker_environ() -> Iterator[None]:
    saved = {k: os.environ.get(k) for k in WORKER_ENV}
    os.environ.update(WORKER_ENV)
    try:
        yield
    finally:
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


def _worker_main(conn, parent_pid: int) -> None:
    """A pool worker: run the tasks it receives until ``None`` or the pipe closes, sending
    ``("frames", k)`` now and then and ``("done", outcome)`` after each task. Ctrl-C, which
    the terminal sends to the whole process group, is the driver's to handle (it ends its
    workers): a worker ignores it, so that no pair is reported as failed by it."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _killed_with_parent()
    exit_with_parent(parent_pid)
    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError):
            return
        if task is None:
            return
        state = {"n": 0, "t": time.monotonic()}

        def on_frame(k: int, state=state) -> None:
            state["n"] += k
            if time.monotonic() - state["t"] >= _FRAME_REPORT_S:
                conn.send(("frames", state["n"]))
                state["n"], state["t"] = 0, time.monotonic()

        outcome = execute(task, on_frame)
        conn.send(("done", outcome))


class _Worker:
    def __init__(self, ctx) -> None:
        self.conn, child = ctx.Pipe()
        self.proc = ctx.Process(target=_worker_main, args=(child, os.getpid()), daemon=True)
        self.proc.start()
        child.close()
        self.task: PairTask | None = None

    def give(self, task: PairTask) -> None:
        self.task = task
        self.conn.send(task)

    def stop(self, timeout: float = 5.0) -> None:
        """End the process: politely when idle, by SIGTERM (then SIGKILL) when busy."""
        with contextlib.suppress(OSError):
            if self.task is None:
                self.conn.send(None)
        if self.task is not None:
            self.proc.terminate()
        self.proc.join(timeout)
        if self.proc.is_alive():
            self.proc.kill()
            self.proc.join(timeout)
        self.conn.close()


class _Pool:
    """``n`` spawned worker processes fed one task at a time over pipes."""

    def __init__(self, n: int, bars) -> None:
        self.n, self.bars = n, bars
        self.ctx = multiprocessing.get_context("spawn")  # safe with OpenCV's threads

    def run(self, tasks: list[PairTask], finish: Finish) -> None:
        pending = collections.deque(tasks)
        with _worker_environ():
            workers = [_Worker(self.ctx) for _ in range(self.n)]
        try:
            for w in workers:
                self._feed(w, pending)
            while any(w.task is not None for w in workers):
                busy = {w.conn: w for w in workers if w.task is not None}
                for conn in wait(list(busy), timeout=0.5):
                    w = busy[conn]
                    if self._receive(w, finish):
                        self._feed(w, pending)
                    elif w.task is None:  # its process died: replace it
                        w.stop()
                        with _worker_environ():
                            workers[workers.index(w)] = fresh = _Worker(self.ctx)
                        self._feed(fresh, pending)
        finally:
            for w in workers:
                w.stop()

    def _feed(self, w: _Worker, pending: collections.deque) -> None:
        if pending:
            task = pending.popleft()
            self.bars.start(task)
            w.give(task)

    def _receive(self, w: _Worker, finish: Finish) -> bool:
        """Handle one message of ``w``; True when it finished its task and is alive."""
        task = w.task
        assert task is not None
        try:
            kind, payload = w.conn.recv()
        except (EOFError, OSError, pickle.UnpicklingError) as exc:
            w.proc.join(1.0)
            w.task = None
            code = w.proc.exitcode
            finish(
                task, None, f"{task.tracker} on {task.sequence.name}: worker failed (exit code {code}, {describe(exc)})"
            )
            return False
        if kind == "frames":
            self.bars.frames(payload, task.key)
            return False
        w.task = None
        finish(task, payload, None)
        return True


# --------------------------------------------------------------------------- Dask


def probe_scheduler(address: str, timeout: float = SCHEDULER_PROBE_S) -> None:
    """Check, within ``timeout`` seconds, that a Dask scheduler listens at ``address``
    (``tcp://host:port`` or ``host:port``); ``OSError`` naming the address and what is
    there otherwise (nothing, a server that says nothing, as an HTTP server, or one that
    replies something else).

    A Dask TCP server greets each connection at once with its handshake: an 8-byte length
    (``struct`` ``"Q"``, as ``distributed.comm.tcp`` reads it), then msgpack frames naming
    ``pickle-protocol``. ``distributed`` itself would wait forever for a silent server and
    allocate whatever length a garbage reply gives. Other protocols (``tls://``, ...) are
    left to ``distributed``.
    """
    try:
        from distributed.comm.addressing import parse_address, parse_host_port
    except ImportError as exc:  # pragma: no cover - optional dependency
        raise ValueError("--scheduler needs dask.distributed (pip install 'smtmvt[distributed]')") from exc
    try:
        scheme, location = parse_address(address)
        host, port = parse_host_port(location, default_port=8786) if scheme == "tcp" else ("", 0)
    except ValueError as exc:
        raise ValueError(f"--scheduler {address}: not an address like tcp://host:8786 ({exc})") from None
    if scheme != "tcp":
        return
    try:
        reply, why = _greeting(host, port, timeout)
    except OSError as exc:  # refused, no route, unknown host: at once
        raise OSError(f"cannot connect to the Dask scheduler at {address}: {exc.strerror or describe(exc)}") from None
    if why is not None:
        got = f"; it sent {reply[:24]!r}" if reply else ""
        raise OSError(f"no Dask scheduler at {address}: {why}{got}")


def _greeting(host: str, port: int, timeout: float) -> tuple[bytes, str | None]:
    """The bytes a server at ``(host, port)`` sends first, and None when they are a Dask
    handshake, else why not. ``OSError`` when no connection can be made."""
    deadline = time.monotonic() + timeout
    with socket.create_connection((host, port), timeout=timeout) as sock:
        reply = b""
        need = 8
        while len(reply) < need:
            sock.settimeout(max(deadline - time.monotonic(), 0.001))
            try:
                chunk = sock.recv(need - len(reply))
            except TimeoutError:
                return reply, f"no Dask handshake within {timeout:g} s (a scheduler greets at once)"
            if not chunk:
                return reply, "the connection was closed without a Dask handshake"
            reply += chunk
            if need == 8 and len(reply) == 8:
                (length,) = struct.unpack("Q", reply)
                if not 0 < length <= _HANDSHAKE_MAX:
                    return reply, "the reply is not a Dask handshake"
                need += length
    if b"pickle-protocol" not in reply:
        return reply, "the reply is not a Dask handshake"
    return reply, None


def _client_for(scheduler):
    try:
        import distributed
    except ImportError as exc:  # pragma: no cover - optional dependency
        raise ValueError("--scheduler needs dask.distributed (pip install 'smtmvt[distributed]')") from exc
    if isinstance(scheduler, distributed.Client):
        return scheduler, False
    probe_scheduler(str(scheduler))
    try:
        # connect timeout: dask's distributed.comm.timeouts.connect (30 s by default)
        return distributed.Client(scheduler), True
    except (OSError, TimeoutError) as exc:
        raise OSError(f"cannot connect to the Dask scheduler at {scheduler}: {exc}") from None


def _run_dask(tasks: list[PairTask], scheduler, finish: Finish) -> None:
    import distributed

    client, owned = _client_for(scheduler)
    try:
        futures = {}
        for t in tasks:
            key = f"smtmvt-{t.tracker}-{t.sequence.name}-{t.repeat}-{uuid.uuid4().hex}"
            futures[client.submit(execute, t, pure=False, key=key)] = t
        try:
            for fut in distributed.as_completed(list(futures)):
                task = futures[fut]
                try:
                    outcome = fut.result()
                except Exception as exc:  # noqa: BLE001 - KilledWorker, unpicklable, ...
                    finish(task, None, f"{task.tracker} on {task.sequence.name}: worker failed: {describe(exc)}")
                else:
                    finish(task, outcome, None)
                fut.release()
        except BaseException:
            client.cancel(list(futures))
            raise
    finally:
        if owned:
            client.close()
