"""Speed-accuracy benchmark of the numerical methods against the closed form (issue 4).

Runs every method of ``core.numerics.METHODS`` over a ladder of resolutions on
psi in {0.4, 1, 2.414, 28.35, 1000} x tau0 in {pi/6, 1.5, -0.9} and records, per
method, resolution and case: wall time, max |T - T_closed| / T0, impulse-ratio error,
stick-radius error. The closed form itself is timed (Contact, T and b on a 200-point
grid, impulse ratio) and checked against 50-digit mpmath evaluations of eqs 39 and 41.

Outputs (benchmarks/results/, or results/quick/ with --quick):
  speed_accuracy.csv    one row per run
  speed_accuracy.html   Bokeh log-log chart: wall time vs error, one line per method
  methods_table.md      markdown table + speed ratios at errors 1e-2, 1e-4, 1e-6, 1e-9

Usage: .venv/bin/python benchmarks/methods.py [--quick]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import mpmath as mp  # noqa: E402
import numpy as np  # noqa: E402
from results_csv import read_csv, write_csv  # noqa: E402
from tqdm import tqdm  # noqa: E402

from core import Contact, impulse_ratio  # noqa: E402
from core.numerics import METHODS, solve  # noqa: E402
from core.numerics.metrics import closed_form_time, errors  # noqa: E402

PSIS = [0.4, 1.0, 2.414, 28.35, 1000.0]
TAU0S = [np.pi / 6, 1.5, -0.9]
LADDERS: dict[str, list[int]] = {
    "mdr": [12, 25, 50, 100, 200, 400, 800, 1600, 3200],
    "annulus": [4, 8, 16, 32, 64, 128],
    **{name: [30, 100, 300, 1000, 3000, 10000, 30000, 100000]
       for name in METHODS if name.startswith(("lammps", "liggghts", "direnzo"))},
    "quad": [2, 3, 4, 6, 8, 12, 16, 24, 32, 64],
    "gauss_legendre": [4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048],
}
QUICK_LADDERS = {k: v[: max(3, len(v) // 2)] for k, v in LADDERS.items()}
THRESHOLDS = [1e-2, 1e-4, 1e-6, 1e-9]
RETIME_BELOW = 2e-3  # seconds: runs this fast are timed in two windows (``retime_fast``)
INDEPENDENT = [m for m in METHODS if m not in ("quad", "gauss_legendre")]
RATIO_GROUPS: dict[str, list[str]] = {
    "converging solvers (MDR, annulus)": ["mdr", "annulus"],
    "independent methods (MDR, annulus, DEM; DEM is exact only for psi <= 1)": INDEPENDENT,
    "all methods (including quadrature of the closed-form T)": list(METHODS),
}
FIELDS = ["method", "resolution", "psi", "tau0", "wall_time", "err_T", "err_impulse",
          "err_b", "err", "err_rel"]


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


def closed_form_row(psi: float, tau0: float) -> dict:
    """Timing and error of the closed form itself (reference: mpmath)."""
    c = Contact(psi, tau0)
    tau = c.tau_grid(200)
    exact_T, exact_ratio = mp_reference(psi, tau0, tau)
    err_T = float(np.max(np.abs(c.tangential_force(tau) - exact_T)))
    err_i = abs(c.impulse_ratio - exact_ratio)
    err_rel = max(err_T / np.max(np.abs(exact_T)), err_i / exact_ratio)
    return dict(method="closed_form", resolution=200, psi=psi, tau0=tau0,
                wall_time=closed_form_time(Contact, psi, tau0), err_T=err_T,
                err_impulse=err_i, err_b=float("nan"), err=max(err_T, err_i),
                err_rel=float(err_rel))


def amortised_impulse_time(tau0: float, n: int = 1000, repeat: int = 50) -> float:
    """Seconds per case of core.impulse_ratio vectorised over n values of psi (Fig. 8)."""
    psis = np.logspace(-1, 3, n)
    best = np.inf
    for _ in range(repeat):
        start = time.perf_counter()
        impulse_ratio(psis, tau0)
        best = min(best, time.perf_counter() - start)
    return float(best / n)


def impulse_speed_ratios(rows: list[dict], methods: list[str]) -> dict[float, dict]:
    """Per threshold: fastest run of ``methods`` with impulse-ratio error <= threshold,
    divided by the amortised vectorised closed-form impulse time (same tau0)."""
    amortised = {t: amortised_impulse_time(t) for t in sorted({r["tau0"] for r in rows})}
    out = {}
    cases = sorted({(r["psi"], r["tau0"]) for r in rows})
    for thr in THRESHOLDS:
        ratios, winners = [], []
        for case in cases:
            ok = [r for r in rows if r["method"] in methods
                  and (r["psi"], r["tau0"]) == case and r["err_impulse"] <= thr]
            if ok:
                best = min(ok, key=lambda r: r["wall_time"])
                ratios.append(best["wall_time"] / amortised[case[1]])
                winners.append(best["method"])
        out[thr] = dict(median=float(np.median(ratios)) if ratios else float("nan"),
                        min=float(np.min(ratios)) if ratios else float("nan"),
                        reached=len(ratios), missing=len(cases) - len(ratios),
                        winners=sorted(set(winners)))
    return out, amortised


def timed_run(name: str, c: Contact, resolution: int):
    """Run once; repeat fast runs (< 20 ms) and keep the best wall time."""
    res = solve(name, c, resolution)
    best = res.wall_time
    if best < 0.02:
        for _ in range(4):
            best = min(best, solve(name, c, resolution).wall_time)
    return res, best


def run_all(psis, tau0s, ladders) -> list[dict]:
    rows: list[dict] = []
    tasks = [(p, t, m, r) for p in psis for t in tau0s for m, rs in ladders.items()
             for r in rs]
    for psi in psis:
        for tau0 in tau0s:
            rows.append(closed_form_row(psi, tau0))
    for psi, tau0, name, resolution in tqdm(tasks, desc="methods x resolutions x cases",
                                            unit="run"):
        c = Contact(psi, tau0)
        res, wall = timed_run(name, c, resolution)
        e = errors(res, c)
        rows.append(dict(method=name, resolution=resolution, psi=psi, tau0=tau0,
                         wall_time=wall, err_T=e.T, err_impulse=e.impulse, err_b=e.b,
                         err=e.combined, err_rel=e.combined_rel))
    retime_fast(rows)
    return rows


def retime_fast(rows: list[dict], limit: float = RETIME_BELOW) -> None:
    """Time every run faster than ``limit`` (the closed form among them) a second time,
    minutes after the first, and keep the better of the two windows.

    On a shared 2-core VM one window of a few milliseconds can land in a stall and
    double a sub-millisecond time; the smallest speed ratios (closed form against a
    30-step DEM run) are made of exactly such times. Every fast row gets the same
    second chance, so the correction favours no method."""
    fast = [r for r in rows if r["wall_time"] < limit]
    for r in tqdm(fast, desc="second timing of the fast runs", unit="run"):
        if r["method"] == "closed_form":
            again = closed_form_time(Contact, r["psi"], r["tau0"])
        else:
            again = timed_run(r["method"], Contact(r["psi"], r["tau0"]), r["resolution"])[1]
        r["wall_time"] = min(r["wall_time"], again)


def summary(rows: list[dict]) -> dict[tuple[str, int], dict]:
    """Per method and resolution: median wall time, worst errors over the cases."""
    groups: dict[tuple[str, int], list[dict]] = {}
    for row in rows:
        groups.setdefault((row["method"], row["resolution"]), []).append(row)
    out = {}
    for key, rs in groups.items():
        out[key] = dict(
            wall_time=float(np.median([r["wall_time"] for r in rs])),
            err_T=float(np.max([r["err_T"] for r in rs])),
            err_impulse=float(np.max([r["err_impulse"] for r in rs])),
            err_b=float(np.nanmax([r["err_b"] for r in rs]))
            if any(np.isfinite(r["err_b"]) for r in rs) else float("nan"),
            err=float(np.max([r["err"] for r in rs])),
            err_rel=float(np.max([r["err_rel"] for r in rs])),
        )
    return out


def speed_ratios(rows: list[dict], methods: list[str], key: str = "err"
                 ) -> dict[float, dict]:
    """Per threshold: over the cases, wall time of the fastest run of ``methods`` with
    row[key] <= threshold divided by the closed-form time on the same case (median, min)."""
    out = {}
    cases = sorted({(r["psi"], r["tau0"]) for r in rows})
    for thr in THRESHOLDS:
        ratios, winners, missing = [], [], 0
        for case in cases:
            cf = next(r for r in rows if r["method"] == "closed_form"
                      and (r["psi"], r["tau0"]) == case)
            ok = [r for r in rows if r["method"] in methods
                  and (r["psi"], r["tau0"]) == case and r[key] <= thr]
            if not ok:
                missing += 1
                continue
            best = min(ok, key=lambda r: r["wall_time"])
            ratios.append(best["wall_time"] / cf["wall_time"])
            winners.append(best["method"])
        out[thr] = dict(
            median=float(np.median(ratios)) if ratios else float("nan"),
            min=float(np.min(ratios)) if ratios else float("nan"),
            reached=len(ratios), missing=missing,
            winners=sorted(set(winners)),
        )
    return out


def markdown(rows: list[dict], summ: dict, ratio_groups: dict[str, dict]) -> str:
    cf = [r for r in rows if r["method"] == "closed_form"]
    lines = [
        "# Speed and accuracy of the numerical methods against the closed form",
        "",
        f"Cases: psi in {PSIS} x tau0 in {{pi/6, 1.5, -0.9}} "
        f"({len({(r['psi'], r['tau0']) for r in rows})} cases). "
        "Wall time: median over the cases; errors: worst case. err = max(err_T, "
        "err_impulse); err_T = max |T - T_closed| / T0 on the method's own times; "
        "err_b = max |b - b_closed| / a*; err_rel = max(err_T / max|T_closed|, "
        "err_impulse / impulse ratio). Runs under "
        f"{RETIME_BELOW * 1e3:g} ms keep the better of two timing windows (start and end "
        "of the run).",
        "",
        f"Closed form (T and b on 200 points and the impulse ratio, from a given Contact, "
        "as the methods are timed): median "
        f"{np.median([r['wall_time'] for r in cf]) * 1e6:.0f} us, worst error against "
        f"50-digit mpmath {max(r['err'] for r in cf):.1e}.",
        "",
        "| method | resolution | wall time (ms) | err_T | err_impulse | err_b | err "
        "| err_rel |",
        "|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for (name, res), s in sorted(summ.items(), key=lambda kv: (kv[0][0] != "closed_form",
                                                                kv[0][0], kv[0][1])):
        lines.append(f"| {name} | {res} | {s['wall_time'] * 1e3:.3f} | {s['err_T']:.1e} | "
                     f"{s['err_impulse']:.1e} | {s['err_b']:.1e} | {s['err']:.1e} | "
                     f"{s['err_rel']:.1e} |")
    for title, ratios in ratio_groups.items():
        lines += ["", f"## Speed ratio: fastest of {title} reaching the threshold, "
                  "divided by the closed-form time (same case, same run)", "",
                  "| threshold | median ratio | smallest ratio | cases reached | winners |",
                  "|---:|---:|---:|---:|---|"]
        for thr, r in ratios.items():
            lines.append(f"| {thr:.0e} | {r['median']:.3g} | {r['min']:.3g} | "
                         f"{r['reached']}/{r['reached'] + r['missing']} | "
                         f"{', '.join(r['winners']) or '-'} |")
    return "\n".join(lines) + "\n"


def chart(rows: list[dict], summ: dict, path: Path) -> None:
    from bokeh.io import save
    from bokeh.models import ColumnDataSource, HoverTool, TabPanel, Tabs
    from bokeh.palettes import Category20
    from bokeh.plotting import figure
    from bokeh.resources import INLINE

    names = ["closed_form", *METHODS]
    colours = dict(zip(names, Category20[20], strict=False))

    def panel(title: str, data: dict[str, tuple[list, list, list]]):
        fig = figure(title=title, x_axis_type="log", y_axis_type="log", width=1100,
                     height=560, x_axis_label="wall time (s)",
                     y_axis_label="error: max(|T - T_closed| / T0, |impulse ratio error|)")
        for name in names:
            if name not in data:
                continue
            x, y, res = data[name]
            y = [max(v, 1e-17) for v in y]
            src = ColumnDataSource(dict(x=x, y=y, res=res, method=[name] * len(x)))
            if name == "closed_form":
                fig.scatter("x", "y", source=src, size=22, marker="star",
                            color="black", line_color="white", legend_label="closed form")
            else:
                fig.line("x", "y", source=src, color=colours[name], legend_label=name,
                         line_width=2)
                fig.scatter("x", "y", source=src, color=colours[name], size=6,
                            legend_label=name)
        fig.add_tools(HoverTool(tooltips=[("method", "@method"), ("resolution", "@res"),
                                          ("time", "@x{0.000e}"), ("error", "@y{0.0e}")]))
        fig.legend.click_policy = "hide"
        fig.legend.label_text_font_size = "8pt"
        fig.add_layout(fig.legend[0], "right")
        return TabPanel(child=fig, title=title)

    def collect(selected: list[dict]) -> dict:
        data: dict[str, tuple[list, list, list]] = {}
        for r in sorted(selected, key=lambda r: (r["method"], r["resolution"])):
            x, y, res = data.setdefault(r["method"], ([], [], []))
            x.append(r["wall_time"])
            y.append(r["err"])
            res.append(r["resolution"])
        return data

    agg = [dict(method=m, resolution=res, wall_time=s["wall_time"], err=s["err"])
           for (m, res), s in summ.items()]
    panels = [panel("all cases (median time, worst error)", collect(agg))]
    for psi in PSIS:
        for tau0 in TAU0S:
            sel = [r for r in rows if r["psi"] == psi and r["tau0"] == tau0]
            if sel:
                panels.append(panel(f"psi={psi:g}, tau0={tau0:.3g}", collect(sel)))
    save(Tabs(tabs=panels), filename=str(path), resources=INLINE,
         title="Speed vs accuracy of the numerical methods")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="2 x 2 cases, half ladders, output in results/quick/")
    parser.add_argument("--replot", action="store_true",
                        help="rebuild the chart and table from the existing CSV")
    args = parser.parse_args(argv)
    out = ROOT / "benchmarks" / "results"
    psis, tau0s, ladders = PSIS, TAU0S, LADDERS
    if args.quick:
        out = out / "quick"
        psis, tau0s, ladders = [1.0, 28.35], [np.pi / 6, -0.9], QUICK_LADDERS
    out.mkdir(parents=True, exist_ok=True)
    if args.replot:
        rows = read_csv(out / "speed_accuracy.csv")
    else:
        rows = run_all(psis, tau0s, ladders)
    summ = summary(rows)
    groups = {title: speed_ratios(rows, ms) for title, ms in RATIO_GROUPS.items()}
    groups |= {f"{title}, relative error (err_rel)": speed_ratios(rows, ms, "err_rel")
               for title, ms in RATIO_GROUPS.items()}
    amortised_ratios, amortised = impulse_speed_ratios(rows, RATIO_GROUPS[
        "converging solvers (MDR, annulus)"])
    groups["converging solvers (MDR, annulus), impulse ratio only, against the closed-form "
           f"impulse vectorised over 1000 psi ({np.median(list(amortised.values())) * 1e9:.0f}"
           " ns per case)"] = amortised_ratios
    if not args.replot:
        write_csv(rows, out / "speed_accuracy.csv", FIELDS)
    (out / "methods_table.md").write_text(markdown(rows, summ, groups))
    chart(rows, summ, out / "speed_accuracy.html")
    for title, ratios in groups.items():
        print(title)
        for thr, r in ratios.items():
            print(f"  err<={thr:.0e}: median ratio {r['median']:.3g}, "
                  f"min {r['min']:.3g}, reached {r['reached']}, winners {r['winners']}")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
