"""Material and FitResult pickle at every protocol (0 to 5), and an unpickled Material holds its
spectral index's data: it reads no file at unpickle time (issue 35)."""

from __future__ import annotations

import pickle
from pathlib import Path

import numpy as np
import pytest

import polbrdf
from polbrdf import Material

PROTOCOLS = range(pickle.HIGHEST_PROTOCOL + 1)

#: A refractiveindex.info file: a table of n and k, and a formula for n with a table of k.
TABLE = "DATA:\n  - type: tabulated nk\n    data: |\n        0.5 1.5 0.01\n        0.7 1.45 0.03\n"
FORMULA = (
    "DATA:\n  - type: formula 2\n    wavelength_range: 0.3 2.5\n"
    "    coefficients: 0 1.03961212 0.00600069867 0.231792344 0.0200179144\n"
    "  - type: tabulated k\n    data: |\n        0.3 1e-6\n        2.5 2e-6\n"
)


@pytest.mark.parametrize("protocol", PROTOCOLS)
@pytest.mark.parametrize(
    "material",
    [
        Material.preset("paint"),
        Material(n=1.5, k=0.01, b=12.0, a=3.0, form="paper", shadowing=False,
                 azimuth_term="eq3", tau_deg=10.0, omega_deg=30.0, name="x\n'\"y"),
        Material(index="library:Au/Johnson", sigma_deg=10.0, name="gold film"),
    ],
    ids=["preset", "every-key", "library-index"],
)  # fmt: skip
def test_a_material_pickles_at_every_protocol(material: Material, protocol: int) -> None:
    back = pickle.loads(pickle.dumps(material, protocol=protocol))
    assert back == material
    assert back.to_dict() == material.to_dict()
    assert repr(back) == repr(material)


@pytest.mark.parametrize("protocol", PROTOCOLS)
@pytest.mark.parametrize("text", [TABLE, FORMULA], ids=["table", "formula"])
def test_an_unpickled_material_does_not_read_its_index_file(
    tmp_path: Path, protocol: int, text: str
) -> None:
    yaml = tmp_path / "glass.yml"
    yaml.write_text(text)
    m = Material(index=str(yaml), sigma_deg=5.0)
    data = pickle.dumps(m, protocol=protocol)
    at = [0.55, 0.6, 0.65]
    before = polbrdf.index(m, at)
    yaml.unlink()  # gone: unpickling must not need it
    back = pickle.loads(data)
    assert back == m and back.index == m.index
    assert back.wavelength_range == m.wavelength_range
    np.testing.assert_array_equal(polbrdf.index(back, at), before)
    np.testing.assert_array_equal(
        polbrdf.mueller(back, 30, 0, 30, 180, wavelength_um=0.6),
        polbrdf.mueller(m, 30, 0, 30, 180, wavelength_um=0.6),
    )


@pytest.mark.parametrize("protocol", PROTOCOLS)
def test_a_fit_result_pickles_at_every_protocol(protocol: int) -> None:
    truth = Material(n=1.5, sigma_deg=12.0, rho_d=0.02)
    t = np.linspace(5, 70, 12)
    data = {"brdf": polbrdf.brdf(truth, t, 0, t, 180), "dolp": polbrdf.dolp(truth, t, 0, t, 180)}
    r = polbrdf.fit(Material(n=1.4, sigma_deg=8.0, rho_d=0.01), t, 0, t, 180, data,
                    free=["n", "sigma_deg", "rho_d"], seed=1)  # fmt: skip
    q = pickle.loads(pickle.dumps(r, protocol=protocol))
    assert q.material == r.material
    np.testing.assert_array_equal(q.values, r.values)
    np.testing.assert_array_equal(q.covariance, r.covariance)
    assert q.names == r.names and q.chi2 == r.chi2 and repr(q) == repr(r)


def test_a_bad_pickled_state_is_a_value_error() -> None:
    from polbrdf import _polbrdf

    with pytest.raises(ValueError, match=r"a pickled Material's `form`: expected"):
        _polbrdf._material_from_state(([("n", 1.5), ("sigma_deg", 5.0), ("form", "x")], None))
