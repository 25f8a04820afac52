#!/usr/bin/env bash
# Re-renders the README's example images into docs/images/ (about two minutes on 2 cores), each
# scene with the integrator that shows it best: bdpt where light reaches the camera through
# glass (the rainbows of both prism scenes, the gems' caustics under the sun and sky), whitted
# for the notes' Phong model, path elsewhere.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release
render() { # scene integrator spp
  target/release/spectrace render "scenes/$1.toml" -o "target/$1.exr" --png "docs/images/$1.png" \
    --integrator "$2" --spp "$3" --quiet
}
render prism bdpt 9
render prism_screen bdpt 32
render gems bdpt 128
render cornell path 16
render furnace path 16
render radiometry path 16
render phong whitted 16
render textures path 16
render polarisation path 64
render lens path 64
render coatings path 256
render bubbles path 128
