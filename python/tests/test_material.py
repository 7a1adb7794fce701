"""Material: construction, validation, properties, files, presets."""

from __future__ import annotations

import pickle
import tomllib
from pathlib import Path

import pytest

from polbrdf import Material

KEYS = [
    "n", "k", "sigma_deg", "b", "a", "form", "shadowing", "tau_deg", "omega_deg",
    "azimuth_term", "rho_d", "rho_v", "name",
]  # fmt: skip


def test_defaults_and_properties() -> None:
    m = Material(1.65, sigma_deg=15)
    assert (m.n, m.k, m.sigma_deg, m.b, m.a) == (1.65, 0.0, 15.0, None, None)
    assert (m.form, m.shadowing, m.tau_deg, m.omega_deg) == ("standard", True, 15.0, 40.0)
    assert (m.azimuth_term, m.rho_d, m.rho_v, m.name) == ("none", 0.0, 0.0, None)
    assert m.b_effective == pytest.approx(1 / (15 * 3.141592653589793 / 180) ** 2, rel=1e-15)
    assert m.a_effective > 0
    for key in KEYS:  # read-only
        with pytest.raises(AttributeError):
            setattr(m, key, 1.0)


def test_every_keyword() -> None:
    m = Material(
        n=1.4, k=0.5, b=3.0, a=2.0, form="paper", shadowing=False, tau_deg=10, omega_deg=30,
        azimuth_term="eq3", rho_d=0.1, rho_v=0.2, name="x",
    )  # fmt: skip
    assert m.to_dict() == {
        "n": 1.4, "k": 0.5, "sigma_deg": None, "b": 3.0, "a": 2.0, "form": "paper",
        "shadowing": False, "tau_deg": 10.0, "omega_deg": 30.0, "azimuth_term": "eq3",
        "rho_d": 0.1, "rho_v": 0.2, "name": "x",
    }  # fmt: skip
    assert (m.a_effective, m.b_effective) == (2.0, 3.0)
    assert Material(**m.to_dict()) == m
    assert list(m.to_dict()) == KEYS


def test_repr_round_trips() -> None:
    m = Material(1.65, sigma_deg=15.0, rho_d=1e-5, name="it's")
    r = repr(m)
    assert r.startswith("Material(n=1.65, k=0.0, sigma_deg=15.0, ")
    assert eval(r, {"Material": Material}) == m
    assert repr(Material.preset("paint")) == (
        "Material(n=1.65, k=0.0, sigma_deg=15.0, form='standard', shadowing=True, "
        "tau_deg=15.0, omega_deg=40.0, azimuth_term='none', rho_d=0.03, rho_v=0.01, "
        "name='paint')"
    )


def test_equality_and_pickle() -> None:
    a, b = Material.preset("glass"), Material.preset("glass")
    assert a == b and a != Material.preset("paint")
    assert pickle.loads(pickle.dumps(a)) == a
    with pytest.raises(TypeError):
        hash(a)


@pytest.mark.parametrize(
    ("kwargs", "pattern"),
    [
        ({"n": -1, "sigma_deg": 10}, r"invalid parameter `n` = -1"),
        ({"n": 0, "sigma_deg": 10}, r"`n`"),
        ({"n": float("nan"), "sigma_deg": 10}, r"`n` = NaN"),
        ({"n": 1.5, "k": -0.1, "sigma_deg": 10}, r"`k`"),
        ({"n": 1.5, "sigma_deg": 0}, r"`sigma_deg`"),
        ({"n": 1.5, "b": -2}, r"`b`"),
        ({"n": 1.5, "sigma_deg": 10, "b": 2}, r"exactly one of `sigma_deg` and `b`"),
        ({"n": 1.5}, r"missing roughness"),
        ({"n": 1.5, "sigma_deg": 10, "a": -1}, r"`a`"),
        ({"n": 1.5, "sigma_deg": 10, "tau_deg": 0}, r"`tau_deg`"),
        ({"n": 1.5, "sigma_deg": 10, "omega_deg": float("inf")}, r"`omega_deg`"),
        ({"n": 1.5, "sigma_deg": 10, "rho_d": -1}, r"`rho_d`"),
        ({"n": 1.5, "sigma_deg": 10, "rho_v": float("nan")}, r"`rho_v`"),
        ({"n": 1.5, "sigma_deg": 10, "form": "fancy"}, r"`form`.*\"fancy\""),
        ({"n": 1.5, "sigma_deg": 10, "azimuth_term": "eq4"}, r"`azimuth_term`"),
    ],
)
def test_invalid_parameters_raise_value_error(kwargs: dict[str, object], pattern: str) -> None:
    with pytest.raises(ValueError, match=pattern):
        Material(**kwargs)  # type: ignore[arg-type]


def test_wrong_types_raise_type_error() -> None:
    with pytest.raises(TypeError):
        Material("1.5", sigma_deg=10)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        Material(1.5, sigma_deg=10, unknown=1)  # type: ignore[call-arg]


def test_presets() -> None:
    names = Material.presets()
    assert names[0] == "paint" and {"glass", "aluminium", "gold"} <= set(names)
    assert list(Material.preset_descriptions()) == names
    for name in names:
        m = Material.preset(name)
        assert m.name == name
    paint = Material.preset("paint")
    assert (paint.n, paint.sigma_deg, paint.rho_d, paint.rho_v) == (1.65, 15.0, 0.03, 0.01)
    with pytest.raises(ValueError, match=r"unknown material preset `nope` \(known: paint, "):
        Material.preset("nope")


def test_toml_round_trip(tmp_path: Path) -> None:
    for name in Material.presets():
        m = Material.preset(name)
        text = m.to_toml()
        assert Material.from_toml_str(text) == m
        # The keyword arguments are exactly the material-file keys.
        assert Material(**tomllib.loads(text)) == m
        p = tmp_path / f"{name}.toml"
        p.write_text(text, encoding="utf-8")
        assert Material.from_toml(p) == m
        assert Material.from_toml(str(p)) == m


def test_from_toml_defaults_and_integers(tmp_path: Path) -> None:
    p = tmp_path / "olive.toml"
    p.write_text('name = "olive paint"\nn = 2\nsigma_deg = 15\nrho_d = 0.03\n', encoding="utf-8")
    m = Material.from_toml(p)
    assert m == Material(n=2.0, sigma_deg=15.0, rho_d=0.03, name="olive paint")


@pytest.mark.parametrize(
    ("text", "line", "pattern"),
    [
        ("n = 1.5\nsigma_deg = 10\ncolour = 3\n", 3, r"field `colour`: unknown key"),
        ("# comment\nn = -1\nsigma_deg = 10\n", 2, r"field `n`: invalid parameter `n` = -1"),
        ("n = 1.5\nsigma_deg = 10\nform = 3\n", 3, r"field `form`: expected a string"),
        ("n = 1.5\nsigma_deg = 10\nshadowing = maybe\n", 3, r""),
        ("n = 1.5\n\nsigma_deg = 10\nb = 3\n", 4, r"field `b`: .*exactly one"),
    ],
)
def test_bad_toml_file_names_file_and_line(
    tmp_path: Path, text: str, line: int, pattern: str
) -> None:
    p = tmp_path / "bad.toml"
    p.write_text(text, encoding="utf-8")
    with pytest.raises(ValueError, match=rf"bad\.toml:{line}: {pattern}") as info:
        Material.from_toml(p)
    assert str(p) in str(info.value)


def test_missing_n_and_bad_files(tmp_path: Path) -> None:
    p = tmp_path / "m.toml"
    p.write_text("sigma_deg = 10\n", encoding="utf-8")
    with pytest.raises(ValueError, match=r"m\.toml: missing required key `n`"):
        Material.from_toml(p)
    p.write_bytes(b'n = 1.5\nname = "\xff"\n')
    with pytest.raises(ValueError, match=r"m\.toml:2: file is not valid UTF-8"):
        Material.from_toml(p)
    with pytest.raises(FileNotFoundError, match="no-such.toml"):
        Material.from_toml(tmp_path / "no-such.toml")
    with pytest.raises(IsADirectoryError):
        Material.from_toml(tmp_path)
    with pytest.raises(ValueError, match=r"<string>:1: "):
        Material.from_toml_str("n = = 1")


#: Bad material files: syntax, unknown key, wrong type, bad value, exclusive keys, a table, no
#: `n`, not UTF-8, a missing index file.
BAD_FILES: list[bytes] = [
    b"n = = 1\n",
    b"n = 1.5\nsigma_deg = 10\ncolour = 3\n",
    b"n = 1.5\nsigma_deg = 10\nform = 3\n",
    b"n = 1.5\nsigma_deg = 10\nform = \"fancy\"\n",
    b"# comment\nn = -1\nsigma_deg = 10\n",
    b"n = 1.5\n\nsigma_deg = 10\nb = 3\n",
    b"n = 1.5\nsigma_deg = 10\n[extra]\nx = 1\n",
    b"sigma_deg = 10\n",
    b'n = 1.5\nname = "\xff"\n',
    b'index = "no-such.yml"\nsigma_deg = 10\n',
    b'index = "library:Au/Johnson"\nn = 1.5\nsigma_deg = 10\n',
]


@pytest.mark.parametrize("content", BAD_FILES)
def test_a_bad_material_file_gives_the_cli_s_message(tmp_path: Path, content: bytes) -> None:
    # One material-file reader: polbrdf-io's, the CLI's; the message names file and line.
    from support import cli_binary

    p = tmp_path / "bad.toml"
    p.write_bytes(content)
    with pytest.raises(ValueError) as info:
        Material.from_toml(p)
    message = str(info.value)
    assert message.startswith(f"{p}:")
    cli = cli_binary()
    if cli is None:
        pytest.skip("the polbrdf CLI binary is not built: only Python's message checked")
    import subprocess

    geometry = tmp_path / "g.csv"
    geometry.write_text("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg\n10,0,10,180\n")
    r = subprocess.run(
        [str(cli), "eval", "--material", str(p), "--input", str(geometry)],
        capture_output=True,
        text=True,
        check=False,
    )
    assert r.returncode == 3, r.stderr
    assert message in r.stderr
