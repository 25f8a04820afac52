#!/usr/bin/env bash
# Seeds each fuzz target's corpus (fuzz/corpus/<target>/) from the repository's test and
# example files. Run from anywhere; the corpora are not committed (see .gitignore).
set -euo pipefail
cd "$(dirname "$0")/.."
seed() { # target, files…
  local t=$1; shift
  mkdir -p "fuzz/corpus/$t"
  for f in "$@"; do
    [ -f "$f" ] && [ "$(stat -c %s "$f")" -le 1000000 ] && cp "$f" "fuzz/corpus/$t/$(echo "$f" | tr / _)"
  done
  echo "$t: $(ls "fuzz/corpus/$t" | wc -l) seeds"
}
seed toml_scene scenes/*.toml tests/bad_scenes/*.toml
seed mitsuba_xml tests/bad_scenes/*.xml tests/reference/*/scene.xml benchmarks/scenes/*.xml
seed obj $(find scenes tests benchmarks -name '*.obj')
seed ply $(find scenes tests benchmarks -name '*.ply')
seed spectrum_csv spectra/*.csv $(find tests -name '*.csv')
seed photometric scenes/luminaires/*
seed vol $(find tests -name '*.vol')
seed lens scenes/lenses/*.lens tests/bad_lenses/*.lens
