"""The README's contrast studies from Python, end to end: which view reveals the target against
its background.

    python python/examples/contrast_study.py OUT_DIR [--grid 1,2]

1. Visible, under the sun: olive paint against dry soil, the sun at 50° zenith
   (``polbrdf contrast --target examples/olive-paint.toml --background examples/dry-soil.toml
   --sun-zenith-deg 50``).
2. Thermal infrared, in a scene: the target and background of ``examples/lwir-scene.toml``
   (8–12 µm band, sky, atmosphere, temperatures: ``polbrdf contrast --scene …``).

Each study is one call of :func:`polbrdf.contrast` (the CLI's own task: the same numbers as its
``contrast.csv`` and ``best.json``). For each, the script prints the best directions and saves
polar maps (radius: view zenith θr, angle: azimuth φr) of the target's DoLP, the background's,
and ΔDoLP with the ranked directions marked; for the scene also ΔS0, the radiance difference, and
the polarization-null loci. Figures go to OUT_DIR (created if needed). Needs matplotlib.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np

import polbrdf

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def polar(ax: Any, study: polbrdf.ContrastStudy, name: str, label: str, cmap: str) -> None:
    """One map of ``study`` on a polar axis, the grid closed over 360°."""
    phi = np.radians(np.append(study.phi_r_deg, study.phi_r_deg[0] + 360.0))
    values = study[name]
    values = np.concatenate([values, values[:, :1]], axis=1)
    finite = values[np.isfinite(values)]
    lim = float(np.max(np.abs(finite))) if finite.size else 1.0
    signed = bool(finite.size and finite.min() < 0)
    im = ax.pcolormesh(
        phi, study.theta_r_deg, values, shading="auto", cmap=cmap,
        vmin=-lim if signed else 0.0, vmax=lim or 1.0,
    )  # fmt: skip
    ax.figure.colorbar(im, ax=ax, label=label, shrink=0.8)
    ax.set_rlim(0, 90)
    ax.set_rticks([30, 60, 90])
    ax.set_title(label, fontsize=10)


def mark_best(ax: Any, study: polbrdf.ContrastStudy) -> None:
    for rank, d in enumerate(study.top, start=1):
        ax.plot(np.radians(d["phi_r_deg"]), d["theta_r_deg"], "k+", markersize=9)
        ax.annotate(str(rank), (np.radians(d["phi_r_deg"]), d["theta_r_deg"]), fontsize=7)


def report(title: str, study: polbrdf.ContrastStudy) -> None:
    print(f"{title}: best directions by {study.best['ranking']['by']}")
    print("    #   θr (°)   φr (°)  DoLP targ.  DoLP back.    ΔDoLP")
    for rank, d in enumerate(study.top, start=1):
        print(
            f"  {rank:3d} {d['theta_r_deg']:8.2f} {d['phi_r_deg']:8.2f} {d['dolp_target']:11.4f}"
            f" {d['dolp_background']:11.4f} {d['delta_dolp']:+8.4f}"
        )
    for w in study.warnings:
        print(f"  warning: {w}")


def figure(plt: Any, study: polbrdf.ContrastStudy, title: str, out: Path) -> None:
    names = [("dolp_target", "DoLP, target", "viridis"),
             ("dolp_background", "DoLP, background", "viridis"),
             ("delta_dolp", "ΔDoLP = target − background", "RdBu_r")]  # fmt: skip
    if "radiance_difference" in study.columns:
        names.append(("radiance_difference", "ΔS0 (target − background)", "RdBu_r"))
    fig, axes = plt.subplots(
        1, len(names), subplot_kw={"projection": "polar"}, figsize=(4.6 * len(names), 4.6)
    )
    for ax, (name, label, cmap) in zip(axes, names):
        polar(ax, study, name, label, cmap)
    mark_best(axes[2], study)
    nulls = study.null_loci
    if nulls:
        for key, style in (("target", "w."), ("background", "m.")):
            locus = np.asarray(nulls[key], dtype=float).reshape(-1, 2)
            if len(locus):
                axes[2].plot(np.radians(locus[:, 1]), locus[:, 0], style, markersize=3)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    plt.close(fig)
    print(f"  wrote {out}")


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("out", type=Path, help="folder for the figures (created if needed)")
    p.add_argument("--grid", default="1,2", help="grid steps Δθ,Δφ in degrees (default 1,2)")
    args = p.parse_args(argv)
    grid = [float(x) for x in args.grid.split(",")]
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("contrast_study: matplotlib is not installed (pip install matplotlib)")
        return 1
    args.out.mkdir(parents=True, exist_ok=True)

    visible = polbrdf.contrast(
        EXAMPLES / "olive-paint.toml",
        EXAMPLES / "dry-soil.toml",
        polbrdf.Illumination(sun_zenith_deg=50),
        grid=grid,
    )
    report("visible: olive paint against dry soil, sun at 50°", visible)
    figure(plt, visible, "Olive paint vs dry soil, sun θi = 50° (+: best directions)",
           args.out / "visible_contrast.png")  # fmt: skip

    lwir = polbrdf.contrast(None, None, EXAMPLES / "lwir-scene.toml", grid=grid)
    report("LWIR scene (8–12 µm)", lwir)
    temperature = (lwir.null_loci or {}).get("uniform_sky_null_temperature_k")
    if temperature is not None:
        print(f"  under this uniform sky both lose their polarization at {temperature:.2f} K")
    figure(plt, lwir, "LWIR scene, 8–12 µm: target vs background (+: best directions)",
           args.out / "lwir_contrast.png")  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main())
