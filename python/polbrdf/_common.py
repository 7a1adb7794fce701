"""What the public functions of ``polbrdf`` share: the checks of their arguments (a
``Material``, arrays of real numbers), NumPy broadcasting into the flat float64 arrays the
compiled half takes, the position of a bad element in the broadcast shape, and the shape of
the results; and :func:`public`, which gives a public name its import path ``polbrdf``."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._polbrdf import Material

_T = TypeVar("_T")


def public(obj: _T) -> _T:
    """Give ``obj``, defined in a private module of the package, the module ``polbrdf`` it is
    imported from (``polbrdf.X``): its repr, its pickles, ``help()`` and
    :func:`typing.get_overloads` name ``polbrdf``, whichever private module defines it."""
    obj.__module__ = "polbrdf"
    return obj


_NAMES = ("theta_i", "phi_i", "theta_r", "phi_r", "wavelength_um")
_F64 = NDArray[np.float64]


def _check_material(material: Material) -> None:
    if not isinstance(material, Material):
        raise TypeError(
            f"material must be a polbrdf.Material, not {type(material).__name__} "
            "(use polbrdf.Material.preset(name) or polbrdf.Material.from_toml(path))"
        )


#: The most dimensions of a broadcast argument (NumPy's limit for broadcasting).
MAX_DIMS = 32


def _real(name: str, a: ArrayLike, masked_as_nan: bool = False) -> np.ndarray:
    """``a`` as an array of real numbers: complex or other dtypes raise ``TypeError``, more than
    :data:`MAX_DIMS` dimensions ``ValueError``. A masked array's masked entries are NaN ("not
    measured") with ``masked_as_nan`` (fit data and sigma), and are refused otherwise (angles
    and wavelengths have no "not given" value)."""
    if isinstance(a, np.ma.MaskedArray):
        mask = np.ma.getmaskarray(a)
        if mask.any() and not masked_as_nan:
            raise ValueError(
                f"`{name}` is a masked array with {int(mask.sum())} masked entr"
                f"{'y' if mask.sum() == 1 else 'ies'}: an angle or wavelength must be given "
                "everywhere (drop the masked entries, or fill them)"
            )
        if a.dtype.kind not in "biuf":
            raise TypeError(f"`{name}` must hold real numbers, got dtype {a.dtype}")
        arr = np.ma.filled(a.astype(np.float64), np.nan)
    else:
        arr = np.asarray(a)
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"`{name}` must hold real numbers, got dtype {arr.dtype}")
    if arr.ndim > MAX_DIMS:
        raise ValueError(f"`{name}` has {arr.ndim} dimensions: at most {MAX_DIMS}")
    return arr


def _broadcast(
    names: Sequence[str], values: tuple[ArrayLike, ...], singles: int = 0
) -> tuple[tuple[int, ...], tuple[_F64, ...]]:
    """Broadcast the arguments ``values`` (named ``names``); return the shape and the flat
    C-contiguous float64 arrays (views when the input already is one, copies otherwise). The
    first ``singles`` arguments are passed as one value when they hold one (a scalar), for the
    Rust side to broadcast without a materialized array."""
    arrays = [_real(name, a) for name, a in zip(names, values)]
    try:
        b = np.broadcast_arrays(*arrays)
    except ValueError as e:
        shapes = ", ".join(f"{n}: {a.shape}" for n, a in zip(names, arrays))
        raise ValueError(f"arrays do not broadcast together ({shapes})") from e
    shape = b[0].shape
    flat = tuple(
        np.ascontiguousarray(a if i < singles and a.size == 1 else x, dtype=np.float64).reshape(-1)
        for i, (a, x) in enumerate(zip(arrays, b))
    )
    return shape, flat


def _flatten(
    material: Material,
    angles: tuple[ArrayLike, ...],
    singles: bool = False,
) -> tuple[tuple[int, ...], tuple[_F64, ...]]:
    """Broadcast the four angle arguments (and the wavelength, when given: a fifth); return the
    shape and the flat C-contiguous float64 arrays (views when the input already is one,
    copies otherwise). With ``singles``, a scalar angle stays one value (the engine calls
    broadcast it)."""
    _check_material(material)
    return _broadcast(_NAMES, angles, 4 if singles else 0)


def _args(
    angles: tuple[ArrayLike, ArrayLike, ArrayLike, ArrayLike], wavelength_um: ArrayLike | None
) -> tuple[ArrayLike, ...]:
    return angles if wavelength_um is None else (*angles, wavelength_um)


def _wl(flat: tuple[_F64, ...]) -> _F64 | None:
    return flat[4] if len(flat) == 5 else None


def _located(e: ValueError, shape: tuple[int, ...]) -> ValueError:
    """Add the position in the broadcast shape to a bad-angle error of a multi-dimensional call."""
    index = getattr(e, "index", None)
    if index is not None and len(shape) >= 2:
        pos = tuple(int(i) for i in np.unravel_index(index, shape))
        e.add_note(f"flat index {index} is position {pos} of the broadcast shape {shape}")
    return e


def _scalar_or_array(a: NDArray[np.float64], shape: tuple[int, ...]) -> NDArray[np.float64]:
    out = a.reshape(shape)
    return out[()] if shape == () else out  # a NumPy scalar for all-scalar input, as ufuncs
