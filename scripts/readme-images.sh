#!/usr/bin/env bash
# Renders the pictures in README.md and docs/ with the release binary.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
lsys=target/release/lsys
$lsys render examples/plants/bush_3d.lsys -o docs/images/bush_3d.png --size 560x440
$lsys render examples/architecture/gate.lsys -o docs/images/gate.png --size 560x440
$lsys render examples/abop/fig1_24d.lsys -o docs/images/fig1_24d.png --view front --size 440x440 --width 0.8
$lsys build std:pailou -o docs/images/pailou.png --size 560x440
$lsys build std:toukung_side -o docs/images/toukung_side.png --size 560x440
$lsys build std:toukung_middle -o docs/images/toukung_middle.png --size 560x440
$lsys pailou examples/pailou/fig19-4_6-5-15.toml -o docs/images/pailou_6-5-15.png --view front --size 800x440
$lsys pailou examples/pailou/fig17-2_6-5-5.toml -o docs/images/pailou_6-5-5_pillar.png --size 800x500
