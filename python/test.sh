#!/usr/bin/env bash
# Builds the Python wheel with maturin in a fresh virtual environment, installs it and runs
# the pytest suite (python/tests). Usage: python/test.sh [pytest arguments]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
venv="${SPECTRACE_VENV:-$here/target/venv}"
rm -rf "$venv"
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet "maturin>=1.9.4,<2" "numpy>=1.21" "pytest>=7"
rm -rf "$here/target/wheels"
"$venv/bin/maturin" build --release --manifest-path "$here/Cargo.toml" --out "$here/target/wheels"
"$venv/bin/python" -m pip install --quiet "$here"/target/wheels/spectrace-*.whl
# run from the tests' folder so that `import spectrace` is the installed wheel, not the source
cd "$here/tests"
"$venv/bin/python" -m pytest -q "$@"
