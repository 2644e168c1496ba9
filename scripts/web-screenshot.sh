#!/usr/bin/env bash
# scripts/web-screenshot.sh BUILD OUT.png: the browser viewer's picture for docs/WEB.md.
# Writes a 225-building grid city (seed 3) and the page into out/web-city/, serves it on loopback,
# and screenshots the page in headless Chromium at 960x540 with its HUD, once the view settled.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:?usage: scripts/web-screenshot.sh BUILD OUT.png}"
out="${2:?usage: scripts/web-screenshot.sh BUILD OUT.png}"
city="$root/out/web-city"
rm -rf "$city"
"$build/cli/nut" city --count 225 --out "$city" --seed 3 --layout grid
"$build/viewer/nut-viewer" --export-web "$city"
node "$root/scripts/web-screenshot.mjs" "$root" "$city" "$out"
