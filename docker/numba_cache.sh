#!/bin/sh
# Does a fresh process load every compiled kernel from a numba cache, compiling none?
#
#   sh docker/numba_cache.sh [CACHE]          (default /opt/zharii/numba-cache)
#   docker exec -i CONTAINER sh -s < docker/numba_cache.sh     (what docker/smoke.sh runs)
#
# Copies CACHE into a fresh temporary NUMBA_CACHE_DIR (as the entry point seeds the
# container's), runs the warm-up (WARM, Python code; default core.warm's warm_all: every
# kernel the server runs) with NUMBA_DEBUG_CACHE=1 and reads numba's own cache log: a
# "data loaded from" line per kernel loaded from the cache, a "data saved to" line per
# kernel compiled and written to it.  Exit 0 when at least one kernel was loaded and
# none compiled; 1 otherwise; 2 if the warm-up itself fails.  The time is only reported.
# Environment: PYTHON (default python), WARM.
set -eu

CACHE=${1:-/opt/zharii/numba-cache}
PYTHON=${PYTHON:-python}
WARM=${WARM:-from core.warm import warm_all; warm_all()}

[ -d "$CACHE" ] || { echo "numba cache: no directory $CACHE" >&2; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cp -R "$CACHE/." "$dir/"
t0=$(date +%s.%N)
if ! log=$(NUMBA_CACHE_DIR="$dir" NUMBA_DEBUG_CACHE=1 "$PYTHON" -c "$WARM" 2>&1); then
    printf '%s\n' "$log" | tail -n 20 >&2
    echo "numba cache: the warm-up failed" >&2
    exit 2
fi
seconds=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
loaded=$(printf '%s\n' "$log" | grep -c 'data loaded from' || true)
compiled=$(printf '%s\n' "$log" | grep -c 'data saved to' || true)
echo "numba cache $CACHE: $loaded kernels loaded, $compiled compiled (warm-up $seconds s)"
[ "$compiled" -eq 0 ] && [ "$loaded" -gt 0 ]
