"""Mitsuba 3 as an oracle where its model and polbrdf's overlap: the DoLP for unpolarized light
of a conductor's specular (facet) term. Mitsuba's polarized `roughconductor` (Beckmann) and
polbrdf's specular term (ρ_D = ρ_V = 0, shadowing off) apply the same Fresnel Mueller matrix
at the half-angle, times scalar factors that leave the DoLP unchanged; the DoLP does not depend
on the Stokes frame's orientation (docs/model.md §2). The harness is scripts/bench_peers.py's
(the peer benchmark runs the same check). Skipped without Mitsuba 3 or a libLLVM for its LLVM
backend (Debian: apt-get install libllvm19)."""

from __future__ import annotations

import importlib.util
import os

import numpy as np
import pytest
from support import REPO

for _lib in ("/usr/lib/x86_64-linux-gnu/libLLVM-19.so", "/usr/lib/llvm-19/lib/libLLVM.so"):
    if "DRJIT_LIBLLVM_PATH" not in os.environ and os.path.exists(_lib):
        os.environ["DRJIT_LIBLLVM_PATH"] = _lib

try:
    import mitsuba as mi
except ImportError as e:  # pragma: no cover - depends on the environment
    pytest.skip(f"Mitsuba 3 is not installed ({e}): pip install mitsuba", allow_module_level=True)
try:
    mi.set_variant("llvm_ad_mono_polarized")
except Exception as e:  # noqa: BLE001 - Dr.Jit raises several kinds  # pragma: no cover
    pytest.skip(
        f"Mitsuba's LLVM backend is unavailable ({e}): install libLLVM (Debian: apt-get install "
        "libllvm19) or set DRJIT_LIBLLVM_PATH",
        allow_module_level=True,
    )



@pytest.fixture(autouse=True)
def _variant() -> None:
    # Mitsuba's variant is global: another test module may have chosen its own since this one
    # was imported.
    mi.set_variant("llvm_ad_mono_polarized")


_spec = importlib.util.spec_from_file_location("bench_peers", REPO / "scripts" / "bench_peers.py")
assert _spec is not None and _spec.loader is not None
bench_peers = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(bench_peers)


def test_dolp_of_a_beckmann_conductor_matches_mitsuba() -> None:
    dev = bench_peers.physics_check(5000)
    # Mitsuba evaluates in float32: agreement to its rounding, not better.
    assert dev < 1e-4, f"max |ΔDoLP| = {dev:e}"


def test_the_check_can_fail() -> None:
    # A different index gives a different DoLP: the comparison discriminates.
    ti, pi, tr, pr = bench_peers.geometries(2000, seed=7)
    m = bench_peers.Mitsuba(ti, pi, tr, pr).mueller()
    import polbrdf

    other = polbrdf.Material(n=bench_peers.N_INDEX, k=bench_peers.K_INDEX * 0.8, sigma_deg=10.0,
                             shadowing=False)
    d = polbrdf.dolp(other, ti, pi, tr, pr, degrees=False)
    ok = m[:, 0, 0] > 1e-30
    assert np.max(np.abs(bench_peers.dolp_of_first_column(m)[ok] - d[ok])) > 1e-3


def test_dolp_at_mitsubas_own_vectors_matches() -> None:
    # The direction entry point evaluates exactly the float32 vectors Mitsuba gets: no angle
    # round trip between the two, only Mitsuba's float32 arithmetic.
    ti, pi, tr, pr = bench_peers.geometries(5000, seed=11)
    mit = bench_peers.Mitsuba(ti, pi, tr, pr)
    m = mit.mueller()
    import polbrdf

    mat = polbrdf.Material(n=bench_peers.N_INDEX, k=bench_peers.K_INDEX,
                           sigma_deg=bench_peers.SIGMA_DEG, shadowing=False)
    f = polbrdf.mueller_directions(mat, mit.w_source, mit.w_detector)
    ok = (m[:, 0, 0] > 1e-30) & np.isfinite(m[:, 0, 0])
    assert ok.sum() > 2500
    dolp = bench_peers.dolp_of_first_column
    dev = np.max(np.abs(dolp(m)[ok] - dolp(f)[ok]))
    # Measured 4.3e-7 (Mitsuba's float32 arithmetic), as on the angle route.
    assert dev < 1e-5, f"max |ΔDoLP| = {dev:e}"
