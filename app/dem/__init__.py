"""The "Check a DEM code" card: a case of `core.dem_check`, its exact T(tau), LAMMPS' five
tangential models over it (precomputed: `app.dem.overlays`), and a visitor's own CSV
scored and overlaid (docs/dem_check.md).

`state` holds what the visitor chose, `data` the numbers (no Bokeh, no Panel), `view`
the card (`DemCard`).
"""
