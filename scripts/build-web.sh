#!/usr/bin/env bash
# Builds the browser app into www/pkg: the UI's and the worker's wasm crates (profile
# wasm-release), wasm-bindgen
# (pinned to the crate's wasm-bindgen version), then wasm-opt -Oz from npm's binaryen.
# Installs what it needs: the wasm32 target, wasm-bindgen-cli, and the npm tools (in tools/).
set -euo pipefail
cd "$(dirname "$0")/.."

export PATH="$HOME/.cargo/bin:$PATH"
WB_VERSION=$(sed -n 's/^wasm-bindgen = "=\(.*\)"/\1/p' web/Cargo.toml)

rustup target list --installed | grep -q wasm32-unknown-unknown || rustup target add wasm32-unknown-unknown
if [ "$(wasm-bindgen --version 2>/dev/null | cut -d' ' -f2)" != "$WB_VERSION" ]; then
    echo "installing wasm-bindgen-cli $WB_VERSION (a few minutes, once)"
    cargo install wasm-bindgen-cli --version "$WB_VERSION"
fi
if [ ! -x tools/node_modules/.bin/wasm-opt ]; then
    (cd tools && npm ci --no-audit --no-fund)
fi

# Two modules, each built with only what it needs: the UI (egui, the wgpu renderer) and the
# worker (analysis, retrieval, refinement). Two cargo runs, so that the worker crate's
# `exports` feature stays off in the UI's build (cargo unifies features within one run).
cargo build -p proctex-web --target wasm32-unknown-unknown --profile wasm-release
cargo build -p proctex-worker --target wasm32-unknown-unknown --profile wasm-worker
rm -rf www/pkg
# module, cargo profile, wasm-opt level: the UI for size, the worker for speed (Cargo.toml).
# The two modules' wasm-bindgen and wasm-opt run side by side (each is one thread; together
# they took 1 min 47 s one after the other on the 2-core CI machine).
finish_module() {
    local module=$1 profile=$2 level=$3
    wasm-bindgen --target web --no-typescript --out-dir www/pkg \
        "target/wasm32-unknown-unknown/$profile/$module.wasm"
    tools/node_modules/.bin/wasm-opt "$level" --enable-bulk-memory \
        --enable-nontrapping-float-to-int --enable-sign-ext --enable-mutable-globals \
        "www/pkg/${module}_bg.wasm" -o "www/pkg/${module}_bg.wasm"
    echo "www/pkg/${module}_bg.wasm: $(stat -c %s "www/pkg/${module}_bg.wasm") bytes"
}
mkdir -p www/pkg
finish_module proctex_web wasm-release -Oz &
ui=$!
finish_module proctex_worker wasm-worker -O3 &
worker=$!
# Both waited for, so that neither is left running; either failing fails the build.
status=0
wait "$ui" || status=$?
wait "$worker" || status=$?
[ "$status" -eq 0 ] || { echo "wasm-bindgen or wasm-opt failed"; exit "$status"; }
# The pattern database (structured-model retrieval) is fetched by the worker, not embedded in
# the wasm: it would more than double the download the app needs before its first frame.
cp analyzer/data/patterns.ptxdb www/pkg/patterns.ptxdb
echo "www/pkg/patterns.ptxdb: $(stat -c %s www/pkg/patterns.ptxdb) bytes"
