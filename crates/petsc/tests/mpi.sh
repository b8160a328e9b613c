#!/usr/bin/env bash
# The distributed checks of bipotential-petsc under mpirun, 1 and 2 ranks (the CI step runs
# it; tests/mpi.rs runs the same through `cargo test --features petsc`). Each check compares
# with the direct path to 1e-8 relative and exits non-zero otherwise; `fail` must end every
# rank with the failing rank's message, within the timeout, not hang. `pile` is the seed's
# axisymmetric pile pull-out (RCCM shaft, geostatic stress). Hertz runs with MUMPS:
# its 441 candidates make ~900 solves for F*, ~0.2 s each with CG+GAMG here (minutes).
#   usage: crates/petsc/tests/mpi.sh [path/to/petsc_check]
set -euo pipefail
cd "$(dirname "$0")/../../.."
bin=${1:-}
if [ -z "$bin" ]; then
  cargo build -p bipotential-petsc --features petsc --example petsc_check
  bin="${CARGO_TARGET_DIR:-target}/debug/examples/petsc_check"
fi
# root in a container, and more ranks than cores on the 2-core CI machine
mpi=(mpirun --oversubscribe --mca mpi_yield_when_idle 1)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
# CHECKS: which scenes (the CI step leaves out `block` and `fail`, which tests/mpi.rs runs)
checks=${CHECKS:-block block-mumps hertz-mumps pile pile-mumps fail}
for n in 1 2; do
  for scene in $checks; do
    [ "$scene" = fail ] && continue
    echo "== mpirun -n $n petsc_check ${scene/-/ }"
    # shellcheck disable=SC2086
    timeout 300 "${mpi[@]}" -n "$n" "$bin" ${scene/-/ }
  done
done
# petsc_scale (issue 41's measuring program): each mode once at a small size (SCALE=0 skips)
scale="$(dirname "$bin")/petsc_scale"
if [ "${SCALE:-1}" = 1 ] && [ -x "$scale" ]; then
  echo "== petsc_scale patch 4 3 mumps (2 ranks), direct, partitions, interface"
  timeout 300 "${mpi[@]}" -n 2 "$scale" patch 4 3 mumps
  timeout 300 "$scale" direct 4 3
  timeout 300 "$scale" partitions 4 2 4
  timeout 300 "$scale" interface 4
fi
case " $checks " in *" fail "*) ;; *) echo "mpi checks: OK"; exit 0 ;; esac
echo "== mpirun -n 2 petsc_check fail (must end both ranks with the message)"
set +e
out=$(timeout 60 "${mpi[@]}" -n 2 "$bin" fail 2>&1)
rc=$?
set -e
echo "$out" | tail -5
if [ "$rc" -eq 0 ] || [ "$rc" -eq 124 ]; then
  echo "FAILED: a failing rank gave exit code $rc (0: not reported; 124: the other rank hung)" >&2
  exit 1
fi
if ! echo "$out" | grep -q "rank 1 of 2: error: a deliberate failure on rank 1"; then
  echo "FAILED: the failing rank's message is missing" >&2
  exit 1
fi
echo "mpi checks: OK"
