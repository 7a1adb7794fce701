"""Bad angles are ValueErrors naming the argument, the value and the index — never a crash."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import polbrdf

FUNCS = [polbrdf.mueller, polbrdf.brdf, polbrdf.dolp, polbrdf.evaluate]


@pytest.mark.parametrize("func", FUNCS)
def test_nan_angle(paint: polbrdf.Material, func: object) -> None:
    theta = np.array([10.0, 20.0, np.nan, 30.0])
    with pytest.raises(ValueError, match=r"invalid angle `theta_i` = NaN \(at index 2\)") as e:
        func(paint, theta, 0, 30, 180)  # type: ignore[operator]
    assert e.value.index == 2  # type: ignore[attr-defined]
    assert e.value.argument == "theta_i"  # type: ignore[attr-defined]


@pytest.mark.parametrize(
    ("args", "pattern"),
    [
        ((10, 0, 181, 0), r"`theta_r` = 181 \(at index 0\): zenith angle must lie in \[0°, 180°\]"),
        ((-0.5, 0, 10, 0), r"`theta_i` = -0.5"),
        ((10, np.inf, 10, 0), r"`phi_i` = inf.*must be finite"),
        ((10, 0, 10, [0, 1, -np.inf]), r"`phi_r` = -inf \(at index 2\)"),
    ],
)
def test_bad_angles_in_degrees(
    paint: polbrdf.Material, args: tuple[Any, ...], pattern: str
) -> None:
    with pytest.raises(ValueError, match=pattern):
        polbrdf.mueller(paint, *args)


def test_bad_angle_in_radians_names_radians(paint: polbrdf.Material) -> None:
    with pytest.raises(ValueError, match=r"`theta_i` = 4 \(at index 1\): .*\[0, π\] rad"):
        polbrdf.brdf(paint, [1, 4], 0, 0, 0, degrees=False)


def test_bad_angle_position_in_broadcast_shape(paint: polbrdf.Material) -> None:
    ti = np.array([[10.0], [np.nan]])  # (2, 1) x (1, 3) -> (2, 3)
    with pytest.raises(ValueError, match="theta_i") as e:
        polbrdf.brdf(paint, ti, 0, 30, [[0, 90, 180]])
    assert e.value.index == 3  # type: ignore[attr-defined]
    assert any("position (1, 0) of the broadcast shape (2, 3)" in n for n in e.value.__notes__)


def test_horizon_is_valid_and_zero(paint: polbrdf.Material) -> None:
    m = polbrdf.mueller(paint, [90, 120, 180, 30], 0, [30, 30, 30, 90], 180)
    assert (m == 0).all()
    e = polbrdf.evaluate(paint, 95, 0, 30, 0)
    assert e.brdf == 0 and e.dolp == 0 and e.aolp == 0


def test_material_argument_checked(paint: polbrdf.Material) -> None:
    with pytest.raises(TypeError, match="Material.preset"):
        polbrdf.brdf("paint", 10, 0, 10, 180)  # type: ignore[arg-type]


def test_error_leaves_the_module_usable(paint: polbrdf.Material) -> None:
    for _ in range(3):
        with pytest.raises(ValueError):
            polbrdf.mueller(paint, np.full(100_000, np.nan), 0, 0, 0)
    assert polbrdf.brdf(paint, 60, 0, 60, 180) > 0


@pytest.mark.parametrize("func", FUNCS)
@pytest.mark.parametrize("degrees", [True, False])
def test_index_beyond_the_first_chunk(paint: polbrdf.Material, func: Any, degrees: bool) -> None:
    """The index is the position in the whole (flattened) batch, the value the one given."""
    theta = np.full(10_000, 0.5)
    theta[7_777] = 200.0
    with pytest.raises(ValueError, match=r"`theta_r` = 200 \(at index 7777\)") as e:
        func(paint, 0.3, 0, theta, 0, degrees=degrees)
    assert e.value.index == 7_777  # type: ignore[attr-defined]
