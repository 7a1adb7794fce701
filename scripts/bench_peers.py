"""polbrdf against Mitsuba 3 on the same random geometries (run by scripts/bench-peers).

    python scripts/bench_peers.py [--count N] [--repeats R] [--threads T,...] [--cli PATH]
                                  [--check-only]

1. The physics check: where the two models overlap — the specular (facet) term of a conductor —
   the DoLP for unpolarized light must agree. Mitsuba's `roughconductor` (Beckmann) is
   D·G·F/(4 cosθ) with F the conductor Fresnel Mueller matrix at the half-angle; polbrdf's
   specular term with ρ_D = ρ_V = 0 and shadowing off is g·R(η_r)·M_d·R(−η_i) (docs/model.md
   §4–6), with M_d the same Fresnel matrix at the same half-angle β. The scalar factors (D, G,
   SO, 1/cos) do not change the DoLP, and the DoLP of a Stokes vector does not depend on the
   frame's orientation (a rotation of the (S1, S2) pair), so Mitsuba's Stokes frames need no
   conversion to psps for this check (docs/model.md §2). Mitsuba computes in float32: the
   agreement asked is 1e-4 absolute.
2. Throughput: Mitsuba's `llvm_ad_mono_polarized` `bsdf.eval` (the full Mueller matrix × cosθo,
   float32) over N geometries in one launch (`dr.eval`), the JIT compiled and warm, against
   polbrdf's `mueller` (full Mueller, float64 and float32, into reused `out=` arrays, also in
   the planar layout, Mitsuba's own) on the same geometries, and its `mueller_directions` on
   Mitsuba's own float32 direction vectors, on one thread each and on every core by default
   (--threads: a comma-separated list of thread counts, `all` for every core; each count runs
   in a process of its own, with Dr.Jit's `set_thread_count` and rayon's `RAYON_NUM_THREADS`);
   and `polbrdf bench` (the Rust batch API) when --cli is given. Timed by **CPU time** (the
   process's CPU-seconds, every thread of either library included) and wall time, in R
   interleaved rounds (one call of each case per round); the ratio to Mitsuba is the median
   over the rounds of each round's ratio (paired, so a change of load between rounds cancels),
   the rates are medians. On a shared host only the CPU-time figures are comparable.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import time

import numpy as np
import polbrdf

# A conductor (aluminium near 0.6 µm) with a Beckmann lobe.
N_INDEX, K_INDEX = 1.2, 7.0
ALPHA = 0.2  # Beckmann roughness: RMS slope
SIGMA_DEG = float(np.degrees(np.arctan(ALPHA)))  # polbrdf's σ of the same lobe width


def cpu_family() -> str:
    """`family F model M` of the first CPU, from /proc/cpuinfo (the model name of a VM can be
    as bare as "AMD EPYC")."""
    fam = mod = "?"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                key = line.split(":", 1)[0].strip()
                if key == "cpu family" and fam == "?":
                    fam = line.split(":", 1)[1].strip()
                elif key == "model" and mod == "?":
                    mod = line.split(":", 1)[1].strip()
    except OSError:
        pass
    return f"family {fam} model {mod}"


def cpu() -> tuple[str, str]:
    """CPU model and SIMD level (the best of avx512f / avx2+fma / baseline), from /proc/cpuinfo."""
    model, flags = platform.processor() or "unknown CPU", set()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name") and model in ("", "unknown CPU", "x86_64"):
                    model = line.split(":", 1)[1].strip()
                if line.startswith("flags"):
                    flags = set(line.split(":", 1)[1].split())
    except OSError:
        pass
    if "avx512f" in flags:
        simd = "AVX-512"
    elif {"avx2", "fma"} <= flags:
        simd = "AVX2+FMA"
    else:
        simd = "baseline"
    return model, simd


def geometries(n: int, seed: int = 2024) -> tuple[np.ndarray, ...]:
    """θ uniform in [0°, 89.9°], φ uniform in [0°, 360°) (radians), as `polbrdf bench`."""
    rng = np.random.default_rng(seed)
    ti, tr = np.radians(rng.uniform(0.0, 89.9, (2, n)))
    pi, pr = np.radians(rng.uniform(0.0, 360.0, (2, n)))
    return ti, pi, tr, pr


def paired(repeats: int, cases: list) -> list[dict[str, float]]:
    """CPU and wall seconds of each callable over `repeats` interleaved rounds (one call of each
    per round, after one warm-up call each): the median of each, and the median over the rounds
    of the first case's time over this one's (a paired ratio, CPU and wall)."""
    for f in cases:
        f()
    cpu: list[list[float]] = [[] for _ in cases]
    wall: list[list[float]] = [[] for _ in cases]
    for _ in range(repeats):
        for f, c, w in zip(cases, cpu, wall):
            c0, w0 = time.process_time(), time.perf_counter()
            f()
            c.append(time.process_time() - c0)
            w.append(time.perf_counter() - w0)
    out = []
    for c, w in zip(cpu, wall):
        out.append({
            "cpu_s": float(np.median(c)),
            "wall_s": float(np.median(w)),
            "cpu_ratio": float(np.median(np.array(cpu[0]) / np.array(c))),
            "wall_ratio": float(np.median(np.array(wall[0]) / np.array(w))),
        })
    return out


class Mitsuba:
    """Mitsuba 3's polarized rough conductor on fixed geometries (LLVM backend)."""

    def __init__(self, ti, pi, tr, pr, threads: int | None = None):
        import drjit as dr
        import mitsuba as mi

        mi.set_variant("llvm_ad_mono_polarized")
        if threads is not None:
            dr.set_thread_count(threads)
        self.dr, self.mi = dr, mi
        self.version = mi.__version__
        self.bsdf = mi.load_dict(
            {
                "type": "roughconductor",
                "distribution": "beckmann",
                "alpha": ALPHA,
                "eta": N_INDEX,
                "k": K_INDEX,
            }
        )

        def components(t, p):
            return np.stack(
                [np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1
            ).astype(np.float32)

        def vec(w):
            return mi.Vector3f(w[:, 0], w[:, 1], w[:, 2])

        # The float32 vectors Mitsuba gets, as (n, 3) float64 arrays for
        # `polbrdf.mueller_directions`: both evaluate exactly the same directions.
        self.w_source = components(ti, pi).astype(np.float64)
        self.w_detector = components(tr, pr).astype(np.float64)

        n = len(ti)
        si = dr.zeros(mi.SurfaceInteraction3f, n)
        # Mitsuba's si.wi points to the sensor (polbrdf's detector, θr), wo to the light
        # (polbrdf's source, θi); eval returns the Mueller matrix from wo's beam to wi's.
        si.wi = vec(self.w_detector.astype(np.float32))
        si.sh_frame = mi.Frame3f(mi.Normal3f(0, 0, 1))
        si.n = mi.Normal3f(0, 0, 1)
        self.si, self.wo, self.ctx = si, vec(self.w_source.astype(np.float32)), mi.BSDFContext()
        dr.eval(self.si, self.wo)

    def eval(self):
        v = self.bsdf.eval(self.ctx, self.si, self.wo)
        self.dr.eval(v)
        self.dr.sync_thread()
        return v

    def mueller(self) -> np.ndarray:
        """(n, 4, 4) Mueller matrices × cosθo."""
        m = np.array(self.eval())  # (4, 4, 1, n)
        return np.moveaxis(m[:, :, 0, :], -1, 0).astype(np.float64)


def dolp_of_first_column(m: np.ndarray) -> np.ndarray:
    i = m[..., 0, 0]
    lin = np.hypot(m[..., 1, 0], m[..., 2, 0])
    return np.divide(lin, i, out=np.zeros_like(i), where=i > 0)


def physics_check(n: int = 20000) -> float:
    """Largest |DoLP_mitsuba − DoLP_polbrdf| over n random geometries where both are defined
    (F00 > 0 and not below Mitsuba's float32 resolution)."""
    ti, pi, tr, pr = geometries(n, seed=7)
    mit = Mitsuba(ti, pi, tr, pr)
    m = mit.mueller()
    mat = polbrdf.Material(n=N_INDEX, k=K_INDEX, sigma_deg=SIGMA_DEG, shadowing=False)
    d_pol = polbrdf.dolp(mat, ti, pi, tr, pr, degrees=False)
    d_mit = dolp_of_first_column(m)
    ok = (m[:, 0, 0] > 1e-30) & np.isfinite(m[:, 0, 0])
    if ok.sum() < n // 2:
        raise SystemExit(f"physics check: only {ok.sum()} of {n} Mitsuba values usable")
    return float(np.max(np.abs(d_mit[ok] - d_pol[ok])))


def timing(n: int, r: int, threads: int | None) -> None:
    """The throughput table on `threads` threads each (None: every core)."""
    where = "every core" if threads is None else f"{threads} thread(s) each"
    ti, pi, tr, pr = geometries(n)
    mit = Mitsuba(ti, pi, tr, pr, threads)
    mat = polbrdf.Material(n=N_INDEX, k=K_INDEX, sigma_deg=SIGMA_DEG, shadowing=False)
    out64 = np.empty((n, 4, 4))
    out32 = np.empty((n, 4, 4), dtype=np.float32)
    planes64 = np.empty((4, 4, n))
    planes32 = np.empty((4, 4, n), dtype=np.float32)
    ws, wd = mit.w_source, mit.w_detector
    cases = [
        (f"Mitsuba {mit.version} llvm_ad_mono_polarized roughconductor eval (float32)", mit.eval),
        ("mueller float64, angles", lambda: polbrdf.mueller(mat, ti, pi, tr, pr, degrees=False,
                                                            out=out64)),
        ("mueller float32, angles", lambda: polbrdf.mueller(mat, ti, pi, tr, pr, degrees=False,
                                                            out=out32)),
        ("mueller_directions float64 (Mitsuba's vectors)",
         lambda: polbrdf.mueller_directions(mat, ws, wd, out=out64)),
        ("mueller_directions float32 (Mitsuba's vectors)",
         lambda: polbrdf.mueller_directions(mat, ws, wd, out=out32)),
        ("mueller float64, angles, layout=\"planar\" (Mitsuba's)",
         lambda: polbrdf.mueller(mat, ti, pi, tr, pr, degrees=False, out=planes64,
                                 layout="planar")),
        ("mueller float32, angles, layout=\"planar\"",
         lambda: polbrdf.mueller(mat, ti, pi, tr, pr, degrees=False, out=planes32,
                                 layout="planar")),
        ("mueller float64, angles, new array",
         lambda: polbrdf.mueller(mat, ti, pi, tr, pr, degrees=False)),
    ]
    res = paired(r, [f for _, f in cases])
    print(f"\n{n} random geometries, {where}, {r} interleaved rounds (out= reused unless said); "
          f"M elements per CPU-second and per wall second (medians), and the paired ratios to "
          f"Mitsuba (medians over the rounds), CPU time and wall time:")
    print(f"  {'':<58} {'M/CPU-s':>8} {'M/s':>7} {'CPU ratio':>9} {'wall ratio':>10}")
    for (name, _), x in zip(cases, res):
        print(f"  {name:<58} {n / x['cpu_s'] / 1e6:8.1f} {n / x['wall_s'] / 1e6:7.1f} "
              f"{x['cpu_ratio']:8.2f}x {x['wall_ratio']:9.2f}x")
    sys.stdout.flush()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--count", type=int, default=2_000_000)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--threads", default="1,all",
                    help="comma-separated thread counts of the timings, `all` for every core "
                         "(default 1,all)")
    ap.add_argument("--timing", help=argparse.SUPPRESS)
    ap.add_argument("--cli", help="the polbrdf binary, for `polbrdf bench` (the Rust batch API)")
    ap.add_argument("--check-only", action="store_true", help="only the physics check")
    args = ap.parse_args()
    if args.timing is not None:
        # A child process: one thread count (rayon's pool size is read from the environment at
        # polbrdf's first parallel call).
        timing(args.count, args.repeats, None if args.timing == "all" else int(args.timing))
        return
    counts = [t.strip() for t in args.threads.split(",") if t.strip()]
    for t in counts:
        if t != "all" and not (t.isdigit() and int(t) >= 1):
            raise SystemExit(f"--threads: {t!r} is not a thread count (an integer ≥ 1 or all)")

    model, simd = cpu()
    print(f"CPU: {model} ({cpu_family()}), {os.cpu_count()} logical CPUs, SIMD level {simd}; "
          f"load average {os.getloadavg()}")
    dev = physics_check()
    print(f"physics: DoLP of a Beckmann conductor (n={N_INDEX}, k={K_INDEX}), Mitsuba vs polbrdf "
          f"(specular term, shadowing off): max |ΔDoLP| = {dev:.2e} over 20000 geometries")
    if dev > 1e-4:
        raise SystemExit("physics check FAILED: the DoLPs differ by more than 1e-4")
    if args.check_only:
        return

    n, r = args.count, args.repeats
    for t in counts:
        env = dict(os.environ)
        if t != "all":
            env["RAYON_NUM_THREADS"] = t
        else:
            env.pop("RAYON_NUM_THREADS", None)
        subprocess.run([sys.executable, __file__, "--timing", t, "--count", str(n),
                        "--repeats", str(r)], check=True, env=env)
    if args.cli:
        for t in counts:
            cmd = [args.cli, "bench", "--json", "--count", str(min(n, 1_000_000)),
                   "--repeats", str(r)]
            if t != "all":
                cmd += ["--threads", t]
            doc = json.loads(subprocess.run(cmd, check=True, capture_output=True,
                                            text=True).stdout)
            best = doc["results"][-1]
            bw = doc.get("write_bandwidth", {})
            print(f"\n`polbrdf bench` (the Rust batch API, `paint`, {doc['count']} geometries, "
                  f"{best['threads']} threads, SIMD level {doc['cpu']['simd']}; wall time):")
            print(f"  full Mueller float64 {best['mueller_evals_per_s'] / 1e6:7.1f} M/s  "
                  f"float32 {best.get('mueller_f32_evals_per_s', float('nan')) / 1e6:7.1f} M/s  "
                  f"BRDF+DoLP {best['brdf_dolp_evals_per_s'] / 1e6:7.1f} M/s")
            if bw:
                print(f"  memory write bandwidth {bw['bytes_per_s'] / 1e9:.1f} GB/s: full-Mueller "
                      f"roofline {bw['full_mueller_roofline_evals_per_s'] / 1e6:.0f} M/s "
                      f"(float64), {bw['full_mueller_f32_roofline_evals_per_s'] / 1e6:.0f} M/s "
                      f"(float32)")
    print(f"\nload average after the run: {os.getloadavg()}")


if __name__ == "__main__":
    sys.exit(main())
