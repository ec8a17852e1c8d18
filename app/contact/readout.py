"""The derived quantities: an HTML table of text, one row per quantity.

Real text in the page, so that it can be read aloud, selected, copied, zoomed and
searched: a caption naming the table, a header row, each quantity a row header
(`<th scope="row">`) and its value a cell.  Names and values are shown as text (escaped),
never interpreted as markup.
"""

from __future__ import annotations

import html

import panel as pn

from app.kit.div import HtmlDiv

#: What the table is, for a screen reader (the card's title shows it on screen).
CAPTION = "Derived quantities of the current contact"

#: The table's look: full width, fixed columns (a new value never moves the columns),
#: a rule between rows, values in bold with digits of equal width; the caption is for
#: screen readers only.
TABLE_CSS = """
table { width: 100%; border-collapse: collapse; table-layout: fixed; }
caption { position: absolute; width: 1px; height: 1px; overflow: hidden;
          clip-path: inset(50%); white-space: nowrap; }
th, td { text-align: left; vertical-align: top; padding: 0.2em 0.4em;
         border-bottom: 1px solid #dddddd; overflow-wrap: anywhere; }
thead th { font-weight: normal; color: #495057; border-bottom: 2px solid #adb5bd; }
tbody th { font-weight: normal; width: 56%; }
td { font-weight: bold; font-variant-numeric: tabular-nums; }
"""


def table_html(rows: list[tuple[str, str]]) -> str:
    """The HTML table of (quantity, value) `rows`, top to bottom, as escaped text."""
    body = "".join(f'<tr><th scope="row">{html.escape(q)}</th><td>{html.escape(v)}</td></tr>'
                   for q, v in rows)
    return (f'<table class="readout"><caption>{html.escape(CAPTION)}</caption>'
            '<thead><tr><th scope="col">Quantity</th><th scope="col">Value</th></tr></thead>'
            f"<tbody>{body}</tbody></table>")


class Readout(pn.viewable.Viewer):
    """The derived quantities of the current contact as an HTML table (`show(rows)`)."""

    def __init__(self) -> None:
        super().__init__()
        #: the (quantity, value) rows shown
        self.rows: list[tuple[str, str]] = []
        self.pane = HtmlDiv(table_html([]), stylesheets=[TABLE_CSS], name="derived_quantities")

    def __panel__(self) -> HtmlDiv:
        return self.pane

    def show(self, rows: list[tuple[str, str]]) -> None:
        """Show (quantity, value) rows, top to bottom (unchanged rows are not sent again)."""
        rows = list(rows)
        if rows != self.rows:
            self.rows = rows
            self.pane.object = table_html(rows)
