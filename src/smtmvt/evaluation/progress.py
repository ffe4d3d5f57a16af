"""Progress bars of a run: pairs done and frames done (tqdm, on stderr)."""

from __future__ import annotations

import sys

__all__ = ["Progress"]


class Progress:
    """Two tqdm bars on stderr: pairs done, and frames done. Frames arrive per frame in this
    process, every 0.5 s from pool workers, and per finished pair from a Dask cluster or a
    fresh process. Pairs are keyed by :attr:`PairTask.key`."""

    def __init__(self, n_pairs: int, n_frames: int, enabled: bool):
        self.enabled = enabled and n_pairs > 0
        self._counted: dict = {}  # pair key -> frames already shown
        self._finished: set = set()
        if not self.enabled:
            return
        from tqdm.auto import tqdm

        self.pairs = tqdm(total=n_pairs, desc="pairs ", unit="pair", position=0, file=sys.stderr, dynamic_ncols=True)
        self.fbar = tqdm(
            total=n_frames, desc="frames", unit="fr", position=1, file=sys.stderr, dynamic_ncols=True, smoothing=0.05
        )

    def __enter__(self) -> Progress:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def start(self, task) -> None:
        if self.enabled:
            self.pairs.set_postfix_str(task.label, refresh=True)

    def frames(self, k: int, key=None) -> None:
        if not self.enabled or key in self._finished:
            return
        self._counted[key] = self._counted.get(key, 0) + k
        self.fbar.update(k)

    def frame_counter(self, task):
        return lambda k: self.frames(k, task.key)

    def pair_done(self, task) -> None:
        self._finished.add(task.key)
        if not self.enabled:
            return
        # a failed or remote pair adds what it did not report frame by frame
        remaining = task.n_frames - self._counted.pop(task.key, 0)
        if remaining > 0:
            self.fbar.update(remaining)
        self.pairs.set_postfix_str(task.label, refresh=False)
        self.pairs.update(1)

    def close(self) -> None:
        if self.enabled:
            self.fbar.close()
            self.pairs.close()
