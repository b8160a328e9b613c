#!/usr/bin/env bash
# capture_outputs.sh BINDIR OUTDIR: run the scene files and the seed's examples with the
# binaries in BINDIR (bipo, delamination, shear, pile_pullout, single_spring) and keep every
# output under OUTDIR. Capture twice (before and after a change) and compare with
# tools/compare_outputs.py BEFORE AFTER (docs/validation.md, "Refactors keep the numbers").
set -uo pipefail
B=$(realpath "$1"); O=$(realpath -m "$2"); R=$(realpath "$(dirname "$0")/..")
mkdir -p "$O/ex"
for s in block hertz delamination shear pile; do
  "$B/bipo" run "$R/examples/scenes/$s.toml" --out "$O/scene_$s" > "$O/scene_$s.stdout" 2>&1
done
cd "$O/ex"
for e in delamination shear pile_pullout single_spring; do "$B/$e" > "$O/ex_$e.stdout" 2>&1; done
