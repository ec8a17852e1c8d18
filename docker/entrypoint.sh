#!/bin/sh
# Container entry point: serve the explorer with `panel serve`, configured from
# the environment (see docs/docker.md):
#   PORT             port to listen on inside the container (default 5006)
#   ADDRESS          address to listen on (default 0.0.0.0; 127.0.0.1 when the
#                    container shares the host's network, as docker/smoke.sh does)
#   ALLOWED_ORIGINS  comma-separated host[:port] list allowed to open the Bokeh
#                    websocket, e.g. "explorer.example.org,localhost:5006";
#                    "*" (the default) allows any origin
#   NUM_PROCS        number of server processes (default 1; 0 = one per CPU)
#   PANEL_ARGS       extra arguments appended to `panel serve` (word-split)
# Arguments given to `docker run IMAGE ...` that start with "-" are appended to
# `panel serve`; any other command (e.g. `sh`) is run instead of the server.
set -eu

if [ "$#" -gt 0 ] && [ "${1#-}" = "$1" ]; then
    exec "$@"
fi

PORT=${PORT:-5006}
ADDRESS=${ADDRESS:-0.0.0.0}
NUM_PROCS=${NUM_PROCS:-1}
ALLOWED_ORIGINS=${ALLOWED_ORIGINS:-*}

case $PORT in '' | *[!0-9]*) echo "entrypoint: PORT must be a number, got '$PORT'" >&2; exit 64 ;; esac
case $NUM_PROCS in '' | *[!0-9]*) echo "entrypoint: NUM_PROCS must be a number >= 0, got '$NUM_PROCS'" >&2; exit 64 ;; esac

# One --allow-websocket-origin per comma-separated entry (blanks ignored).
set -f  # no globbing: "*" is a literal origin here
origin_args=
old_ifs=$IFS
IFS=,
for origin in $ALLOWED_ORIGINS; do
    origin=$(printf '%s' "$origin" | tr -d '[:space:]')
    [ -n "$origin" ] && origin_args="$origin_args --allow-websocket-origin=$origin"
done
IFS=$old_ifs
[ -n "$origin_args" ] || { echo "entrypoint: ALLOWED_ORIGINS is empty" >&2; exit 64; }

echo "entrypoint: panel serve app/main.py on $ADDRESS:$PORT, $NUM_PROCS process(es), websocket origins: $ALLOWED_ORIGINS" >&2
# $origin_args and $PANEL_ARGS are split on blanks on purpose (globbing is off).
# shellcheck disable=SC2086
exec panel serve app/main.py \
    --address "$ADDRESS" --port "$PORT" \
    --liveness --index main \
    --num-procs "$NUM_PROCS" \
    $origin_args \
    ${PANEL_ARGS:-} "$@"
