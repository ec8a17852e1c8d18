"""The symbols of the page in plain words, for a class: one sentence each.

The lesson file (`app.contact.lesson`) prints them under its plots; every entry names
what the symbol stands for in the paper (Zharii 1996) and, where it has one, its unit.
"""

from __future__ import annotations

#: Symbol -> what it is, in plain words.
GLOSSARY: dict[str, str] = {
    "ψ (psi)": "how strongly the drive pushes sideways compared with what friction can "
               "hold (ψ = tan θ / tan θ₀); above 1 the spheres slip at first touch",
    "θ (theta)": "the angle of the lower sphere's path from the vertical (degrees)",
    "θ₀": "the critical angle: below it the contact sticks at first",
    "τ (tau)": "the time, as an angle of the oscillation: τ = ωt, in radians",
    "τ₀ (tau0)": "when the spheres touch: they touch while sin τ > sin τ₀, until π − τ₀",
    "τ₁ (tau1)": "when the central stick disc disappears and the contact slips back",
    "P, P₀": "the force pressing the spheres together, and its scale P₀",
    "T, T₀": "the friction force along the contact, and its scale T₀ = μP₀",
    "μ (mu)": "the friction coefficient: T can never exceed μP (Coulomb's law)",
    "ν (nu)": "Poisson's ratio of the spheres' material",
    "a, b": "the radius of the contact patch, and of the stick disc inside it",
    "a*": "the largest contact radius, reached at τ = π/2",
    "stick / slip": "stick: the surfaces move together; slip: they slide over each other",
}
