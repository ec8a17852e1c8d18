"""The methods' benchmark charts as stand-alone HTML pages, and their publication.

`python -m app.methods.publish benchmarks/results --publish` (`make bench-charts`)
renders speed_accuracy.html and stability_map.html beside the benchmarks' CSV files
(every view in the page, the selectors run in the browser) and, with --publish, copies
the two CSV files into the app's package data (`app.methods.results.RESULTS`).
"""

from __future__ import annotations

import argparse
import shutil
from importlib import resources
from pathlib import Path

from bokeh.models import CustomJS, Div, Select
from bokeh.plotting import figure

from app.methods.results import RESULTS, read_rows
from app.methods.speed_chart import EMPTY, speed_accuracy_chart, speed_accuracy_data
from app.methods.stability_chart import (
    STABILITY_FIELDS,
    STABILITY_NOTE,
    colour_bar,
    error_mapper,
    stability_data,
    stability_figure,
)


def speed_accuracy_page(rows: list[dict], path: Path) -> None:
    """The speed chart as a stand-alone page: every view in the page, its selector run
    in the browser."""
    from bokeh.io import save
    from bokeh.layouts import column
    from bokeh.resources import INLINE

    data = speed_accuracy_data(rows)
    shown = speed_accuracy_chart(data, width=1100)
    select = Select(title="View (time: median over the cases shown; error: worst)",
                    value=data.keys[0], options=data.keys, width=700)
    select.js_on_change("value", CustomJS(
        args=dict(views=data.views, stars=data.closed_form, star=shown.closed_form,
                  sources={k: list(v) for k, v in shown.sources.items()},
                  empty=EMPTY),
        code="""
const v = views[this.value];
for (const [name, [every, front]] of Object.entries(sources)) {
  every.data = v[name] ? v[name].all : empty;
  front.data = v[name] ? v[name].front : empty;
}
star.data = stars[this.value];
"""))
    intro = Div(width=1100, text=(
        "<p>One contact from (psi, tau0): T on the method's own times and the impulse ratio. "
        "Peers are numba kernels called from Python (compile time excluded); the closed "
        "form is <code>core.curve</code> (one compiled call: T and b on 200 points, impulse "
        "ratio). Same timing for all: the best of several windows of a few ms each "
        "(<code>benchmarks/core/methods.py</code>). "
        "Lines: each method's Pareto front (no faster run of it is more accurate); faint "
        "markers: every run. Errors against core (the closed form's own error against "
        "mpmath is the star). Click a legend entry to hide a method.</p>"))
    save(column(intro, select, shown.peers, shown.checks), filename=str(path),
         resources=INLINE, title="Speed against accuracy, like for like")


def stability_page(rows: list[dict], path: Path) -> None:
    """The maps, one per method, as a stand-alone page; the quantity's selector runs in
    the browser."""
    from bokeh.io import save
    from bokeh.layouts import column, gridplot
    from bokeh.resources import INLINE

    data = stability_data(rows)
    mapper = error_mapper(data)
    figs, sources = [], []
    for name in data.methods:
        fig, src = stability_figure(data, name, mapper, width=470, height=400,
                                    toolbar_location=None)
        figs.append(fig)
        sources.append(src)
    bar = figure(width=470, height=340, toolbar_location=None, min_border=0,
                 outline_line_color=None, title="colour scale")
    bar.add_layout(colour_bar(mapper), "left")
    bar.axis.visible = False
    bar.grid.visible = False
    figs.append(bar)
    select = Select(title="Quantity", value=next(iter(STABILITY_FIELDS)),
                    options=list(STABILITY_FIELDS), width=500)
    select.js_on_change("value", CustomJS(
        args=dict(sources=sources, fields=STABILITY_FIELDS), code="""
const col = fields[this.value];
for (const src of sources) {
  src.data = Object.assign({}, src.data, {shown: src.data[col]});
}
"""))
    intro = Div(text=f"<p>{STABILITY_NOTE.format(high=data.high)}</p>", width=1300)
    save(column(intro, select, gridplot(figs, ncols=3)), filename=str(path),
         resources=INLINE, title="Stability map of the numerical methods")


PAGES = {"speed_accuracy.csv": speed_accuracy_page, "stability_map.csv": stability_page}


def main(argv: list[str] | None = None) -> None:
    """`python -m app.methods.publish DIR [--publish]`: the HTML page of each results
    file in DIR, written beside it; with --publish the files are copied to `RESULTS`."""
    parser = argparse.ArgumentParser(description=main.__doc__)
    parser.add_argument("folder", type=Path, help="where the benchmarks wrote their CSV "
                        "files (benchmarks/results)")
    parser.add_argument("--publish", action="store_true",
                        help="copy the files to the app's package data (app/results/)")
    args = parser.parse_args(argv)
    for name, page in PAGES.items():
        path = args.folder / name
        page(read_rows(path), path.with_suffix(".html"))
        print(f"wrote {path.with_suffix('.html')}")
        if args.publish:
            with resources.as_file(RESULTS / name) as target:
                shutil.copyfile(path, target)
            print(f"copied {path} to {target}")


if __name__ == "__main__":
    main()
