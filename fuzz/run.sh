#!/usr/bin/env bash
# Fuzzes every target for a bounded time (default 120 s each), growing corpus/<target>.
# Needs a nightly toolchain and cargo-fuzz: `rustup toolchain install nightly` (or any
# nightly present) and `cargo install cargo-fuzz`. A crash leaves its input in
# artifacts/<target>/; add it to corpus/<target>/ once fixed, so that the stable replay
# (`cargo test --workspace`, tests named fuzz_corpus) keeps it fixed.
# Usage: fuzz/run.sh [SECONDS_PER_TARGET] [TARGET ...]
set -euo pipefail
cd "$(dirname "$0")"
secs="${1:-120}"; shift || true
targets=("$@"); [ ${#targets[@]} -eq 0 ] && targets=(scene gmsh reduced_json)
for t in "${targets[@]}"; do
  echo "== fuzz $t for ${secs}s"
  # -timeout: a unit slower than 20 s is a hang; -rss_limit_mb: 4 GiB; inputs up to 64 kB
  cargo +nightly fuzz run -O "$t" "corpus/$t" -- \
    -max_total_time="$secs" -timeout=20 -rss_limit_mb=4096 -max_len=65536 -print_final_stats=1
done
