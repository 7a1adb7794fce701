"""Every case of the shared test vectors (tests/data/test-vectors.json), through Python.

Tolerances are the vectors' own (their meta.tolerance_hint, as the Rust tests use): f to rtol
1e-9, F entries to 1e-9·F00 (+1e-12), DoLP to 1e-9 absolute.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from support import material_of

import polbrdf

ANGLES = ("theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg")


def check(case: dict[str, Any], f: float, m: np.ndarray, d: float) -> None:
    out = case["outputs"]
    f_ref, m_ref = out["f"], np.array(out["F"])
    cid = case["id"]
    assert abs(f - f_ref) <= 1e-9 * abs(f_ref) + 1e-12, f"{cid}: f = {f}, expected {f_ref}"
    np.testing.assert_allclose(m, m_ref, rtol=0, atol=1e-9 * abs(m_ref[0, 0]) + 1e-12, err_msg=cid)
    assert abs(d - out["dolp"]) <= 1e-9, f"{cid}: dolp = {d}, expected {out['dolp']}"


def test_every_vector_through_each_function(vectors: list[dict[str, Any]]) -> None:
    for case in vectors:
        inp = case["inputs"]
        mat = material_of(inp)
        angles = [inp[k] for k in ANGLES]
        m = polbrdf.mueller(mat, *angles)
        assert m.shape == (4, 4)
        check(case, float(polbrdf.brdf(mat, *angles)), m, float(polbrdf.dolp(mat, *angles)))
        e = polbrdf.evaluate(mat, *angles, with_mueller=True)
        assert e.mueller is not None
        check(case, float(e.brdf), e.mueller, float(e.dolp))
        e2 = polbrdf.evaluate(mat, *angles)
        assert e2.mueller is None
        assert (e2.brdf, e2.dolp, e2.aolp) == (e.brdf, e.dolp, e.aolp), case["id"]


def test_vectors_in_radians(vectors: list[dict[str, Any]]) -> None:
    for case in vectors:
        inp = case["inputs"]
        angles = [np.radians(inp[k]) for k in ANGLES]
        mat = material_of(inp)
        m = polbrdf.mueller(mat, *angles, degrees=False)
        check(case, m[0, 0], m, float(polbrdf.dolp(mat, *angles, degrees=False)))


@pytest.mark.parametrize("form", ["standard", "paper"])
def test_vectors_batched_per_material(vectors: list[dict[str, Any]], form: str) -> None:
    """All geometries of the default-material cases in one call, against each case."""
    groups: dict[str, list[dict[str, Any]]] = {}
    for case in vectors:
        inp = case["inputs"]
        if inp["form"] != form:
            continue
        key = repr(material_of(inp))
        groups.setdefault(key, []).append(case)
    assert groups
    for cases in groups.values():
        mat = material_of(cases[0]["inputs"])
        cols = [np.array([c["inputs"][k] for c in cases]) for k in ANGLES]
        m = polbrdf.mueller(mat, *cols)
        f, d = polbrdf.brdf(mat, *cols), polbrdf.dolp(mat, *cols)
        for i, case in enumerate(cases):
            check(case, f[i], m[i], d[i])


def test_normalization_reproduces_the_vectors_a(vectors: list[dict[str, Any]]) -> None:
    for case in vectors:
        inp = case["inputs"]
        mat = material_of(inp)
        assert mat.a_effective == pytest.approx(inp["a"], rel=1e-11), case["id"]
        assert mat.b_effective == pytest.approx(inp["b"], rel=1e-13), case["id"]
