"""Time polbrdf from Python on 10^6 random valid geometries of the `paint` preset.

    python python/examples/bench.py [N [REPEATS]]
    cargo run --release -p polbrdf-python --example bench_batch [-- N REPEATS]   # pure Rust

Prints the median wall time of each call over REPEATS runs (after one warm-up run).
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable

import numpy as np

import polbrdf


def median_ms(repeats: int, f: Callable[[], object]) -> tuple[float, float]:
    """Median wall time and median process CPU time (all threads) of f(), in ms."""
    f()  # warm-up
    wall, cpu = [], []
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        f()
        cpu.append((time.process_time() - c0) * 1e3)
        wall.append((time.perf_counter() - t0) * 1e3)
    return float(np.median(wall)), float(np.median(cpu))


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 7
    paint = polbrdf.Material.preset("paint")
    rng = np.random.default_rng(2024)
    ti, tr = rng.uniform(0, 89.9, (2, n))
    pi, pr = rng.uniform(0, 360, (2, n))
    rad = [np.radians(x) for x in (ti, pi, tr, pr)]
    out64 = np.empty((n, 4, 4))
    out32 = np.empty((n, 4, 4), dtype=np.float32)
    print(f"{n} geometries of `paint`, medians of {repeats} (ms); cores: {os.cpu_count()}")
    cases: list[tuple[str, Callable[[], object]]] = [
        ("mueller, degrees (converted in Rust)", lambda: polbrdf.mueller(paint, ti, pi, tr, pr)),
        (
            "mueller, np.radians then degrees=False",
            lambda: polbrdf.mueller(
                paint, *[np.radians(x) for x in (ti, pi, tr, pr)], degrees=False
            ),
        ),
        ("mueller, radians input", lambda: polbrdf.mueller(paint, *rad, degrees=False)),
        (
            "mueller, radians input, out= reused",
            lambda: polbrdf.mueller(paint, *rad, degrees=False, out=out64),
        ),
        (
            "mueller float32, radians input, out= reused",
            lambda: polbrdf.mueller(paint, *rad, degrees=False, out=out32),
        ),
        (
            "mueller float32, radians input, new array",
            lambda: polbrdf.mueller(paint, *rad, degrees=False, precision="float32"),
        ),
        ("brdf, degrees (brdf+dolp pass)", lambda: polbrdf.brdf(paint, ti, pi, tr, pr)),
        ("dolp, radians input", lambda: polbrdf.dolp(paint, *rad, degrees=False)),
        ("evaluate (brdf, dolp, aolp)", lambda: polbrdf.evaluate(paint, ti, pi, tr, pr)),
        (
            "evaluate with_mueller",
            lambda: polbrdf.evaluate(paint, ti, pi, tr, pr, with_mueller=True),
        ),
        ("mueller, scalar x array broadcast", lambda: polbrdf.mueller(paint, 45.0, 0.0, tr, pr)),
    ]
    for name, f in cases:
        wall, cpu = median_ms(repeats, f)
        print(f"python {name:<50} wall {wall:8.1f}  cpu {cpu:8.1f}")


if __name__ == "__main__":
    main()
