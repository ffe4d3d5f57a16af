"""Ctrl-C and SIGTERM always stop a command (130, 143), even inside compiled code (issue 46, fault 4).

A signal that lands in Python code called by a numba kernel comes out of the kernel as
``SystemError: CPUDispatcher(...) returned a result with an exception set`` whose cause is
the interrupt. The test trackers here raise exactly that, or swallow the interrupt as
compiled code may, at a chosen frame of a chosen sequence.
"""

from __future__ import annotations

import functools
import json
import os
import signal
import time

import pytest

from smtmvt.cli import Terminated, main
from smtmvt.evaluation import register_tracker, unregister_tracker
from smtmvt.interrupts import interruption
from test_runner import ConstantVelocity, evaluate_cli, first_box_of, make_otb_dataset

_KERNEL_ERROR = "CPUDispatcher(<function _run at 0x7f06076fab60>) returned a result with an exception set"


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    return make_otb_dataset(tmp_path_factory.mktemp("otb"), n_frames=8)


def raise_as_compiled_code(stop: type[KeyboardInterrupt]) -> None:
    """Raise ``stop`` the way a numba kernel lets it out: as the cause of a SystemError."""
    try:
        raise stop()
    except KeyboardInterrupt as exc:
        raise SystemError(_KERNEL_ERROR) from exc


class StopAt(ConstantVelocity):
    """At frame ``frame`` of the sequence whose first box is ``first_box``: ``how`` is
    ``"wrapped-int"`` / ``"wrapped-term"`` (the interrupt as a SystemError's cause) or
    ``"swallowed"`` (SIGTERM to this process, its exception caught and dropped)."""

    def __init__(self, first_box, frame, how, seed=None):
        super().__init__(seed=seed)
        self.first_box, self.frame, self.how = tuple(first_box), frame, how

    def init(self, frame, box):
        super().init(frame, box)
        self.i, self.armed = 0, tuple(box) == self.first_box

    def update(self, frame):
        self.i += 1
        if self.armed and self.i == self.frame:
            if self.how == "swallowed":
                try:
                    os.kill(os.getpid(), signal.SIGTERM)
                    time.sleep(5)  # the handler raises during the sleep
                except KeyboardInterrupt:
                    pass
            else:
                raise_as_compiled_code(Terminated if self.how == "wrapped-term" else KeyboardInterrupt)
        return super().update(frame)


def test_interruption_is_found_in_the_chain_of_causes_and_contexts():
    with pytest.raises(SystemError) as info:
        raise_as_compiled_code(Terminated)
    assert isinstance(interruption(info.value), Terminated)
    try:
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt:
            raise ValueError("raised while stopping") from None  # context kept, only not shown
    except ValueError as exc:
        assert type(interruption(exc)) is KeyboardInterrupt
    assert interruption(SystemError(_KERNEL_ERROR)) is None
    assert interruption(RuntimeError("simulated tracker bug")) is None


@pytest.mark.parametrize(("how", "status"), [("wrapped-int", 130), ("wrapped-term", 143), ("swallowed", 143)])
def test_evaluate_stops_on_an_interrupt_inside_compiled_code(dataset, tmp_path, capsys, how, status):
    """``evaluate --workers 1``: the interrupted pair is not an error, the pairs after it do
    not run, the exit status is the signal's and stderr has one line, no traceback."""
    name = f"test-stop-{how}"
    register_tracker(name, functools.partial(StopAt, first_box_of(dataset, "SquareB"), 3, how), replace=True)
    try:
        rc = evaluate_cli(dataset, tmp_path / "run", "--trackers", name, "--workers", "1", "--no-report", "--quiet")
    finally:
        unregister_tracker(name)
    err = capsys.readouterr().err
    assert rc == status, err
    assert err.strip().splitlines()[-1] == ("interrupted" if status == 130 else "terminated")
    assert "Traceback" not in err and "SystemError" not in err
    errors_json = tmp_path / "run" / "errors.json"
    assert not errors_json.exists() or json.loads(errors_json.read_text()) == []
    results = tmp_path / "run" / "results" / name
    assert sorted(p.name for p in results.glob("*.txt")) == ["SquareA.txt"]  # B stopped, C never ran


@pytest.mark.parametrize(("stop", "status"), [(KeyboardInterrupt, 130), (Terminated, 143)])
def test_track_stops_on_an_interrupt_inside_compiled_code(dataset, tmp_path, capsys, monkeypatch, stop, status):
    from smtmvt import Tracker

    original, calls = Tracker.update, []

    def update(self, frame, *args, **kwargs):
        calls.append(1)
        if len(calls) == 3:
            raise_as_compiled_code(stop)
        return original(self, frame, *args, **kwargs)

    monkeypatch.setattr(Tracker, "update", update)
    out = tmp_path / "res.txt"
    rc = main(["track", str(dataset / "SquareA"), "--out", str(out), "--particles", "40", "--quiet"])
    err = capsys.readouterr().err
    assert rc == status, err
    assert "stopped after 3 of 8 frames" in err and err.strip().splitlines()[-1] in ("interrupted", "terminated")
    assert "Traceback" not in err and "SystemError" not in err
    assert not out.exists()


class CtrlCAt(ConstantVelocity):
    """Sends SIGINT to its own process at frame ``frame`` (as Ctrl-C reaches every process
    of the terminal's process group), then goes on."""

    def __init__(self, frame, seed=None):
        super().__init__(seed=seed)
        self.frame = frame

    def init(self, frame, box):
        super().init(frame, box)
        self.i = 0

    def update(self, frame):
        self.i += 1
        if self.i == self.frame:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.2)
        return super().update(frame)


def test_pool_workers_leave_ctrl_c_to_the_driver(dataset, tmp_path):
    """A worker of ``--workers 2`` that gets Ctrl-C neither dies nor reports its pair as
    failed: the driver, which gets it too, decides (here it did not, so every pair completes)."""
    from smtmvt.evaluation import run_evaluation

    register_tracker("test-ctrl-c", functools.partial(CtrlCAt, 3), replace=True)
    try:
        run = run_evaluation(dataset, ["test-ctrl-c"], tmp_path / "run", workers=2, progress=False, report=False)
    finally:
        unregister_tracker("test-ctrl-c")
    assert run.errors == [] and len(run.done) == 3
