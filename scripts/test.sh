#!/usr/bin/env bash
# Runs every test of the project, exactly as CI does (.ci/run calls this script):
# formatting, lints (warnings are errors), all cargo tests, then the speed benchmark (prints
# ratios measured in one run; it asserts nothing about time).
# Installs what it needs: a Rust toolchain with rustfmt and clippy, and Mesa's software Vulkan
# driver (lavapipe) for the GPU-vs-CPU test of the shaders.
set -euo pipefail
cd "$(dirname "$0")/.."

step() { printf '\n== %s\n' "$*"; }

# apt-get as root, or through sudo.
apt_install() {
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "$@"
}

step "system packages"
if ! ls /usr/share/vulkan/icd.d/lvp_icd.*.json >/dev/null 2>&1; then
    echo "installing mesa-vulkan-drivers (software Vulkan for the GPU-vs-CPU test)"
    apt_install mesa-vulkan-drivers
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

step "cargo clippy --all-targets -- -D warnings"
cargo clippy --workspace --release --all-targets -- -D warnings

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

step "benchmark (ratios within one run; not a pass/fail test)"
cargo bench -p proctex-analyzer --bench analysis

step "summary"
echo "cargo tests: ${passed} passed, ${failed} failed"
