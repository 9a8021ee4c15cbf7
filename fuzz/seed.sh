#!/usr/bin/env bash
# Seeds the fuzz corpora (fuzz/corpus/<target>/, not committed) from the
# examples, the test fixtures and the committed regression inputs.
set -euo pipefail
cd "$(dirname "$0")"
for t in parse compile derive build_glb; do
  mkdir -p "corpus/$t"
  find ../examples ../tests/fixtures -name '*.lsys' | while read -r f; do
    cp "$f" "corpus/$t/seed_$(echo "$f" | tr '/.' '__')"
  done
  cp ../tests/fuzz_regressions/* "corpus/$t/" 2>/dev/null || true
done
