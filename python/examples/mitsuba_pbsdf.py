"""Render a polbrdf material in Mitsuba 3 through the stock `measured_polarized` plugin.

    polbrdf export --material paint --output paint.pbsdf     # done by this script
    python python/examples/mitsuba_pbsdf.py [--material paint] [--out docs/img/mitsuba_dolp.png]

Needs the `polbrdf` binary (on PATH or in $POLBRDF_CLI) and `pip install mitsuba numpy`. A sphere
under a uniform sky and a directional light, rendered with the `stokes` integrator in the
`scalar_spectral_polarized` variant (one to three minutes on two cores at 160 × 160 pixels, 32
samples per pixel; DoLP of per-pixel Monte Carlo estimates, so slightly noisy);
writes a picture of the intensity S0 (left) and the DoLP sqrt(S1² + S2²)/S0 (right, 0…1).
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np


def render_stokes(table: Path | str, size: int = 160, spp: int = 32) -> np.ndarray:
    """The Stokes image (S0, S1, S2, S3), shape (size, size, 4), of the example's scene with
    the `.pbsdf` table on the sphere (mean over the integrator's RGB channels)."""
    import mitsuba as mi

    mi.set_variant("scalar_spectral_polarized")
    scene = mi.load_dict({
        "type": "scene",
        "integrator": {"type": "stokes", "integrator": {"type": "path", "max_depth": 3}},
        "sensor": {
            "type": "perspective", "fov": 28,
            "to_world": mi.ScalarTransform4f().look_at(origin=[0, -4.2, 1.2], target=[0, 0, 0],
                                                       up=[0, 0, 1]),
            "film": {"type": "hdrfilm", "width": size, "height": size, "pixel_format": "rgb"},
            "sampler": {"type": "independent", "sample_count": spp},
        },
        "sphere": {"type": "sphere", "bsdf": {"type": "measured_polarized", "filename": str(table),
                                              "alpha_sample": 0.25}},
        "sky": {"type": "constant", "radiance": {"type": "rgb", "value": 0.6}},
        "sun": {"type": "directional", "direction": [0.8, 0.6, -0.5],
                "irradiance": {"type": "rgb", "value": 4.0}},
    })
    img = np.array(mi.render(scene))
    # The stokes integrator's channels: the image (RGB), then S0, S1, S2, S3 (RGB each).
    return img.reshape(size, size, -1, 3).mean(axis=-1)[..., 1:5]


def export(cli: str, material: str, table: Path) -> None:
    """`polbrdf export --material <material> --output <table>`."""
    subprocess.run([cli, "export", "--material", material, "--output", str(table)], check=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--material", default="paint")
    ap.add_argument("--out", default="docs/img/mitsuba_dolp.png")
    ap.add_argument("--size", type=int, default=160)
    ap.add_argument("--spp", type=int, default=32)
    args = ap.parse_args()

    import mitsuba as mi

    cli = os.environ.get("POLBRDF_CLI") or shutil.which("polbrdf") or "polbrdf"
    with tempfile.TemporaryDirectory() as tmp:
        table = Path(tmp) / "material.pbsdf"
        export(cli, args.material, table)
        s = render_stokes(table, args.size, args.spp)
    s0, s1, s2 = s[..., 0], s[..., 1], s[..., 2]
    dolp = np.where(s0 > 1e-6, np.hypot(s1, s2) / np.maximum(s0, 1e-6), 0.0)
    intensity = np.clip(s0 / np.percentile(s0[s0 > 0], 99), 0, 1) ** (1 / 2.2)
    # DoLP on a perceptual ramp (black → magenta → yellow), intensity in grey.
    d = np.clip(dolp, 0, 1)[..., None]
    ramp = np.concatenate([np.clip(2 * d, 0, 1), np.clip(2 * d - 1, 0, 1),
                           np.clip(1.2 * d * (1 - d) * 4, 0, 1)], axis=-1)
    left = np.repeat(intensity[..., None], 3, axis=-1)
    pic = np.concatenate([left, np.ones((left.shape[0], 4, 3)), ramp], axis=1)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    mi.Bitmap(pic.astype(np.float32)).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.UInt8,
                                              srgb_gamma=False).write(str(out))
    print(f"{out}: S0 (left), DoLP 0…1 (right); max DoLP {dolp.max():.3f}")


if __name__ == "__main__":
    main()
