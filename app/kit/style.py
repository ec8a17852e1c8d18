"""Styles shared by the page and its features (CSS properties and stylesheets)."""

#: Colour of the ring around the control the keyboard is on (6.3:1 on white).
FOCUS_COLOR = "#1A5FB4"
#: The ring itself, 3 px, 2 px outside the control (a CSS declaration for `:focus-visible`).
FOCUS_RING = f"outline: 3px solid {FOCUS_COLOR}; outline-offset: 2px;"

#: The note under the preset selector: what to notice in the figure on screen.
NOTE_STYLE = {"background": "#eef5fb", "color": "#1b3a57", "border-left": "4px solid #0072B2",
              "padding": "0.4em 0.8em", "font-size": "1rem"}

#: The warning box above the plots (rejected URL values).
MESSAGE_STYLE = {"background": "#fff3cd", "color": "#664d03", "border": "1px solid #ffe69c",
                 "border-radius": "6px", "padding": "0.6em 1em"}

#: Tabs' stylesheet: their titles wrap onto a second row on a narrow screen (BokehJS
#: scrolls the row sideways, hiding the last titles on a phone).
TAB_ROW_CSS = ".bk-headers-wrapper { flex-wrap: wrap; }"

#: The formula card's stylesheet: an equation's type (KaTeX's 1.21 em) shrinks with the
#: card's width below about 500 px, so that the longest (25 em wide) fits a phone's card.
FORMULA_CSS = (":host { container-type: inline-size; }"
               " .katex-display > .katex { font-size: min(1.21em, 3.9cqw); }")

#: Text for a screen reader only: out of sight, yet in the accessibility tree (not
#: `display: none`, which would take it out).
VISUALLY_HIDDEN_CSS = (":host { position: absolute !important; width: 1px !important;"
                       " height: 1px !important; overflow: hidden !important;"
                       " clip-path: inset(50%) !important; white-space: nowrap;"
                       " margin: 0 !important; }")

#: BokehJS's tab titles hidden: the page draws its own tab list (`app.kit.a11y.TabList`,
#: keyboard operable) above the Tabs' content.
HIDE_TAB_HEADERS_CSS = ".bk-header { display: none; }"
