# Sourced by tests/cli/report_html.sh and report_html_browser.sh (after $bin, $src, $tmp are set): runs the shipped
# studies that finish in seconds, made small as tests/cli/plot_layout.sh makes them (2 models per period pair, 100
# bootstrap replicates), in $tmp/studies -> $tmp/<name>.h5 and the Markdown report $tmp/<name>.md.
#   html_studies [NAME...]  the names run (default: all of them), in $html_names
html_studies() {
  mkdir -p "$tmp/studies"
  ln -sfn "$src/records" "$tmp/records"
  cp "$src/studies/"*.csv "$tmp/studies/"
  html_names=""
  local name
  for name in ${@:-example-pair fragility-pair quick quick-impacts fragility-grid fragility-pair-ida}; do
    sed -e 's/^samples_per_pair = [0-9_]*/samples_per_pair = 2/' -e 's/^bootstrap = [0-9_]*/bootstrap = 100/' \
        -e '/^output = /d' "$src/studies/$name.toml" > "$tmp/studies/$name.toml"
    "$bin" run "$tmp/studies/$name.toml" --out "$tmp/$name.h5" --quiet > "$tmp/$name.md" 2> "$tmp/$name.log" ||
      { cat "$tmp/$name.log"; echo "FAIL: studies/$name.toml (small) did not run"; exit 1; }
    html_names="$html_names $name"
  done
}
