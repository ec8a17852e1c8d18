"""A quasi-static 3D boundary-element referee for the paper's model: two elastic
half-spaces in frictional contact in Kalker's formulation (uniform tractions on square
elements, Love's and Cerruti's influence coefficients with the cross terms that carry nu,
the normal-tangential coupling through Dundurs' beta), convolutions by DC-FFT, the normal
problem by Polonsky & Keer's constrained CG, Coulomb's law per element by an accelerated
projected gradient on the step's convex QP, marched in time with the shift's history.

    >>> from core.bem import cattaneo
    >>> r = cattaneo(nu=0.0, load=0.875, grid=16)
    >>> round(r.shift_ratio, 3), round(r.stick_radius, 2)
    (1.0, 0.5)

See docs/bem.md for the method, its checks and the model's error it measures.
"""

from core.bem.cases import CattaneoResult, SpenceResult, cattaneo, spence
from core.bem.convolution import Operators
from core.bem.grid import Grid
from core.bem.march import State, StepSettings, step
from core.bem.pair import Pair

__all__ = [
    "CattaneoResult",
    "Grid",
    "Operators",
    "Pair",
    "SpenceResult",
    "State",
    "StepSettings",
    "cattaneo",
    "spence",
    "step",
]
