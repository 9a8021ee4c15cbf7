#!/usr/bin/env bash
# Runs one fuzz target for MINUTES minutes on one core, niced:
#   fuzz/run.sh parse 10
#   fuzz/run.sh derive 10 -fork=1 -ignore_crashes=1   (keep going, collect all)
# Needs cargo-fuzz (`cargo install cargo-fuzz`) and a nightly compiler, or
# a stable one with RUSTC_BOOTSTRAP=1 (set here). Crashes land in
# fuzz/artifacts/<target>/.
set -euo pipefail
cd "$(dirname "$0")"
target=$1
minutes=${2:-10}
shift 2 || shift $#
[ -d "corpus/$target" ] || ./seed.sh
export RUSTC_BOOTSTRAP=1
exec nice -n 10 cargo fuzz run --fuzz-dir . --sanitizer none --debug-assertions \
  --target-dir "${CARGO_TARGET_DIR:-$PWD/target}/fuzz" "$target" "corpus/$target" -- \
  -max_total_time=$((minutes * 60)) -rss_limit_mb=2048 -timeout=10 -max_len=4096 \
  -dict=lsys.dict -print_final_stats=1 "$@"
