"""Helpers shared by the tests (imported as `support`; pytest puts this folder on sys.path)."""

from __future__ import annotations

import os
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


def cli_binary() -> Path | None:
    """The `polbrdf` CLI binary: $POLBRDF_CLI, else target/{debug,release}/polbrdf if built."""
    env = os.environ.get("POLBRDF_CLI")
    if env:
        return Path(env)
    for profile in ("debug", "release"):
        p = REPO / "target" / profile / "polbrdf"
        if p.is_file() and os.access(p, os.X_OK):
            return p
    return None


#: Why a test that runs the CLI is skipped when there is no binary.
NO_CLI = (
    "the polbrdf CLI binary is not built (run `cargo build -p polbrdf-cli` in the repository "
    "root, or set POLBRDF_CLI to its path)"
)
