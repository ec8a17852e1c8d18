"""The boundary-element grid: equal square elements on the contact plane, centred on the
origin so that the grid is symmetric in x and in y.

Lengths are dimensionless, in units of the largest contact radius a* (the paper's loading)
or of the Hertz radius a (Cattaneo, Spence). ``elements_across`` counts the elements across
that radius's diameter 2, so the element side is h = 2 / elements_across; the grid adds a
margin of empty elements around the circle of radius 1 so that a contact slightly larger
than predicted (dissimilar bodies) still fits.
"""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

#: Fewest and most elements across the contact diameter.
MIN_ACROSS = 4
MAX_ACROSS = 1024


def check_across(n: object, name: str = "grid") -> int:
    """n as an int if it is an integer in [MIN_ACROSS, MAX_ACROSS]; ValueError naming the
    argument otherwise."""
    if (isinstance(n, bool) or not isinstance(n, int | np.integer)
            or not MIN_ACROSS <= n <= MAX_ACROSS):
        raise ValueError(f"{name} must be an integer in [{MIN_ACROSS}, {MAX_ACROSS}] "
                         f"(elements across the contact diameter), got {n!r}")
    return operator.index(n)


@dataclass(frozen=True)
class Grid:
    """M x M square elements of side ``h`` centred on the origin.

    Parameters
    ----------
    elements_across : int
        Elements across the diameter 2 of the unit circle (h = 2 / elements_across).
    margin : float
        Half-width of the grid in units of the radius, >= 1 (default 1.08).
    """

    elements_across: int
    margin: float = 1.08

    def __post_init__(self) -> None:
        object.__setattr__(self, "elements_across", check_across(self.elements_across))
        if not (isinstance(self.margin, int | float) and 1.0 <= self.margin <= 4.0):
            raise ValueError(f"margin must be a number in [1, 4], got {self.margin!r}")

    @property
    def h(self) -> float:
        """Element side (units of the radius)."""
        return 2.0 / self.elements_across

    @cached_property
    def size(self) -> int:
        """M, the number of elements along each side: the smallest count of the parity of
        ``elements_across`` whose half-width reaches ``margin``."""
        n = self.elements_across
        extra = math.ceil((self.margin - 1.0) * n / 2.0)
        return n + 2 * max(extra, 1)

    @cached_property
    def centres(self) -> NDArray[np.float64]:
        """The element centres along one axis, (k - (M - 1)/2) h, symmetric about 0."""
        m = self.size
        return (np.arange(m) - (m - 1) / 2.0) * self.h

    @cached_property
    def xy(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(x, y) of every element centre, each of shape (M, M), indexed [ix, iy]."""
        return np.meshgrid(self.centres, self.centres, indexing="ij")

    @property
    def area(self) -> float:
        """Area h^2 of one element."""
        return self.h * self.h
