"""Mitsuba 3 as the peer of `polbrdf export` (docs/model.md §20): the stock
`measured_polarized` plugin loads an exported `.pbsdf` table, and its `bsdf.eval` agrees with
polbrdf's pBRDF after the documented frame conversion; Mitsuba's `roughconductor` checks that
conversion (frames and the sign of S3) independently of the table. Needs the `polbrdf` binary
($POLBRDF_CLI) and the `mitsuba` package (variant `scalar_spectral_polarized`); skipped with
the reason when either is absent.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import numpy as np
import pytest
from test_cli import CLI

import polbrdf
from polbrdf import bridges

mi = pytest.importorskip("mitsuba", reason="mitsuba is not installed (pip install mitsuba)")
if "scalar_spectral_polarized" not in mi.variants():  # pragma: no cover
    pytest.skip("mitsuba lacks the scalar_spectral_polarized variant", allow_module_level=True)
pytestmark = pytest.mark.skipif(CLI is None, reason="no polbrdf binary (set POLBRDF_CLI)")
mi.set_variant("scalar_spectral_polarized")


@pytest.fixture(autouse=True)
def _variant() -> None:
    # Mitsuba's variant is global: another test module (test_peer_mitsuba.py) may have chosen
    # its own since this one was imported.
    mi.set_variant("scalar_spectral_polarized")

#: The test grid: φ_d 10°, θ_d 2°, θ_h 1° (the default of `polbrdf export`).
GRID = (37, 46, 91)
BANDS = (450, 500, 550, 600, 650)


def direction(theta: np.ndarray, phi: np.ndarray) -> np.ndarray:
    return np.stack(
        [np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], axis=-1
    )


def mitsuba_frames(f: np.ndarray, wi: np.ndarray, wr: np.ndarray, out_x, in_x):
    """A psps pBRDF (docs/model.md §2) re-expressed by Mitsuba's own `rotate_mueller_basis` in
    the given reference axes, with Mitsuba's sign of S3 (docs/model.md §20). Mitsuba's implicit
    bases are `polbrdf.bridges.mueller_to_mitsuba`'s (test_bridges_peers.py)."""
    pi, pr = np.arctan2(wi[1], wi[0]), np.arctan2(wr[1], wr[0])
    s_in = mi.Vector3f(np.sin(pi), -np.cos(pi), 0.0)
    s_out = mi.Vector3f(-np.sin(pr), np.cos(pr), 0.0)
    k_in, k_out = mi.Vector3f(*(-wi)), mi.Vector3f(*wr)
    x_in, x_out = mi.Vector3f(*in_x), mi.Vector3f(*out_x)
    m = np.array(mi.mueller.rotate_mueller_basis(
        mi.Matrix4f(f.tolist()), k_in, s_in, x_in, k_out, s_out, x_out
    ))
    # Mitsuba's S3 is minus psps's (its Fresnel amplitudes take N = n − ik): P·M·P.
    p = np.diag([1.0, 1.0, 1.0, -1.0])
    return p @ m @ p


def mitsuba_eval(bsdf, wi: np.ndarray, wr: np.ndarray, wavelengths) -> np.ndarray:
    """`bsdf.eval` in radiance mode, light toward `wi`, camera toward `wr`: shape (4, 4, n_λ)."""
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(*wr)
    si.wavelengths = list(wavelengths)
    return np.array(bsdf.eval(mi.BSDFContext(), si, mi.Vector3f(*wi)))


def rusinkiewicz(wi: np.ndarray, wr: np.ndarray) -> tuple[float, float, float]:
    """(φ_d, θ_d, θ_h) as the plugin computes them (after its φ rotation; invariant)."""
    h = (wi + wr) / np.linalg.norm(wi + wr)
    b = np.cross([0.0, 0.0, 1.0], h)
    b /= np.linalg.norm(b)
    t = np.cross(b, h)
    p = wi - np.dot(wi, h) * h
    return np.arctan2(np.dot(b, p), np.dot(t, p)), np.arccos(np.dot(h, wi)), np.arccos(h[2])


@pytest.fixture(scope="module")
def exported(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("pbsdf") / "paint.pbsdf"
    assert CLI is not None
    subprocess.run(
        [str(CLI), "export", "--material", "paint", "--output", str(out),
         "--grid", ",".join(map(str, GRID))],
        check=True, capture_output=True,
    )
    return out


def test_roughconductor_fixes_the_frames_and_the_sign_of_s3() -> None:
    # Mitsuba's rough conductor is F(β)·D·G/(4cosθ) with the Fresnel Mueller matrix in the
    # facet's s-p frames turned into Mitsuba's bases; polbrdf's surface term without volume and
    # shadowing is the same Fresnel Mueller matrix times a scalar. Normalized by M00 the two
    # must agree entry by entry: any error in the frame conversion or in the sign of S3 shows.
    n, k = 0.27, 3.41
    bsdf = mi.load_dict({"type": "roughconductor", "distribution": "beckmann", "alpha": 0.3,
                         "eta": n, "k": k})
    mat = polbrdf.Material(n=n, k=k, sigma_deg=12.0, shadowing=False, rho_d=0.0, rho_v=0.0)
    rng = np.random.default_rng(3)
    coupling = 0.0
    compared = 0
    while compared < 40:
        ti, tr = rng.uniform(0.05, 1.3, 2)
        pi, pr = rng.uniform(-np.pi, np.pi, 2)
        wi, wr = direction(ti, pi), direction(tr, pr)
        got = mitsuba_eval(bsdf, wi, wr, [550.0] * 4)[:, :, 0]
        if got[0, 0] < 1e-6:
            continue  # the Beckmann lobe (α = 0.3) underflows in float32 far from specular
        f = polbrdf.mueller(mat, ti, pi, tr, pr, degrees=False)
        want = bridges.mueller_to_mitsuba(f, ti, pi, tr, pr, degrees=False)
        np.testing.assert_allclose(got / got[0, 0], want / want[0, 0], atol=2e-5)
        compared += 1
        coupling = max(coupling, abs(want[2, 3]) / want[0, 0], abs(want[3, 2]) / want[0, 0])
    # S3 is there to be tested: the conductor's retardance couples S2 and S3 strongly.
    assert coupling > 0.1


def test_measured_polarized_at_grid_nodes(exported: Path) -> None:
    # At a node the plugin's multilinear interpolation returns the stored matrix: the plugin's
    # eval / cosθ_i must equal polbrdf's pBRDF in Mitsuba's frames to float32 precision (1e-4
    # of the largest entry allows for the float32 rounding of the angles), after turning both
    # directions about the normal by a random φ_h (the plugin's isotropy rotation).
    bsdf = mi.load_dict({"type": "measured_polarized", "filename": str(exported)})
    mat = polbrdf.Material.preset("paint")
    p_nodes = np.linspace(-np.pi, np.pi, GRID[0])
    d_nodes = np.linspace(0, np.pi / 2, GRID[1])
    h_nodes = np.linspace(0, np.pi / 2, GRID[2])
    rng = np.random.default_rng(5)
    done = 0
    while done < 40:
        pd = p_nodes[rng.integers(1, GRID[0] - 1)]
        td = d_nodes[rng.integers(1, GRID[1] - 1)]
        th = h_nodes[rng.integers(1, GRID[2] - 1)]
        h = np.array([np.sin(th), 0.0, np.cos(th)])
        t = np.array([np.cos(th), 0.0, -np.sin(th)])
        b = np.array([0.0, 1.0, 0.0])
        wi = np.cos(td) * h + np.sin(td) * (np.cos(pd) * t + np.sin(pd) * b)
        wr = 2 * np.cos(td) * h - wi
        if wi[2] < 0.1 or wr[2] < 0.1:
            continue
        a = rng.uniform(0, 2 * np.pi)
        rot = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
        wi, wr = rot @ wi, rot @ wr
        ti, pi = np.arccos(wi[2]), np.arctan2(wi[1], wi[0])
        tr, pr = np.arccos(wr[2]), np.arctan2(wr[1], wr[0])
        f = polbrdf.mueller(mat, ti, pi, tr, pr, degrees=False)
        want = bridges.mueller_to_mitsuba(f, ti, pi, tr, pr, degrees=False)
        got = mitsuba_eval(bsdf, wi, wr, BANDS[:4]) / wi[2]
        for band in range(4):
            np.testing.assert_allclose(got[:, :, band], want, atol=1e-4 * np.abs(want).max())
        done += 1


def test_measured_polarized_between_nodes(exported: Path) -> None:
    # Between nodes the plugin interpolates multilinearly in (φ_d, θ_d, θ_h) in the
    # plane-of-reflection frame, then turns the result into Mitsuba's bases (an orthogonal map
    # of the matrix). Its weights are non-negative and sum to one, so the interpolated matrix
    # lies within max over the 8 surrounding cells of ‖T_cell − T(x)‖_F of the exact one: that
    # is the interpolation error this test allows (computed per geometry from the stored table),
    # plus 1e-4 of F00 for float32.
    bsdf = mi.load_dict({"type": "measured_polarized", "filename": str(exported)})
    table = mi.tensor_io.read(str(exported))
    axes = [table["phi_d"][0], table["theta_d"][0], table["theta_h"][0]]
    mat = polbrdf.Material.preset("paint")
    rng = np.random.default_rng(11)
    rel = []
    done = 0
    while done < 60:
        ti, tr = rng.uniform(0.05, 1.35, 2)
        pi, pr = rng.uniform(-np.pi, np.pi, 2)
        wi, wr = direction(ti, pi), direction(tr, pr)
        coords = rusinkiewicz(wi, wr)
        cells = []
        for c, ax in zip(coords, axes):
            j = int(np.clip(np.searchsorted(ax, c) - 1, 0, len(ax) - 2))
            cells.append((j, j + 1))
        corners = [table["M"][p, d, h, 0] for p in cells[0] for d in cells[1] for h in cells[2]]
        # Below-horizon cells are stored as zero (no cell touches the horizon here: skip those).
        if any(not np.any(cn) for cn in corners):
            continue
        f = polbrdf.mueller(mat, ti, pi, tr, pr, degrees=False)
        x = np.cross(wi, wr)
        x /= np.linalg.norm(x)
        t_exact = mitsuba_frames(f, wi, wr, out_x=x, in_x=x)
        bound = max(np.linalg.norm(cn - t_exact) for cn in corners)
        want = bridges.mueller_to_mitsuba(f, ti, pi, tr, pr, degrees=False)
        got = mitsuba_eval(bsdf, wi, wr, BANDS[:4])[:, :, 0] / wi[2]
        err = np.linalg.norm(got - want)
        assert err <= bound + 1e-4 * f[0, 0], (err, bound)
        rel.append((err / np.linalg.norm(f), bound / np.linalg.norm(f)))
        done += 1
    rel = np.array(rel)
    # The bound is tight enough to mean something, and the plugin is well inside it.
    # (300 geometries, this grid: median error 0.04 % of ‖F‖, 90th percentile 0.15 %, largest
    # 1.6 %; the bound's median 2.3 %.)
    assert np.median(rel[:, 1]) < 0.05
    assert np.median(rel[:, 0]) < 0.005
