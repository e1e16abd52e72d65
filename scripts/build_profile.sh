#!/usr/bin/env bash
# The first build, measured (docs/performance.md, First build): a clean catkin_make into a
# scratch workspace, as scripts/setup.sh runs it, with ccache off and every compile and link
# timed (CPU user+sys per object through CMAKE_CXX_COMPILER_LAUNCHER). Prints the wall and
# CPU time of the build and its heaviest translation units.
#   scripts/build_profile.sh [--release] [--make|--ninja] [--top N] [DIR]
#   DIR: default /tmp/tianracer_build_profile
# --release builds as ./run.sh does on a new workspace (scripts/setup.sh --demo); the generator
# is the one scripts/setup.sh picks for a new workspace (Ninja when installed) unless --make or
# --ninja says; any other argument starting with -D goes to CMake (e.g. -DTIANRACER_PCH=OFF).
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
TYPE=RelWithDebInfo; TOP=25; DIR=/tmp/tianracer_build_profile; EXTRA=(); GEN=default
while (($#)); do
  case "$1" in
    --release) TYPE=Release; EXTRA=(-DTIANRACER_EXTRAS=OFF "${EXTRA[@]}") ;;
    --top) TOP="$2"; shift ;;
    --make) GEN=make ;;
    --ninja) GEN=ninja ;;
    -D*) EXTRA+=("$1") ;;
    -*) echo "usage: $0 [--release] [--make|--ninja] [--top N] [-DVAR=VALUE...] [DIR]" >&2; exit 2 ;;
    *) DIR="$1" ;;
  esac
  shift
done
command -v /usr/bin/time >/dev/null || { echo "ERROR [build_profile] needs /usr/bin/time (apt-get install time)" >&2; exit 1; }
[[ "$DIR" == "$REPO/.build" ]] && { echo "ERROR [build_profile] $DIR is the repo's own workspace: give a scratch folder" >&2; exit 1; }

rm -rf "$DIR"; mkdir -p "$DIR"
# shellcheck source=catkin_generator.sh
source "$REPO/scripts/catkin_generator.sh"
case "$GEN" in
  default) mapfile -t GEN_ARG < <(catkin_generator "$DIR") ;;
  make) GEN_ARG=() ;;
  ninja) command -v ninja >/dev/null || { echo "ERROR [build_profile] --ninja: ninja is not installed (apt-get install ninja-build)" >&2; exit 1; }
         GEN_ARG=(--use-ninja) ;;
esac
LOG="$DIR/objects.log"
WRAP="$DIR/timed_compiler"
# One line per object: CPU user, CPU sys, peak RSS (kB), compile|link, output file, and the
# wall-clock start and end (s since the epoch), written in one append once the job ends.
cat >"$WRAP" <<WRAPPER
#!/usr/bin/env bash
out=""; prev=""
for a in "\$@"; do [[ "\$prev" == "-o" ]] && out="\$a"; prev="\$a"; done
kind=link; [[ " \$* " == *" -c "* ]] && kind=compile
start=\$(date +%s.%N)
t=\$(mktemp)
/usr/bin/time -o "\$t" -f "%U %S %M" "\$@"; rc=\$?
echo "\$(cat "\$t") \$kind \$out \$start \$(date +%s.%N)" >>"$LOG"
rm -f "\$t"
exit \$rc
WRAPPER
chmod +x "$WRAP"

export PATH="/usr/bin:$PATH" CCACHE_DISABLE=1
unset CC CXX  # a fresh machine has no ccache wrapper
echo "==> [build_profile] clean catkin_make ${GEN_ARG[*]:-(make)} -j$(nproc) ($TYPE) in $DIR; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
build_start="$(date +%s.%N)"
/usr/bin/time -o "$DIR/total.txt" -f "%e %U %S" \
  catkin_make "${GEN_ARG[@]}" -C "$DIR" --source "$REPO" -DPYTHON_EXECUTABLE=/usr/bin/python3 \
  -DCMAKE_BUILD_TYPE="$TYPE" -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" -DCMAKE_C_FLAGS_RELEASE="-O2 -DNDEBUG" \
  -DCMAKE_CXX_COMPILER_LAUNCHER="$WRAP" -DCMAKE_CXX_LINKER_LAUNCHER="$WRAP" "${EXTRA[@]}" \
  -j"$(nproc)" >"$DIR/build.log" 2>&1 || { tail -30 "$DIR/build.log" >&2; exit 1; }
read -r wall user sys <"$DIR/total.txt"
echo "==> [build_profile] wall ${wall} s, CPU ${user} s user + ${sys} s sys; load after: $(cut -d' ' -f1-3 /proc/loadavg)"
awk '{t = $1 + $2; if ($5 ~ /cmake_pch/) {p += t; np++} else if ($4 == "compile") {c += t; nc++} else {l += t; nl++}}
     END {printf "==> [build_profile] %d translation units %.0f s CPU, %d precompiled headers %.0f s, %d links %.0f s\n", nc, c, np, p, nl, l}' "$LOG"
# The timeline: what comes before the first compile (CMake, message generation) and how busy
# the cores were from the first compile to the last job.
awk -v t0="$build_start" -v cores="$(nproc)" -v wall="$wall" \
  '{if (first == "" || $6 < first) first = $6; if ($7 > last) last = $7; busy += $7 - $6}
   END {span = last - first; printf "==> [build_profile] %.0f s before the first compile (CMake, messages), %.0f s of compiles and links (cores busy %.0f %%), %.0f s after\n", first - t0, span, 100 * busy / (cores * span), t0 + wall - last}' "$LOG"
echo "CPU s (user+sys)  peak MB  object"
awk '$4 == "compile" {o = $5; sub(/.*CMakeFiles\//, "", o); printf "%8.2f %9d  %s\n", $1 + $2, $3 / 1024, o}' "$LOG" \
  | sort -rn | awk -v n="$TOP" 'NR <= n'  # (head would end sort with SIGPIPE under pipefail)
