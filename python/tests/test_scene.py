"""polbrdf.Scene: exactly the scene file's keys, read by the CLI's reader (polbrdf-io), and
radiance(material, scene, views) — the same numbers as the flat keywords and, bit for bit, as
`polbrdf radiance` (the README's example and a band and a daylight scene)."""

from __future__ import annotations

import csv
import dataclasses
import io
import subprocess
from pathlib import Path

import numpy as np
import pytest
from support import NO_CLI, REPO, cli_binary

import polbrdf
from polbrdf import Atmosphere, Band, Material, Scene, SceneObject, Sky, Sun, Surface, _polbrdf

EXAMPLES = REPO / "examples"
CLI = cli_binary()
needs_cli = pytest.mark.skipif(CLI is None, reason=NO_CLI)

#: The README's scene file ("Scene files"), without its comments: the surface of
#: painted-aluminium-lwir.toml at 300 K under a 250 K sky, at 10 µm.
README_SCENE = """wavelength_um = 10.0
[surface]
temperature_k = 300
[sky]
model = "thermal"
temperature_k = 250
[atmosphere]
transmittance = 1.0
path_radiance = 0.0
"""
#: The README's output of `polbrdf radiance --material examples/painted-aluminium-lwir.toml
#: --scene scene.toml --theta-deg 0,45,70`.
README_ROWS = """0.0,0.0,9.530202524987157,-4.427903577306755e-12,0.0,0.0,4.646179937621758e-13,90.0
45.0,0.0,9.475655650868422,-0.18002365883844526,0.0,0.0,0.018998543791737144,90.0
70.0,0.0,9.075719089762572,-0.4557341456953721,0.0,0.0,0.0502146597077295,90.0
"""

#: The LWIR band of the README's contrast example, the daylight sun and clear sky, each with a
#: [surface] for `radiance`.
BAND_SCENE = f"""[band]
response = "{EXAMPLES / "lwir-8-12um.csv"}"
step_um = 0.25
[surface]
temperature_k = 305
[sky]
model = "thermal"
temperature_k = 250
[atmosphere]
transmittance = 0.9
path_radiance = 0.3
"""
DAYLIGHT_SCENE = """wavelength_um = 0.55
[sun]
zenith_deg = 40
azimuth_deg = 20
irradiance = 1400
stokes = [1, 0.1, 0, 0]
[sky]
model = "cie-clear"
irradiance = 200
dop_max = 0.6
"""


def write(tmp_path: Path, text: str, name: str = "scene.toml") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def dotted_fields(cls: type) -> list[str]:
    out = []
    for f in dataclasses.fields(cls):
        table = polbrdf.scene._TABLES.get(f.name)
        out.append(f.name)
        if table is not None:
            out += [f"{f.name}.{g.name}" for g in dataclasses.fields(table)]
    return out


def test_the_scene_s_fields_are_exactly_the_scene_file_s_keys() -> None:
    # polbrdf-io's list of keys, tables before their keys, in the format's order.
    assert dotted_fields(Scene) == _polbrdf.vocabulary()["scene_key"]


@pytest.mark.parametrize("name", ["daylight-scene.toml", "lwir-scene.toml", "sun-only-scene.toml"])
def test_the_examples_read_and_round_trip(name: str, tmp_path: Path) -> None:
    s = Scene.from_toml(EXAMPLES / name)
    # File names come back as the reader found them: joined to the scene file's folder.
    for obj in (s.target, s.background):
        assert obj is not None and Path(obj.material).is_file()
    back = Scene.from_toml(write(tmp_path, s.to_toml()))
    assert back == s


def test_from_toml_gives_every_key() -> None:
    s = Scene.from_toml(EXAMPLES / "lwir-scene.toml")
    assert s == Scene(
        band=Band(response=str(EXAMPLES / "lwir-8-12um.csv")),
        target=SceneObject(material=str(EXAMPLES / "painted-aluminium-lwir.toml"),
                           temperature_k=305.0),
        background=SceneObject(material=str(EXAMPLES / "soil-lwir.toml"), temperature_k=300.0),
        sky=Sky(model="thermal", temperature_k=250.0),
        atmosphere=Atmosphere(transmittance=1.0, path_radiance=0.0),
    )  # fmt: skip
    d = Scene.from_toml(EXAMPLES / "daylight-scene.toml")
    assert d.sun == Sun(zenith_deg=40.0, azimuth_deg=0.0, irradiance=1400.0)
    assert d.sky == Sky(model="cie-clear", irradiance=200.0, dop_max=0.75)


def cli_error(*args: str) -> str:
    assert CLI is not None
    r = subprocess.run([str(CLI), *args], capture_output=True, text=True, check=False)
    assert r.returncode != 0
    return r.stderr


BAD_SCENES = [
    ("wavelength_um = 10\n[sky]\nmodel = \"thermal\"\nradiance = 1\n", r"scene\.toml:4"),
    ("wavelength_um = 10\n[sky]\nmodel = \"cloudy\"\n", r"unknown sky model"),
    ("wavelength_um = 10\n[sun]\nzenith_deg = 95\nirradiance = 1\n", r"sun\.zenith_deg"),
    ("wavelength_um = 10\nsky.model = \"none\"\n", r"dotted keys"),
    ("wavelength_um = 10\n[surface]\ntemperature_k = -3\n", r"temperature_k"),
    ("[band]\nresponse = \"missing.csv\"\n", r"missing\.csv"),
    ("wavelength_um = 10\n[sky]\nmodel = \"cie-clear\"\nirradiance = 5\n", r"\[sun\]"),
]


@pytest.mark.parametrize(("text", "pattern"), BAD_SCENES)
def test_a_bad_scene_file_gives_the_reader_s_error(
    text: str, pattern: str, tmp_path: Path
) -> None:
    path = write(tmp_path, text)
    with pytest.raises(ValueError, match=pattern) as e:
        Scene.from_toml(path)
    assert str(e.value).startswith(f"{path}:")
    if CLI is not None:  # the CLI's reader says the same
        assert str(e.value) in cli_error("radiance", "--material", "paint", "--scene", str(path))


def test_a_missing_scene_file_is_an_os_error(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match="nothing.toml: cannot read"):
        Scene.from_toml(tmp_path / "nothing.toml")


def test_a_bad_value_of_a_scene_object_is_the_reader_s_error() -> None:
    with pytest.raises(ValueError, match=r"<polbrdf\.Scene>:\d+: .*sky\.dop_max"):
        polbrdf.radiance(
            Material.preset("paint"),
            Scene(wavelength_um=0.55, sun=Sun(zenith_deg=30, irradiance=1),
                  sky=Sky(model="cie-clear", irradiance=1, dop_max=1.5)),
            (10, 0),
        )  # fmt: skip
    with pytest.raises(TypeError, match=r"scene key `wavelength_um`: expected a number"):
        Scene(wavelength_um=object()).to_toml()  # type: ignore[arg-type]


FLAT_EQUIVALENTS = [
    (
        Scene(wavelength_um=10.0, surface=Surface(temperature_k=300),
              sky=Sky(model="uniform", radiance=2.0),
              atmosphere=Atmosphere(transmittance=0.8, path_radiance=0.5)),
        {"wavelength_um": 10.0, "temperature_k": 300, "sky": "uniform", "sky_radiance": 2.0,
         "transmittance": 0.8, "path_radiance": 0.5},
    ),
    (
        Scene(wavelength_um=0.55, sun=Sun(zenith_deg=40, azimuth_deg=20, irradiance=1400,
                                           stokes=(1, 0.1, 0, 0)),
              sky=Sky(model="cie-clear", irradiance=200, dop_max=0.6)),
        {"wavelength_um": 0.55, "sun": (40, 20, 1400, (1, 0.1, 0, 0)), "sky": "cie-clear",
         "sky_irradiance": 200, "dop_max": 0.6},
    ),
    (
        Scene(wavelength_um=0.55, sun=Sun(zenith_deg=40, irradiance=1400),
              sky=Sky(model="cie-clear", irradiance=200)),
        {"wavelength_um": 0.55, "sun": (40, 0, 1400), "sky": "cie-clear", "sky_irradiance": 200},
    ),
    (
        Scene(band=Band(response=str(EXAMPLES / "lwir-8-12um.csv"), step_um=0.25),
              surface=Surface(temperature_k=305), sky=Sky(model="thermal", temperature_k=250)),
        {"band": ([7.8, 8.0, 12.0, 12.2], [0, 1, 1, 0]), "band_step_um": 0.25,
         "temperature_k": 305, "sky": "thermal", "sky_temperature_k": 250},
    ),
]  # fmt: skip


@pytest.mark.parametrize(("scene", "flat"), FLAT_EQUIVALENTS)
def test_a_scene_and_the_flat_keywords_give_identical_numbers(
    scene: Scene, flat: dict[str, object]
) -> None:
    m = Material.preset("paint")
    theta, phi = np.array([0.0, 30.0, 60.0, 85.0]), np.array([[0.0], [90.0], [200.0]])
    a = polbrdf.radiance(m, scene, (theta, phi))
    b = polbrdf.radiance(m, theta, phi, **flat)  # type: ignore[arg-type]
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)
    assert a.stokes.shape == (3, 4, 4)
    r = polbrdf.radiance(m, scene, (np.radians(theta), np.radians(phi)), degrees=False)
    np.testing.assert_allclose(r.stokes, a.stokes, rtol=1e-12, atol=0)


def test_the_defaults_are_the_reader_s() -> None:
    # No key, no table: the scene files' defaults (no sky, τ = 1, no path radiance), the same
    # as the flat keywords left at None.
    m = Material.preset("paint")
    a = polbrdf.radiance(m, Scene(wavelength_um=10.0, surface=Surface(temperature_k=300)),
                         (45, 0))  # fmt: skip
    b = polbrdf.radiance(m, 45, 0, wavelength_um=10.0, temperature_k=300)
    c = polbrdf.radiance(m, 45, 0, wavelength_um=10.0, temperature_k=300, sky="none",
                         transmittance=1.0, path_radiance=0.0)  # fmt: skip
    for x, y, z in zip(a, b, c):
        np.testing.assert_array_equal(x, y)
        np.testing.assert_array_equal(x, z)
    assert polbrdf.DEFAULT_DOP_MAX == Scene.from_toml(EXAMPLES / "daylight-scene.toml").sky.dop_max


def test_a_scene_for_contrast_is_refused_by_radiance() -> None:
    s = Scene.from_toml(EXAMPLES / "daylight-scene.toml")
    with pytest.raises(ValueError, match=r"\[target\] table, which is for `contrast`"):
        polbrdf.radiance(Material.preset("paint"), s, (10, 0))


def test_a_scene_takes_no_flat_keyword_and_views_are_a_pair() -> None:
    s = Scene(wavelength_um=10.0)
    m = Material.preset("paint")
    with pytest.raises(TypeError, match=r"the scene's own keys, not `sky`"):
        polbrdf.radiance(m, s, (10, 0), sky="none")  # type: ignore[call-overload]
    with pytest.raises(TypeError, match=r"`views` must be a pair"):
        polbrdf.radiance(m, s, 10)  # type: ignore[call-overload]


def cli_radiance(material: Path, scene: Path, *views: str) -> list[list[float]]:
    assert CLI is not None
    out = subprocess.run(
        [str(CLI), "radiance", "--material", str(material), "--scene", str(scene), *views],
        capture_output=True, text=True, check=True,
    ).stdout  # fmt: skip
    rows = list(csv.reader(io.StringIO(out)))
    assert rows[0] == ["theta_r_deg", "phi_r_deg", "s0", "s1", "s2", "s3", "dolp", "aolp_deg"]
    return [[float(v) for v in r] for r in rows[1:]]


def python_rows(material: Path, scene: Path, theta: list[float], phi: list[float]) -> np.ndarray:
    t, p = np.meshgrid(theta, phi, indexing="ij")
    r = polbrdf.radiance(Material.from_toml(material), Scene.from_toml(scene), (t, p))
    return np.column_stack(
        [t.ravel(), p.ravel(), r.stokes.reshape(-1, 4), r.dolp.ravel(), r.aolp.ravel()]
    )


def test_the_readme_radiance_example_gives_the_readme_s_numbers(tmp_path: Path) -> None:
    scene = write(tmp_path, README_SCENE)
    got = python_rows(EXAMPLES / "painted-aluminium-lwir.toml", scene, [0, 45, 70], [0])
    want = [[float(v) for v in r.split(",")] for r in README_ROWS.splitlines()]
    np.testing.assert_array_equal(got, want)
    guide = (REPO / "docs" / "guide-emission.md").read_text(encoding="utf-8")
    for row in README_ROWS.splitlines():  # the emission guide (from the README) shows these rows
        assert row in guide, row


@needs_cli
@pytest.mark.parametrize(
    ("material", "text", "views"),
    [
        ("painted-aluminium-lwir.toml", README_SCENE, ["--theta-deg", "0,45,70"]),
        ("painted-aluminium-lwir.toml", README_SCENE, []),
        ("painted-aluminium-lwir.toml", BAND_SCENE, ["--theta-deg", "0,30,60,80"]),
        ("olive-paint.toml", DAYLIGHT_SCENE,
         ["--theta-deg", "0,20,40,60,80", "--phi-deg", "0,45,180,270"]),
    ],
    ids=["readme", "readme-default-views", "lwir-band", "daylight"],
)  # fmt: skip
def test_radiance_equals_the_cli_bit_for_bit(
    material: str, text: str, views: list[str], tmp_path: Path
) -> None:
    scene = write(tmp_path, text)
    cli = np.array(cli_radiance(EXAMPLES / material, scene, *views))
    theta = sorted(set(cli[:, 0].tolist()))
    phi = list(dict.fromkeys(cli[:, 1].tolist()))
    got = python_rows(EXAMPLES / material, scene, theta, phi)
    np.testing.assert_array_equal(got, cli)
