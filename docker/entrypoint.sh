#!/bin/sh
# Container entry point: serve the explorer with `python -m app.serve` (app/serve.py:
# security headers, websocket origin check, session lifetimes, message cap),
# configured from the environment (see docs/docker.md):
#   PORT             port to listen on inside the container (default 5006)
#   ADDRESS          address to listen on (default 0.0.0.0; 127.0.0.1 when the
#                    container shares the host's network, as docker/smoke.sh does)
#   ALLOWED_ORIGINS  comma-separated host[:port] list allowed to open the Bokeh
#                    websocket: the address users type in their browser, e.g.
#                    "explorer.example.org,localhost:5006".  Default (empty):
#                    localhost:PORT and 127.0.0.1:PORT only.  "*" allows any origin
#                    (an explicit opt-in, for a classroom LAN; the server logs a warning)
#   NUM_PROCS        number of server processes (default 0 = one per CPU available
#                    to the container: its CPU quota when one is set, e.g. by
#                    `docker run --cpus` or a compose file's cpus limit)
#   BASIC_AUTH       password, or the path of a JSON file of {"user": "password"}
#                    (e.g. a mounted secret), required on every page (optional); read
#                    by app.serve from the environment, never put on its command line.
#                    ADMIN=1 also serves Panel's /admin page, which app.serve allows
#                    only together with BASIC_AUTH
#   PANEL_ARGS       extra arguments appended to `python -m app.serve` (word-split)
# Arguments given to `docker run IMAGE ...` that start with "-" are appended to
# `python -m app.serve`; any other command (e.g. `sh`) is run instead of the server.
set -eu

if [ "$#" -gt 0 ] && [ "${1#-}" = "$1" ]; then
    exec "$@"
fi

# numba's compiled kernels: the cache built with the image, copied into the writable
# NUMBA_CACHE_DIR (a tmpfs on /tmp in a read-only container) when that does not exist
# yet, so that the server loads the kernels instead of compiling them.
IMAGE_CACHE=${IMAGE_CACHE:-/opt/zharii/numba-cache}
if [ -n "${NUMBA_CACHE_DIR:-}" ] && [ -d "$IMAGE_CACHE" ] && [ ! -e "$NUMBA_CACHE_DIR" ]; then
    mkdir -p "$NUMBA_CACHE_DIR" && cp -R "$IMAGE_CACHE/." "$NUMBA_CACHE_DIR/" \
        || echo "entrypoint: could not copy $IMAGE_CACHE to $NUMBA_CACHE_DIR (kernels compile at start)" >&2
fi

PORT=${PORT:-5006}
ADDRESS=${ADDRESS:-0.0.0.0}
NUM_PROCS=${NUM_PROCS:-0}
ALLOWED_ORIGINS=${ALLOWED_ORIGINS:-}
PYTHON=${PYTHON:-python}

case $PORT in '' | *[!0-9]*) echo "entrypoint: PORT must be a number, got '$PORT'" >&2; exit 64 ;; esac
case $NUM_PROCS in '' | *[!0-9]*) echo "entrypoint: NUM_PROCS must be a number >= 0, got '$NUM_PROCS'" >&2; exit 64 ;; esac

# NUM_PROCS=0: one process per CPU the container may use.  `nproc` follows the CPU
# set; a CPU quota (cgroup v2 cpu.max "QUOTA PERIOD", v1 cfs files) lowers it, rounded
# up.  Python's os.cpu_count() would count every CPU of the host.
if [ "$NUM_PROCS" = 0 ]; then
    NUM_PROCS=$(nproc 2>/dev/null || echo 1)
    quota= period=
    if [ -r /sys/fs/cgroup/cpu.max ]; then
        read -r quota period </sys/fs/cgroup/cpu.max || true
    elif [ -r /sys/fs/cgroup/cpu/cpu.cfs_quota_us ] && [ -r /sys/fs/cgroup/cpu/cpu.cfs_period_us ]; then
        quota=$(cat /sys/fs/cgroup/cpu/cpu.cfs_quota_us) period=$(cat /sys/fs/cgroup/cpu/cpu.cfs_period_us)
    fi
    case "$quota:$period" in
        *[!0-9:]* | :* | *:) ;;  # "max", -1 or unreadable: no quota
        *) cpus=$(( (quota + period - 1) / period ))
           [ "$cpus" -ge 1 ] && [ "$cpus" -lt "$NUM_PROCS" ] && NUM_PROCS=$cpus ;;
    esac
fi

# One --allow-websocket-origin per comma-separated entry (blanks ignored); none at
# all leaves app.serve's default, localhost:PORT and 127.0.0.1:PORT.
set -f  # no globbing: "*" is a literal origin here
origin_args=
old_ifs=$IFS
IFS=,
for origin in $ALLOWED_ORIGINS; do
    origin=$(printf '%s' "$origin" | tr -d '[:space:]')
    [ -n "$origin" ] && origin_args="$origin_args --allow-websocket-origin=$origin"
done
IFS=$old_ifs
if [ -n "$(printf '%s' "$ALLOWED_ORIGINS" | tr -d '[:space:]')" ] && [ -z "$origin_args" ]; then
    echo "entrypoint: ALLOWED_ORIGINS lists no origin: '$ALLOWED_ORIGINS'" >&2; exit 64
fi

# BASIC_AUTH stays in the environment, where app.serve reads it: on the command line
# the password would be shown to every user of the machine (ps, /proc/PID/cmdline).
admin_args=
case ${ADMIN:-} in
    '' | 0 | false | no) ;;
    *) [ -n "${BASIC_AUTH:-}" ] || { echo "entrypoint: ADMIN needs BASIC_AUTH (the admin page shows every session)" >&2; exit 64; }
       admin_args=--admin ;;
esac

echo "entrypoint: python -m app.serve on $ADDRESS:$PORT, $NUM_PROCS process(es), websocket origins: ${ALLOWED_ORIGINS:-localhost:$PORT,127.0.0.1:$PORT}" >&2
# $origin_args, $admin_args and $PANEL_ARGS are split on blanks on purpose (globbing is off).
# shellcheck disable=SC2086
exec "$PYTHON" -m app.serve \
    --address "$ADDRESS" --port "$PORT" \
    --num-procs "$NUM_PROCS" \
    $origin_args $admin_args \
    ${PANEL_ARGS:-} "$@"
