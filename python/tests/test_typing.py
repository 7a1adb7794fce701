"""The stub of the compiled module: its Literal types are the closed sets the extension accepts,
taken from the Rust enums (`vocabulary()`), and mypy's stubtest finds the stub true to the
module."""

from __future__ import annotations

import ast
import importlib.util
import subprocess
import sys
import typing
from pathlib import Path

import numpy as np
import pytest

import polbrdf
from polbrdf import Material, _polbrdf

STUB = Path(polbrdf.__file__).with_name("_polbrdf.pyi")

#: Which set of `vocabulary()` each Literal alias of the stub spells.
ALIASES = {
    "_Form": "form",
    "_AzimuthTerm": "azimuth_term",
    "_Precision": "precision",
    "_SkyModel": "sky",
    "_Parameter": "parameter",
    "_Quantity": "quantity",
    "_RankBy": "rank_by",
    "_LutQuantity": "lut_quantity",
    "_Feature": "feature",
}

#: The sets of `vocabulary()` that no Literal of the stub spells, and why: each is taken from
#: the extension at run time or checked elsewhere.
UNSPELLED = {
    "layout": "polbrdf.mueller unpacks vocabulary()['layout'] itself",
    "scene_key": "the Scene dataclasses' fields, checked by test_scene.py",
    "mueller_column": "column names, not a parameter: polbrdf.xarray reads them from vocabulary()",
}


def stub_literals() -> dict[str, list[str]]:
    """Every module-level `NAME: TypeAlias = Literal[...]` of the stub, members in order."""
    out = {}
    for node in ast.parse(STUB.read_text()).body:
        if isinstance(node, ast.AnnAssign) and isinstance(node.value, ast.Subscript):
            value = node.value
            if isinstance(value.value, ast.Name) and value.value.id == "Literal":
                elts = value.slice.elts if isinstance(value.slice, ast.Tuple) else [value.slice]
                out[node.target.id] = [e.value for e in elts]  # type: ignore[attr-defined]
    return out


def test_every_literal_of_the_stub_is_a_set_of_the_extension() -> None:
    vocabulary = _polbrdf.vocabulary()
    literals = stub_literals()
    literals.pop("_VocabularySet")
    assert set(literals) == set(ALIASES)
    for alias, members in literals.items():
        assert members == vocabulary[ALIASES[alias]], alias
    # The vocabulary's own names are a Literal too.
    assert set(stub_literals()["_VocabularySet"]) == set(vocabulary)


def test_every_set_of_the_extension_is_a_literal_or_taken_from_it() -> None:
    # A new closed set must be spelled by a Literal of the stub or be listed with its reason.
    vocabulary = _polbrdf.vocabulary()
    assert set(vocabulary) == set(ALIASES.values()) | set(UNSPELLED)
    assert not set(ALIASES.values()) & set(UNSPELLED)


def test_the_mueller_columns_are_the_core_s_one_list() -> None:
    v = _polbrdf.vocabulary()
    assert v["mueller_column"] == [f"m{i}{j}" for i in range(4) for j in range(4)]
    # The fit quantities end with them, in the same order.
    assert v["quantity"][-16:] == v["mueller_column"]


def test_literal_is_written_only_in_the_aliases() -> None:
    # A closed set spelled inline could drift: every Literal of the stub is one of the aliases.
    text = STUB.read_text()
    assert text.count("Literal[") == len(ALIASES) + 1


def test_the_python_layer_s_sets_are_the_extension_s() -> None:
    vocabulary = _polbrdf.vocabulary()
    assert list(typing.get_args(polbrdf.scene.SkyModel)) == vocabulary["sky"]
    assert list(typing.get_args(polbrdf.tasks.RankBy)) == vocabulary["rank_by"]
    assert list(typing.get_args(polbrdf.detection.Feature)) == vocabulary["feature"]
    assert vocabulary["layout"] == ["interleaved", "planar"]


def test_the_extension_accepts_every_member_and_nothing_else() -> None:
    v = _polbrdf.vocabulary()
    for form in v["form"]:
        assert Material(n=1.5, sigma_deg=5, form=form).form == form
    for term in v["azimuth_term"]:
        assert Material(n=1.5, sigma_deg=5, azimuth_term=term).azimuth_term == term
    for bad, key in (("Standard", "form"), ("eq4", "azimuth_term")):
        with pytest.raises(ValueError):
            Material(n=1.5, sigma_deg=5, **{key: bad})
    m = Material.preset("paint")
    for precision in v["precision"]:
        assert polbrdf.mueller(m, 30, 0, 30, 180, precision=precision).dtype == precision
    for layout in v["layout"]:
        assert polbrdf.mueller(m, [30, 40], 0, 30, 180, layout=layout).shape[-1] in (2, 4)
    for sky in v["sky"]:
        # Known to the flat keywords (which then ask for the model's own arguments).
        try:
            polbrdf.radiance(m, 10, 0, wavelength_um=10.0, sky=sky)
        except ValueError as e:
            assert "unknown sky model" not in str(e)
    with pytest.raises(ValueError, match=r"unknown sky model `cloudy` \(expected \"none\", "):
        polbrdf.radiance(m, 10, 0, wavelength_um=10.0, sky="cloudy")
    t = np.linspace(5, 60, 8)
    f = polbrdf.mueller(m, t, 0, t, 40)
    exact = {"brdf": f[:, 0, 0], "dolp": polbrdf.dolp(m, t, 0, t, 40),
             "brdf_s": f[:, 0, 0] + f[:, 0, 1], "brdf_p": f[:, 0, 0] - f[:, 0, 1]}  # fmt: skip
    exact |= {f"m{i}{j}": f[:, i, j] for i in range(4) for j in range(4)}
    assert list(exact) == v["quantity"]
    for q in v["quantity"]:
        r = polbrdf.fit(m, t, 0, t, 40, {q: exact[q], "brdf": exact["brdf"]}, free=["rho_d"])
        assert r.values[0] == pytest.approx(m.rho_d, rel=1e-6), q
    for p in v["parameter"]:
        assert _polbrdf.derivative_step(p, 1.0) > 0


@pytest.mark.skipif(
    importlib.util.find_spec("mypy") is None,
    reason="mypy is not installed (pip install mypy): the stub is not checked by stubtest",
)
def test_stubtest_finds_the_stub_true_to_the_module() -> None:
    r = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "polbrdf._polbrdf"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert r.returncode == 0, r.stdout + r.stderr
