#!/usr/bin/env bash
# Docker smoke test (`make docker-smoke`): build the image, run it, wait for
# /liveness and the HEALTHCHECK, check the page, run the browser smoke tests
# (`pytest -m smoke tests/app`) against the container, try NUM_PROCS=2, clean up.
# The container runs as in docker/compose.yaml: read-only root filesystem, a tmpfs
# on /tmp; the script also checks that a foreign websocket Origin is refused (403),
# that there is no /admin page and no autoload script, that the image trusts only
# Debian's CA certificates (none of the build host's: docker/trust_store.py on the
# exported container), and that the server loads the compiled kernels from the
# image's numba cache (numba's own cache log, NUMBA_DEBUG_CACHE=1).
#
# Works on a machine that cannot pull from any container registry: the base is
# made locally by docker/build-base.sh (debootstrap) when absent, and a Docker
# engine is started (vfs storage, no bridge, no iptables) when none answers.
# Every address used is on the loopback interface.  Idempotent: reuses the
# base image and the build cache, replaces a container left by an earlier run.
#
# Environment (all optional):
#   BASE_IMAGE   base image passed as --build-arg BASE (default zharii-base:trixie,
#                built here if absent); BASE_IMAGE=python:3.12-slim on a normal machine
#   BUILD_BASE_IMAGE  base of the build stages (--build-arg BUILD_BASE; default
#                BASE_IMAGE-build for a zharii-base, which trusts the host's extra CAs
#                for pip, else BASE_IMAGE)
#   EXTRA_CA_DIR the build host's extra CA certificates, which must be nowhere in the
#                image (default /usr/local/share/ca-certificates)
#   IMAGE        tag of the image built (default zharii-explorer:latest)
#   SMOKE_PORT   host port (default 5006, or a free one if 5006 is taken)
#   LIVENESS_TIMEOUT  seconds to wait for /liveness (default 120)
#   SKIP_BUILD=1      test the existing IMAGE without building
#   SKIP_BROWSER=1    skip the Playwright smoke tests (HTTP checks only)
#   SKIP_MULTIPROC=1  skip the NUM_PROCS=2 run
#   KEEP_DOCKERD=1    leave a dockerd started by this script running
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

DOCKER=${DOCKER:-docker}
BASE_IMAGE=${BASE_IMAGE:-zharii-base:trixie}
case $BASE_IMAGE in
    zharii-base:*) BUILD_BASE_IMAGE=${BUILD_BASE_IMAGE:-$BASE_IMAGE-build} ;;
    *) BUILD_BASE_IMAGE=${BUILD_BASE_IMAGE:-$BASE_IMAGE} ;;
esac
EXTRA_CA_DIR=${EXTRA_CA_DIR-/usr/local/share/ca-certificates}
IMAGE=${IMAGE:-zharii-explorer:latest}
CACHE_REPO=${CACHE_REPO:-zharii-explorer-cache}
NAME=zharii-explorer-smoke
LIVENESS_TIMEOUT=${LIVENESS_TIMEOUT:-120}
WORKDIR=${WORKDIR:-/var/tmp/zharii-docker}
VENV=${VENV:-$ROOT/.venv}
export WORKDIR DOCKER EXTRA_CA_DIR

log() { printf '[smoke] %s\n' "$*" >&2; }
die() { printf '[smoke] FAIL: %s\n' "$*" >&2; exit 1; }
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }

mkdir -p "$WORKDIR"
STARTED_DOCKERD=
CONTAINERS=()
cleanup() {
    local rc=$?
    for c in "${CONTAINERS[@]}"; do
        log "removing container $c"
        "$DOCKER" rm -f "$c" >/dev/null 2>&1 || true
    done
    if [ -n "$STARTED_DOCKERD" ] && [ -z "${KEEP_DOCKERD:-}" ]; then
        log "stopping the dockerd started here (pid $STARTED_DOCKERD)"
        kill "$STARTED_DOCKERD" 2>/dev/null || true
        for _ in $(seq 50); do kill -0 "$STARTED_DOCKERD" 2>/dev/null || break; sleep 0.2; done
    fi
    [ "$rc" = 0 ] && log "PASS" || log "FAILED (exit $rc)"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# ---- 1. a Docker engine ------------------------------------------------------
if ! "$DOCKER" info >/dev/null 2>&1; then
    [ "$(id -u)" = 0 ] || die "no Docker engine answers and starting one needs root"
    if ! command -v dockerd >/dev/null 2>&1; then
        log "installing Debian's docker.io (apt-get)"
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq docker.io >/dev/null
    fi
    log "starting dockerd --storage-driver vfs --iptables=false --bridge=none (log: $WORKDIR/dockerd.log)"
    dockerd --storage-driver vfs --iptables=false --bridge=none >"$WORKDIR/dockerd.log" 2>&1 &
    STARTED_DOCKERD=$!
    for _ in $(seq 60); do "$DOCKER" info >/dev/null 2>&1 && break; sleep 0.5; done
    "$DOCKER" info >/dev/null 2>&1 || { tail -n 20 "$WORKDIR/dockerd.log" >&2; die "dockerd did not come up in 30 s"; }
fi
log "docker engine: $("$DOCKER" version -f '{{.Server.Version}}'), storage $("$DOCKER" info -f '{{.Driver}}')"

# ---- 2. base image and build -------------------------------------------------
if [ -z "${SKIP_BUILD:-}" ]; then
    case $BASE_IMAGE in
        zharii-base:*) # builds them when absent (or made by its earlier version)
                       bash docker/build-base.sh "$BASE_IMAGE" "$BUILD_BASE_IMAGE" ;;
        *) "$DOCKER" image inspect "$BASE_IMAGE" >/dev/null 2>&1 \
               && log "base image $BASE_IMAGE present" \
               || log "base image $BASE_IMAGE absent: docker build will pull it" ;;
    esac
    # The classic builder's cache is its intermediate images.  The stages that
    # are not the final one are tagged ($CACHE_REPO:deps, :pkg) so that they
    # stay cached; the images these tags (and $IMAGE) pointed to before are
    # removed afterwards if replaced, so that repeated runs do not fill the disk.
    old_ids=()
    for ref in "$CACHE_REPO:deps" "$CACHE_REPO:pkg" "$IMAGE"; do
        old_ids+=("$("$DOCKER" image inspect -f '{{.Id}}' "$ref" 2>/dev/null || true)")
    done
    build() {  # build TARGET-ARGS... ; appends to the build log
        DOCKER_BUILDKIT=0 "$DOCKER" build --network host --build-arg "BASE=$BASE_IMAGE" \
            --build-arg "BUILD_BASE=$BUILD_BASE_IMAGE" "$@" . \
            >>"$WORKDIR/build.log" 2>&1 \
            || { tail -n 30 "$WORKDIR/build.log" >&2; die "docker build $* failed; see $WORKDIR/build.log"; }
    }
    log "building $IMAGE: DOCKER_BUILDKIT=0 docker build --network host --build-arg BASE=$BASE_IMAGE --build-arg BUILD_BASE=$BUILD_BASE_IMAGE (log: $WORKDIR/build.log)"
    : >"$WORKDIR/build.log"
    t=$(now)
    build --target deps -t "$CACHE_REPO:deps"
    build --target pkg -t "$CACHE_REPO:pkg"
    build -t "$IMAGE"
    BUILD_S=$(since "$t")
    log "built in $BUILD_S s ($(grep -c -- '---> Using cache' "$WORKDIR/build.log" || true) of $(grep -c '^Step ' "$WORKDIR/build.log") steps cached)"
    for old in "${old_ids[@]}"; do
        [ -n "$old" ] || continue
        if ! "$DOCKER" image inspect -f '{{.RepoTags}}' "$old" 2>/dev/null | grep -q ':'; then
            "$DOCKER" rmi "$old" >/dev/null 2>&1 && log "removed the replaced image ${old#sha256:}" || true
        fi
    done
fi
"$DOCKER" image inspect "$IMAGE" >/dev/null 2>&1 || die "image $IMAGE does not exist"
SIZE_MB=$("$DOCKER" image inspect -f '{{.Size}}' "$IMAGE" | awk '{ printf "%.0f", $1 / 1e6 }')
log "image $IMAGE: $SIZE_MB MB, user $("$DOCKER" image inspect -f '{{.Config.User}}' "$IMAGE")"

# The image trusts Debian's CA certificates only: no setting points a client at another
# bundle, and its whole filesystem (exported from a container that never runs) holds
# only Debian's in its trust store and none of the build host's extra CAs anywhere.
image_env=$("$DOCKER" image inspect -f '{{range .Config.Env}}{{println .}}{{end}}' "$IMAGE")
if grep -E '^(PIP_CERT|SSL_CERT_FILE|SSL_CERT_DIR|REQUESTS_CA_BUNDLE|CURL_CA_BUNDLE)=' <<<"$image_env" >&2; then
    die "the image's environment points at a CA bundle of its own (above)"
fi
forbid=()
if [ -n "$EXTRA_CA_DIR" ] && compgen -G "$EXTRA_CA_DIR/*.crt" >/dev/null; then
    forbid=("$EXTRA_CA_DIR"/*.crt)
fi
"$DOCKER" rm -f "$NAME-fs" >/dev/null 2>&1 || true
CONTAINERS+=("$NAME-fs")
"$DOCKER" create --name "$NAME-fs" "$IMAGE" >/dev/null
"$DOCKER" export "$NAME-fs" | python3 docker/trust_store.py --tar - --forbid "${forbid[@]}" >&2 \
    || die "the image trusts CA certificates that are not Debian's (above)"
"$DOCKER" rm -f "$NAME-fs" >/dev/null
log "trust store: Debian's own; none of the ${#forbid[@]} extra CA certificate(s) of this host in the image"

# ---- 3. run it -----------------------------------------------------------------
free_port() {
    python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
port_busy() {
    python3 -c 'import socket, sys; s = socket.socket(); sys.exit(s.connect_ex(("127.0.0.1", int(sys.argv[1]))) != 0)' "$1"
}
PORT=${SMOKE_PORT:-5006}
if port_busy "$PORT"; then
    [ -z "${SMOKE_PORT:-}" ] || die "port $PORT on 127.0.0.1 is already in use"
    PORT=$(free_port)
    log "port 5006 is in use here; using $PORT"
fi

# Without a Docker bridge (dockerd --bridge=none) the container shares the
# host's network and listens on 127.0.0.1 only; with one, -p publishes the port
# on 127.0.0.1 only.  Either way the server is reached at 127.0.0.1:$PORT.
if "$DOCKER" network inspect bridge >/dev/null 2>&1; then
    NET_MODE=publish
else
    NET_MODE=host
fi

# start_container NAME PORT [docker run options...]
start_container() {
    local name=$1 port=$2; shift 2
    "$DOCKER" rm -f "$name" >/dev/null 2>&1 || true
    CONTAINERS+=("$name")
    local net=()
    if [ "$NET_MODE" = host ]; then
        net=(--network host -e ADDRESS=127.0.0.1 -e "PORT=$port")
    else
        net=(-p "127.0.0.1:$port:5006")
    fi
    log "docker run $name: ${net[*]} $*"
    "$DOCKER" run -d --name "$name" "${net[@]}" \
        -e "ALLOWED_ORIGINS=127.0.0.1:$port,localhost:$port" \
        --health-interval 2s --health-start-period 60s \
        "$@" "$IMAGE" >/dev/null
}

# wait_liveness NAME PORT T0 -> prints the seconds since T0 (taken before docker run)
wait_liveness() {
    local name=$1 port=$2 t=$3 deadline
    deadline=$(( $(date +%s) + LIVENESS_TIMEOUT ))
    until curl -fsS --max-time 2 "http://127.0.0.1:$port/liveness" 2>/dev/null | grep -q true; do
        if [ "$("$DOCKER" inspect -f '{{.State.Running}}' "$name" 2>/dev/null)" != true ]; then
            "$DOCKER" logs "$name" 2>&1 | tail -n 30 >&2
            die "container $name exited before /liveness answered"
        fi
        if [ "$(date +%s)" -ge "$deadline" ]; then
            "$DOCKER" logs "$name" 2>&1 | tail -n 30 >&2
            die "http://127.0.0.1:$port/liveness did not answer within $LIVENESS_TIMEOUT s"
        fi
        sleep 0.25
    done
    since "$t"
}

# check_page PORT PATH
check_page() {
    local url="http://127.0.0.1:$1$2" body code
    body="$WORKDIR/page.html"
    code=$(curl -sSL --max-time 60 -o "$body" -w '%{http_code}' "$url") || die "GET $url failed"
    [ "$code" = 200 ] || die "GET $url answered HTTP $code"
    grep -qi '<script[^>]*bokeh' "$body" || die "GET $url: no Bokeh script in the page"
    grep -q 'Bokeh.embed' "$body" || die "GET $url: the page does not embed a Bokeh document"
    log "GET $url: HTTP 200, $(wc -c <"$body") bytes, Bokeh scripts present"
}

t_start=$(now)
start_container "$NAME" "$PORT" --read-only --tmpfs /tmp:rw,nosuid,nodev,size=64m
RUN_S=$(since "$t_start")
LIVE_S=$(wait_liveness "$NAME" "$PORT" "$t_start")
log "/liveness answered $LIVE_S s after the start of docker run (docker run -d itself: $RUN_S s)"

check_page "$PORT" /main
check_page "$PORT" /

# The image's own HEALTHCHECK command (run every 2 s here instead of 30 s).
deadline=$(( $(date +%s) + 60 ))
until [ "$("$DOCKER" inspect -f '{{.State.Health.Status}}' "$NAME")" = healthy ]; do
    [ "$(date +%s)" -lt "$deadline" ] || die "container never became healthy: $("$DOCKER" inspect -f '{{json .State.Health}}' "$NAME")"
    sleep 1
done
log "HEALTHCHECK: healthy"
uid=$("$DOCKER" exec "$NAME" id -u)
[ "$uid" != 0 ] || die "the server runs as root"
log "server runs as uid $uid"

# The image's compiled kernels reach the server: a fresh process running every kernel
# (core.warm) on a copy of the image's cache, as the entry point seeds the tmpfs, loads
# each from it and compiles none.  The evidence is numba's own cache log
# (docker/numba_cache.sh: NUMBA_DEBUG_CACHE=1, kernels loaded and kernels saved); the
# warm-up's time is only reported.
cache_check=$("$DOCKER" exec -i "$NAME" sh -s <docker/numba_cache.sh 2>&1) \
    || die "the server would compile kernels the image should hold: $cache_check"
log "kernels loaded from the image's cache, none compiled: $cache_check"

# Locked down: a websocket from an origin not in ALLOWED_ORIGINS gets 403 (the
# page's own origin gets 101), and there is no admin page.
ws_status() {  # ws_status ORIGIN -> HTTP status of a websocket handshake on /main/ws
    local token
    token=$(curl -fsS --max-time 30 "http://127.0.0.1:$PORT/main" | grep -o '\\\?"token\\\?": *\\\?"[^"\\]*' | head -n1 | sed 's/.*"//')
    [ -n "$token" ] || die "no session token in the page"
    curl -s -o /dev/null -w '%{http_code}' --max-time 5 \
        -H 'Connection: Upgrade' -H 'Upgrade: websocket' -H 'Sec-WebSocket-Version: 13' \
        -H 'Sec-WebSocket-Key: x3JJHMbDL1EzLkh9GBhXDw==' -H "Origin: $1" \
        -H "Sec-WebSocket-Protocol: bokeh, $token" "http://127.0.0.1:$PORT/main/ws" || true
}
code=$(ws_status http://evil.example)
[ "$code" = 403 ] || die "websocket from Origin http://evil.example answered HTTP $code, not 403"
code=$(ws_status "http://127.0.0.1:$PORT")
[ "$code" = 101 ] || die "websocket from the page's own origin answered HTTP $code, not 101"
code=$(curl -s -o /dev/null -w '%{http_code}' --max-time 10 "http://127.0.0.1:$PORT/admin" || true)
[ "$code" = 404 ] || die "/admin answered HTTP $code, not 404"
body=$(curl -s -w ' HTTP %{http_code}' --max-time 30 "http://127.0.0.1:$PORT/main/autoload.js?bokeh-autoload-element=smoke-probe" || true)
[ "$body" = ' HTTP 404' ] || die "/main/autoload.js answered: ${body:0:200}"
log "websocket origins: foreign 403, own 101; /admin 404; /main/autoload.js 404; root filesystem read-only"

# ---- 4. browser smoke tests --------------------------------------------------
if [ -z "${SKIP_BROWSER:-}" ]; then
    if [ ! -x "$VENV/bin/pytest" ]; then
        log "no $VENV/bin/pytest: make venv"
        make -s venv
    fi
    command -v chromium >/dev/null 2>&1 || { log "no chromium: make browser"; make -s browser; }
    log "EXPLORER_URL=http://127.0.0.1:$PORT/main $VENV/bin/pytest -m smoke tests/app"
    set +e
    EXPLORER_URL="http://127.0.0.1:$PORT/main" "$VENV/bin/pytest" -m smoke -p no:cacheprovider tests/app
    rc=$?
    set -e
    case $rc in
        0) log "browser smoke tests passed" ;;
        5) die "no smoke test was collected in tests/app (pytest -m smoke)" ;;
        *) "$DOCKER" logs "$NAME" 2>&1 | tail -n 30 >&2; die "browser smoke tests failed (pytest exit $rc)" ;;
    esac
else
    log "SKIP_BROWSER set: browser smoke tests skipped"
fi
"$DOCKER" rm -f "$NAME" >/dev/null

# ---- 5. several server processes -----------------------------------------------
if [ -z "${SKIP_MULTIPROC:-}" ]; then
    PORT2=$(free_port)
    t2=$(now)
    start_container "$NAME-procs" "$PORT2" -e NUM_PROCS=2
    LIVE2_S=$(wait_liveness "$NAME-procs" "$PORT2" "$t2")
    check_page "$PORT2" /main
    check_page "$PORT2" /main
    # the parent process forks NUM_PROCS children that serve (no ps in slim images)
    n=$("$DOCKER" exec "$NAME-procs" python -c "import os; print(sum(b'app.serve' in open(f'/proc/{p}/cmdline', 'rb').read() for p in os.listdir('/proc') if p.isdigit()))") || true
    [ "${n:-0}" -ge 3 ] || { "$DOCKER" logs "$NAME-procs" 2>&1 | tail -n 20 >&2; die "NUM_PROCS=2 did not start 2 server processes besides the parent ($n app.serve processes)"; }
    n=$((n - 1))
    log "NUM_PROCS=2: $n server processes, /liveness after $LIVE2_S s"
    "$DOCKER" rm -f "$NAME-procs" >/dev/null
fi

log "summary: image $IMAGE ${SIZE_MB} MB; build ${BUILD_S:-skipped} s; /liveness ${LIVE_S} s after docker run; checks took $(since "$t_start") s"
