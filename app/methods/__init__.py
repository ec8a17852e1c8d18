"""The Methods feature: the numerical methods of `core.numerics` against the closed form
(`view.MethodsScene`, the card; `data`, the runs and their table), and the charts of
their benchmarks (`speed_chart`, `stability_chart`; the data in `results`, the
stand-alone pages in `publish`)."""

from app.methods.data import DEFAULT_METHODS
from app.methods.view import MethodsScene

__all__ = ["DEFAULT_METHODS", "MethodsScene"]
