#!/usr/bin/env bash
# Seeds the fuzz corpora (fuzz/corpus/<target>/, not committed) from the
# examples, the test fixtures and the committed regression inputs.
set -euo pipefail
cd "$(dirname "$0")"
for t in parse compile derive build_glb lsp; do
  mkdir -p "corpus/$t"
  find ../examples ../tests/fixtures -name '*.lsys' | while read -r f; do
    cp "$f" "corpus/$t/seed_$(echo "$f" | tr '/.' '__')"
  done
  cp ../tests/fuzz_regressions/* "corpus/$t/" 2>/dev/null || true
done
# cpfg models: the `.l` examples and fixtures (the corpus of others'
# models in ../shared/corpus is not ours to copy; point CPFG_SEEDS at it
# to seed from it locally).
mkdir -p corpus/cpfg
find ../examples ../tests/fixtures ${CPFG_SEEDS:-} -name '*.l' 2>/dev/null | while read -r f; do
  cp "$f" "corpus/cpfg/seed_$(echo "$f" | tr '/.' '__')"
done || true
