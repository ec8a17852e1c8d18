"""`parse_query` applies a link to a scratch state: the state's own rules decide what
follows from a preset, a material, the drive and the physical inputs."""

from __future__ import annotations

from app.contact.query import parse_query
from app.contact.state import PRESETS, SQRT2_1, ExplorerState, drive_angle
from app.page.url import apply_contact
from core import DRY_MU, MATERIALS


def applied(query: dict) -> tuple[ExplorerState, list[str]]:
    """A fresh state with `query` applied as a page applies a link."""
    state = ExplorerState()
    return state, apply_contact(state, query)


def test_a_psi_of_another_contact_leaves_the_preset_even_if_it_is_the_default() -> None:
    # psi = the default psi: no change event of psi, yet not fig7b's contact
    values, messages = parse_query({"preset": "fig7b", "psi": repr(SQRT2_1)})
    assert messages == [] and values["psi"] == SQRT2_1 and values["preset"] == ""
    state, _ = applied({"preset": "fig7b", "psi": repr(SQRT2_1)})
    assert (state.preset, state.psi, state.tau) == ("", SQRT2_1, PRESETS["fig7b"].tau)
    assert state.theta == drive_angle(SQRT2_1, 0.2, 0.3)


def test_refused_physical_inputs_keep_the_preset_whose_contact_is_shown() -> None:
    query = {"preset": "fig6f", "physical": "1", "h": "5e-06"}
    values, messages = parse_query(query)
    assert len(messages) == 1 and messages[0].startswith("the physical inputs are not applied")
    assert values["physical"] is False and values["preset"] == "fig6f"
    state, _ = applied(query)
    assert state.preset == "fig6f" and state.matches("fig6f") and state.h == 5e-6


def test_a_material_after_a_preset_sets_its_constants_and_leaves_the_preset() -> None:
    values, messages = parse_query({"preset": "fig4", "material": "aluminium"})
    m = MATERIALS["aluminium"]
    assert messages == []
    assert (values["G"], values["nu"], values["mu"]) == (m.G, m.nu, DRY_MU["aluminium"])
    assert values["physical"] is True and values["preset"] == ""
    assert values["material"] == "aluminium"
    state, _ = applied({"preset": "fig4", "material": "aluminium"})
    c = state.contact()
    assert (state.psi, state.tau0) == (c.psi, c.tau0) and c.scales is not None


def test_the_drive_angle_and_psi_of_one_link_are_applied_together() -> None:
    # theta and the psi that gives it: psi is kept as the very float (not recomputed)
    theta = drive_angle(3.3, 0.35, 0.3)
    query = {"drive": "angle", "theta": repr(theta), "psi": "3.3", "mu": "0.35"}
    values, messages = parse_query(query)
    assert messages == [] and (values["psi"], values["theta"]) == (3.3, theta)
    # a psi that does not give theta follows from it, said
    values, messages = parse_query({**query, "psi": "5"})
    assert messages == ["psi = '5' ignored: with drive = angle it follows from theta, mu "
                        "and nu"]
    assert values["psi"] == ExplorerState(drive="angle", theta=theta, mu=0.35).drive_psi()


def test_a_drive_angle_whose_psi_is_out_of_range_is_not_applied() -> None:
    values, messages = parse_query({"drive": "angle", "theta": "90"})
    assert len(messages) == 1 and messages[0].startswith(
        "the drive angle is not applied: psi = ") and "[0, 1e+12]" in messages[0]
    assert values["drive"] == "psi" and "theta" not in values
