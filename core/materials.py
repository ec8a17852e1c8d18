"""The materials of core, with their sources: isotropic elastic constants, hardness (for
Archard wear) and density (`MATERIALS`); the motor's bodies (the rod's contact layer and
the rotor) are `MOTOR_MATERIALS`, the explorer's identical spheres are the keys of
`DRY_MU`, which holds the typical dry friction coefficient of two bodies of each.

Values are nominal, for a first estimate; a real motor's datasheet wins. Piezoceramics are
transversely isotropic: the isotropic G and nu below are the in-plane ones,
G = 1 / (2 (s11 - s12)) and nu = -s12 / s11 from the short-circuit compliances s^E
(the plane of a rod's top face contains the poling direction for some cuts and not for
others; the in-plane values are within ~20 % of the others). Where a source gives no
value, the entry says so in ``note`` and the value is an assumption.

    from core.materials import MATERIALS
    rotor, rod = MATERIALS["steel"], MATERIALS["PZT-4"]
    Motor(rod_geometry, R=5e-3, G=rotor.G, nu=rotor.nu, mu=0.2, preload=0.05,
          rod_G=rod.G, rod_nu=rod.nu)
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Material:
    """An isotropic elastic material: shear modulus G (Pa), Poisson ratio nu, Vickers
    hardness (Pa; the H of Archard's law), density (kg/m^3), and where the numbers come
    from."""

    name: str
    G: float
    nu: float
    hardness: float
    density: float
    source: str
    note: str = ""

    @property
    def E(self) -> float:
        """Young's modulus 2 G (1 + nu) (Pa)."""
        return 2.0 * self.G * (1.0 + self.nu)


def _pzt(name: str, s11: float, s12: float, density: float, source: str) -> Material:
    """An isotropic stand-in for a piezoceramic from its compliances s11^E, s12^E (m^2/N)."""
    return Material(name, G=1.0 / (2.0 * (s11 - s12)), nu=-s12 / s11, hardness=5.0e9,
                    density=density, source=source,
                    note="hardness assumed (Vickers hardness of dense PZT ceramics is of "
                         "order 4-6 GPa); G, nu in-plane, from s11^E and s12^E")


#: name -> Material. PZT-4, PZT-8: Berlincourt, Curran & Jaffe, "Piezoelectric and piezomagnetic
#: materials and their function in transducers", Physical Acoustics vol. 1A (1964), the
#: table reproduced in manufacturers' datasheets (e.g. Morgan Electro Ceramics, "Properties
#: of piezoelectric ceramics"): PZT-4 s11^E = 12.3, s12^E = -4.05; PZT-8 s11^E = 11.5,
#: s12^E = -3.7 (1e-12 m^2/N).
MATERIALS: dict[str, Material] = {
    "PZT-4": _pzt("PZT-4", 12.3e-12, -4.05e-12, 7500.0,
                  "Berlincourt, Curran & Jaffe (1964); Morgan Electro Ceramics datasheet"),
    "PZT-8": _pzt("PZT-8", 11.5e-12, -3.7e-12, 7600.0,
                  "Berlincourt, Curran & Jaffe (1964); Morgan Electro Ceramics datasheet"),
    "alumina": Material(
        "alumina (99.5 %)", G=152e9, nu=0.22, hardness=14.1e9, density=3890.0,
        source="CoorsTek AD-995 datasheet: E = 370 GPa, G = 152 GPa, nu = 0.22, "
               "HV0.5 1440"),
    "steel": Material(
        "steel (hardened bearing steel, AISI 52100)", G=79.3e9, nu=0.29, hardness=7.4e9,
        density=7830.0,
        source="handbook values for carbon and low-alloy steels (ASM Handbook vol. 1): "
               "G = 79.3 GPa, nu = 0.29; 52100 hardened to ~62 HRC, ~750 HV"),
    "phosphor bronze": Material(
        "phosphor bronze (C51000, spring temper)", G=41.0e9, nu=0.34, hardness=2.0e9,
        density=8860.0,
        source="Copper Development Association, C51000 data: E = 110 GPa, G = 41 GPa "
               "(nu = E / 2G - 1); spring temper ~200 HV"),
    "PEEK composite": Material(
        "PEEK friction composite (carbon fibre, PTFE, graphite; Victrex 450FC30 class)",
        G=4.6e9, nu=0.40, hardness=0.3e9, density=1450.0,
        source="Victrex 450FC30 datasheet: tensile modulus ~13 GPa, density 1.45 g/cm^3",
        note="nu = 0.40 assumed (unfilled PEEK); G = E / (2 (1 + nu)); hardness assumed "
             "(~30 HV, of the order of unfilled PEEK's)"),
    "aluminium": Material(
        "aluminium alloy (6061-T6)", G=26.0e9, nu=0.33, hardness=1.05e9, density=2700.0,
        source="ASM Handbook vol. 2, 6061-T6: E = 68.9 GPa, G = 26 GPa, nu = 0.33, "
               "density 2.70 g/cm^3, 107 HV"),
    "glass": Material(
        "soda-lime glass", G=28.7e9, nu=0.22, hardness=5.5e9, density=2500.0,
        source="handbook values for soda-lime glass (CRC Handbook of Chemistry and "
               "Physics; Shelby, Introduction to Glass Science and Technology): "
               "E = 70 GPa, nu = 0.22, density 2.5 g/cm^3, ~550 HV"),
    "PZT ceramic": Material(
        "PZT ceramic (soft, typical)", G=24.0e9, nu=0.31, hardness=5.0e9, density=7700.0,
        source="typical of soft PZT ceramics (Morgan Electro Ceramics datasheet: PZT-5A "
               "and PZT-5H, 1 / s11^E = 61 GPa, density 7.5-7.75 g/cm^3): "
               "E = 63 GPa, nu = 0.31",
        note="an isotropic stand-in of round numbers between PZT-5A's and PZT-5H's "
             "in-plane constants; hardness assumed as for PZT-4 and PZT-8"),
}

#: The motor's materials (its rod's contact layer and its rotor), in its menus' order.
MOTOR_MATERIALS: tuple[str, ...] = ("PZT-4", "PZT-8", "alumina", "steel",
                                    "phosphor bronze", "PEEK composite")

#: A typical dry friction coefficient of two bodies of one material, for the explorer's
#: identical spheres (its materials: the keys). A friction coefficient belongs to a pair
#: of surfaces and their state (roughness, films, humidity), not to a material: these are
#: starting values for a first estimate, meant to be edited.
DRY_MU: dict[str, float] = {"steel": 0.2, "aluminium": 0.3, "glass": 0.3,
                            "PZT ceramic": 0.2}
