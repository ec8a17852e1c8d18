"""The derived quantities: an HTML table of text, one row per quantity.

Real text in the page, so that it can be read aloud, selected, copied, zoomed and
searched: a caption naming the table, a header row, each quantity a row header
(`<th scope="row">`) and its value a cell (`app.kit.texts.TextTable`, built in the browser
from the rows: names and values are set as text, never interpreted as markup).
"""

from __future__ import annotations

import panel as pn

from app.kit.texts import TextTable

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


class Readout(pn.viewable.Viewer):
    """The derived quantities of the current contact as a table of text (`show(rows)`)."""

    def __init__(self) -> None:
        super().__init__()
        self.pane = TextTable(caption=CAPTION, stylesheets=[TABLE_CSS],
                              name="derived_quantities")

    def __panel__(self) -> TextTable:
        return self.pane

    def show(self, rows: list[tuple[str, str]]) -> None:
        """Show (quantity, value) rows, top to bottom (unchanged rows are not sent
        again; `app.kit.texts.WrittenHTML.write`)."""
        self.pane.write(rows=[list(r) for r in rows])
