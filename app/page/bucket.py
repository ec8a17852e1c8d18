"""A token bucket: `burst` tokens at once, refilled at `rate` per second, and the key of a
client it is kept for.

What limits a client's page loads (`app.page.gate.PAGES`), page builds
(`app.page.guard.BUILDS`) and pages closed soon after their build
(`app.page.gate.THROWN`), all `AddressLimit` keyed by `client_key`, and a session's
whole-document pulls (`app.page.pulls.PullGuard`).
"""

from __future__ import annotations

import ipaddress
import threading
import time
from collections import OrderedDict
from collections.abc import Callable

#: The most visitors behind one client address (a school's NAT) that open the page at
#: once, by default (``python -m app.serve --class-size``): the page builds' and page
#: loads' bursts per address are sized for it (`app.page.guard.BUILDS`,
#: `app.page.gate.PAGES`).
CLASS_SIZE = 40

#: The length of the IPv6 prefix that is one client (RFC 6177: a site, a household or one
#: machine is given a /64 or more, and picks any of its 2**64 addresses at will).
IPV6_CLIENT_PREFIX = 64


def client_key(address: str) -> str:
    """The key of the client at `address` (a request's ``remote_ip``) for the limits per
    client: an IPv4 address itself (a school's NAT is one client: the limits are sized
    for a class behind it), an IPv6 address's /64 network (one machine may use any
    address of its /64, so keying by address would give it 2**64 budgets), an
    IPv4-mapped IPv6 address as its IPv4 one; a text that is no address, as it is."""
    try:
        ip = ipaddress.ip_address(address.split("%", 1)[0])
    except ValueError:
        return address
    if ip.version == 6 and ip.ipv4_mapped is not None:
        return str(ip.ipv4_mapped)
    if ip.version == 6:
        return str(ipaddress.ip_network(f"{ip}/{IPV6_CLIENT_PREFIX}", strict=False))
    return str(ip)


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


class ThrownPages:
    """Pages a client closed while their explorer was being built, or within `within` s
    of its being sent, limited per client: each takes one from the client's
    `AddressLimit` of `burst`, refilled at `rate` per second; `retry_after` is 0 while
    the client has one left.

    A browser takes a second or more to show a page's explorer once it has it, and a
    pupil keeps the page open for the lesson: reloading it closes a page built minutes
    ago, which takes nothing; a script loading pages in a loop closes each as soon as it
    has it (or before).  Only pages built within the last `remember` s are kept (at most
    `pages`)."""

    def __init__(self, burst: float, rate: float, within: float, remember: float = 600.0,
                 pages: int = 10_000, clock: Callable[[], float] = time.monotonic) -> None:
        self.limit = AddressLimit(burst, rate, clock=clock)
        self.within, self.remember, self.pages, self._clock = within, remember, pages, clock
        #: page (session) id -> (client, when its build started, when it was sent or None)
        self._built: OrderedDict[str, tuple[str, float, float | None]] = OrderedDict()
        self._lock = threading.Lock()

    def building(self, page: str, client: str) -> None:
        """The explorer of page (session) id `page`, of `client`, is being built."""
        now = self._clock()
        with self._lock:
            while self._built and (now - next(iter(self._built.values()))[1] >= self.remember
                                   or len(self._built) >= self.pages):
                self._built.popitem(last=False)
            self._built[page] = (client, now, None)

    def sent(self, page: str) -> None:
        """The explorer of `page` was built and sent to its browser."""
        with self._lock:
            if page in self._built:
                client, started, _ = self._built[page]
                self._built[page] = (client, started, self._clock())

    def closed(self, page: str) -> None:
        """The page `page` was closed (its websocket): if its explorer was being built or
        was sent within `within` s, its client's bucket loses one."""
        with self._lock:
            entry = self._built.pop(page, None)
        if entry is None:
            return
        client, _, sent = entry
        if sent is None or self._clock() - sent < self.within:
            self.limit.allow(client)

    def retry_after(self, client: str) -> float:
        """Seconds until `client` may have a page built again (0: now)."""
        return self.limit.retry_after(client)
