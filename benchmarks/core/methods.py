"""Speed against accuracy, like for like: the closed form of ``core`` against compiled peers.

Every method computes one contact from its two parameters (psi, tau0): T / T0 on its
own times and the impulse ratio T_imp / (mu P_imp) (eq 41). Peers: the time-stepping
methods of ``core.numerics`` (MDR, annulus, the DEM rules), each a numba kernel called
once per contact from Python with scalar arguments. The closed form: ``core.curve``
(what users call for one contact: one compiled call from (psi, tau0)), T and b on
``Contact.tau_grid(200)`` and the impulse ratio.
Quadrature of the closed-form T (``quad``, ``gauss_legendre``) is a check of eq 41, not a
peer: it needs the closed form to run, and is reported apart.

Timing (``per_call``): every method, the closed form included, is timed the same way:
calls in a loop until a window lasts at least WINDOW seconds, REPEATS such windows, the
best window's time per call. Each kernel is called once before (compilation or loading
from numba's disk cache is excluded); that first call is reported apart, and the cold
compile time of every kernel is measured in a subprocess with an empty numba cache.
The sweep times every rung of every ladder; the ratios of the tables come from a second
timing (``head_to_head``): per case, the fastest peer at each target, the closed form on
200 points and the closed form on as many points as that peer returns, their windows
interleaved so that a burst of load on the shared machine hits all of them alike.
``call_floors`` times numba functions that only return new arrays of each method's
size: the cost of the call itself, under any method with that interface. That cost
(0.6-1.0 us) is the interpreter's, not the method's, and at 1e-2 it is most of every
method's time; so the head-to-head runs are timed once more many contacts a call
(``batched``: the kernel looped in compiled code, as a DEM code or a sweep over a rod
runs it, the same count rule for every method) and reported per contact as well.

Cases: psi in {0.4, 1, 2.414, 28.35, 1000} x tau0 in {pi/6, 1.5, -0.9}, in four regimes:
"psi <= 1" and "psi > 1" (tau0 = pi/6), "grazing" (tau0 = 1.5), "preload" (tau0 = -0.9).

Outputs (benchmarks/results/, or results/quick/ with --quick), data only:
  speed_accuracy.csv    one row per run (method, resolution, steps, case, time, errors);
                        its chart (speed_accuracy.html, per regime or case, time against
                        error, Pareto fronts) is the app's: ``make bench-charts``
  head_to_head.csv      per case, error kind and target: the fastest peer, the closed form
                        on 200 points and on as many points as the peer, timed interleaved,
                        one contact a call and (*_batch, per contact) many a call
  call_floors.json      the cost of a numba call returning new arrays of each method's size
  methods_table.md      per case and per regime: fastest peer reaching each error target
  compile_times.json    cold compile and cached first-call time of each kernel

Usage: .venv/bin/python -m benchmarks.core.methods [--quick] [--replot]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path

import mpmath as mp
import numpy as np
from numba import njit
from tqdm import tqdm

from benchmarks.core.results_csv import read_csv, write_csv
from core import Contact, curve, kernels
from core.numerics import (
    METHODS,
    MethodResult,
    Params,
    annulus,
    dem,
    mdr,
    quadrature,
)
from core.numerics.metrics import errors

ROOT = Path(__file__).resolve().parents[2]

#: Quadrature of core's T: a check of eq 41 (it needs the closed form), not a peer.
CHECKS = ("quad", "gauss_legendre")
PEERS = tuple(m for m in METHODS if m not in CHECKS)
REGIMES = ("psi <= 1", "psi > 1", "grazing", "preload")
PSIS = [0.4, 1.0, 2.414, 28.35, 1000.0]
TAU0S = [np.pi / 6, 1.5, -0.9]
THRESHOLDS = [1e-2, 1e-4, 1e-6, 1e-9]
WINDOW = 2e-3
REPEATS = 5
BATCH_SECONDS = 1e-3
CLOSED_FORM_POINTS = 200
DEM = list(dem.MODELS)
MDR_SPRINGS = [4, 6, 8, 12, 16, 24, 32, 48, 64, 100, 140, 200, 280, 400, 560, 800, 1600,
               3200]
MDR_STEP_FACTORS = [0.25, 0.5, 1.0, 2.0, 4.0]
LADDERS: dict[str, list[tuple[int, int | None]]] = {
    "mdr": [(n, max(8, int(f * n))) for n in MDR_SPRINGS for f in MDR_STEP_FACTORS],
    "annulus": [(n, None) for n in (4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128)],
    **{name: [(s, None) for s in (10, 20, 30, 50, 100, 200, 300, 1000, 3000, 10000, 30000,
                                  100000)] for name in DEM},
    "quad": [(n, None) for n in (2, 3, 4, 6, 8, 12, 16, 24, 32, 64)],
    "gauss_legendre": [(n, None) for n in (4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048)],
}
QUICK_LADDERS = {k: v[::3] for k, v in LADDERS.items()}
FIELDS = ["method", "resolution", "steps", "psi", "tau0", "regime", "points", "wall_time",
          "err_T", "err_impulse", "err_b", "err", "err_rel"]
HEAD_FIELDS = ["psi", "tau0", "regime", "kind", "threshold", "peer", "peer_points",
               "peer_time", "cf_time", "cf_n", "cf_points", "cf_n_time", "peer_batch",
               "cf_batch", "cf_n_batch"]


def label(r: dict) -> str:
    """A run's name: method and resolution (and MDR's time steps)."""
    if r["method"] == "mdr":
        return f"mdr N={r['resolution']} M={r['steps']}"
    return f"{r['method']} {r['resolution']}"


def regime(psi: float, tau0: float) -> str:
    """The regime of a benchmark case (see the module docstring)."""
    if tau0 >= 1.4:
        return "grazing"
    if tau0 < 0:
        return "preload"
    return "psi <= 1" if psi <= 1 else "psi > 1"


# ------------------------------------------------------------------ the work per contact


def closed_form(psi: float, tau0: float):
    """One contact by core's closed form, from (psi, tau0): T, b on 200 points, impulse."""
    (tau, T, b), ratio = curve(psi, tau0, CLOSED_FORM_POINTS)
    return tau, T, b, ratio


def job(name: str, psi: float, tau0: float, resolution: int, steps: int | None
        ) -> Callable[[], tuple]:
    """The call that computes one contact with ``name``, and nothing else: the function
    users call (``core.curve``) or the method's kernel, with its arguments bound (a
    ``functools.partial`` for every method alike). What it returns differs per method;
    ``as_result`` turns it into (tau, T, b, ratio)."""
    if name == "closed_form":
        return partial(curve, psi, tau0, CLOSED_FORM_POINTS)
    if name == "quad":
        return partial(quadrature.solve_quad, Params(psi, tau0), resolution)
    if name == "gauss_legendre":
        return partial(quadrature.solve_gauss_legendre, Params(psi, tau0), resolution)
    kernel, args, _ = compiled(name, psi, tau0, resolution, steps)
    return partial(kernel, *args)


# ------------------------------------------------------------------ many contacts a call


@njit
def repeat(kernel, args, check, count):
    """``kernel(*args)`` ``count`` times in one compiled loop, no Python between two
    contacts; returns the sum of ``check(result)``, which reads every call's T and impulse
    ratio, so that no call's work can be left out."""
    acc = 0.0
    for _ in range(count):
        acc += check(kernel(*args))
    return acc


@njit
def _check_rows(out):
    """The closed form's (rows, ratio): last T and the ratio."""
    return out[0][1, -1] + out[1]


@njit
def _check_numerics(out):
    """MDR's and the annulus's (tau, T, b, ratio, ...): last T and the ratio."""
    return out[1][-1] + out[3]


@njit
def _check_dem(out):
    """A DEM rule's (tau, T, ratio): last T and the ratio."""
    return out[1][-1] + out[2]


def compiled(name: str, psi: float, tau0: float, resolution: int, steps: int | None
             ) -> tuple[Callable, tuple, Callable]:
    """(kernel, args, check) of one contact by ``name``: the compiled kernel alone (the
    closed form's is ``core.kernels.curve`` on about ``resolution`` points: arguments are
    checked once per batch, as ``core.batch`` does), for ``repeat``."""
    if name == "closed_form":
        return kernels.curve, (psi, tau0, resolution), _check_rows
    if name == "mdr":
        return mdr.contact, (psi, tau0, resolution, steps), _check_numerics
    if name == "annulus":
        m = annulus.default_steps(resolution) if steps is None else steps
        return (annulus.contact, (psi, tau0, annulus.compliance(resolution), m),
                _check_numerics)
    if name in dem.MODELS:
        return dem.contact, (dem.MODELS[name], psi, tau0, resolution), _check_dem
    raise KeyError(name)


def batched(name: str, psi: float, tau0: float, resolution: int, steps: int | None,
            seconds_each: float) -> tuple[int, Callable[[], float]]:
    """(count, call): ``count`` contacts by ``name`` in one compiled call, count chosen
    by one rule for every method (a call of about BATCH_SECONDS, given one contact's
    time ``seconds_each``), so that the call from Python, 0.6-1.0 us whatever the method
    (``call_floors``), is shared by the contacts: per-contact time = call time / count."""
    kernel, args, check = compiled(name, psi, tau0, resolution, steps)
    count = max(1, round(BATCH_SECONDS / seconds_each))
    return count, partial(repeat, kernel, args, check, count)


def as_result(name: str, out: tuple) -> tuple:
    """The output of ``job(name, ...)()`` as (tau, T, b or None, impulse ratio)."""
    if name == "closed_form":
        (tau, T, b), ratio = out
        return tau, T, b, ratio
    if name in dem.MODELS:
        tau, T, ratio = out
        return tau, T, None, ratio
    return out[:4]


def calls_per_window(fn: Callable[[], object], window: float = WINDOW) -> int:
    """The number k of calls of ``fn`` that lasts at least ``window`` seconds, the larger
    of two calibrations (a burst of load during one would make k too small)."""
    return max(_calibrate(fn, window), _calibrate(fn, window))


def _calibrate(fn: Callable[[], object], window: float) -> int:
    k = 1
    while True:
        start = time.perf_counter()
        for _ in range(k):
            fn()
        elapsed = time.perf_counter() - start
        if elapsed >= window:
            return k
        k = max(2 * k, int(k * 1.2 * window / max(elapsed, 1e-9)))


def one_window(fn: Callable[[], object], k: int) -> float:
    """Seconds per call over one loop of k calls."""
    start = time.perf_counter()
    for _ in range(k):
        fn()
    return (time.perf_counter() - start) / k


def per_call(fn: Callable[[], object], window: float = WINDOW, repeats: int = REPEATS
             ) -> float:
    """Seconds per call: loops of k calls lasting >= ``window``, best of ``repeats``."""
    return head_to_head([fn], window, repeats)[0]


def head_to_head(fns: list[Callable[[], object]], window: float = WINDOW,
                 repeats: int = REPEATS) -> list[float]:
    """``per_call`` of each of ``fns``, their windows interleaved (f1, f2, ..., f1, f2,
    ...) so that a burst of load on the shared machine hits all of them alike."""
    ks = [calls_per_window(fn, window) for fn in fns]
    best = [np.inf] * len(fns)
    for _ in range(repeats):
        for i, (fn, k) in enumerate(zip(fns, ks, strict=True)):
            best[i] = min(best[i], one_window(fn, k))
    return best


def closed_form_points(psi: float, tau0: float, n: int) -> int:
    """The number of times of ``core.curve(psi, tau0, n)``."""
    return int(Contact(psi, tau0).tau_grid(n).size)


def closed_form_n_for(psi: float, tau0: float, points: int) -> int:
    """The least n (>= 2) for which ``core.curve(psi, tau0, n)`` returns at least
    ``points`` times: the closed form with as many output points as a peer."""
    lo, hi = 2, max(2, points)
    while lo < hi:  # the grid size is non-decreasing in n
        mid = (lo + hi) // 2
        if closed_form_points(psi, tau0, mid) >= points:
            hi = mid
        else:
            lo = mid + 1
    return lo


# ------------------------------------------------------------------ errors


def mp_reference(psi: float, tau0: float, tau: np.ndarray) -> tuple[np.ndarray, float]:
    """T / T0 (eqs 38-39) at ``tau`` and the impulse ratio (eq 41), with 50 digits."""
    mp.mp.dps = 50
    s0 = mp.sin(mp.mpf(tau0))

    def elliptic_f(s):
        m = (1 - s) / 2
        return (1 + s) * (1 + 3 * s) * mp.ellipk(m) - 8 * s * mp.ellipe(m)

    out = np.empty(tau.size)
    if psi <= 1:
        s1 = t1 = None
        ratio = mp.mpf(psi)
    else:
        s1 = 1 - 2 * (1 - s0) / (mp.mpf(psi) + 1)
        t1 = mp.pi - mp.asin(s1)
        ratio = ((mp.mpf(psi) + 1) / 2) ** 1.5 * elliptic_f(s1) / elliptic_f(s0)
    for i, t in enumerate(tau):
        tm = mp.mpf(float(t))
        load = max(mp.sin(tm) - s0, 0) ** 1.5
        if psi <= 1:
            val = psi * load
        elif tm <= mp.pi / 2:
            val = load
        elif tm < t1:
            val = -load + 2 * ((mp.mpf(psi) + 1) / 2) ** 1.5 * max(mp.sin(tm) - s1, 0) ** 1.5
        else:
            val = -load
        out[i] = float(val)
    return out, float(ratio)


def closed_form_errors(psi: float, tau0: float) -> dict:
    tau, T, _, ratio = closed_form(psi, tau0)
    exact_T, exact_ratio = mp_reference(psi, tau0, tau)
    err_T = float(np.max(np.abs(T - exact_T)))
    err_i = abs(ratio - exact_ratio)
    return dict(err_T=err_T, err_impulse=err_i, err_b=float("nan"), err=max(err_T, err_i),
                err_rel=max(err_T / np.max(np.abs(exact_T)), err_i / exact_ratio))


def run_errors(name: str, resolution: int, out: tuple, contact: Contact) -> dict:
    tau, T, b, ratio = out
    res = MethodResult(name, resolution, np.asarray(tau), np.asarray(T),
                       None if b is None else np.asarray(b), float(ratio), 0.0)
    e = errors(res, contact)
    return dict(err_T=e.T, err_impulse=e.impulse, err_b=e.b, err=e.combined,
                err_rel=e.combined_rel)


# ------------------------------------------------------------------ compile times

_COLD = """
import json, time, math
t0 = time.perf_counter()
from core.numerics import annulus, dem, mdr
out = {"import core.numerics": time.perf_counter() - t0}
from numba import njit
t0 = time.perf_counter()
njit(lambda x: x + 1.0)(1.0)
out["numba start-up (a trivial function)"] = time.perf_counter() - t0
from core import batch, curve, impulse_ratio
calls = {
    "closed form (core.curve, core.batch, core.impulse_ratio)": lambda: (
        curve(2.0, 0.3, 8), batch.tangential_force(2.0, 0.3, [1.0]),
        impulse_ratio([2.0], 0.3)),
    "mdr": lambda: mdr.contact(2.0, 0.3, 8, 8),
    "annulus": lambda: annulus.contact(2.0, 0.3, annulus.compliance(4), 16),
    "dem (all seven rules)": lambda: dem.contact(0, 2.0, 0.3, 10),
}
for name, call in calls.items():
    t0 = time.perf_counter()
    call()
    out[name] = time.perf_counter() - t0
print(json.dumps(out))
"""


def compile_times() -> dict[str, dict[str, float]]:
    """Cold compile (empty numba cache, fresh process) and cached first call (fresh
    process, the repository's cache) of each kernel family, in seconds."""
    result: dict[str, dict[str, float]] = {}
    for kind, cache in (("cold compile", tempfile.mkdtemp()), ("cached first call", None)):
        env = dict(os.environ)
        if cache:
            env["NUMBA_CACHE_DIR"] = cache
        text = subprocess.run([sys.executable, "-c", _COLD], cwd=ROOT, env=env, check=True,
                              capture_output=True, text=True).stdout
        result[kind] = json.loads(text.strip().splitlines()[-1])
    return result


# ------------------------------------------------------------------ the run


def run_all(ladders: dict[str, list[tuple[int, int | None]]]) -> list[dict]:
    rows: list[dict] = []
    cases = [(p, t) for t in TAU0S for p in PSIS]
    for name in PEERS:  # compile or load every kernel before any timing
        job(name, 2.0, 0.3, 8, 8)()
    for psi, tau0 in tqdm(cases, desc="cases", unit="case"):
        c = Contact(psi, tau0)
        fn = job("closed_form", psi, tau0, CLOSED_FORM_POINTS, None)
        fn()
        rows.append(dict(method="closed_form", resolution=CLOSED_FORM_POINTS, steps=0,
                         psi=psi, tau0=tau0, regime=regime(psi, tau0),
                         points=closed_form_points(psi, tau0, CLOSED_FORM_POINTS),
                         wall_time=per_call(fn), **closed_form_errors(psi, tau0)))
        for name, ladder in ladders.items():
            for resolution, steps in ladder:
                fn = job(name, psi, tau0, resolution, steps)
                out = as_result(name, fn())  # warm-up (and the result measured)
                wall = per_call(fn)
                rows.append(dict(method=name, resolution=resolution, steps=steps or 0,
                                 psi=psi, tau0=tau0, regime=regime(psi, tau0),
                                 points=len(out[0]), wall_time=wall,
                                 **run_errors(name, resolution, out, c)))
    return rows


def fastest(rows: list[dict], methods: list[str], case: tuple[float, float], key: str,
            thr: float) -> dict | None:
    ok = [r for r in rows if r["method"] in methods and (r["psi"], r["tau0"]) == case
          and r[key] <= thr]
    return min(ok, key=lambda r: r["wall_time"]) if ok else None


def per_case(rows: list[dict], key: str, methods: list[str]) -> list[dict]:
    """Per case and threshold: the fastest run of ``methods`` reaching it, and its time
    over the closed form's (same case, same run)."""
    out = []
    for cf in (r for r in rows if r["method"] == "closed_form"):
        case = (cf["psi"], cf["tau0"])
        entry = dict(psi=cf["psi"], tau0=cf["tau0"], regime=cf["regime"],
                     cf_time=cf["wall_time"], cf_err=cf[key], best={})
        for thr in THRESHOLDS:
            best = fastest(rows, methods, case, key, thr)
            entry["best"][thr] = None if best is None else dict(
                run=label(best), time=best["wall_time"],
                ratio=best["wall_time"] / cf["wall_time"])
        out.append(entry)
    return out


KINDS = (("err_rel", "relative"), ("err", "absolute"))
RATIOS = (
    ("ratio", f"one contact a call, against the closed form on {CLOSED_FORM_POINTS} points"),
    ("ratio_points", "one contact a call, against the closed form on as many points as "
                     "the peer"),
    ("ratio_batch", "many contacts a call, against the closed form on "
                    f"{CLOSED_FORM_POINTS} points"),
    ("ratio_points_batch", "many contacts a call, against the closed form on as many "
                           "points as the peer"),
)


def head_to_head_rows(rows: list[dict]) -> list[dict]:
    """The ratios of the tables: per case, error kind and threshold, the fastest peer of
    the sweep reaching it, timed again interleaved (``head_to_head``) with the closed
    form on 200 points and with the closed form on at least as many points as that
    peer returns (``core.curve(psi, tau0, n)``, n from ``closed_form_n_for``); then the
    same runs again, each as many contacts a call (``batched``), timed interleaved: the
    ``*_batch`` columns, seconds per contact."""
    out = []
    cases = [(r["psi"], r["tau0"]) for r in rows if r["method"] == "closed_form"]
    for psi, tau0 in tqdm(cases, desc="head to head", unit="case"):
        winners: dict[str, dict] = {}
        picks = {}
        for key, kind in KINDS:
            for thr in THRESHOLDS:
                best = fastest(rows, PEERS, (psi, tau0), key, thr)
                picks[kind, thr] = best
                if best is not None:
                    winners[label(best)] = best
        ns = sorted({closed_form_n_for(psi, tau0, w["points"]) for w in winners.values()})
        runs = [("closed_form", CLOSED_FORM_POINTS, None)]
        runs += [("closed_form", n, None) for n in ns]
        runs += [(w["method"], w["resolution"], w["steps"] or None) for w in winners.values()]
        fns = [job("closed_form", psi, tau0, 0, None)]
        fns += [partial(curve, psi, tau0, n) for n in ns]
        fns += [job(name, psi, tau0, res, steps) for name, res, steps in runs[1 + len(ns):]]
        for fn in fns:
            fn()
        times = head_to_head(fns)
        # the same contacts, many a call: counts from the times just measured
        batches = [batched(name, psi, tau0, res, steps, t)
                   for (name, res, steps), t in zip(runs, times, strict=True)]
        for _, fn in batches:
            fn()
        each = [t / count for (count, _), t in
                zip(batches, head_to_head([fn for _, fn in batches]), strict=True)]
        cf_time, cf_batch = times[0], each[0]
        cf_n = dict(zip(ns, zip(times[1:1 + len(ns)], each[1:1 + len(ns)],
                                strict=True), strict=True))
        peer = dict(zip(winners, zip(times[1 + len(ns):], each[1 + len(ns):], strict=True),
                        strict=True))
        for (kind, thr), best in picks.items():
            row = dict(psi=psi, tau0=tau0, regime=regime(psi, tau0), kind=kind,
                       threshold=thr, cf_time=cf_time, peer="", peer_points=0,
                       peer_time=float("nan"), cf_n=0, cf_points=0, cf_n_time=float("nan"),
                       peer_batch=float("nan"), cf_batch=cf_batch,
                       cf_n_batch=float("nan"))
            if best is not None:
                n = closed_form_n_for(psi, tau0, best["points"])
                row.update(peer=label(best), peer_points=best["points"],
                           peer_time=peer[label(best)][0], peer_batch=peer[label(best)][1],
                           cf_n=n, cf_points=closed_form_points(psi, tau0, n),
                           cf_n_time=cf_n[n][0], cf_n_batch=cf_n[n][1])
            out.append(row)
    return out


def cases_of(head: list[dict], kind: str) -> list[dict]:
    """Per case: the closed form's time and, per threshold, the peer reaching it with its
    time and the two ratios (peer time over the closed form's on 200 points, and over
    the closed form's on as many points as the peer), all from one interleaved timing."""
    out: dict[tuple[float, float], dict] = {}
    for r in head:
        if r["kind"] != kind:
            continue
        entry = out.setdefault((r["psi"], r["tau0"]), dict(
            psi=r["psi"], tau0=r["tau0"], regime=r["regime"], cf_time=r["cf_time"],
            best={}))
        entry["best"][r["threshold"]] = None if not r["peer"] else dict(
            run=r["peer"], points=int(r["peer_points"]), time=r["peer_time"],
            ratio=r["peer_time"] / r["cf_time"], cf_points=int(r["cf_points"]),
            cf_n_time=r["cf_n_time"], ratio_points=r["peer_time"] / r["cf_n_time"],
            batch=r["peer_batch"], ratio_batch=r["peer_batch"] / r["cf_batch"],
            ratio_points_batch=r["peer_batch"] / r["cf_n_batch"])
    return list(out.values())


def call_floors() -> dict[str, float]:
    """Seconds per call of numba functions that do nothing but return what a method
    returns (fresh arrays of its size), interleaved: the floor under any method that
    returns its results as new arrays from one Python call."""
    from numba import njit

    @njit
    def scalars(a, b, n):
        return a

    @njit
    def like_dem(a, b, n):
        return np.empty(n + 1), np.empty(n + 1), a

    @njit
    def like_curve(a, b, n):
        return np.empty((3, n)), a

    calls = {
        "a numba call with three scalar arguments, returning a float": (scalars, 10),
        "returning two new arrays of 11 floats and a float (a 10-step DEM rule)":
            (like_dem, 10),
        "returning a new 3 x 11 array and a float (the closed form on 11 points)":
            (like_curve, 11),
        "returning a new 3 x 226 array and a float (the closed form on 200 points)":
            (like_curve, 226),
    }
    fns = [partial(f, 0.5, 0.5, n) for f, n in calls.values()]
    psi, tau0 = 2.414, np.pi / 6
    calls["the closed form at psi = 2.414, tau0 = pi/6: core.curve(psi, tau0, 200)"] = None
    fns.append(partial(curve, psi, tau0, CLOSED_FORM_POINTS))
    calls["the same without the argument checks: core.kernels.curve(psi, tau0, 200)"] = None
    fns.append(partial(kernels.curve, psi, tau0, CLOSED_FORM_POINTS))
    for fn in fns:
        fn()
    return dict(zip(calls, head_to_head(fns), strict=True))


def per_regime(cases: list[dict], ratio: str = "ratio") -> dict[str, dict[float, dict]]:
    out: dict[str, dict[float, dict]] = {}
    for reg in [*REGIMES, "all"]:
        sel = [c for c in cases if reg in ("all", c["regime"])]
        out[reg] = {}
        for thr in THRESHOLDS:
            hits = [c["best"][thr] for c in sel if c["best"][thr] is not None]
            ratios = [h[ratio] for h in hits]
            out[reg][thr] = dict(
                median=float(np.median(ratios)) if ratios else float("nan"),
                min=float(np.min(ratios)) if ratios else float("nan"),
                max=float(np.max(ratios)) if ratios else float("nan"),
                reached=len(hits), cases=len(sel),
                winners=sorted({h["run"].split()[0] for h in hits}))
    return out


def fmt_time(t: float) -> str:
    return f"{t * 1e6:.3g} us" if t < 1e-3 else f"{t * 1e3:.3g} ms"


def markdown(rows: list[dict], head: list[dict], compile_info: dict | None,
             floors: dict | None) -> str:
    lines = ["# Speed against accuracy, like for like", "",
             "One contact from (psi, tau0): T on the method's own times and the impulse "
             "ratio. Peers: numba kernels (MDR, annulus, DEM rules) called from Python "
             "with scalar arguments, no argument checks; closed form: `core.curve` (one "
             "compiled call, its arguments checked: T and b on `tau_grid(n)`, impulse "
             "ratio). The sweep over every ladder finds, per case and target, the fastest "
             "peer reaching it; that peer and the closed form are then timed again "
             "interleaved, and the tables give those times. "
             f"Every time is the best of {REPEATS} windows of at least {WINDOW * 1e3:g} ms "
             "of repeated calls, after a warm-up call. ratio = peer time / closed-form "
             "time (> 1: the closed form is faster): **ratio** against `core.curve(psi, "
             f"tau0, {CLOSED_FORM_POINTS})`, **same points** against `core.curve(psi, "
             "tau0, n)` with the least n that returns at least as many times as the peer "
             "(pts). **Many a call**: the same runs, each as many contacts in one compiled "
             f"loop as last about {BATCH_SECONDS * 1e3:g} ms (the closed form's kernel "
             "`core.kernels.curve`, arguments checked once a batch), time per contact; "
             "the per-case cells give the peer's time per contact and both ratios.", ""]
    for key, kind in KINDS:
        cases = cases_of(head, kind)
        errs = {(r["psi"], r["tau0"]): r[key] for r in rows if r["method"] == "closed_form"}
        lines += [f"## Per case, {kind} error", "",
                  "| psi | tau0 | regime | closed form (200) | its error | "
                  + " | ".join(f"{t:.0e}: fastest peer (pts), time, ratio, same points; "
                               "many a call: time, ratio, same points"
                               for t in THRESHOLDS)
                  + " |", "|---:|---:|---|---:|---:|" + "---|" * len(THRESHOLDS)]
        for c in cases:
            cells = []
            for thr in THRESHOLDS:
                b = c["best"][thr]
                cells.append("not reached" if b is None else
                             f"{b['run']} ({b['points']}), {fmt_time(b['time'])}, "
                             f"**{b['ratio']:.3g}**, {b['ratio_points']:.3g}; "
                             f"{fmt_time(b['batch'])}, **{b['ratio_batch']:.3g}**, "
                             f"{b['ratio_points_batch']:.3g}")
            lines.append(f"| {c['psi']:g} | {c['tau0']:.4g} | {c['regime']} | "
                         f"{fmt_time(c['cf_time'])} | {errs[c['psi'], c['tau0']]:.1e} | "
                         + " | ".join(cells) + " |")
        for ratio, what in RATIOS:
            lines += ["", f"## Per regime, {kind} error, {what}: ratio over the cases "
                      "(median, smallest, largest)", "",
                      "| regime | " + " | ".join(f"{t:.0e}" for t in THRESHOLDS) + " |",
                      "|---|" + "---:|" * len(THRESHOLDS)]
            for reg, by_thr in per_regime(cases, ratio).items():
                cells = []
                for thr in THRESHOLDS:
                    r = by_thr[thr]
                    if not r["reached"]:
                        cells.append("not reached")
                        continue
                    cells.append(f"{r['median']:.3g} ({r['min']:.3g}-{r['max']:.3g})"
                                 + ("" if r["reached"] == r["cases"]
                                    else f", {r['reached']}/{r['cases']} cases")
                                 + f"; {', '.join(r['winners'])}")
                lines.append(f"| {reg} | " + " | ".join(cells) + " |")
        lines.append("")
    if floors:
        lines += ["## The cost of the call itself (numba functions that only return "
                  "new arrays, timed interleaved in the same run)", "",
                  "| call | time |", "|---|---:|"]
        lines += [f"| {k} | {fmt_time(v)} |" for k, v in floors.items()]
        lines.append("")
    checks = per_case(rows, "err_rel", CHECKS)
    lines += ["## Quadrature of core's T (check of eq 41, not a peer), relative error", "",
              "| psi | tau0 | " + " | ".join(f"{t:.0e}" for t in THRESHOLDS) + " |",
              "|---:|---:|" + "---|" * len(THRESHOLDS)]
    for c in checks:
        cells = ["not reached" if c["best"][t] is None else
                 f"{c['best'][t]['run']}, {fmt_time(c['best'][t]['time'])}"
                 for t in THRESHOLDS]
        lines.append(f"| {c['psi']:g} | {c['tau0']:.4g} | " + " | ".join(cells) + " |")
    if compile_info:
        lines += ["", "## Compilation (excluded from the times above)", "",
                  "| kernel | cold compile (empty cache) | first call, cached |",
                  "|---|---:|---:|"]
        cold, warm = compile_info["cold compile"], compile_info["cached first call"]
        for k in cold:
            lines.append(f"| {k} | {cold[k]:.2f} s | {warm[k] * 1e3:.1f} ms |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="every third rung of each ladder, output in results/quick/")
    parser.add_argument("--replot", action="store_true",
                        help="rebuild the tables from the existing CSV")
    parser.add_argument("--compile-times", action="store_true",
                        help="measure the compile times again, then replot")
    args = parser.parse_args(argv)
    out = ROOT / "benchmarks" / "results"
    ladders = QUICK_LADDERS if args.quick else LADDERS
    if args.quick:
        out = out / "quick"
    out.mkdir(parents=True, exist_ok=True)
    compile_info = floors = None
    if args.compile_times:
        (out / "compile_times.json").write_text(json.dumps(compile_times(), indent=1) + "\n")
        args.replot = True
    if args.replot:
        rows = read_csv(out / "speed_accuracy.csv")
        head = read_csv(out / "head_to_head.csv")
        if (out / "compile_times.json").exists():
            compile_info = json.loads((out / "compile_times.json").read_text())
        if (out / "call_floors.json").exists():
            floors = json.loads((out / "call_floors.json").read_text())
    else:
        compile_info = compile_times()
        (out / "compile_times.json").write_text(json.dumps(compile_info, indent=1) + "\n")
        rows = run_all(ladders)
        write_csv(rows, out / "speed_accuracy.csv", FIELDS)
        head = head_to_head_rows(rows)
        write_csv(head, out / "head_to_head.csv", HEAD_FIELDS)
        floors = call_floors()
        (out / "call_floors.json").write_text(json.dumps(floors, indent=1) + "\n")
    text = markdown(rows, head, compile_info, floors)
    (out / "methods_table.md").write_text(text)
    print(text)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
