#!/usr/bin/env bash
# The compare report in a real browser (headless Chromium, installed by tools/setup.sh): the page
# opens offline from file://, its script runs without error and renders every compared channel
# (the script's marker element lists each channel whose images decoded).
#
#   tests/report_browser_test.sh PATH/TO/oceanref
set -uo pipefail

bin=${1:?usage: report_browser_test.sh PATH/TO/oceanref}
root=$(cd "$(dirname "$0")/.." && pwd)
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  # tools/setup.sh installs chromium, so CI always runs this test.
  echo "report_browser_test: chromium not installed (tools/setup.sh installs it): skipped"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
  # tools/mutation.py: the first failure is enough.
  if [ -n "${OCEANREF_TESTS_FAIL_FAST:-}" ]; then exit 1; fi
}

# A failing comparison with several channels: the float32 backend with a dropped term.
scene=$root/reference/scenes/golden/pm_high_sun.json
"$bin" bench float32 "$scene" --time 2.5 -o "$tmp/good.exr" --golden "$tmp/gold.exr" >/dev/null ||
  fail "bench float32 failed"
"$bin" bench float32 "$scene" --time 2.5 -o "$tmp/bad.exr" --defect drop-conjugate-term \
  >/dev/null || fail "bench float32 --defect failed"
"$bin" compare "$tmp/bad.exr" "$tmp/gold.exr" --report "$tmp/report" --json "$tmp/c.json" \
  >/dev/null
[ $? -eq 1 ] || fail "compare of the broken backend did not exit 1"
# A passing one, with the shipped profile.
"$bin" compare "$tmp/good.exr" "$tmp/gold.exr" --report "$tmp/report_pass" \
  --profile "$root/reference/profiles/fields_float32.json" --json "$tmp/p.json" >/dev/null ||
  fail "compare of the float32 backend with its profile did not pass"

check_page() {  # DIR JSON
  local dir=$1 json=$2
  grep -Eq 'src="(https?:)?//' "$dir/index.html" && fail "$dir/index.html loads from the network"
  "$browser" --headless --no-sandbox --disable-gpu --user-data-dir="$tmp/profile" \
    --virtual-time-budget=10000 --dump-dom "file://$dir/index.html" >"$tmp/dom.html" \
    2>"$tmp/browser.log"
  [ -s "$tmp/dom.html" ] || { fail "$browser printed no DOM: $(tail -3 "$tmp/browser.log")"; return; }
  grep -q 'id="script-error"' "$tmp/dom.html" &&
    fail "$dir: script error: $(grep -o 'id="script-error"[^<]*' "$tmp/dom.html")"
  local marker
  marker=$(tr '\n' '|' <"$tmp/dom.html" | grep -o 'id="rendered-channels"[^<]*')
  [ -n "$marker" ] || { fail "$dir: the script wrote no rendered-channels marker"; return; }
  local channels count=0
  channels=$(grep -o '"golden": "[^"]*"' "$json" | sed 's/"golden": "//; s/"$//' | grep -v '\.exr$')
  for c in $channels; do
    count=$((count + 1))
    # Labelled CHANNEL, or PART/CHANNEL when the files have several parts.
    echo "$marker" | grep -q "[|/]$c\(|\|$\)" || fail "$dir: channel $c not rendered by the page"
  done
  [ "$count" -ge 8 ] || fail "$dir: expected 8 compared channels, found $count"
  echo "$marker" | grep -q "data-count=\"$count\"" ||
    fail "$dir: the page rendered a different number of channels than $count: $marker"
}
check_page "$tmp/report" "$tmp/c.json"
check_page "$tmp/report_pass" "$tmp/p.json"

echo "report_browser_test: $failures failed"
[ "$failures" -eq 0 ]
