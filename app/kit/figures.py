"""Figures of the app's scenes: one style, one way to draw a glyph, ranges that fit.

A scene (`app.kit.scene.Scene`) is one Bokeh figure fed by one named `ColumnDataSource`;
the helpers here make every figure look alike
(`new_figure`, `style_figure`, `draw`, `add_legend`) and fit its ranges to the data
(`fit_range`, `nice_step`); `png_name` names a plot's PNG download and `stamp`
draws in it the contact and the time it shows.  What changes with a frame of the
animation is drawn at `FRAME_LEVEL`, where the browser repaints only a plot's overlay
layer; `style_figure` moves a figure's glyphs from there into the clipped
`CLIPPED_LEVEL` once the user pans or zooms it (`clip_when_moved`).
"""

from __future__ import annotations

import math
import re
import unicodedata

import numpy as np
from bokeh.events import LODStart, RangesUpdate
from bokeh.models import (
    AllIndices,
    BoxZoomTool,
    ColumnDataSource,
    CustomJS,
    CustomJSTransform,
    Glyph,
    GlyphRenderer,
    Label,
    Legend,
    LegendItem,
    PanTool,
    Range1d,
    SaveTool,
    Title,
    UnionRenderers,
    WheelZoomTool,
)
from bokeh.plotting import figure
from bokeh.transform import transform

from app.kit.image_export import add_image_export

TOOLS = "pan,wheel_zoom,box_zoom,reset,save"
#: Greek letters of the plots' titles, spelled out in the PNG file names
GREEK = str.maketrans({"α": "alpha", "μ": "mu", "ν": "nu", "τ": "tau", "ψ": "psi",
                       "ω": "omega", "θ": "theta"})
CURVE_POINTS = 400  # points per curve over the contact: finer than any screen needs
PROFILE_POINTS = 151  # points across the contact diameter for the traction profile

LINE_COLORS = ("#000000", "#D55E00", "#0072B2", "#CC79A7", "#009E73")
#: Bokeh level of what changes on an animation frame or a slider move, and of labels
#: (which BokehJS clips to the frame): the browser then repaints only the plot's overlay
#: layer, not its axes, grid, legend and everything else drawn at the lower levels.
#: BokehJS does not clip glyphs at this level: in a figure with pan or zoom tools,
#: `style_figure` moves them to `CLIPPED_LEVEL` the moment the user pans or zooms it.
FRAME_LEVEL = "overlay"
#: Bokeh level of the data glyphs of a figure with pan and zoom tools: `FRAME_LEVEL`
#: until the user pans or zooms the figure (`clip_when_moved`), `CLIPPED_LEVEL` after.
DATA_LEVEL = FRAME_LEVEL
#: Bokeh level of glyphs clipped to the frame (when they change, BokehJS repaints the
#: plot's primary layer: axes, grid and title too).
CLIPPED_LEVEL = "glyph"


def style_figure(fig) -> None:
    """Large type, readable on a projector; the glyphs drawn so far lean (`lean`)."""
    fig.title.text_font_size = "15pt"
    for axis in (*fig.xaxis, *fig.yaxis):
        axis.axis_label_text_font_size = "14pt"
        axis.major_label_text_font_size = "12pt"
    fig.toolbar.logo = None
    fig.toolbar.autohide = True
    if fig.legend:
        fig.legend.label_text_font_size = "12pt"
        fig.legend.background_fill_alpha = 0.7
        fig.legend.click_policy = "hide"
    lean(fig)
    clip_when_moved(fig)


#: The tools by which a user moves a figure's view (its ranges).
MOVING_TOOLS = (PanTool, WheelZoomTool, BoxZoomTool)

#: JavaScript (a `CustomJS` of `plot`'s LODStart and RangesUpdate events): the glyphs at
#: `FRAME_LEVEL` of `plot` and of the plots sharing a range with it go to
#: `CLIPPED_LEVEL`, in the browser only; the ranges change after this runs and the
#: plots are then repainted whole (both layers).
CLIP_JS = f"""
const moved = [...plot.document.all_models].filter((m) => m.type === "Figure"
  && (m.x_range === plot.x_range || m.y_range === plot.y_range));
for (const fig of moved) {{
  for (const r of fig.renderers) {{
    if (r.type === "GlyphRenderer" && r.level === {FRAME_LEVEL!r}) {{
      r.setv({{level: {CLIPPED_LEVEL!r}}}, {{sync: false}});
    }}
  }}
}}
"""


def clip_when_moved(fig) -> None:
    """Keep `fig`'s data inside its frame once the user moves its view.

    Its glyphs at `FRAME_LEVEL` (`DATA_LEVEL`) are painted on the plot's overlay layer,
    which BokehJS does not clip to the frame: a frame of the animation or a slider move
    repaints that layer only (the axes, grid, title and legend stay as painted), but a
    panned or zoomed curve would be drawn over the title and the axes.  So when the user
    starts to pan or zoom `fig` (BokehJS's LODStart event, fired before the ranges
    change; RangesUpdate after a box zoom or a reset), those glyphs, and those of the
    plots sharing a range with it, go to `CLIPPED_LEVEL` for the rest of the page's life
    (`CLIP_JS`).  Nothing for a figure without pan or zoom tools."""
    if not any(isinstance(tool, MOVING_TOOLS) for tool in fig.toolbar.tools):
        return
    clip = CustomJS(args={"plot": fig}, code=CLIP_JS)
    fig.js_on_event(LODStart, clip)
    fig.js_on_event(RangesUpdate, clip)


def lean(fig) -> None:
    """Drop the copies of every glyph that Bokeh's glyph methods make for unselected and
    for muted points: no plot has a selection tool and every legend hides (never mutes)
    its curves, so those copies are never drawn; with 'auto' BokehJS makes one if ever
    needed.  Two models fewer per glyph in every page (each model costs the server
    per page load, and on every message: Bokeh indexes the document's models for
    each).  For the same reason the renderers share one filter of all rows (their
    views' `AllIndices`, which holds nothing: it returns every row of the source it is
    given), and their sources one selection policy (`UnionRenderers`, which holds
    nothing; a source's `Selection` can only be given when it is made)."""
    every: AllIndices | None = None
    policy: UnionRenderers | None = None
    for r in fig.renderers:
        if isinstance(r, GlyphRenderer):
            r.nonselection_glyph = r.muted_glyph = "auto"
            if type(r.view.filter) is AllIndices:
                every = every or r.view.filter
                r.view.filter = every
            source = r.data_source
            if isinstance(source, ColumnDataSource):
                policy = policy or source.selection_policy
                source.selection_policy = policy


#: What `draw` gives the renderer (the rest goes to the glyph), as Bokeh's glyph methods.
RENDERER_PROPS = ("level", "name", "view", "visible")


def draw(fig, glyph: type[Glyph], source: ColumnDataSource | None = None,
         **props) -> GlyphRenderer:
    """Draw a `glyph` (a Bokeh glyph type: `Line`, `Segment`, ...) of `props` from
    `source` on `fig`, as its glyph method (`fig.line`, `fig.segment`, ...) would, as one
    glyph model where the method makes three (with the copies `lean` drops).  As in the
    methods, `color` and `alpha` stand for each colour and alpha of the glyph not given
    (line, fill, hatch, text), strings name the source's columns, and `RENDERER_PROPS`
    go to the renderer."""
    renderer = {k: props.pop(k) for k in RENDERER_PROPS if k in props}
    for trait in ("color", "alpha"):
        if trait in props:
            value = props.pop(trait)
            for prop in glyph.properties():
                feature, _, rest = prop.partition("_")
                if rest == trait and feature in VISUALS:
                    props.setdefault(prop, value)
    return fig.add_glyph(source or ColumnDataSource(), glyph(**props), **renderer)


#: JavaScript of a `CustomJSTransform`: each value negated.
NEGATED_JS = "return xs.map((x) => -x)"


def negated(column: str) -> dict:
    """A glyph property drawing the negative of the source's `column`, computed by the
    browser: a curve that mirrors another (-mu P, the lower envelope -p) is not sent."""
    return transform(column, CustomJSTransform(v_func=NEGATED_JS))


#: The visual features of a glyph's properties (line_color, fill_alpha, ...).
VISUALS = ("line", "fill", "hatch", "text", "global")


def add_legend(fig, entries: list[tuple[str, list[GlyphRenderer]]], place: str = "right",
               location: str = "top_left") -> Legend:
    """A legend that the browser never repaints when the data change.

    BokehJS repaints a legend whenever anything its entries refer to changes, data
    included, and a legend repaint restyles the page (the costliest part of a slider
    move).  So each entry shows a copy of its first renderer drawing one NaN point
    (nowhere; BokehJS draws no legend swatch for an empty renderer), and clicking it
    hides or shows the real renderers: the copies' callback finds them by id, since a
    reference to them would tie the legend to their data again.  The copies share one
    source and one callback.
    """
    columns = dict.fromkeys(k for _, renderers in entries for k in renderers[0].data_source.data)
    nowhere = ColumnDataSource({k: [math.nan] for k in columns})
    proxies = [fig.add_glyph(nowhere, renderers[0].glyph.clone()) for _, renderers in entries]
    targets = {proxy.id: [r.id for r in renderers]
               for proxy, (_, renderers) in zip(proxies, entries, strict=True)}
    toggle = CustomJS(code=(
        f"for (const id of {targets!r}[cb_obj.id]) {{\n"
        "  const r = cb_obj.document.get_model_by_id(id);\n"
        "  if (r != null) r.visible = cb_obj.visible;\n}"))
    for proxy in proxies:
        proxy.js_on_change("visible", toggle)
    items = [LegendItem(label=label, renderers=[proxy])
             for (label, _), proxy in zip(entries, proxies, strict=True)]
    legend = Legend(items=items, location=location, click_policy="hide")
    place_legend(fig, legend, place)
    return legend


def place_legend(fig, legend: Legend, place: str) -> None:
    """Put `legend` in `fig`'s side panel `place` ('above', 'right', ...), out of any
    other: a row above or below (tighter around, wider between entries), a column
    beside."""
    for side in ("above", "below", "left", "right", "center"):
        setattr(fig, side, [m for m in getattr(fig, side) if m is not legend])
    row = place in ("above", "below")
    legend.update(orientation="horizontal" if row else "vertical", spacing=16 if row else 3,
                  padding=5 if row else 10, margin=4 if row else 10)
    fig.add_layout(legend, place)


def nice_step(span: float, parts: int = 10) -> float:
    """The 1-2-5 x 10^k step nearest above span / parts (span > 0)."""
    raw = span / parts
    k = math.floor(math.log10(raw))
    f = raw / 10.0**k
    return next(m for m in (1.0, 2.0, 5.0, 10.0) if f <= m * (1 + 1e-12)) * 10.0**k


def fit_range(rng: Range1d, *columns, pad: float = 0.06, snap: bool = False) -> None:
    """Set a fixed range around the finite values of `columns`.

    Ranges are explicit (not auto-ranged) so that moving a marker never makes the
    browser lay the plot out again: only the data of a frame changes.  With `snap` the
    ends are rounded outwards to a multiple of a 1-2-5 step of about a tenth of the
    span, so that a small parameter move usually leaves the range (and the axes, which
    the browser would otherwise redraw) as they were.
    """
    values = np.concatenate([np.ravel(np.asarray(c, float)) for c in columns])
    values = values[np.isfinite(values)]
    lo, hi = (float(values.min()), float(values.max())) if values.size else (0.0, 1.0)
    margin = pad * (hi - lo) if hi > lo else 0.5
    lo, hi = lo - margin, hi + margin
    if snap:
        step = nice_step(hi - lo)
        lo, hi = math.floor(lo / step) * step, math.ceil(hi / step) * step
    if (rng.start, rng.end) != (lo, hi):
        rng.start, rng.end = lo, hi


def new_figure(title: str, x_label: str, y_label: str, **kwargs):
    """A Bokeh figure as every scene has it: unit ranges to be fitted, the scenes'
    tools, stretching to its column, and a save tool that downloads a PNG named after
    the title (`png_name`); `kwargs` override these and go to `bokeh.plotting.figure`."""
    kwargs.setdefault("x_range", Range1d(0, 1))
    kwargs.setdefault("y_range", Range1d(0, 1))
    kwargs.setdefault("tools", TOOLS)
    kwargs.setdefault("sizing_mode", "stretch_width")
    kwargs.setdefault("height", 340)
    kwargs.setdefault("min_width", 300)
    fig = figure(title=title, x_axis_label=x_label, y_axis_label=y_label, **kwargs)
    for tool in fig.select(type=SaveTool):  # downloads the PNG without asking for a name
        tool.filename = png_name(title)
    add_image_export(fig)  # Save PNG 2x, 3x and SVG in the toolbar
    return fig


#: The source that holds the time tau shown and the contact's psi and tau0 (columns `tau`,
#: `psi`, `tau0`): the spheres' forces, which change with each of them and which the
#: browser's player moves frame by frame (`app.contact.spheres`).
CLOCK = "spheres_forces"
#: The tag of the plots' stamps (`stamp`); their second tag is the stamp's separator.
STAMP_TAG = "png-stamp"

#: JavaScript: every plot's stamp shows the psi, tau0 and tau of the clock (`source`, or
#: when None the source named `CLOCK`), as the browser holds them (the player's frame
#: while playing): written in the browser only (BokehJS's public `setv(..., {sync:
#: false})`), and only where its text changes.  The stamps are looked up among the
#: document's models when a plot is laid out (`scan`, a plot built later brings its own)
#: and kept per document, not on every frame.
STAMPS_JS = f"""
const doc = cb_obj.document;
if (doc == null) {{ return; }}
const kept = window.__zharii_stamps || (window.__zharii_stamps = new WeakMap());
if (scan || !kept.has(doc)) {{
  kept.set(doc, [...doc.all_models].filter(
    (m) => m.tags.length === 2 && m.tags[0] === {STAMP_TAG!r}));
}}
const clock = source ?? doc.get_model_by_name({CLOCK!r});
const col = (c) => (clock.data instanceof Map ? clock.data.get(c) : clock.data[c]);
if (clock == null || col("tau") == null || col("tau").length === 0) {{ return; }}
const [psi, tau0, tau] = ["psi", "tau0", "tau"].map((c) => col(c)[0]);
const parts = [`ψ = ${{Number(psi.toPrecision(6))}}`, `τ₀ = ${{tau0.toFixed(4)}} rad`,
  `τ = ${{tau.toFixed(4)}} rad`];
for (const m of kept.get(doc)) {{
  const text = parts.join(m.tags[1]);
  if (m.text !== text) {{ m.setv({{text: text}}, {{sync: false}}); }}
}}
"""


def follow_clock(source: ColumnDataSource) -> None:
    """Make every plot's stamp follow `source` (the clock) in the browser: whenever its
    data change (a message from the server, or a frame the player copies into it)."""
    source.js_on_change("change", CustomJS(code=STAMPS_JS, args={"scan": False,
                                                                 "source": source}))


def stamp(fig, sep: str = "   ", **place) -> Label:
    """A line drawn in `fig`'s frame naming the contact's psi, tau0 and the time tau
    shown, so that a PNG saved from its toolbar stands alone: by default in the frame's
    bottom left corner (`place` overrides the `Label`'s x, y, units, offsets and
    alignment; `sep` comes between the three values: a newline stacks them).  The
    browser writes it (`STAMPS_JS`), when the plot is first laid out and whenever the
    clock changes (every frame while playing): the server sends nothing for it.  So it
    lies at `FRAME_LEVEL` (clipped to the frame, as every label), where a change repaints
    only the plot's overlay layer, over the data (on a half-transparent ground, which
    lets a curve through)."""
    where = {"x": 6, "y": 6, "x_units": "screen", "y_units": "screen",
             "text_align": "left", "text_baseline": "bottom", "level": FRAME_LEVEL} | place
    label = Label(text="", text_font_size="9pt", text_color="#555555",
                  tags=[STAMP_TAG, sep], background_fill_color="white",
                  background_fill_alpha=0.5, **where)
    fig.add_layout(label)
    fig.js_on_change("inner_width", CustomJS(code=STAMPS_JS, args={"scan": True,
                                                                    "source": None}))
    return label


#: The separator and type of a stamp drawn under the frame (`stamp_outside`): one line of
#: 210 px, for the narrowest plots (240 px).
BELOW_SEP, BELOW_FONT = ", ", "8pt"


def stamp_outside(fig, side: str = "below") -> None:
    """Draw `fig`'s stamp (`stamp`) outside its frame, in one line: below the x axis
    (`side` "below"), ending at the frame's right edge, or up the frame's right edge
    ("right", for a plot whose height is dear), as a `Title` the browser writes as it
    writes the stamp, where no data is drawn (for plots too small for the stamp to find
    a free corner of the frame).  Its `Label` leaves the figure; calling it again
    changes nothing."""
    labels = [r for r in fig.center if isinstance(r, Label) and STAMP_TAG in r.tags]
    if not labels:
        return
    fig.center = [r for r in fig.center if r not in labels]
    label = labels[0]
    fig.add_layout(Title(text="", tags=[STAMP_TAG, BELOW_SEP],
                         align="right" if side == "below" else "left",
                         text_font_size=BELOW_FONT, text_font_style="normal",
                         text_color=label.text_color, standoff=2), side)


def png_name(title: str) -> str:
    """The name (without .png) under which the save tool downloads the plot titled
    `title`: 'zharii_' and the title's words in lower-case ASCII (Greek letters spelled
    out, subscripts as digits).  Fixed per plot: a name following the parameters would
    re-render the tool's button in the browser on every parameter change."""
    text = unicodedata.normalize("NFKD", title.translate(GREEK)).lower()
    return "_".join(["zharii", *re.findall(r"[a-z0-9]+", text)])
