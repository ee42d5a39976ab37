#!/usr/bin/env bash
# Builds the browser app and serves it on http://localhost:${PORT:-8080}/ with the built-in
# sample photo. Installs what it needs (see scripts/build-web.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build-web.sh
PORT=${PORT:-8080}
echo "Proctex: http://localhost:$PORT/"
exec python3 -m http.server "$PORT" --bind 127.0.0.1 --directory www
