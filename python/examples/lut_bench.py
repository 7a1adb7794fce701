"""Benchmark of polbrdf.lut: a chunked table computed with dask, written to Zarr, its peak
memory measured (docs/scaling.md).

    python lut_bench.py table   [--out /tmp/lut-bench.zarr] [--wavelengths 50] [--n 100]
    python lut_bench.py workers [--workers 1 2] [--repeat 3]

``table``: 2 materials × W wavelengths × n³ geometries (default 2 × 50 × 10⁶ = 10⁸ Mueller
matrices, 12.8 GB of float64) to Zarr with dask's threaded scheduler (each chunk one engine
call, the GIL released); prints the wall time, the throughput and the peak RSS of the process
(``resource.getrusage``), then deletes the store (unless ``--keep``).

``workers``: a ``dask.distributed.LocalCluster`` of 1, 2, … single-threaded worker processes
(``RAYON_NUM_THREADS=1`` in each) computes a table of 2 × 20 × 50³ = 5·10⁶ matrices reduced to
one number (no I/O), ``--repeat`` times: the median throughput per worker count.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import time

import numpy as np

import polbrdf
from polbrdf.xarray import lut


def materials() -> dict[str, polbrdf.Material]:
    return {
        "paint": polbrdf.Material.preset("paint"),
        "gold": polbrdf.Material(index="library:Au/Johnson", sigma_deg=8.0, rho_d=0.01),
    }


def grid(w: int, n: int) -> tuple[np.ndarray, ...]:
    return (
        np.linspace(0.4, 1.8, w),
        np.linspace(0.0, 89.0, n),
        np.linspace(0.0, 89.0, n),
        np.linspace(0.0, 180.0, n),
    )


def rss_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # KiB on Linux


def table(args: argparse.Namespace) -> None:
    import dask

    wl, ti, tr, dp = grid(args.wavelengths, args.n)
    ds = lut(
        materials(),
        wl,
        ti,
        tr,
        dp,
        quantities=("mueller",),
        chunks={"wavelength": 1, "theta_i": args.chunk_theta_i},
    )
    count = ds.mueller.size // 16
    chunk = ds.mueller.data.chunksize
    print(
        f"table: {count:.3e} Mueller matrices, {ds.mueller.nbytes / 1e9:.1f} GB float64, "
        f"chunks {chunk} ({np.prod(chunk) * 8 / 2**20:.0f} MiB), {ds.mueller.data.npartitions} tasks"
    )
    shutil.rmtree(args.out, ignore_errors=True)
    before = rss_mib()
    t0 = time.perf_counter()
    with dask.config.set(scheduler="threads", num_workers=args.threads):
        ds.to_zarr(args.out, mode="w", consolidated=False)
    dt = time.perf_counter() - t0
    size = sum(os.path.getsize(os.path.join(d, f)) for d, _, fs in os.walk(args.out) for f in fs)
    print(
        f"written to {args.out} in {dt:.1f} s: {count / dt / 1e6:.2f} M matrices/s, "
        f"{size / 1e9:.2f} GB on disk; peak RSS {rss_mib():.0f} MiB (before compute {before:.0f} MiB)"
    )
    if not args.keep:
        shutil.rmtree(args.out)


def workers(args: argparse.Namespace) -> None:
    from distributed import Client, LocalCluster

    wl, ti, tr, dp = grid(20, 50)
    for n in args.workers:
        with LocalCluster(
            n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
            env={"RAYON_NUM_THREADS": "1"},
        ) as cluster, Client(cluster) as client:  # fmt: skip
            # The two lines that change for a real cluster (docs/scaling.md):
            #     client = Client("tcp://scheduler-host:8786")
            # and nothing else: the same lut(...) and compute.
            ds = lut(
                materials(),
                wl,
                ti,
                tr,
                dp,
                quantities=("mueller",),
                chunks={"wavelength": 1, "theta_i": 10},
            )
            count = ds.mueller.size // 16
            client.compute(ds.mueller.sum()).result()  # warm-up: import polbrdf in the workers
            times = []
            for _ in range(args.repeat):
                t0 = time.perf_counter()
                client.compute(ds.mueller.sum()).result()
                times.append(time.perf_counter() - t0)
            peak = client.run(lambda: resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
            med = statistics.median(times)
            print(
                f"{n} worker(s): median {med:.3f} s over {args.repeat} for {count:.3e} matrices "
                f"= {count / med / 1e6:.2f} M/s; worker peak RSS "
                f"{max(peak.values()):.0f} MiB"
            )


def main() -> None:
    p = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    sub = p.add_subparsers(dest="what", required=True)
    t = sub.add_parser("table")
    t.add_argument("--out", default="/tmp/lut-bench.zarr")
    t.add_argument("--wavelengths", type=int, default=50)
    t.add_argument("--n", type=int, default=100)
    t.add_argument("--chunk-theta-i", type=int, default=25)
    t.add_argument("--threads", type=int, default=2)
    t.add_argument("--keep", action="store_true")
    w = sub.add_parser("workers")
    w.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    w.add_argument("--repeat", type=int, default=3)
    args = p.parse_args()
    table(args) if args.what == "table" else workers(args)


if __name__ == "__main__":
    main()
