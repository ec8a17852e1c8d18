"""Chung & Ooi's (2011) impact tests 4 to 8 (Granular Matter 13: 643-656) as bench cases:
their materials and speeds, one ``core.impact.Impact`` per incidence.

Each test is a function of the incidence theta (deg) of the contact point:

* test 4: a sphere (R = 2.5 mm) on a rigid flat, |v| = 3.9 m/s at theta, no spin,
  mu = 0.092, e = 0.98 (Kharaz, Gorham & Salman's 2001 set-up); alumina or aluminium alloy;
* test 5: R = 10 um on a rigid flat, v_n = 5 m/s, v_t = v_n tan(theta), mu = 0.3, e = 1;
  steel or polyethylene;
* test 6: R = 0.1 m on a rigid flat, v_n = 0.2 m/s, no centre tangential velocity, the
  spin giving the contact point v_n tan(theta) (w = -v_n tan(theta) / R), mu = 0.4, e = 0.5;
* test 7: two identical free spheres (R = 0.1 m), each at 0.2 m/s towards the other, with
  opposite spins w = +-(0.2 / R) tan(theta) about the same axis: their contact points move
  together (no slip), so the spins must come back unchanged;
* test 8: R1 = 0.1 m spinning as in test 6 onto a fixed rigid sphere R2 = 5 R1.

Materials (E, nu, density) are Chung & Ooi's as restated in ../shared/physics.md
(tests 4, 5) and in the bench scripts that reproduce the tests: Yade's
``examples/ChungOoi/Test4.py`` (alumina, aluminium alloy) and Kratos'
``DEMApplication/test_examples/basic_benchmarks/benchmark6DEM.mdpa`` to ``benchmark8DEM.mdpa``
(aluminium alloy, mu = 0.4, e = 0.5, R2 = 0.5 m held and 1000 times stiffer). Tests 6-8's
second materials (nylon, copper) are not in those sources with their constants, so they
are left out rather than guessed.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from core.impact import Impact, Material, Target

MATERIALS: dict[str, Material] = {
    "alumina": Material("alumina", E=380e9, nu=0.23, density=4000.0,
                        source="Chung & Ooi 2011 test 4; Yade Test4.py"),
    "aluminium_alloy": Material("aluminium_alloy", E=70e9, nu=0.33, density=2700.0,
                                source="Chung & Ooi 2011 tests 4, 6-8; Yade Test4.py; "
                                       "Kratos benchmark6-8DEM.mdpa"),
    "steel": Material("steel", E=208e9, nu=0.30, density=7850.0,
                      source="Chung & Ooi 2011 test 5 (physics.md)"),
    "polyethylene": Material("polyethylene", E=1e9, nu=0.40, density=1400.0,
                             source="Chung & Ooi 2011 test 5 (physics.md)"),
}


@dataclass(frozen=True)
class ImpactTest:
    """One of Chung & Ooi's tests: its materials and the impact at an incidence."""

    number: int
    title: str
    materials: tuple[str, ...]
    build: Callable[[Material, float], Impact]

    def impact(self, material: str, incidence_deg: float) -> Impact:
        """The impact of ``material`` at ``incidence_deg`` (0 <= theta < 90)."""
        if material not in self.materials:
            raise ValueError(f"material must be one of {', '.join(self.materials)} for test "
                             f"{self.number}, got {material!r}")
        th = float(incidence_deg)
        if not (math.isfinite(th) and 0.0 <= th < 90.0):
            raise ValueError(f"incidence = {incidence_deg!r} deg is outside [0, 90)")
        return self.build(MATERIALS[material], math.radians(th))


def _test4(m: Material, th: float) -> Impact:
    return Impact(radius=2.5e-3, material=m, mu=0.092, e=0.98,
                  vx=3.9 * math.sin(th), vz=-3.9 * math.cos(th))


def _test5(m: Material, th: float) -> Impact:
    return Impact(radius=1e-5, material=m, mu=0.3, e=1.0, vx=5.0 * math.tan(th), vz=-5.0)


def _test6(m: Material, th: float) -> Impact:
    R = 0.1
    return Impact(radius=R, material=m, mu=0.4, e=0.5, vz=-0.2, w=-0.2 * math.tan(th) / R)


def _test7(m: Material, th: float) -> Impact:
    R = 0.1
    w = 0.2 / R * math.tan(th)
    return Impact(radius=R, material=m, target=Target(radius=R, material=m, free=True),
                  mu=0.4, e=0.5, vz=-0.2, vz2=0.2, w=w, w2=-w)


def _test8(m: Material, th: float) -> Impact:
    R = 0.1
    return Impact(radius=R, material=m, target=Target(radius=5 * R), mu=0.4, e=0.5,
                  vz=-0.2, w=-0.2 * math.tan(th) / R)


TESTS: dict[int, ImpactTest] = {
    4: ImpactTest(4, "sphere on a rigid flat, |v| = 3.9 m/s at varied incidence",
                  ("alumina", "aluminium_alloy"), _test4),
    5: ImpactTest(5, "sphere on a rigid flat, v_n = 5 m/s, v_t varied",
                  ("steel", "polyethylene"), _test5),
    6: ImpactTest(6, "spinning sphere on a rigid flat, v_n = 0.2 m/s", ("aluminium_alloy",),
                  _test6),
    7: ImpactTest(7, "two identical spheres with opposite spins", ("aluminium_alloy",), _test7),
    8: ImpactTest(8, "spinning sphere on a fixed rigid sphere R2 = 5 R1",
                  ("aluminium_alloy",), _test8),
}

#: Chung & Ooi's incidences (5 to 85 deg by 5).
DEFAULT_INCIDENCE = tuple(float(a) for a in range(5, 90, 5))


def impact_test(number: object) -> ImpactTest:
    """The test of that number (4 to 8); ValueError otherwise."""
    if isinstance(number, bool) or not isinstance(number, int) or number not in TESTS:
        raise ValueError(f"test must be one of {', '.join(map(str, TESTS))}, got {number!r}")
    return TESTS[number]


__all__ = ["DEFAULT_INCIDENCE", "MATERIALS", "TESTS", "ImpactTest", "impact_test"]
