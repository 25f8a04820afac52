#!/usr/bin/env bash
# Copies Mitsuba 3's participating-media test scenes and their official spectral references from
# a checkout of the public repository mitsuba-renderer/mitsuba-data into
# tests/reference/mitsuba-data/, keeping the repository's layout so that the scenes' relative
# paths (`<path value="../../../common"/>`, `include/…`) resolve unchanged.
#
#   scripts/copy_mitsuba_media.sh /path/to/mitsuba-data
#
# The references (refs/*_ref_spectral.exr, linear sRGB, and *_ref_spectral_var.exr, the per-sample
# variance) are Mitsuba's own: rendered by mitsuba3/src/render/tests/test_renders.py at 32 000 spp
# with its scalar_spectral variant. Only the spectral ones are copied.
set -euo pipefail
src="${1:?usage: $0 /path/to/mitsuba-data}"
dst="$(cd "$(dirname "$0")/.." && pwd)/tests/reference/mitsuba-data"
pm=tests/scenes/participating_media
mkdir -p "$dst/$pm/refs" "$dst/$pm/include" "$dst/$pm/meshes" "$dst/$pm/textures" "$dst/common/textures"
cp "$src/$pm"/test_*.xml "$dst/$pm/"
cp "$src/$pm"/include/*.xml "$dst/$pm/include/"
cp "$src/$pm"/meshes/*.obj "$dst/$pm/meshes/"
cp "$src/$pm"/textures/*.vol "$dst/$pm/textures/"
cp "$src/$pm"/refs/*_ref_spectral.exr "$src/$pm"/refs/*_ref_spectral_var.exr "$dst/$pm/refs/"
cp "$src/common/textures/museum.exr" "$dst/common/textures/"
if git -C "$src" rev-parse HEAD >/dev/null 2>&1; then
  git -C "$src" rev-parse HEAD > "$dst/COMMIT"
fi
echo "copied into $dst"
