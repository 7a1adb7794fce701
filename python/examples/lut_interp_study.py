"""Interpolation error of a lookup table against its resolution (docs/scaling.md).

A table over θi, θr ∈ [0°, 72°], Δφ ∈ [0°, 180°] at steps of 12°, 6°, 3°, 1.5°, read back
through ``Dataset.interp`` (linear) at 2000 random geometries, compared with direct evaluation:

- "off-specular": θi, θr ∈ [10°, 60°], Δφ ∈ [20°, 160°];
- "specular": θr = θi ∈ [10°, 60°], Δφ = 180° (the peak of the facet distribution).

Prints, per material and step, the largest error of the Mueller matrix relative to the largest
|F| at those points, and the largest absolute DoLP error.

    python lut_interp_study.py
"""

from __future__ import annotations

import numpy as np

import polbrdf
from polbrdf.xarray import lut


def main() -> None:
    rng = np.random.default_rng(11)
    n = 2000
    sets = {
        "off-specular": (rng.uniform(10, 60, n), rng.uniform(10, 60, n), rng.uniform(20, 160, n)),
    }
    t = rng.uniform(10, 60, n)
    sets["specular"] = (t, t, np.full(n, 180.0))
    paint = polbrdf.Material.preset("paint")
    materials = {
        f"paint (σ = {paint.sigma_deg:g}°)": paint,
        "smooth (n = 1.5, σ = 5°)": polbrdf.Material(n=1.5, sigma_deg=5.0, rho_d=0.01),
    }
    print("| material | points | step | max rel. error of F | max abs. error of DoLP |")
    print("|---|---|---|---|---|")
    for name, m in materials.items():
        for where, (ti, tr, dp) in sets.items():
            want = polbrdf.evaluate(m, ti, 0.0, tr, dp, with_mueller=True)
            for step in (12.0, 6.0, 3.0, 1.5):
                axis = np.linspace(0.0, 72.0, round(72 / step) + 1)
                dphi = np.linspace(0.0, 180.0, round(180 / step) + 1)
                ds = lut(m, [0.6], axis, axis, dphi, quantities=("mueller", "dolp"))
                at = ds.isel(material=0, wavelength=0).interp(
                    theta_i=("p", ti), theta_r=("p", tr), dphi=("p", dp)
                )
                em = np.abs(at.mueller.values - want.mueller).max() / np.abs(want.mueller).max()
                ed = np.abs(at.dolp.values - want.dolp).max()
                print(f"| {name} | {where} | {step:g}° | {em:.2e} | {ed:.2e} |")


if __name__ == "__main__":
    main()
