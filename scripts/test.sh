#!/usr/bin/env bash
# Runs every test of the project, exactly as CI does (.ci/run calls this script):
# formatting, lints (warnings are errors, native and wasm), all cargo tests (with naga
# validation and the native GPU-vs-CPU shader test), the wasm build, the Playwright tests in
# Chromium, then the speed benchmarks, analyzer and browser app (they print ratios measured in
# one run and assert nothing about time; quick mode here, PROCTEX_BENCH=full for the full run).
# Two slow cargo tests check a sample by default (the retrieval database's freshness, the
# synthetic retrieval round trip); PROCTEX_TEST=full runs them whole.
# At the end (also after a failure) it prints every stage's wall time and the ten slowest
# Playwright tests.
# Installs what it needs: a Rust toolchain with rustfmt and clippy, Mesa's software Vulkan
# driver (lavapipe), Debian's chromium and glslang-tools (compiles the exported GLSL), and (through scripts/build-web.sh) the wasm target,
# wasm-bindgen-cli and the npm packages.
set -euo pipefail
cd "$(dirname "$0")/.."

# Every stage's wall time, printed at the end (also when a stage fails), so that every CI log
# shows where the time goes.
STAGE_NAMES=()
STAGE_SECONDS=()
stage_name=""
stage_start=0
run_start=$(date +%s)
end_stage() {
    if [ -n "$stage_name" ]; then
        STAGE_NAMES+=("$stage_name")
        STAGE_SECONDS+=($(($(date +%s) - stage_start)))
    fi
    stage_name=""
}
step() {
    end_stage
    printf '\n== %s\n' "$*"
    stage_name="$*"
    stage_start=$(date +%s)
}
print_stage_times() {
    end_stage
    printf '\n== wall time per stage\n'
    local i
    for i in "${!STAGE_NAMES[@]}"; do
        printf '%7s  %s\n' "$(date -u -d "@${STAGE_SECONDS[$i]}" +%H:%M:%S)" "${STAGE_NAMES[$i]}"
    done
    printf '%7s  %s\n' "$(date -u -d "@$(($(date +%s) - run_start))" +%H:%M:%S)" "total"
    if [ -f target/e2e/results.json ]; then
        node e2e/slowest.js target/e2e/results.json 10 || true
    fi
}
trap print_stage_times EXIT

# apt-get as root, or through sudo.
apt_install() {
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "$@"
}

step "system packages"
need=()
ls /usr/share/vulkan/icd.d/lvp_icd.*.json >/dev/null 2>&1 || need+=(mesa-vulkan-drivers)
[ -x /usr/bin/chromium ] || need+=(chromium)
command -v glslangValidator >/dev/null 2>&1 || need+=(glslang-tools)
if [ ${#need[@]} -gt 0 ]; then
    echo "installing ${need[*]}"
    apt_install "${need[@]}"
fi

step "toolchain"
if ! command -v cargo >/dev/null 2>&1; then
    if [ -x "$HOME/.cargo/bin/cargo" ]; then
        export PATH="$HOME/.cargo/bin:$PATH"
    else
        echo "installing Rust (rustup)"
        curl --proto '=https' --tlsv1.2 -sSf https://sh.rustup.rs | sh -s -- -y --profile minimal
        export PATH="$HOME/.cargo/bin:$PATH"
    fi
fi
for component in rustfmt clippy; do
    if ! cargo "${component/rustfmt/fmt}" --version >/dev/null 2>&1; then
        rustup component add "$component"
    fi
done
cargo --version

step "cargo fmt --check"
cargo fmt --all --check

step "cargo clippy --all-targets -- -D warnings (native)"
cargo clippy --workspace --release --all-targets -- -D warnings

step "cargo clippy -- -D warnings (wasm)"
rustup target list --installed | grep -q wasm32-unknown-unknown || rustup target add wasm32-unknown-unknown
cargo clippy -p proctex-web --target wasm32-unknown-unknown --release -- -D warnings
cargo clippy -p proctex-worker --target wasm32-unknown-unknown --release -- -D warnings

step "cargo test"
log=$(mktemp)
cargo test --workspace --release 2>&1 | tee "$log"
read -r passed failed < <(awk '/^test result:/ {
    for (i = 1; i < NF; i++) {
        if ($(i + 1) ~ /^passed/) p += $i
        if ($(i + 1) ~ /^failed/) f += $i
    }
} END { print p + 0, f + 0 }' "$log")
rm -f "$log"

step "wasm build (scripts/build-web.sh)"
./scripts/build-web.sh
# Each module has its own 4 MB budget: the UI's (egui, renderer) and the worker's (analysis).
for module in proctex_web proctex_worker; do
    size=$(stat -c %s "www/pkg/${module}_bg.wasm")
    echo "wasm after wasm-opt, $module: $size bytes (budget 4000000)"
    [ "$size" -le 4000000 ] || { echo "the $module wasm is over its 4 MB budget"; exit 1; }
done

step "Playwright (e2e/, Chromium with SwiftShader WebGPU)"
(cd e2e && npm ci --no-audit --no-fund)
# A free port for the test server, so that another server (or another run) cannot collide.
PROCTEX_E2E_PORT=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export PROCTEX_E2E_PORT
elog=$(mktemp)
rm -f target/e2e/results.json
(cd e2e && npx playwright test) 2>&1 | grep -v '^\[WebServer\]' | tee "$elog"
e2e_passed=$(sed -nE 's/^ *([0-9]+) passed.*/\1/p' "$elog" | tail -1)
e2e_failed=$(sed -nE 's/^ *([0-9]+) failed.*/\1/p' "$elog" | tail -1)
rm -f "$elog"
e2e_passed=${e2e_passed:-0}
e2e_failed=${e2e_failed:-0}

# The benchmarks' quick mode (fewer repetitions, the database build projected from a part;
# every ratio printed): PROCTEX_BENCH=full ./scripts/test.sh runs them in full.
PROCTEX_BENCH=${PROCTEX_BENCH:-quick}
export PROCTEX_BENCH
bench_args=()
[ "$PROCTEX_BENCH" = full ] || bench_args=(--quick)

step "benchmark: analyzer, $PROCTEX_BENCH (ratios within one run; not a pass/fail test)"
# --workspace: the same feature set as cargo test's build, so its artefacts serve (with -p the
# dependencies were built again for the analyzer's features alone: 1 min 20 s).
cargo bench --workspace --bench analysis -- "${bench_args[@]}"
cargo bench --workspace --bench pyramid -- "${bench_args[@]}"

step "benchmark: browser app, $PROCTEX_BENCH (ratios within one run; not a pass/fail test)"
(cd e2e && npx playwright test --config bench.config.js) 2>&1 | grep -v -e '^\[WebServer\]' -e '^\[page\]'

step "summary"
echo "cargo: ${passed} passed, ${failed} failed; playwright: ${e2e_passed} passed, ${e2e_failed} failed"
echo "tests: $((passed + e2e_passed)) passed, $((failed + e2e_failed)) failed"
