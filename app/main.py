"""Entry point of `panel serve app/main.py`: one explorer per browser session, its page
built from the URL whatever the URL holds (`app.page.guard`)."""

import panel as pn

from app.page.guard import serve_page

pn.extension("katex", notifications=False, lazy_resources=False)

serve_page()
