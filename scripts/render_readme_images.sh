#!/usr/bin/env bash
# Re-renders the README's example images into docs/images/ (about a minute on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release
for s in cornell furnace radiometry phong gems prism textures; do
  spp=16
  [ "$s" = gems ] && spp=32
  target/release/spectrace render "scenes/$s.toml" -o "target/$s.exr" --png "docs/images/$s.png" --spp "$spp" --quiet
done
