#!/usr/bin/env bash
# Peak memory of `polbrdf fit --data table.pbsdf` on a KAIST-sized table (issue 17): exports the
# `paint` preset on the KAIST grid (361 × 91 × 91 cells × 5 bands, 0.96 GB), then fits it from a
# perturbed start under /usr/bin/time and prints the peak resident set size of each run.
# Usage: [SUBSAMPLES="auto 4"] scripts/bench_pbsdf_memory.sh [POLBRDF_BINARY] [REPEATS]
# Needs about 1 GB of free disk in $TMPDIR. Not a timed test: run it on a quiet machine.
set -euo pipefail
bin="${1:-${CARGO_TARGET_DIR:-target}/release/polbrdf}"
repeats="${2:-3}"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
printf 'n = 1.5\nsigma_deg = 20\nrho_d = 0.02\nrho_v = 0.02\n' > "$dir/start.toml"
/usr/bin/time -f "export: %e s, peak RSS %M KB" "$bin" export --material paint --grid 361,91,91 --output "$dir/big.pbsdf"
ls -l "$dir/big.pbsdf"
for sub in ${SUBSAMPLES:-auto 4}; do
    for r in $(seq "$repeats"); do
        extra=()
        [ "$sub" != auto ] && extra=(--subsample "$sub")
        /usr/bin/time -f "fit (--subsample $sub, run $r): %e s, peak RSS %M KB" \
            "$bin" fit --material "$dir/start.toml" --data "$dir/big.pbsdf" \
            --free n,sigma_deg,rho_d,rho_v --output "$dir/fit.json" "${extra[@]}" 2>&1 \
            | grep -E "fit \(|nm:" | tail -n 6
    done
done
