"""Helpers shared by the tests (imported as `support`; pytest puts this folder on sys.path)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import polbrdf

#: The repository root: python/tests/support.py -> python/tests -> python -> root.
REPO = Path(__file__).resolve().parents[2]
VECTORS = REPO / "tests" / "data" / "test-vectors.json"


def material_of(inp: dict[str, Any]) -> polbrdf.Material:
    """The material of a test-vector case, as a user would write it: sigma_deg with the
    hemispherical normalization (so `a` is recomputed), explicit `a` and `b` otherwise."""
    hemisphere = inp["a_source"] == "hemisphere"
    return polbrdf.Material(
        n=inp["N"][0],
        k=inp["N"][1],
        sigma_deg=inp["sigma_deg"] if hemisphere else None,
        b=None if hemisphere else inp["b"],
        a=None if hemisphere else inp["a"],
        form=inp["form"],
        shadowing=inp["shadow"],
        tau_deg=inp["tau_deg"],
        omega_deg=inp["Omega_deg"],
        azimuth_term=inp["azimuth_term"],
        rho_d=inp["rho_D"],
        rho_v=inp["rho_V"],
    )
