"""Hemispherical maps of the DoLP (and BRDF) of the reflected light for one illumination.

    python python/examples/dolp_map.py [--material paint] [--theta-i 60] [--out dolp_map.png]

``--material`` is a preset name or a material file (TOML). The source is at zenith angle
``--theta-i`` (degrees) and azimuth 0; the maps cover every viewing direction of the upper
hemisphere (polar plot: radius = viewing zenith angle θr in degrees, angle = azimuth φr; the
specular direction is at φr = 180°). Needs matplotlib; without it the script says so and exits.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

import polbrdf


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--material", default="paint", help="preset name or material TOML file")
    p.add_argument("--theta-i", type=float, default=60.0, help="source zenith angle, degrees")
    p.add_argument("--out", type=Path, default=Path("dolp_map.png"), help="output image")
    p.add_argument("--show", action="store_true", help="also open a window")
    args = p.parse_args(argv)

    try:
        import matplotlib

        if not args.show:
            matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.colors import LogNorm
    except ImportError:
        print("dolp_map: matplotlib is not installed (pip install matplotlib); no plot made.")
        return 0

    if Path(args.material).is_file():
        material = polbrdf.Material.from_toml(args.material)
    else:
        material = polbrdf.Material.preset(args.material)

    # Viewing hemisphere: theta_r in [0, 89.5] deg, phi_r in [0, 360] deg; broadcast (R,1)x(1,P).
    theta_r = np.linspace(0.0, 89.5, 180)[:, None]
    phi_r = np.linspace(0.0, 360.0, 361)[None, :]
    e = polbrdf.evaluate(material, args.theta_i, 0.0, theta_r, phi_r)

    fig, axes = plt.subplots(1, 2, subplot_kw={"projection": "polar"}, figsize=(11, 5))
    phi_rad = np.radians(phi_r)
    im = axes[0].pcolormesh(phi_rad, theta_r, e.dolp, shading="auto", vmin=0, vmax=1)
    fig.colorbar(im, ax=axes[0], label="DoLP (unpolarized source)")
    axes[0].set_title("DoLP")
    im = axes[1].pcolormesh(
        phi_rad, theta_r, e.brdf, shading="auto", norm=LogNorm(vmin=max(e.brdf.min(), 1e-4))
    )
    fig.colorbar(im, ax=axes[1], label="BRDF f (sr⁻¹)")
    axes[1].set_title("BRDF")
    for ax in axes:
        ax.set_rlim(0, 90)
        ax.set_rticks([30, 60, 90])
        ax.plot([np.pi], [args.theta_i], "r+", markersize=12)  # specular direction
    name = material.name or str(args.material)
    fig.suptitle(f"{name}: source at θi = {args.theta_i:g}°, φi = 0° (+: specular)")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"dolp_map: wrote {args.out}")
    if args.show:
        plt.show()
    return 0


if __name__ == "__main__":
    sys.exit(main())
