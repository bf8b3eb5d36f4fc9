#!/usr/bin/env bash
# The campaign report as a reader sees it: a small campaign of the stand-in driver (warnings,
# collisions, warning scenes, on a real network for the maps), reported with figures, then
# index.html opened in headless Chromium at 1400 px: every image loads, no script error, no
# table wider than the window, no snake_case header; a screenshot is kept as an artifact
# (WORK_DIR/index.png). The checker is shown to catch a broken page first. Skips (exit 77) where
# Chromium (Debian's chromium) or matplotlib is missing.
# Usage: report_browser_test.sh CRITICALITY_CAMPAIGN STAND_IN_DRIVER CRITICALITY_BENCH REPO WORK_DIR
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
tool=$1 driver=$2 bench=$3 repo=$4 work=$5
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  echo "SKIP: no chromium (Debian package chromium; tools/setup.sh installs it)"
  exit 77
fi
if ! /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  echo "SKIP: /usr/bin/python3 has no matplotlib (python3-matplotlib): no figures to check"
  exit 77
fi
rm -rf "$work" && mkdir -p "$work/a" "$work/b" && cd "$work" || exit 1
. "$here/test_helpers.sh"  # failures, fail, check

# Headless Chromium with the page's console on stderr; a fresh profile, nothing from the network.
chrome() {
  timeout 120 "$browser" --headless --no-sandbox --disable-gpu --disable-background-networking \
    --disable-component-update --no-first-run --disable-dev-shm-usage \
    --user-data-dir="$work/profile" --enable-logging=stderr --v=0 \
    --allow-file-access-from-files "$@"
}

# What a page shows in a 1400 px frame: images (loaded or not), its width, tables that must
# scroll, headers with underscores. Printed as one JSON line.
inspect() {  # PAGE (a file name in the folder of check.html)
  local dir
  dir=$(dirname "$1")
  cat >"$dir/check.html" <<HTML
<!DOCTYPE html><html><body>
<iframe id="f" src="$(basename "$1")" style="width:1400px;height:900px;border:0"></iframe>
<script>
const f = document.getElementById('f');
f.addEventListener('load', () => {
  const d = f.contentDocument;
  const imgs = Array.from(d.images);
  Promise.all(imgs.map(i => i.complete ? null :
      new Promise(r => { i.addEventListener('load', r); i.addEventListener('error', r); })))
    .then(() => {
      const r = {images: imgs.length,
                 broken: imgs.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.getAttribute('src')),
                 page_width: d.documentElement.scrollWidth,
                 scrolling_tables: Array.from(d.querySelectorAll('.table-wrap'))
                     .filter(w => w.scrollWidth > w.clientWidth + 1).length,
                 snake_headers: Array.from(d.querySelectorAll('th')).map(t => t.textContent)
                     .filter(t => t.includes('_'))};
      const p = document.createElement('pre');
      p.id = 'result';
      p.textContent = JSON.stringify(r);
      document.body.appendChild(p);
    });
});
</script></body></html>
HTML
  chrome --virtual-time-budget=15000 --dump-dom "file://$dir/check.html" 2>"$dir/check.err" |
    sed -n 's|.*<pre id="result">\(.*\)</pre>.*|\1|p' | sed 's/&quot;/"/g'
}
# Script errors of a page, from its console (Chromium's log on stderr).
script_errors() {  # PAGE
  chrome --virtual-time-budget=5000 --dump-dom "file://$1" 2>&1 >/dev/null |
    grep -E 'CONSOLE.*(Uncaught|Error)' || true
}
field() { python3 -c "import json,sys; print(json.loads(sys.argv[1])[sys.argv[2]])" "$1" "$2"; }

# --- the checker finds what is wrong on a broken page ---------------------------------------
mkdir -p broken
cat >broken/page.html <<'HTML'
<!DOCTYPE html><html><body><img src="missing.png"><div class="table-wrap" style="width:200px;
overflow-x:auto"><table><tr><th>raw_name</th></tr><tr><td style="white-space:nowrap">
a cell far too wide for two hundred pixels of width</td></tr></table></div>
<script>notDefinedAnywhere();</script></body></html>
HTML
out=$(inspect "$work/broken/page.html")
check [ -n "$out" ]
if [ -n "$out" ]; then
  check [ "$(field "$out" broken)" = "['missing.png']" ]
  check [ "$(field "$out" scrolling_tables)" = 1 ]
  check [ "$(field "$out" snake_headers)" = "['raw_name']" ]
fi
check [ -n "$(script_errors "$work/broken/page.html")" ]

# --- a campaign's report --------------------------------------------------------------------
for s in a b; do
  echo "sumo-config = $repo/scenarios/rear_end/rear_end.sumocfg" >$s/scenario.cfg
done
cat >c.yaml <<EOF
name: browser
output: out
scenarios: [a/scenario.cfg, b/scenario.cfg]
driver:
  stand-in-newer: true
  stand-in-collide: 1.0
  stand-in-warn: 0.6
grid:
  driver:
    act: [warn, brake]
  sumo:
    seed: [1, 2]
EOF
"$tool" run c.yaml -j 2 --driver "$driver" --no-check --no-progress >/dev/null 2>run.err ||
  fail "run: $(tail -n 1 run.err)"
"$tool" report out --bench "$bench" >report.out 2>report.err || fail "report: $(tail -n 2 report.err)"
page=$work/out/report/index.html
check [ -s "$page" ]
check [ -s out/report/scenes/warning_0_1.png ]  # a warning scene, linked from the table
check grep -q 'href="scenes/warning_0_1.png"' "$page"
check grep -q 'src="map_a.png"' "$page"
out=$(inspect "$page")
echo "page: $out"
check [ -n "$out" ]
if [ -n "$out" ]; then
  check [ "$(field "$out" images)" -ge 5 ]
  check [ "$(field "$out" broken)" = "[]" ]
  check [ "$(field "$out" page_width)" -le 1400 ]
  check [ "$(field "$out" scrolling_tables)" = 0 ]
  check [ "$(field "$out" snake_headers)" = "[]" ]
fi
errors=$(script_errors "$page")
check [ -z "$errors" ]
[ -n "$errors" ] && echo "$errors" >&2
# The artifact: the page as it looks at 1400 px.
chrome --screenshot="$work/index.png" --window-size=1400,2400 --hide-scrollbars "file://$page" \
  >/dev/null 2>&1
check [ -s "$work/index.png" ]
echo "screenshot: $work/index.png"
# A later report with fewer pictures leaves none of the earlier ones behind.
check [ "$(ls out/report/scenes/*.png | wc -l)" -ge 2 ]
"$tool" report out --bench "$bench" --scene-pictures 1 >/dev/null 2>&1
check [ "$(ls out/report/scenes/*.png | wc -l)" = 1 ]

if [ $failures -gt 0 ]; then
  echo "$failures check(s) failed (work folder $work)" >&2
  exit 1
fi
echo "report_browser: all checks passed"
