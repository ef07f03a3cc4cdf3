#!/usr/bin/env bash
# Render an upliftlab HTML report in headless Chromium and save a PNG of it, to look at.
#
#   benchmarks/report_screenshot.sh [REPORT.html] [OUT.png] [WIDTH] [HEIGHT]
#
# Defaults: results/report-fast/report.html, its directory's report.png, 1280 x 6000 px.
# Builds the report first (upliftlab report --fast) when it does not exist. Needs Debian's
# chromium (apt-get install -y chromium). The browser gets a throwaway profile and no network
# features; the report itself loads nothing from outside (images are embedded).
set -euo pipefail
html="${1:-results/report-fast/report.html}"
if [[ ! -f "$html" ]]; then
    upliftlab report --fast --out "$(dirname "$html")" || true
fi
[[ -f "$html" ]] || { echo "report_screenshot: no report at $html" >&2; exit 2; }
png="${2:-$(dirname "$html")/report.png}"
width="${3:-1280}"
height="${4:-6000}"
browser="$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)"
[[ -n "$browser" ]] || { echo "report_screenshot: chromium not found (apt-get install -y chromium)" >&2; exit 2; }
profile="$(mktemp -d)"
trap 'rm -rf "$profile"' EXIT
"$browser" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --hide-scrollbars --user-data-dir="$profile" --window-size="${width},${height}" \
    --screenshot="$(realpath -m "$png")" "file://$(realpath "$html")" 2>/dev/null
echo "report_screenshot: wrote $png (${width} x ${height})"
