"""Suspicious units warn (issue 36; docs/bridges.md "Unit warnings"): a roughness below 1° and
angles in degree arguments that all look like radians raise ``UserWarning`` (the category is
documented) with the core's message, and the call still returns its result."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import polbrdf


def test_a_roughness_below_one_degree_warns() -> None:
    with pytest.warns(UserWarning, match=r"^Material: sigma_deg = 0\.26 is below 1°, a "
                      r"near-mirror; if 0\.26 is in radians, write sigma_deg = 14\.8969$"):
        m = polbrdf.Material(n=1.5, sigma_deg=0.26)
    assert m.sigma_deg == 0.26
    with pytest.warns(UserWarning, match=r"^m\.toml: sigma_deg = 0\.5 is below 1°"):
        polbrdf.Material.from_toml_str("n = 1.5\nsigma_deg = 0.5\n", source="m.toml")
    with pytest.warns(UserWarning, match=r"tau_deg = 0\.2 is below 1°"):
        polbrdf.Material(n=1.5, sigma_deg=10.0, tau_deg=0.2)


def test_plausible_materials_do_not_warn() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        polbrdf.Material(n=1.5, sigma_deg=1.0)
        polbrdf.Material(n=1.5, sigma_deg=12.0, tau_deg=0.2, shadowing=False)
        for name in polbrdf.Material.presets():
            polbrdf.Material.preset(name)


def test_fit_warns_about_radians_in_degree_angles() -> None:
    paint = polbrdf.Material.preset("paint")
    theta = np.linspace(10, 70, 12)
    brdf = polbrdf.brdf(paint, theta, 0.0, theta, 180.0)
    with pytest.warns(UserWarning, match=r"^polbrdf\.fit \(degrees=True\): every angle in "
                      r"theta_i_deg, phi_i_deg, theta_r_deg, phi_r_deg is small"):
        polbrdf.fit(paint, np.radians(theta), 0.0, np.radians(theta), np.pi, {"brdf": brdf},
                    "rho_d")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = polbrdf.fit(paint, theta, 0.0, theta, 180.0, {"brdf": brdf}, "rho_d")
        assert r.values[0] == pytest.approx(paint.rho_d, abs=1e-6)
        # Radians given as radians: no warning.
        polbrdf.fit(paint, np.radians(theta), 0.0, np.radians(theta), np.pi, {"brdf": brdf},
                    "rho_d", degrees=False)
