"""A token bucket: `burst` tokens at once, refilled at `rate` per second.

What limits a client address's page builds (`app.page.guard.BuildLimit`) and a session's
whole-document pulls (`app.page.pulls.PullGuard`).
"""

from __future__ import annotations


def take(tokens: float, elapsed: float, burst: float, rate: float) -> tuple[float, bool]:
    """Ask a bucket that held `tokens` `elapsed` s ago for one token: the tokens it holds
    after the refill (never above `burst`) less the one taken, and whether one was (not
    when fewer than one are left; nothing is taken then)."""
    tokens = min(burst, tokens + elapsed * rate)
    if tokens < 1.0:
        return tokens, False
    return tokens - 1.0, True
