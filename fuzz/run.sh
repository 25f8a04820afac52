#!/usr/bin/env bash
# Runs one fuzz target for SECONDS (default 600) with the memory and time bounds every loader
# must meet: 2 GiB of resident memory, 10 s per input. Usage: fuzz/run.sh TARGET [SECONDS]
# Needs the nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz`); seed first with
# fuzz/seed.sh. A crash, timeout or out-of-memory input is saved in fuzz/artifacts/TARGET/.
set -euo pipefail
cd "$(dirname "$0")"
t=$1; secs=${2:-600}
exec cargo +nightly fuzz run "$t" "corpus/$t" -- \
  -max_total_time="$secs" -rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10 -print_final_stats=1
