#!/usr/bin/env bash
# Build a local Python base image without pulling from any container registry:
# debootstrap a minimal Debian trixie (python3 is 3.13 there; bookworm's 3.11 is
# too old for Panel >= 1.10) with python3, python3-venv and ca-certificates,
# then `docker import` it.  Idempotent: does nothing when the image exists.
#
#   bash docker/build-base.sh [TAG]        (default TAG: zharii-base:trixie)
#
# Environment: BASE_SUITE (default trixie), DEBIAN_MIRROR (default: the Debian
# mirror apt already uses on this machine, else http://deb.debian.org/debian),
# WORKDIR (default /var/tmp/zharii-docker; the rootfs never goes in the repo),
# DOCKER (default docker), EXTRA_CA_DIR (default /usr/local/share/ca-certificates:
# the host's extra CA certificates, e.g. of a TLS-intercepting egress proxy, are
# added to the base's trust store so that pip inside `docker build` reaches the
# package index exactly as pip on the host does; set it empty to skip).
# Needs root (debootstrap, chroot).
set -euo pipefail

TAG=${1:-${BASE_IMAGE:-zharii-base:trixie}}
SUITE=${BASE_SUITE:-trixie}
WORKDIR=${WORKDIR:-/var/tmp/zharii-docker}
DOCKER=${DOCKER:-docker}

log() { printf '[build-base] %s\n' "$*" >&2; }

if "$DOCKER" image inspect "$TAG" >/dev/null 2>&1; then
    log "base image $TAG already exists; nothing to do"
    exit 0
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

EXTRA_CA_DIR=${EXTRA_CA_DIR-/usr/local/share/ca-certificates}
if [ -n "$EXTRA_CA_DIR" ] && compgen -G "$EXTRA_CA_DIR/*.crt" >/dev/null; then
    log "adding the host's extra CA certificates from $EXTRA_CA_DIR: $(cd "$EXTRA_CA_DIR" && echo *.crt)"
    cp "$EXTRA_CA_DIR"/*.crt "$ROOTFS/usr/local/share/ca-certificates/"
    chroot "$ROOTFS" update-ca-certificates >/dev/null 2>&1
fi

log "trimming apt lists, caches, docs and locales"
chroot "$ROOTFS" apt-get clean
rm -rf "$ROOTFS"/var/lib/apt/lists/* "$ROOTFS"/var/cache/apt/*.bin \
       "$ROOTFS"/usr/share/doc/* "$ROOTFS"/usr/share/man/* "$ROOTFS"/usr/share/info/* \
       "$ROOTFS"/var/log/*.log "$ROOTFS"/tmp/*
find "$ROOTFS"/usr/share/locale -mindepth 1 -maxdepth 1 ! -name 'locale.alias' -exec rm -rf {} +
# Same convention as the official python images: `python3` on PATH, UTF-8.
log "python in the rootfs: $(chroot "$ROOTFS" python3 --version)"

log "docker import -> $TAG"
tar --numeric-owner -C "$ROOTFS" -c . | "$DOCKER" import \
    --change 'ENV LANG=C.UTF-8' \
    --change 'ENV PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin' \
    --change 'ENV PIP_CERT=/etc/ssl/certs/ca-certificates.crt' \
    --change 'CMD ["python3"]' \
    --message "debootstrap --variant=minbase $SUITE + python3 python3-venv ca-certificates" \
    - "$TAG" >/dev/null
log "built $TAG in $(( $(date +%s) - start )) s ($("$DOCKER" image inspect -f '{{.Size}}' "$TAG" | awk '{printf "%.0f MB", $1/1e6}'))"
