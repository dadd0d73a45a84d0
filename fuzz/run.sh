#!/usr/bin/env bash
# Fuzzes every target of fuzz/ for SECONDS each (default 20): one build of
# all targets (`cargo fuzz build`: release, debug assertions, libFuzzer's
# coverage instrumentation, no sanitizer: the decoders have no unsafe code),
# then each binary with its committed corpus (fuzz/corpus/<name>, read only)
# and a scratch corpus that keeps what it finds. Prints per target the
# executions, coverage (libFuzzer's `cov:` edges and `ft:` features) and the
# corpus size; a crash, timeout or out-of-memory fails the script after every
# target ran, naming the crashing input's file and printing it in base64.
#
# Usage: fuzz/run.sh [SECONDS]    (stable Rust: RUSTC_BOOTSTRAP=1 allows the
# flags cargo-fuzz passes; cargo-fuzz from `cargo install cargo-fuzz --locked`)
# Environment: CARGO_TARGET_DIR (the build goes to its `fuzz` folder),
# FUZZ_WORK (scratch corpora, logs and crashing inputs; default
# <target dir>/fuzz/work) and FUZZ_JOBS (targets fuzzed at once, default 1).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-20}"
export RUSTC_BOOTSTRAP=1
target_dir="${CARGO_TARGET_DIR:-$PWD/target}/fuzz"
work="${FUZZ_WORK:-$target_dir/work}"
triple="$(rustc -vV | sed -n 's/^host: //p')"
bin_dir="$target_dir/$triple/release"

echo "== cargo fuzz build (every target, release with debug assertions)"
build_start=$SECONDS
cargo fuzz build --release --debug-assertions --sanitizer none --features libfuzzer \
  --target-dir "$target_dir"
echo "built in $((SECONDS - build_start)) s"

# The longest input tried: 4096 bytes (libFuzzer's default), or more when a
# committed input is longer (file and device-session seeds).
max_len() {
  local longest
  longest="$(find "$1" -type f -printf '%s\n' | sort -n | tail -1)"
  echo $(( ${longest:-0} > 4096 ? ${longest:-0} : 4096 ))
}

# Fuzzes target $1; writes its table row to $work/results/$1 and, if it
# failed, what to show to $work/results/$1.failed.
fuzz_one() {
  local name="$1" corpus="fuzz/corpus/$1" scratch="$work/corpus/$1"
  local artifacts="$work/artifacts/$1" log="$work/logs/$1.log" status=0
  mkdir -p "$scratch" "$artifacts" "$work/logs" "$work/results"
  rm -f "$work/results/$name" "$work/results/$name.failed"
  "$bin_dir/$name" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -max_len="$(max_len "$corpus")" -print_final_stats=1 -artifact_prefix="$artifacts/" \
    "$scratch" "$corpus" >"$log" 2>&1 || status=$?
  local executions last cov ft files
  executions="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  last="$(grep -E '^#[0-9]+' "$log" | tail -1 || true)"
  cov="$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")"
  ft="$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$last")"
  files="$(find "$scratch" "$corpus" -type f | wc -l)"
  printf '%-22s %12s %8s %8s %8s\n' "$name" "${executions:-?}" "${cov:-?}" "${ft:-?}" "$files" \
    >"$work/results/$name"
  if [ "$status" -ne 0 ]; then
    {
      echo "!! $name failed (exit $status); log $log:"
      grep -E -A12 'panicked|ERROR: libFuzzer|deadly signal' "$log" | head -40 || true
      for input in "$artifacts"/*; do
        [ -f "$input" ] || continue
        echo "!! crashing input $input (base64):"
        base64 -w 76 "$input"
      done
    } >"$work/results/$name.failed"
  fi
}

parallel="${FUZZ_JOBS:-1}"
names="$(cargo fuzz list)"
echo "== fuzzing each target for ${seconds} s, ${parallel} at a time"
fuzz_start=$SECONDS
for name in $names; do
  while [ "$(jobs -rp | wc -l)" -ge "$parallel" ]; do wait -n || true; done
  fuzz_one "$name" &
done
wait
echo "fuzzed in $((SECONDS - fuzz_start)) s"

printf '%-22s %12s %8s %8s %8s\n' target executions cov ft corpus
failed=()
for name in $names; do
  if [ ! -f "$work/results/$name" ]; then
    # Its run stopped before writing its row: never count that as a pass.
    echo "!! $name: no result (its run was cut short; see $work/logs/$name.log)" \
      >"$work/results/$name.failed"
    printf '%-22s %12s\n' "$name" "no result"
  else
    cat "$work/results/$name"
  fi
  if [ -f "$work/results/$name.failed" ]; then
    failed+=("$name")
  fi
done
for name in "${failed[@]}"; do
  cat "$work/results/$name.failed"
done

if [ "${#failed[@]}" -gt 0 ]; then
  echo "== FAILED: ${failed[*]}"
  echo "reproduce: $bin_dir/<target> <input>; keep it as fuzz/corpus/<target>/crash-<what>"
  exit 1
fi
echo "== every target ran ${seconds} s without a failure"
