"""A lap timer for the cost-by-stage measurements of the benchmarks (wall-clock seconds)."""

from __future__ import annotations

import time


class LapTimer:
    """Adds the seconds since the previous lap to ``store[key]``; a no-op when ``store`` is None."""

    def __init__(self, store: dict[str, float] | None) -> None:
        self.store = store
        self.t = time.perf_counter()

    def lap(self, key: str) -> None:
        """Charge the time since the previous lap (or construction) to ``key``."""
        if self.store is not None:
            now = time.perf_counter()
            self.store[key] = self.store.get(key, 0.0) + now - self.t
            self.t = now
