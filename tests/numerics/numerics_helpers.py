"""Shared fixtures: the closed form of ``core`` is the reference of these tests."""

from __future__ import annotations

import numpy as np


def max_error(contact, res) -> float:
    """max |T - T_closed| / T0 over the method's own times."""
    return float(np.max(np.abs(res.T - contact.tangential_force(res.tau))))


def slope(resolutions, errors) -> float:
    """Least-squares slope of log(error) against log(resolution)."""
    return float(np.polyfit(np.log(resolutions), np.log(errors), 1)[0])
