#!/usr/bin/env bash
# Build local Python base images without pulling from any container registry:
# debootstrap a minimal Debian trixie (python3 is 3.13 there; bookworm's 3.11 is
# too old for Panel >= 1.10) with python3, python3-venv and ca-certificates,
# then `docker import` it.  Idempotent: does nothing when the images exist.
#
#   bash docker/build-base.sh [TAG [BUILD_TAG]]
#
# Two images from one rootfs:
#   TAG        (default zharii-base:trixie): the base of the shipped image.  Its trust
#              store is Debian's own (checked with docker/trust_store.py before import).
#   BUILD_TAG  (default TAG-build, e.g. zharii-base:trixie-build): TAG plus the build
#              host's extra CA certificates (EXTRA_CA_DIR, default
#              /usr/local/share/ca-certificates: e.g. those of a TLS-intercepting egress
#              proxy) in its trust store, and PIP_CERT pointing at that bundle, so that
#              pip in the Dockerfile's build stages (--build-arg BUILD_BASE) reaches the
#              package index as pip on the host does.  Never the base of a shipped image:
#              the runtime stage is FROM TAG.  With no extra CA it is a second tag of TAG.
# A TAG made by an earlier version of this script, which put the host's CAs into it
# (its environment sets PIP_CERT), is removed and rebuilt.
#
# Environment: BASE_SUITE (default trixie), DEBIAN_MIRROR (default: the Debian
# mirror apt already uses on this machine, else http://deb.debian.org/debian),
# WORKDIR (default /var/tmp/zharii-docker; the rootfs never goes in the repo),
# DOCKER (default docker), EXTRA_CA_DIR (see BUILD_TAG; set it empty to add none).
# Needs root (debootstrap, chroot).
set -euo pipefail

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
TAG=${1:-${BASE_IMAGE:-zharii-base:trixie}}
BUILD_TAG=${2:-${BUILD_BASE_IMAGE:-$TAG-build}}
SUITE=${BASE_SUITE:-trixie}
WORKDIR=${WORKDIR:-/var/tmp/zharii-docker}
DOCKER=${DOCKER:-docker}
EXTRA_CA_DIR=${EXTRA_CA_DIR-/usr/local/share/ca-certificates}
EXTRA_CAS=()
if [ -n "$EXTRA_CA_DIR" ] && compgen -G "$EXTRA_CA_DIR/*.crt" >/dev/null; then
    EXTRA_CAS=("$EXTRA_CA_DIR"/*.crt)
fi

log() { printf '[build-base] %s\n' "$*" >&2; }

have() { "$DOCKER" image inspect "$1" >/dev/null 2>&1; }
image_env() { "$DOCKER" image inspect -f '{{range .Config.Env}}{{println .}}{{end}}' "$1"; }
if have "$TAG"; then
    if grep -q '^PIP_CERT=' <<<"$(image_env "$TAG")"; then
        log "$TAG trusts the build host's CA certificates (made by an earlier build-base.sh): rebuilding it"
    elif have "$BUILD_TAG"; then
        log "base images $TAG and $BUILD_TAG already exist; nothing to do"
        exit 0
    else
        log "$BUILD_TAG is missing: rebuilding both"
    fi
    for t in "$TAG" "$BUILD_TAG"; do
        if have "$t"; then "$DOCKER" rmi "$t" >/dev/null; fi
    done
    if have "$TAG"; then log "error: could not remove $TAG"; exit 1; fi
fi

[ "$(id -u)" = 0 ] || { log "error: debootstrap needs root"; exit 1; }

if ! command -v debootstrap >/dev/null 2>&1; then
    log "installing debootstrap (apt-get)"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null
fi

# The Debian mirror apt is already configured with (deb822 or one-line format).
detect_mirror() {
    local f
    for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.sources /etc/apt/sources.list.d/*.list; do
        [ -r "$f" ] || continue
        grep -hoE '^(URIs:[[:space:]]*|deb[[:space:]]+(\[[^]]*\][[:space:]]+)?)[a-z]+://[^[:space:]]+/debian/?([[:space:]]|$)' "$f" \
            | grep -oE '[a-z]+://[^[:space:]]+' | head -n1 && return 0
    done
    return 1
}
MIRROR=${DEBIAN_MIRROR:-$(detect_mirror || echo http://deb.debian.org/debian)}
MIRROR=${MIRROR%/}

mkdir -p "$WORKDIR"
ROOTFS=$(mktemp -d "$WORKDIR/rootfs.XXXXXX")
chmod 755 "$ROOTFS"  # mktemp makes it 0700: it becomes the image's /
cleanup() { rm -rf "$ROOTFS"; }
trap cleanup EXIT

start=$(date +%s)
log "debootstrap --variant=minbase $SUITE from $MIRROR into $ROOTFS"
debootstrap --variant=minbase --include=python3,python3-venv,ca-certificates \
    "$SUITE" "$ROOTFS" "$MIRROR" >"$WORKDIR/debootstrap.log" 2>&1 \
    || { log "error: debootstrap failed; see $WORKDIR/debootstrap.log"; tail -n 20 "$WORKDIR/debootstrap.log" >&2; exit 1; }

log "trimming apt lists, caches, docs and locales"
chroot "$ROOTFS" apt-get clean
rm -rf "$ROOTFS"/var/lib/apt/lists/* "$ROOTFS"/var/cache/apt/*.bin \
       "$ROOTFS"/usr/share/doc/* "$ROOTFS"/usr/share/man/* "$ROOTFS"/usr/share/info/* \
       "$ROOTFS"/var/log/*.log "$ROOTFS"/tmp/*
find "$ROOTFS"/usr/share/locale -mindepth 1 -maxdepth 1 ! -name 'locale.alias' -exec rm -rf {} +
# Same convention as the official python images: `python3` on PATH, UTF-8.
log "python in the rootfs: $(chroot "$ROOTFS" python3 --version)"

# The shipped base: Debian's trust store and nothing else (the host's extra CAs
# nowhere in the rootfs), checked before it is imported.
python3 "$HERE/trust_store.py" --root "$ROOTFS" --forbid "${EXTRA_CAS[@]}" >&2 \
    || { log "error: the rootfs trusts certificates that are not Debian's"; exit 1; }
import_rootfs() {  # import_rootfs TAG MESSAGE [--change ...]
    local tag=$1 message=$2; shift 2
    log "docker import -> $tag"
    tar --numeric-owner -C "$ROOTFS" -c . | "$DOCKER" import \
        --change 'ENV LANG=C.UTF-8' \
        --change 'ENV PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin' \
        --change 'CMD ["python3"]' \
        "$@" --message "$message" - "$tag" >/dev/null
}
import_rootfs "$TAG" "debootstrap --variant=minbase $SUITE + python3 python3-venv ca-certificates"

# The build-only base: the same rootfs, its trust store with the host's extra CAs.
if [ "${#EXTRA_CAS[@]}" -gt 0 ]; then
    log "$BUILD_TAG (build stages only): adding the host's extra CA certificates from $EXTRA_CA_DIR: $(cd "$EXTRA_CA_DIR" && echo *.crt)"
    cp "${EXTRA_CAS[@]}" "$ROOTFS/usr/local/share/ca-certificates/"
    chroot "$ROOTFS" update-ca-certificates >/dev/null 2>&1
    import_rootfs "$BUILD_TAG" "$TAG + the build host's CA certificates: for build stages only, never shipped" \
        --change 'ENV PIP_CERT=/etc/ssl/certs/ca-certificates.crt'
else
    log "no extra CA certificate in '${EXTRA_CA_DIR}': $BUILD_TAG is $TAG"
    "$DOCKER" tag "$TAG" "$BUILD_TAG"
fi
log "built $TAG and $BUILD_TAG in $(( $(date +%s) - start )) s ($("$DOCKER" image inspect -f '{{.Size}}' "$TAG" | awk '{printf "%.0f MB", $1/1e6}'))"
