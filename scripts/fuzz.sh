#!/usr/bin/env bash
# Builds the libFuzzer harnesses (tianracer_sim/fuzz) with clang and runs each in turn.
#   scripts/fuzz.sh [seconds]        seconds per harness, default 600
#   FUZZ_TARGETS="mesh" scripts/fuzz.sh 1200   only those harnesses (default: extensions world mesh
#                                   sim controllers)
#   scripts/fuzz.sh 600 --merge      afterwards, minimise the committed corpora
#                                   (-set_cover_merge=1: fewest files
#                                   that keep every feature)
# Needs clang and libFuzzer (Debian: apt-get install clang libclang-rt-14-dev). Not part of CI:
# the unit tests already replay a small mutation set; this is the long run.
# New inputs go to $OUT/corpus (a scratch copy), crashes to $OUT/crashes; the committed seed
# corpus in tianracer_sim/fuzz/corpus/ is only rewritten with --merge.
set -euo pipefail

SECONDS_PER="${1:-600}"
MERGE=0
[[ "${2:-}" == "--merge" ]] && MERGE=1
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
FUZZ="$REPO/tianracer_sim/fuzz"
OUT="${FUZZ_OUT:-$REPO/.build/fuzz}"
CXX_BIN="${CXX:-$(command -v clang++ || command -v clang++-14 || true)}"
[[ -n "$CXX_BIN" ]] || { echo "ERROR [fuzz] clang++ not found (apt-get install clang libclang-rt-14-dev)" >&2; exit 1; }

say() { printf '==> [fuzz] %s\n' "$*"; }
say "building with $CXX_BIN in $OUT/build"
mkdir -p "$OUT/build" "$OUT/crashes"
cmake -S "$FUZZ" -B "$OUT/build" -DCMAKE_CXX_COMPILER="$CXX_BIN" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  >"$OUT/cmake.log" 2>&1 || { tail -20 "$OUT/cmake.log" >&2; exit 1; }
TARGETS="${FUZZ_TARGETS:-extensions world mesh sim controllers}"
targets=(); for name in $TARGETS; do targets+=(--target "fuzz_$name"); done
cmake --build "$OUT/build" -j"${JOBS:-2}" "${targets[@]}" >"$OUT/build.log" 2>&1 || { tail -30 "$OUT/build.log" >&2; exit 1; }

status=0
for name in $TARGETS; do
  bin="$OUT/build/fuzz_$name"
  work="$OUT/corpus/$name"
  mkdir -p "$work" "$OUT/crashes/$name"
  find "$FUZZ/corpus/$name" -type f ! -name README.md -exec cp -n {} "$work"/ \; 2>/dev/null || true
  log="$OUT/fuzz_$name.log"
  say "fuzz_$name: ${SECONDS_PER} s, corpus $(ls "$work" | wc -l) files, log $log"
  rc=0
  # -rss_limit_mb: urdfdom, tinyxml2 and assimp are not instrumented, ASan's shadow adds its
  # share; a single allocation above it (-malloc_limit_mb defaults to it) is a finding too.
  # fuzz_mesh: its own dictionary (mesh.dict: COLLADA elements, STL and OBJ keywords).
  # assimp (Debian's, not instrumented) leaks on some of its own error paths: fuzz_mesh runs
  # without LeakSanitizer, so that those do not stop it; crashes and memory limits stay.
  dict="$FUZZ/xml.dict"; extra=()
  leaks=1; [[ "$name" == mesh ]] && { dict="$FUZZ/mesh.dict"; extra=(-detect_leaks=0); leaks=0; }
  # fuzz_controllers: YAML keys and values; fuzz_sim (URDF and SDF) keeps xml.dict.
  [[ "$name" == controllers ]] && dict="$FUZZ/controllers.dict"
  # (-detect_leaks=0 is per input; ASAN_OPTIONS also spares the exit-time report.)
  ASAN_OPTIONS="detect_leaks=$leaks${ASAN_OPTIONS:+:$ASAN_OPTIONS}" "$bin" "$work" "${extra[@]}" -dict="$dict" -max_total_time="$SECONDS_PER" -max_len=65536 \
    -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$OUT/crashes/$name/" >"$log" 2>&1 || rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 || true)
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 || true)
  crashes=$(ls "$OUT/crashes/$name" | wc -l)
  say "fuzz_$name: exit $rc, ${execs:-?} executions, ${speed:-?} exec/s, ${cov:-cov: ?}, ${ft:-ft: ?}, corpus $(ls "$work" | wc -l) files, crashes $crashes"
  if ((rc != 0 || crashes != 0)); then
    status=1
    grep -m5 -E 'ERROR|SUMMARY|broken promise|deadly' "$log" >&2 || true
  fi
  if ((MERGE)); then
    tmp="$OUT/merged_$name"; rm -rf "$tmp"; mkdir -p "$tmp"
    "$bin" -set_cover_merge=1 "$tmp" "$work" "$FUZZ/corpus/$name" >"$OUT/merge_$name.log" 2>&1
    # Regression inputs (crash_*: past crashers, named after what they found) stay.
    find "$FUZZ/corpus/$name" -type f ! -name 'crash_*' ! -name README.md -delete; cp "$tmp"/* "$FUZZ/corpus/$name"/
    say "fuzz_$name: corpus minimised to $(ls "$FUZZ/corpus/$name" | wc -l) files in $FUZZ/corpus/$name"
  fi
done
exit $status
