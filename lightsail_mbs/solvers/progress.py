"""Progress of a run in simulated time, shown on stderr (tqdm) or silent."""

from __future__ import annotations

import sys

# called (no arguments) at every update while a base run's twins may start beside it (solvers.twin_workers)
watcher = None
prefix = ""  # before every bar's label: "twin " in a twin's worker process


class Progress:
    """Reports simulated time t ∈ [0, t_final]; `update(t)` is cheap and may be called every step."""

    def __init__(self, t_final: float, enabled: bool = False, label: str = "simulating"):
        self.t_final = t_final
        self._bar = None
        if enabled:
            from tqdm import tqdm

            tqdm.monitor_interval = 0  # no monitor thread: twins' workers are forked while bars are open
            self._bar = tqdm(
                total=round(t_final, 9),
                desc=prefix + label,
                unit="s(sim)",
                file=sys.stderr,
                bar_format="{desc}: {percentage:3.0f}%|{bar}| t={n:.3g}/{total:.3g} s [{elapsed}<{remaining}]",
                mininterval=0.5,
            )

    def update(self, t: float) -> None:
        if watcher is not None:
            watcher()
        if self._bar is not None:
            self._bar.n = min(round(t, 9), self._bar.total)
            self._bar.refresh() if self._bar.n >= self._bar.total else self._bar.update(0)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None
