"""The "Check a DEM code" card: `DemCard()`, a collapsed card whose content is built when
it is first opened, in two tabs under a keyboard-operable tab list (`app.kit.a11y.TabList`,
as the page's curve tabs): "The paper's loading" (below) and "Impacts" (Chung & Ooi's
impact tests, `app.dem.impacts_view.ImpactsTab`, built when that tab is first opened).

In the first: a case of `core.dem_check` and LAMMPS' models to overlay; one figure with the
exact T(tau), the Coulomb bounds, LAMMPS' precomputed runs and the visitor's history
(named sources `dem_exact`, `dem_lammps`, `dem_upload`, updated in place); an upload box
for a CSV (`app.dem.upload.CsvUpload`: a file over the cap is refused by the browser
before it is sent, a smaller one is sent in pieces and read in memory only,
`app.dem.data.read_upload`) with the reason under it when it is refused, and the score
table; the case's test vectors and LAMMPS deck to
download. It needs nothing from the rest of the page.
"""

from __future__ import annotations

import html
import io

import panel as pn
import param
from bokeh.models import ColumnDataSource

from app.dem import data
from app.dem.impacts_view import ImpactsTab
from app.dem.state import DemState
from app.dem.upload import CsvUpload
from app.kit.a11y import TabList
from app.kit.batch import held
from app.kit.figures import fit_range, new_figure, style_figure
from app.kit.lazy_card import LazyCard
from app.kit.style import TAB_ROW_CSS
from app.kit.widgets import ERROR_STYLE, shortened, sync, text_html
from core.dem_check import CASES, lammps

#: The card's tabs.
TAB_TITLES = ("The paper's loading", "Impacts")
TITLE = "Check a DEM code: LAMMPS and yours against the exact solution"
INTRO = (
    "The paper's loading as a test of a discrete-element tangential contact model: the "
    "lower sphere driven along an oblique, oscillating path, the upper one held. The "
    "thick grey curve is the exact T/T₀ of the case, the dashed ones the Coulomb bound ±μP/T₀; "
    "the coloured ones LAMMPS' tangential models on the same loading. Run the case in "
    "your own code, upload its force history on the held sphere as a CSV with columns "
    "`tau` (rad), `T` (T/T₀, along the drive) and `P` (P/P₀), and see it scored and drawn "
    f"(at most {data.size_text(data.MAX_UPLOAD_BYTES)} and {data.MAX_UPLOAD_ROWS:,} rows: "
    "keep every k-th step of a longer run). `docs/dem_check.md` says how the scores are "
    "defined.")

#: The score table's look.
TABLE_CSS = """
table { border-collapse: collapse; }
caption { text-align: left; font-weight: bold; padding-bottom: 0.3em; }
th, td { text-align: left; padding: 0.15em 0.6em 0.15em 0; vertical-align: top; }
th { font-weight: normal; white-space: nowrap; }
"""


def score_html(rows: list[tuple[str, str]], caption: str) -> str:
    """The score table as HTML (every text escaped)."""
    body = "".join(f'<tr><th scope="row">{html.escape(q)}</th><td>{html.escape(v)}</td></tr>'
                   for q, v in rows)
    return f"<table><caption>{html.escape(caption)}</caption>{body}</table>"


class DemCard(pn.viewable.Viewer):
    """The card; `state` holds the visitor's choices (a fresh `DemState` by default)."""

    state = param.ClassSelector(class_=DemState, constant=True)

    def __init__(self, state: DemState | None = None, **params) -> None:
        super().__init__(state=state or DemState(), **params)
        self.sources = {
            "exact": ColumnDataSource({"tau": [], "T": [], "P": [], "minus_P": []},
                                      name="dem_exact"),
            "lammps": ColumnDataSource({"xs": [], "ys": [], "label": [], "color": []},
                                       name="dem_lammps"),
            "upload": ColumnDataSource({"tau": [], "T": []}, name="dem_upload"),
        }
        self.lazy = LazyCard(TITLE, lambda: [self._build_tabs()])
        self.card = self.lazy.card
        #: the Impacts tab, built when first opened
        self.impacts: ImpactsTab | None = None

    def __panel__(self) -> pn.Card:
        return self.card

    @property
    def built(self) -> bool:
        """Whether the card's content exists (it has been opened)."""
        return self.lazy.built

    def close(self) -> None:
        """The session ended: stop the Impacts tab's runs."""
        if self.impacts is not None:
            self.impacts.close()

    def _build_tabs(self) -> TabList:
        """The card's two tabs under a keyboard-operable tab list: the paper's loading
        (built now) and the impacts (built when first opened)."""
        self.impacts_panel = pn.Column(sizing_mode="stretch_width")
        self.tabs = pn.Tabs((TAB_TITLES[0], pn.Column(*self._build(),
                                                      sizing_mode="stretch_width")),
                            (TAB_TITLES[1], self.impacts_panel), dynamic=True,
                            sizing_mode="stretch_width", stylesheets=[TAB_ROW_CSS])
        self.tabs.param.watch(self._on_tab, "active")
        return TabList.for_tabs(self.tabs, list(TAB_TITLES), label="What to check",
                                sizing_mode="stretch_width")

    def _on_tab(self, event: param.parameterized.Event) -> None:
        if event.new == 1 and self.impacts is None:
            with held():
                self.impacts = ImpactsTab(table_css=TABLE_CSS)
                self.impacts_panel.objects = [self.impacts]

    # ------------------------------------------------------------------ build

    def _build(self) -> list:
        """The controls, the figure, the upload and the downloads, showing the state."""
        s = self.state
        self.case_select = pn.widgets.Select(label="Case", options=list(CASES), value=s.case,
                                             width=260)
        sync(self.case_select, s.param.case)
        self.case_note = pn.pane.Markdown("", sizing_mode="stretch_width")
        self.model_boxes = pn.widgets.CheckBoxGroup(label="LAMMPS models",
                                                    options=list(lammps.MODELS),
                                                    value=list(s.models), inline=True)
        sync(self.model_boxes, s.param.models)
        self.overlay_note = pn.pane.Markdown("", sizing_mode="stretch_width",
                                             styles={"font-size": "0.9em"})
        self.figure = self._figure()
        self.upload = CsvUpload(on_file=s.upload, on_refused=s.refuse,
                                label="Your code's history (CSV: tau, T, P)",
                                accept=".csv,text/csv,text/plain",
                                max_bytes=data.MAX_UPLOAD_BYTES, name="dem_upload_box",
                                margin=(5, 10), sizing_mode="stretch_width")
        self.message = pn.pane.HTML("", visible=False, styles=ERROR_STYLE,
                                    sizing_mode="stretch_width", name="dem_message")
        self.score_table = pn.pane.HTML("", visible=False, stylesheets=[TABLE_CSS],
                                        sizing_mode="stretch_width", name="dem_score")
        self.vectors_button = pn.widgets.FileDownload(
            callback=self._vectors_file, filename=data.vectors_filename(s.case),
            label="CSV: the case's test vectors", width=260)
        self.deck_button = pn.widgets.FileDownload(
            callback=self._deck_file, filename=self._deck_name(), label="LAMMPS deck",
            width=300)
        s.param.watch(lambda *_: self._show_case(), "case")
        s.param.watch(lambda *_: self._show_models(), "models")
        s.param.watch(lambda *_: self._show_upload(), "history")
        s.param.watch(lambda *_: self._show_score(), ["score", "message"])
        self._show_case()
        self._show_upload()
        self._show_score()
        return [
            pn.pane.Markdown(INTRO, sizing_mode="stretch_width"),
            pn.Row(self.case_select, self.case_note, sizing_mode="stretch_width"),
            self.model_boxes,
            pn.pane.Bokeh(self.figure, sizing_mode="stretch_width"),
            self.overlay_note,
            self.upload,
            self.message,
            self.score_table,
            pn.Row(self.vectors_button, self.deck_button),
        ]

    def _figure(self):
        fig = new_figure("T / T₀ of the held sphere: exact, LAMMPS and yours",
                         "τ = ωt (rad)", "T / T₀", height=380)
        exact, lmp, upload = (self.sources[k] for k in ("exact", "lammps", "upload"))
        for column in ("P", "minus_P"):
            fig.line("tau", column, source=exact, color="#555555", line_dash="dashed",
                     line_width=1.5, legend_label="±μP/T₀ (Coulomb)")
        fig.line("tau", "T", source=exact, color="black", line_width=5, alpha=0.35,
                 legend_label="exact")
        fig.multi_line("xs", "ys", source=lmp, color="color", line_width=2,
                       legend_field="label")
        fig.line("tau", "T", source=upload, color=data.UPLOAD_COLOR, line_width=2.5,
                 legend_label="your file")
        style_figure(fig)
        fig.add_layout(fig.legend[0], "right")  # beside the frame: it covers no curve
        return fig

    # ------------------------------------------------------------------- show

    def _show_case(self) -> None:
        """The case's exact curve, LAMMPS' runs of it and its note."""
        name = self.state.case
        columns = data.exact_columns(name)
        with held():
            self.sources["exact"].data = columns
            fit_range(self.figure.x_range, columns["tau"], pad=0.02)
            fit_range(self.figure.y_range, columns["P"], columns["minus_P"])
            self.case_note.object = data.case_note(name)
            self.overlay_note.object = data.overlay_note(name)
            self._show_models()

    def _show_models(self) -> None:
        """LAMMPS' runs of the models chosen; the deck is the first one's."""
        models = list(self.state.models)
        with held():
            self.sources["lammps"].data = data.overlay_columns(self.state.case, models)
            self.deck_button.label = f"LAMMPS deck: {data.deck_model(models)}"

    def _show_upload(self) -> None:
        self.sources["upload"].data = data.upload_columns(self.state.history)

    def _show_score(self) -> None:
        """The score table, or the reason there is none under the upload box."""
        s = self.state
        text = shortened(s.message)
        with held():
            self.message.param.update(object=text_html(text), visible=bool(text))
            if s.score is None:
                self.score_table.param.update(object="", visible=False)
            else:
                caption = f"Your file against {s.case}"
                self.score_table.param.update(
                    object=score_html(data.score_rows(s.score), caption), visible=True)

    # -------------------------------------------------------------- downloads

    def _deck_name(self) -> str:
        return data.deck_filename(self.state.case, data.deck_model(list(self.state.models)))

    def _vectors_file(self) -> io.StringIO:
        """The case's test vectors (named when clicked, not per case change)."""
        self.vectors_button.filename = data.vectors_filename(self.state.case)
        return io.StringIO(data.vectors_text(self.state.case))

    def _deck_file(self) -> io.StringIO:
        """The deck of the case for the first model chosen (`data.deck_model`)."""
        model = data.deck_model(list(self.state.models))
        self.deck_button.filename = data.deck_filename(self.state.case, model)
        return io.StringIO(data.deck_text(self.state.case, model))
