"""A token bucket: `burst` tokens at once, refilled at `rate` per second.

What limits a client address's page loads (`app.page.gate.PAGES`) and page builds
(`app.page.guard.BUILDS`), both `AddressLimit`, and a session's whole-document pulls
(`app.page.pulls.PullGuard`).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

#: The most visitors behind one client address (a school's NAT) that open the page at
#: once, by default (``python -m app.serve --class-size``): the page builds' and page
#: loads' bursts per address are sized for it (`app.page.guard.BUILDS`,
#: `app.page.gate.PAGES`).
CLASS_SIZE = 40


def take(tokens: float, elapsed: float, burst: float, rate: float) -> tuple[float, bool]:
    """Ask a bucket that held `tokens` `elapsed` s ago for one token: the tokens it holds
    after the refill (never above `burst`) less the one taken, and whether one was (not
    when fewer than one are left; nothing is taken then)."""
    tokens = min(burst, tokens + elapsed * rate)
    if tokens < 1.0:
        return tokens, False
    return tokens - 1.0, True


class AddressLimit:
    """How many of something (page loads, page builds) each client address may have: a
    token bucket of `burst` per address, refilled at `rate` per second.

    Idle clients' buckets are forgotten (at most `clients` are kept).
    """

    def __init__(self, burst: float, rate: float, clients: int = 10_000,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.burst, self.rate, self.clients, self._clock = burst, rate, clients, clock
        self._buckets: dict[str, tuple[float, float]] = {}  # address -> (tokens, when)
        self._lock = threading.Lock()

    def allow(self, client: str) -> bool:
        """Take one from `client`'s bucket; False (nothing taken) when it is empty."""
        now = self._clock()
        with self._lock:
            tokens, when = self._buckets.get(client, (self.burst, now))
            if len(self._buckets) >= self.clients and client not in self._buckets:
                self._forget_full(now)
            tokens, taken = take(tokens, now - when, self.burst, self.rate)
            self._buckets[client] = (tokens, now)
            return taken

    def retry_after(self, client: str) -> float:
        """Seconds until `client`'s bucket holds one again."""
        with self._lock:
            tokens, when = self._buckets.get(client, (self.burst, self._clock()))
        return max(0.0, (1.0 - tokens) / self.rate - (self._clock() - when))

    def _forget_full(self, now: float) -> None:
        full = [c for c, (tokens, when) in self._buckets.items()
                if tokens + (now - when) * self.rate >= self.burst]
        for c in full or list(self._buckets)[: len(self._buckets) // 2]:
            del self._buckets[c]
