#!/usr/bin/env bash
# Fuzzes what Proctex reads from users (fuzz/fuzz_targets: image decode + analysis, params JSON,
# presets libraries, share-link fragments) with cargo-fuzz (libFuzzer), MINUTES per target,
# JOBS targets at a time, starting from and adding to the corpus kept in fuzz/corpus/TARGET.
# Prints, per target, the executions, the corpus size and the crashes (saved under
# fuzz/artifacts/TARGET; rerun one with `cargo +nightly fuzz run --fuzz-dir fuzz TARGET FILE`).
# The corpus is kept in the repository as fuzz/corpus/TARGET.tar.xz (minimised, ~0.4 MB for all
# targets against ~25 MB unpacked): unpacked before a run, minimised and packed again after.
#
# Not part of CI (it needs nightly and minutes per target); installs what it needs.
#
#   scripts/fuzz.sh [MINUTES=10] [TARGET...]      JOBS=2 by default
set -euo pipefail
cd "$(dirname "$0")/.."
MINUTES=${1:-10}
shift || true
if ! [ "$MINUTES" -ge 1 ] 2>/dev/null; then
    echo "scripts/fuzz.sh: MINUTES must be a whole number ≥ 1 (libFuzzer reads 0 as no limit)" >&2
    exit 2
fi
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then
    TARGETS=(decode_analyze params_json presets_library share_fragment)
fi
JOBS=${JOBS:-2}
rustup toolchain list | grep -q '^nightly' || rustup toolchain install nightly --profile minimal
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked
cargo +nightly fuzz build --fuzz-dir fuzz -O
mkdir -p fuzz/logs
run_one() {
    local t=$1
    if [ ! -d "fuzz/corpus/$t" ] && [ -f "fuzz/corpus/$t.tar.xz" ]; then
        tar -xJf "fuzz/corpus/$t.tar.xz" -C fuzz/corpus
    fi
    mkdir -p "fuzz/corpus/$t"
    # -timeout: an input that takes 30 s is a hang; -rss_limit_mb: a runaway allocation.
    cargo +nightly fuzz run --fuzz-dir fuzz -O "$t" "fuzz/corpus/$t" -- \
        -max_total_time=$((MINUTES * 60)) -timeout=30 -rss_limit_mb=2048 \
        -print_final_stats=1 >"fuzz/logs/$t.log" 2>&1 || true
    cargo +nightly fuzz cmin --fuzz-dir fuzz -O "$t" "fuzz/corpus/$t" >"fuzz/logs/$t.cmin.log" 2>&1 || true
    tar --sort=name --mtime=@0 --owner=0 --group=0 --numeric-owner -cJf "fuzz/corpus/$t.tar.xz" \
        -C fuzz/corpus "$t"
}
export -f run_one
export MINUTES
printf '%s\n' "${TARGETS[@]}" | xargs -P "$JOBS" -I{} bash -c 'run_one {}'
printf '%-16s %12s %8s %8s\n' target executions corpus crashes
for t in "${TARGETS[@]}"; do
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "fuzz/logs/$t.log" | grep -o '[0-9]*$' || echo '?')
    corpus=$(find "fuzz/corpus/$t" -type f | wc -l)
    crashes=$(find "fuzz/artifacts/$t" -type f 2>/dev/null | wc -l)
    printf '%-16s %12s %8s %8s\n' "$t" "${runs:-?}" "$corpus" "$crashes"
done
