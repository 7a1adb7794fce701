"""The book's Python API reference, `docs/python-api.md`, is generated from the package's
docstrings and signatures (every name of `polbrdf.__all__` and the public methods of its
classes); this test fails when the committed file differs, so the reference cannot drift from
the code. Regenerate it (one command, from the repository root, with the package installed):

    UPDATE_API_REFERENCE=1 python -m pytest python/tests/test_api_reference.py
"""

from __future__ import annotations

import importlib
import inspect
import os
import pickle
import typing
from pathlib import Path

import polbrdf

REFERENCE = Path(__file__).resolve().parents[2] / "docs" / "python-api.md"
HEADER = (
    "<!-- Generated from the docstrings of the `polbrdf` package by "
    "python/tests/test_api_reference.py: do not edit. Regenerate with\n"
    "     UPDATE_API_REFERENCE=1 python -m pytest python/tests/test_api_reference.py -->\n\n"
    "# Python API reference\n\n"
    "Every public name of the `polbrdf` package (`polbrdf.__all__`), with its signature and "
    "docstring. The [Python guide](python.md) shows them at work.\n"
)


def signature(obj: object) -> str:
    try:
        return str(inspect.signature(obj))  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return ""


def doc(obj: object) -> str:
    text = inspect.getdoc(obj) or "(no docstring)"
    return "```text\n" + text.replace("```", "'''") + "\n```\n"


def generated() -> str:
    parts = [HEADER]
    for name in sorted(polbrdf.__all__, key=str.lower):
        if name == "__version__":
            continue
        obj = getattr(polbrdf, name)
        if inspect.isclass(obj):
            parts.append(f"\n## class `{name}`\n\n" + doc(obj))
            members = sorted(
                (m, v)
                for m, v in vars(obj).items()
                if not m.startswith("_")
                and (callable(v) or isinstance(v, (property, staticmethod, classmethod)))
            )
            for m, v in members:
                target = v.__func__ if isinstance(v, (staticmethod, classmethod)) else v
                sig = "" if isinstance(v, property) else signature(target)
                parts.append(f"\n### `{name}.{m}{sig}`\n\n" + doc(target))
        elif callable(obj):
            parts.append(f"\n## `{name}{signature(obj)}`\n\n" + doc(obj))
        else:
            parts.append(f"\n## `{name}`\n\n`{obj!r}`\n")
    return "".join(parts)


def test_api_reference_matches_the_docstrings() -> None:
    expected = generated()
    if os.environ.get("UPDATE_API_REFERENCE"):
        REFERENCE.write_text(expected)
        return
    committed = REFERENCE.read_text() if REFERENCE.exists() else ""
    assert committed == expected, (
        "docs/python-api.md differs from the package's docstrings; regenerate it: "
        "UPDATE_API_REFERENCE=1 python -m pytest python/tests/test_api_reference.py"
    )


def test_every_public_name_says_where_it_is_imported_from() -> None:
    # The NumPy API is defined in private modules by concern (`polbrdf._evaluate`, `_thermal`,
    # …) and imported as `polbrdf.X`: its `__module__` is that import path (or a public
    # submodule's), never a private module, so its repr, help() and pickles name `polbrdf`.
    for name in polbrdf.__all__:
        module = getattr(getattr(polbrdf, name), "__module__", None)
        if module is not None:
            assert not any(part.startswith("_") for part in module.split(".")), (name, module)
            assert getattr(importlib.import_module(module), name) is getattr(polbrdf, name)
    # A result pickles by that path, its annotations resolve, the overloads are registered.
    result = polbrdf.evaluate(polbrdf.Material.preset("paint"), 30, 0, 30, 180)
    data = pickle.dumps(result)
    assert b"polbrdf" in data and b"_evaluate" not in data
    back = pickle.loads(data)
    assert type(back) is polbrdf.Evaluation and back.brdf == result.brdf
    for cls in (polbrdf.Evaluation, polbrdf.Emissivity, polbrdf.Radiance):
        assert set(typing.get_type_hints(cls)) == set(cls._fields)
    assert len(typing.get_overloads(polbrdf.radiance)) == 2
