# ruff: noqa: E501  (LaTeX lines are kept whole)
"""The formulas of each contact phase, as HTML with $$...$$ LaTeX (rendered in the
browser by KaTeX, which Panel bundles: `pn.pane.LaTeX`), one equation per line so that
a narrow card stacks them.

Text only: these are the paper's equations (Zharii 1996, restated in docs/physics.md),
shown beside the plots; nothing here is evaluated.
"""

from __future__ import annotations

from html import escape

from core import PHASE_NAMES, Phase

#: The tag of the formula card's model in a page (the browser's player and
#: `app.kit.texts.PaneText` find it by it).
FORMULAS_TAG = "formulas"

_COMMON = r"""
$$p(r) = \frac{4G}{(1-\nu)\pi R}\sqrt{a^2 - r^2}$$

$$a^2 = \tfrac{R}{2} H(\sin\tau - \sin\tau_0)$$
"""

#: Per phase: when it holds and the equations (the phase's name comes from core).
_PHASES: dict[Phase, tuple[str, str]] = {
    Phase.NO_CONTACT: ("", r"""
The spheres are apart (τ < τ₀ or τ > π − τ₀): no force.
"""),
    Phase.FULL_STICK: ("ψ ≤ 1; eqs 36, 38", r"""
$$\tau_u(r) = \psi \mu p(r)$$

$$T = \psi T_0 (\sin\tau - \sin\tau_0)^{3/2}$$
"""),
    Phase.SLIP: ("while loading, τ₀ ≤ τ ≤ π/2; eqs 18, 39", r"""
$$\tau_u(r) = \mu p(r)$$

$$T = T_0 (\sin\tau - \sin\tau_0)^{3/2}$$
"""),
    Phase.PARTIAL_STICK: ("π/2 < τ < τ₁; eqs 24, 30, 39", r"""
$$\tau_u(r) = -\frac{4\mu G}{(1-\nu)\pi R}\left[\sqrt{a^2-r^2} - 2\sqrt{b^2-r^2}\right] \quad (r \le b)$$

$$\tau_u(r) = -\mu p(r) \quad (b \lt r \lt a)$$

$$b^2 = \frac{\psi+1}{2} \frac{RH}{2} (\sin\tau - \sin\tau_1)$$

$$\sin\tau_1 = 1 - \frac{2(1-\sin\tau_0)}{\psi+1}$$

$$T = T_0\left[2\left(\frac{\psi+1}{2}\right)^{3/2}(\sin\tau - \sin\tau_1)^{3/2} - (\sin\tau - \sin\tau_0)^{3/2}\right]$$
"""),
    Phase.COUNTER_SLIP: ("τ₁ ≤ τ ≤ π − τ₀; eqs 33, 39", r"""
$$\tau_u(r) = -\mu p(r)$$

$$T = -T_0 (\sin\tau - \sin\tau_0)^{3/2}$$
"""),
}


def _body(phase: Phase) -> list[str]:
    """The paragraphs of phase `phase`'s equations (and the common ones in contact)."""
    _, body = _PHASES[phase]
    common = _COMMON if phase else ""
    return [" ".join(block.split("\n")).strip()
            for block in f"{body}\n{common}".split("\n\n") if block.strip()]


def _title(phase: Phase) -> str:
    when, _ = _PHASES[phase]
    name = PHASE_NAMES[phase]
    return f"{name[0].upper()}{name[1:]}" + (f" ({when})" if when else "")


#: Inline styles (the text is the whole of the pane, wherever it is shown): every
#: phase's equations stacked in one grid cell, the phase's own on top, the others hidden
#: (`visibility`: not seen, not read aloud), so that the equations take the height of the
#: tallest phase's at any width and the page under them never moves when the phase
#: changes.
_STACK = "display: grid; grid-template-columns: minmax(0, 1fr);"
_CELL = "grid-area: 1 / 1; min-width: 0;"
_SPARE = f'style="{_CELL} visibility: hidden;" aria-hidden="true"'


def formulas(phase: int) -> str:
    """HTML (with $$...$$ math, one paragraph each) for the contact phase `phase` (a
    core.Phase code): its name and when it holds in bold, then its equations.

    The other phases' equations are there too, hidden in the same place (`_STACK`): the
    text is as tall as with the tallest phase's (partial stick's) at any width, so a
    change of phase (while playing, at the frame it happens) never moves what is below."""
    phase = Phase(int(phase))

    def paragraphs(p: Phase) -> str:
        return "".join(f"<p>{escape(text, quote=False)}</p>" for text in _body(p))

    spares = "".join(f"<div {_SPARE}>{paragraphs(p)}</div>" for p in Phase
                     if p != phase and _body(p))
    return (f"<p><b>{escape(_title(phase))}</b></p>"
            f'<div style="{_STACK}"><div style="{_CELL}">{paragraphs(phase)}</div>'
            f"{spares}</div>")
