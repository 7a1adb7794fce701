"""Shared fixtures. The package under test is the installed one (`pip install ./python`)."""

from __future__ import annotations

import json
from typing import Any

import pytest
from support import VECTORS

import polbrdf


@pytest.fixture(scope="session")
def vectors() -> list[dict[str, Any]]:
    with VECTORS.open(encoding="utf-8") as f:
        cases: list[dict[str, Any]] = json.load(f)["cases"]
    assert len(cases) >= 40, f"test vectors loaded from {VECTORS}: {len(cases)}"
    return cases


@pytest.fixture(scope="session")
def paint() -> polbrdf.Material:
    return polbrdf.Material.preset("paint")
