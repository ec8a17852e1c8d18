"""Images of a plot for slides: PNG at 2x and 3x and SVG, from the plot's toolbar.

Bokeh's save tool writes a PNG at the screen's resolution only (BokehJS's
`PlotView.export("png")` draws at `devicePixelRatio`), too coarse for a projected slide.
`add_image_export` gives a figure three more toolbar actions (Bokeh `CustomAction`s):
"Save PNG 2x", "Save PNG 3x" and "Save SVG".  All three are drawn in the browser from
the plot as it is shown, its stamp (`app.kit.figures.stamp`) included, with BokehJS's
public API: `Bokeh.index` finds the plot's view and `export("svg")` paints it, as the
save tool paints its PNG, into BokehJS's SVG context.  The SVG is saved as it is; a
PNG is that SVG drawn onto a canvas of 2 or 3 times the plot's CSS size, so its lines
and text are sharp at any scale.  The files are named as the save tool's PNG
(`app.kit.figures.png_name`): `zharii_traction_profile_2x.png`, `..._3x.png`, `.svg`.
"""

from __future__ import annotations

import base64

from bokeh.models import CustomAction, CustomJS, SaveTool

#: The actions: their tooltip (the button's accessible name), what they write (a PNG's
#: scale, or "svg") and the text of their icon.
ACTIONS = (("Save PNG 2x", 2, "2x"), ("Save PNG 3x", 3, "3x"), ("Save SVG", "svg", "SVG"))

#: JavaScript of the actions (`cb_obj` the action, whose first tag says what it writes):
#: the plot's shown view exported as SVG, then saved, or drawn at the scale and saved
#: as a PNG, under the save tool's file name (in an async function: a CustomJS's code
#: is a plain one).
EXPORT_JS = """
(async () => {
  const what = cb_obj.tags[0];
  const view = [...Bokeh.index.find(plot)].find((v) => v.el.isConnected) ?? null;
  if (view == null) { return; }
  const saver = plot.toolbar.tools.find((t) => t.type === "SaveTool");
  const name = saver != null && saver.filename != null ? saver.filename : "plot";
  const save = (blob, file) => {
    const link = document.createElement("a");
    link.href = URL.createObjectURL(blob);
    link.download = file;
    link.dispatchEvent(new MouseEvent("click"));
    setTimeout(() => URL.revokeObjectURL(link.href), 60_000);
  };
  const svg = await view.export("svg").to_blob();
  if (what === "svg") { save(svg, `${name}.svg`); return; }
  const {width, height} = view.bbox;
  const image = new Image();
  const url = URL.createObjectURL(svg);
  try {
    image.src = url;
    await image.decode();
    const canvas = document.createElement("canvas");
    canvas.width = Math.round(width * what);
    canvas.height = Math.round(height * what);
    canvas.getContext("2d").drawImage(image, 0, 0, canvas.width, canvas.height);
    const png = await new Promise((resolve, reject) => canvas.toBlob(
      (b) => b != null ? resolve(b) : reject(new Error("no PNG")), "image/png"));
    save(png, `${name}_${what}x.png`);
  } finally {
    URL.revokeObjectURL(url);
  }
})().catch((e) => console.error("image export:", e));
"""


def icon(text: str) -> str:
    """A toolbar icon (a data URL of an SVG) showing `text` in Bokeh's icon grey."""
    size = 12 if len(text) < 3 else 9
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" width="24" height="24">'
           f'<text x="12" y="17" text-anchor="middle" font-family="sans-serif" '
           f'font-weight="bold" font-size="{size}" fill="#5f6368">{text}</text></svg>')
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode()).decode()


def add_image_export(fig) -> None:
    """Give `fig`'s toolbar "Save PNG 2x", "Save PNG 3x" and "Save SVG" (`ACTIONS`),
    sharing one callback (`EXPORT_JS`); nothing for a figure without a save tool (its
    toolbar saves nothing)."""
    if not fig.select(type=SaveTool):
        return
    callback = CustomJS(args={"plot": fig}, code=EXPORT_JS)
    fig.add_tools(*(CustomAction(description=tip, icon=icon(text), callback=callback,
                                 tags=[what]) for tip, what, text in ACTIONS))
