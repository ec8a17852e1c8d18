"""What to notice in each of the paper's figures: a few plain words per preset, shown
under the preset selector while the preset's contact is on screen (at any tau: the notes
of Fig. 6 name their own tau).

Text only, for a class; each statement is one the plots of the preset show (the tests
check the ones that are numbers: phases, signs, where the stick disc starts and ends).
"""

from __future__ import annotations

#: Per preset key of `app.contact.state.PRESETS`: what to look at.
NOTES: dict[str, str] = {
    "fig4": "The contact radius a grows while the spheres approach and shrinks as they "
            "part. The stick disc b appears at π/2, when unloading starts, as large as "
            "the whole contact, and shrinks to nothing at τ₁ = 3π/4. Disks a-f mark the "
            "times of the six profiles of Fig. 6.",
    "fig6a": "τ = π/4, loading with ψ = 2.414 > 1: the drive is more oblique (more "
             "tangential) than the critical angle, so the whole contact slips forward "
             "and the traction is μ times the Hertz pressure everywhere (half an "
             "ellipse).",
    "fig6b": "τ = π/3, still loading: the contact has grown, and it still slips as a whole: "
             "τᵤ = μp.",
    "fig6c": "τ = π/2: the spheres stop approaching. The contact is at its largest and this "
             "is the last instant of forward slip.",
    "fig6d": "τ = 7π/12, unloading: the centre sticks again while the rim slips backwards. The "
             "traction is −μp in the rim and the difference of two ellipses in the stick "
             "disc.",
    "fig6e": "τ = 17π/24, later in partial stick: the stick disc is smaller; the forward traction "
             "inside it and the backward traction in the rim nearly cancel: T has just "
             "changed sign and is small.",
    "fig6f": "τ = τ₁ = 3π/4: the stick disc has shrunk to nothing; from now until the "
             "spheres part the whole contact slips backwards (counter-slip), τᵤ = −μp.",
    "fig7a": "ψ ≤ 1: the drive is no more oblique than the critical angle, so the contact "
             "sticks all the time it lasts; T rises and falls symmetrically about π/2 "
             "(ψ = 1 touches the slip bound μP).",
    "fig7b": "ψ > 1: T follows +μP while loading, then switches to −μP; the larger ψ, "
             "the sooner after π/2 the switch ends (τ₁ = 3π/4, 2π/3, 7π/12).",
    "fig8": "The tangential impulse over μ times the normal impulse is largest at ψ = 1 "
            "and falls off slowly (like ψ^(-1/2)) for more oblique drives; points 1-6 are the "
            "ψ of the curves of Fig. 7.",
    "fig9": "The contact centre's velocity jumps when the contact starts, at τ₁ and when "
            "it ends; during partial stick it moves with half the drive's velocity.",
}
