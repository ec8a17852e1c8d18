"""The abuse mode of the load test (``python -m benchmarks.app.load_test --abuse``).

One probe session (`docker.browser_client.Session`) moves ψ every ``--interval`` s; per
kind of abusive client (`ABUSE_KINDS`: websockets with invented session ids, PULL-DOC
spam, the Methods card at 16x with live recompute, NaN as ψ, page loops) it is recorded
for a window alone, then for a window beside one abusive client of that kind, and so on
for ``--rounds`` pairs, in turn baseline first and abuse first, in one run against one
server; each abusive client connects from a loopback address of its own
(`abuser_address`), so that each starts with a new client's limits.  Per kind: the
probe's p50/p95 over its baseline windows and over its abuse windows (moves pooled),
their p95 ratio against the kind's target (`TARGETS`, else `ABUSE_TARGET`) and each
round's ratio, the moves answered, the server's CPU, the most lines it logged in an
abuse window (target `LOG_LINES_TARGET`) and the machine's load average.  Run through
load_test.py:

    python -m benchmarks.app.load_test --abuse --window 20
    python -m benchmarks.app.load_test --abuse pull-doc page-load-loop --window 20 --rounds 4
"""

from __future__ import annotations

import asyncio
import json
import os
import random
import sys
import time
from pathlib import Path

from tornado.httpclient import AsyncHTTPClient, HTTPClientError
from tornado.websocket import WebSocketClosedError

from app.page.gate import HOLD_S
from benchmarks.app.common import pct, usage
from docker.browser_client import REFUSED, Session, Stats, models_of, strings

#: The abusive clients of `--abuse`, in the order they run.
#: ``page-loop`` fetches the page's HTML in a loop and never opens its websocket;
#: ``page-load-loop`` loads the page whole, as a browser does, closes it and loads it
#: again, and is recorded from its first load (its address's page limits are spent in
#: the window); ``page-load-loop-steady`` from its first refused or held-back load on.
ABUSE_KINDS = ("invented-ids", "pull-doc", "methods-16x", "nan", "page-loop",
               "page-load-loop", "page-load-loop-steady")

#: The probe's p95 under abuse may be at most this many times its baseline, and for the
#: kinds named in `TARGETS` that many times.
ABUSE_TARGET = 1.5
TARGETS = {"pull-doc": 1.2, "page-load-loop": 1.3}

#: The most lines the server may log for an abusive client in one window.
LOG_LINES_TARGET = 20

#: The pairs of windows (baseline, abuse) per kind.
ROUNDS = 3

#: How long the probe waits, unrecorded, after an abusive client has stopped, before the
#: next window (s): the server discards a closed page's session 20 s after its
#: websocket closed, checking every 5 s (`app.serve.SESSION`), so that what one abuse
#: window leaves does not fall into the next.
SETTLE_S = 25.0

#: How fast the abusive clients send at most (a bound, not a pace: each also waits for
#: its socket): PULL-DOC requests and NaN values per second.
PULL_DOC_RATE = 100.0
NAN_RATE = 20.0

#: The values the `nan` client sends as ψ, in turn: bare JSON (Python's json writes
#: NaN and Infinity) and Bokeh's own encoding of non-finite numbers.
NAN_VALUES = (float("nan"), float("inf"), float("-inf"),
              {"type": "number", "value": "nan"}, {"type": "number", "value": "+inf"})

METHODS_TITLE = "Methods: numerical"
LIVE_LABEL = "Recompute live on every change"


def methods_controls(patches: list[str]) -> dict[str, tuple[str, object]]:
    """The Methods card's controls in the PATCH-DOCs that filled it, as {role: (model
    id, value to set)}: every method chosen, 16x resolution, live recompute on."""
    found: dict[str, tuple[str, object]] = {}
    for content in patches:
        for i, m in models_of(json.loads(content))[0].items():
            a = m.get("attributes", {})
            if m.get("name") == "MultiChoice" and a.get("options"):
                found["methods"] = (i, [o[0] if isinstance(o, list) else o for o in a["options"]])
            elif m.get("name", "").endswith("Select") and any(
                    isinstance(o, list) and o[1].startswith("16 ") for o in a.get("options", [])):
                found["resolution"] = (i, next(o[0] for o in a["options"]
                                               if isinstance(o, list) and o[1].startswith("16 ")))
            elif m.get("name") == "CheckboxGroup" and a.get("labels") == [LIVE_LABEL]:
                found["live"] = (i, [0])
    missing = {"methods", "resolution", "live"} - set(found)
    if missing:
        raise LookupError(f"the Methods card's {', '.join(sorted(missing))} not found")
    return found


def methods_card(doc_json: dict) -> str:
    """The id of the Methods card (a Panel Card whose header names it) in a document."""
    models, _ = models_of(doc_json)
    cards = [i for i, m in models.items() if m.get("name") == "panel.models.layout.Card"
             and any(METHODS_TITLE in t for t in strings(m.get("attributes", {}).get("children")))]
    if len(cards) != 1:
        raise LookupError(f"expected one Methods card, found {len(cards)}")
    return cards[0]


def changed(model: str, attr: str, new) -> dict:
    """A PATCH-DOC event setting `model`'s `attr` to `new`, as BokehJS sends it."""
    return {"kind": "ModelChanged", "model": {"id": model}, "attr": attr, "new": new}


async def paced(stop: asyncio.Event, rate: float):
    """Yields at most `rate` times a second until `stop` is set."""
    next_t = time.perf_counter()
    while not stop.is_set():
        yield
        next_t = max(next_t + 1.0 / rate, time.perf_counter() - 1.0)
        await asyncio.sleep(max(0.0, next_t - time.perf_counter()))


async def abuse_page_loop(url: str, http: AsyncHTTPClient, stop: asyncio.Event,
                          counts: dict, source: str | None = None) -> None:
    """GET the page in a loop, each as soon as the previous one is answered, never
    opening its websocket (a crawler, a script); past the address's page loads
    (`app.page.gate`) the redirect to the busy page is followed."""
    while not stop.is_set():
        r = await http.fetch(url, request_timeout=60, raise_error=False,
                             network_interface=source)
        key = {200: "pages", 429: "refused"}.get(r.code, f"HTTP {r.code}")
        counts[key] = counts.get(key, 0) + 1


async def abuse_page_load_loop(url: str, http: AsyncHTTPClient, stop: asyncio.Event,
                               counts: dict, ready: asyncio.Event | None = None,
                               source: str | None = None) -> None:
    """Load the page in a loop as a browser does (its HTML, its websocket, the document,
    the document-ready event, then the explorer built into it), each load as soon as
    the previous one has its explorer or its refusal, then closed; `ready` (if given) is
    set at the first load refused (the busy page, or a page showing the refusal note) or
    held back (built, but answered `HOLD_S` late: its client threw its pages away), and
    only then are loads counted."""
    while not stop.is_set():
        s = Session(url, http, 5.0, None, source)
        start = time.monotonic()
        try:
            await asyncio.wait_for(s.open(), 120)
            key = "built, held back" if time.monotonic() - start >= HOLD_S else "built"
        except LookupError as err:
            key = ("refused" if REFUSED in str(err) else "refused (429)" if "429" in str(err)
                   else "no explorer")
        except (TimeoutError, ConnectionError, WebSocketClosedError, OSError):
            key = "failed"
        finally:
            s.close()
        if ready is not None and not ready.is_set():
            if key == "built":  # (not its note, the busy page (429) or a held page)
                continue
            ready.set()
        counts[key] = counts.get(key, 0) + 1


async def abuse_invented_ids(url: str, http: AsyncHTTPClient, stop: asyncio.Event,
                             counts: dict, source: str | None = None) -> None:
    """Open websockets with made-up session ids, in turn unsigned and signed with
    another key than the server's, each as soon as the previous one is settled."""
    from bokeh.util.token import generate_jwt_token, generate_secret_key, generate_session_id

    other_key = generate_secret_key().encode()
    n = 0
    while not stop.is_set():
        n += 1
        signed = n % 2 == 0
        key = other_key if signed else None
        sid = generate_session_id(secret_key=key, signed=signed)
        token = generate_jwt_token(sid, secret_key=key, signed=signed)
        s = Session(url, http, 5.0, None, source)
        try:
            await asyncio.wait_for(s.connect(token), 30)
            counts["accepted"] = counts.get("accepted", 0) + 1
        except HTTPClientError as err:  # (refused before the handshake)
            key = f"refused (HTTP {err.code})"
            counts[key] = counts.get(key, 0) + 1
        except (TimeoutError, ConnectionError, WebSocketClosedError, OSError):
            counts["refused"] = counts.get("refused", 0) + 1
        finally:
            s.close()


async def flood(url: str, http: AsyncHTTPClient, stop: asyncio.Event, counts: dict,
                rate: float, message, reply: str, replies: str,
                ready: asyncio.Event | None = None, source: str | None = None) -> None:
    """A loaded session sending `message(session, n)` (a message type and its content)
    for n = 0, 1, ..., up to `rate` a second, without waiting for the replies (its
    reader takes them), until `stop` or the server closes it; counts those sent and,
    as `replies`, the server's messages of type `reply` (and its ERROR replies).
    `ready` (if given) is set once the session is loaded: the flood starts then."""
    s = Session(url, http, 5.0, None, source)
    await s.open()
    if ready is not None:
        ready.set()
        await asyncio.sleep(0)
    n = 0
    try:
        async for _ in paced(stop, rate):
            if not s.alive:
                counts["connection closed by the server"] = 1
                break
            await s.send(*message(s, n))
            n += 1
    except WebSocketClosedError:
        counts["connection closed by the server"] = 1
    finally:
        counts["sent"] = n
        counts[replies] = s.received.get(reply, 0)
        if reply != "ERROR":
            counts["refused (ERROR replies)"] = s.received.get("ERROR", 0)
        s.close()


async def abuse_pull_doc(url: str, http: AsyncHTTPClient, stop: asyncio.Event,
                         counts: dict, ready: asyncio.Event | None = None,
                         source: str | None = None) -> None:
    """A loaded session sending PULL-DOC requests, up to `PULL_DOC_RATE` a second,
    without waiting for the replies (the server closes a connection at its second:
    `app.page.websocket`); closed at the end."""
    await flood(url, http, stop, counts, PULL_DOC_RATE, lambda s, n: ("PULL-DOC-REQ", {}),
                "PULL-DOC-REPLY", "replies", ready, source)


async def abuse_methods_16x(url: str, http: AsyncHTTPClient, stop: asyncio.Event,
                            counts: dict, source: str | None = None,
                            interval: float = 0.3) -> None:
    """A session that opens the Methods card, chooses every method at 16x resolution
    with live recompute on, then moves ψ every `interval` s (as the probe does)."""
    s = Session(url, http, 5.0, None, source)
    await s.open()
    try:
        s.patches = []
        await s.send("PATCH-DOC", {"events": [changed(methods_card(s.doc), "collapsed",
                                                       False)]})
        end = time.perf_counter() + 30
        controls = None
        while controls is None and time.perf_counter() < end and not stop.is_set():
            await asyncio.sleep(0.1)
            try:
                controls = methods_controls(s.patches)
            except LookupError:
                pass
        s.patches = None
        if controls is None:
            counts["Methods card not filled"] = 1
            return
        for role in ("live", "resolution", "methods"):
            model, value = controls[role]
            attr = {"live": "active", "resolution": "value", "methods": "value"}[role]
            await s.send("PATCH-DOC", {"events": [changed(model, attr, value)]})
        counts["methods"] = len(controls["methods"][1])
        async for _ in paced(stop, 1.0 / interval):
            if not s.pending:
                counts["ψ moves"] = counts.get("ψ moves", 0) + 1
            await s.move()
    finally:
        s.close()


async def abuse_nan(url: str, http: AsyncHTTPClient, stop: asyncio.Event,
                    counts: dict, ready: asyncio.Event | None = None,
                    source: str | None = None) -> None:
    """A session sending NaN and ±inf as the ψ slider's value, up to `NAN_RATE` a
    second; counts the server's ERROR replies."""
    def value(s: Session, n: int) -> tuple[str, dict]:
        event = changed(s.slider, "value", NAN_VALUES[n % len(NAN_VALUES)])
        return "PATCH-DOC", {"events": [event]}

    await flood(url, http, stop, counts, NAN_RATE, value, "ERROR", "server ERROR replies",
                ready, source)


async def abuse_page_load_loop_steady(url: str, http: AsyncHTTPClient, stop: asyncio.Event,
                                      counts: dict, ready: asyncio.Event,
                                      source: str | None = None) -> None:
    """`abuse_page_load_loop`, recorded from its first refused load on."""
    await abuse_page_load_loop(url, http, stop, counts, ready, source)


#: The abusers that set their `ready` event themselves, recorded from then on (the others
#: from their start): the floods of messages once their page is loaded (a page load is
#: what the page-load loops measure), the steady page-load loop once the address's
#: page builds are spent.
PRELUDE = {"pull-doc": abuse_pull_doc, "nan": abuse_nan,
           "page-load-loop-steady": abuse_page_load_loop_steady}

ABUSERS = {"page-loop": abuse_page_loop, "page-load-loop": abuse_page_load_loop,
           "invented-ids": abuse_invented_ids, "methods-16x": abuse_methods_16x, **PRELUDE}


def log_lines(log: Path | None) -> tuple[int, int]:
    """(lines, tracebacks) in the server's log so far."""
    if log is None or not log.exists():
        return 0, 0
    text = log.read_bytes()
    return text.count(b"\n"), text.count(b"Traceback (most recent call last)")


async def quiet_log(log: Path | None, quiet: float = 2.0, limit: float = 30.0) -> None:
    """Wait until the server's log has not grown for `quiet` s (at most `limit` s): what
    an abusive client leaves behind is written before the next window."""
    end = time.perf_counter() + limit
    last, since = log_lines(log), time.perf_counter()
    while time.perf_counter() < end and time.perf_counter() - since < quiet:
        await asyncio.sleep(0.25)
        now = log_lines(log)
        if now != last:
            last, since = now, time.perf_counter()


async def abuse_window(probe: Session, kind: str | None, url: str, http: AsyncHTTPClient,
                       duration: float, interval: float, timeout: float, pids: list[int],
                       log: Path | None, source: str | None = None) -> dict:
    """The probe moving ψ every `interval` s for `duration` s, alone (`kind` None) or
    beside one abusive client of `kind` (its connections from the local address
    `source`); its figures, the server's CPU over the window and the lines the server
    logged from its start until its log was quiet again."""
    stats = Stats()
    counts: dict = {}
    stop, ready = asyncio.Event(), asyncio.Event()
    task = None
    if kind in PRELUDE:  # the abuser runs unrecorded until it says it is ready
        task = asyncio.create_task(PRELUDE[kind](url, http, stop, counts, ready,
                                                 source=source))
        try:
            await asyncio.wait_for(ready.wait(), 120)
        except TimeoutError:
            counts["not ready after 120 s"] = 1
    lines0, tb0 = log_lines(log)
    _, cpu0 = usage(pids)
    t0 = time.perf_counter()
    if kind and task is None:
        task = asyncio.create_task(ABUSERS[kind](url, http, stop, counts, source=source))
    probe.stats = stats
    next_t = t0 + random.uniform(0, interval)
    while next_t < t0 + duration:
        await asyncio.sleep(max(0.0, next_t - time.perf_counter()))
        await probe.move()
        next_t += interval
    end = time.perf_counter() + timeout
    while probe.pending and probe.alive and time.perf_counter() < end:
        await asyncio.sleep(0.05)
    wall = time.perf_counter() - t0
    _, cpu1 = usage(pids)
    if probe.pending and probe.alive:
        stats.error(f"no update within {timeout:g} s")
    probe.stats = probe.pending = None
    stop.set()
    if task is not None:
        try:
            await asyncio.wait_for(task, 60)
        except Exception as err:  # the abuser's own failure: reported with its counts
            counts["client failed"] = f"{type(err).__name__}: {err}"[:100]
    await quiet_log(log)
    lines1, tb1 = log_lines(log)
    lat = sorted(x * 1e3 for x in stats.latencies)
    return {
        "kind": kind or "baseline", "duration_s": round(wall, 1), "moves_sent": stats.sent,
        "answered": len(lat), "late_ticks": stats.late, "errors": sum(stats.errors.values()),
        "p50_ms": round(pct(lat, 50), 1), "p95_ms": round(pct(lat, 95), 1),
        "server_cpu_pct": round(100 * (sum(cpu1.values()) - sum(cpu0.values())) / wall)
        if pids else None,
        "log_lines": lines1 - lines0, "tracebacks": tb1 - tb0, "abuser": counts,
        "source": source, "load_average": os.getloadavg()[0], "latencies_ms": lat,
    }


async def settle(probe: Session, interval: float, seconds: float) -> None:
    """The probe moving ψ every `interval` s for `seconds` s, unrecorded."""
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        await probe.move()
        await asyncio.sleep(interval)


def abuser_address(n: int) -> str:
    """The loopback address of the `n`-th abusive client (127.0.0.10, 127.0.0.11, ...):
    each starts with its own fresh limits per client (`app.page.bucket.client_key`), as
    a new client from elsewhere would, and none spends the probe's (127.0.0.1)."""
    return f"127.0.{(10 + n) // 250}.{(10 + n) % 250 + 1}"


async def run_abuse(url: str, kinds: list[str], duration: float, warmup: float,
                    interval: float, timeout: float, pids: list[int],
                    log: Path | None, rounds: int = ROUNDS) -> list[dict]:
    """Per kind, `rounds` pairs of a baseline window and an abuse window, in turn
    baseline first and abuse first (so that a drift of the machine's load weighs on
    both alike); each abuse window's client from an address of its own
    (`abuser_address`)."""
    AsyncHTTPClient.configure(None, max_clients=20)
    http = AsyncHTTPClient()
    probe = Session(url, http, timeout, None)
    rows = []
    n = 0
    try:
        await asyncio.wait_for(probe.open(), 120)
        print(f"[abuse] probe open; warm-up {warmup:g} s", file=sys.stderr)
        end = time.perf_counter() + warmup
        while time.perf_counter() < end:
            await probe.move()
            await asyncio.sleep(interval)
        await quiet_log(log)
        for kind in kinds:
            for r in range(rounds):
                for k in ((None, kind) if r % 2 == 0 else (kind, None)):
                    source = None if k is None else abuser_address(n)
                    n += k is not None
                    row = await abuse_window(probe, k, url, http, duration, interval,
                                             timeout, pids, log, source)
                    row["for"], row["round"] = kind, r + 1
                    rows.append(row)
                    if k is not None:
                        await settle(probe, interval, SETTLE_S)
                    shown = {x: v for x, v in row.items() if x != "latencies_ms"}
                    print(f"[abuse] {json.dumps(shown)}", file=sys.stderr)
    finally:
        probe.close()
        http.close()
    return rows


def target_of(kind: str) -> float:
    """The p95 ratio a kind must stay within (`TARGETS`, else `ABUSE_TARGET`)."""
    return TARGETS.get(kind, ABUSE_TARGET)


def abuse_summary(rows: list[dict]) -> list[dict]:
    """Per kind: the probe's p95 over its baseline windows and over its abuse windows
    (each the p95 of the windows' moves pooled), their ratio, each round's ratio, the
    most log lines an abuse window wrote, and whether the ratio is within the kind's
    target (`target_of`) and the lines within `LOG_LINES_TARGET` (rows as `run_abuse`
    gives them)."""
    out = []
    for kind in dict.fromkeys(r["for"] for r in rows):
        base = [r for r in rows if r["for"] == kind and r["kind"] == "baseline"]
        bad = [r for r in rows if r["for"] == kind and r["kind"] == kind]
        pooled = {name: sorted(x for r in rs for x in r["latencies_ms"])
                  for name, rs in (("baseline", base), ("abuse", bad))}
        p95 = {name: pct(lat, 95) for name, lat in pooled.items()}
        ratio = (p95["abuse"] / p95["baseline"] if pooled["baseline"] and pooled["abuse"]
                 else float("inf"))
        per_round = [a["p95_ms"] / b["p95_ms"] if b["p95_ms"] > 0 and a["answered"]
                     else float("inf")
                     for b, a in zip(sorted(base, key=lambda r: r["round"]),
                                     sorted(bad, key=lambda r: r["round"]), strict=True)]
        lines = max(r["log_lines"] for r in bad)
        out.append({"kind": kind, "baseline": base, "abuse": bad, "p95_ms": p95,
                    "p50_ms": {name: pct(lat, 50) for name, lat in pooled.items()},
                    "ratio": ratio, "round_ratios": per_round, "log_lines": lines,
                    "target": target_of(kind),
                    "met": ratio <= target_of(kind) and lines <= LOG_LINES_TARGET})
    return out


def abuse_table(rows: list[dict]) -> str:
    """The Markdown table of `--abuse` (per kind: its baseline windows, then its abuse
    windows, pooled; each round's ratio; what the abuser did, summed over its windows)."""
    head = ("| abusive client | probe p50 ms (alone / beside) | probe p95 ms (alone / beside) "
            "| p95 ratio | target | each round's ratio | met | moves answered (alone / beside) "
            "| server CPU % (alone / beside) | server log lines per window (alone / beside, "
            f"most; target <= {LOG_LINES_TARGET}) | tracebacks beside | load average "
            "| what the abuser did |")
    lines = [head, "|" + " --- |" * 13]

    def total(rs: list[dict], key: str) -> int:
        return sum(r[key] for r in rs)

    for s in abuse_summary(rows):
        b, a = s["baseline"], s["abuse"]
        did: dict = {}
        for r in a:
            for k, v in r["abuser"].items():
                did[k] = did.get(k, 0) + v if isinstance(v, int) else v
        cpu = [round(sum(r["server_cpu_pct"] or 0 for r in rs) / len(rs)) for rs in (b, a)]
        load = [r["load_average"] for r in b + a]
        lines.append(
            f"| {s['kind']} | {s['p50_ms']['baseline']:.0f} / {s['p50_ms']['abuse']:.0f} "
            f"| {s['p95_ms']['baseline']:.0f} / {s['p95_ms']['abuse']:.0f} "
            f"| {s['ratio']:.2f} | {s['target']:g} "
            f"| {', '.join(f'{x:.2f}' for x in s['round_ratios'])} "
            f"| {'yes' if s['met'] else '**no**'} "
            f"| {total(b, 'answered')}/{total(b, 'moves_sent')} "
            f"/ {total(a, 'answered')}/{total(a, 'moves_sent')} "
            f"| {cpu[0]} / {cpu[1]} "
            f"| {max(r['log_lines'] for r in b)} / {s['log_lines']} "
            f"| {total(a, 'tracebacks')} | {min(load):.1f}-{max(load):.1f} "
            f"| {', '.join(f'{k} {v}' for k, v in did.items()) or '-'} |")
    return "\n".join(lines)
