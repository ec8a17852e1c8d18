"""Check that an image trusts only Debian's own CA certificates.

    docker export CONTAINER | python3 docker/trust_store.py --tar - \\
        --forbid /usr/local/share/ca-certificates/*.crt
    python3 docker/trust_store.py --root ROOTFS [--forbid CERT ...]

The base image is built on a host whose egress proxy intercepts TLS with its own CA
(docker/build-base.sh); pip inside `docker build` must trust that CA, the shipped image
must not.  This reads a whole filesystem (an exported container, or a directory) and
fails (exit 1, one line per problem) unless:

1. every certificate of the trust store (the bundle /etc/ssl/certs/ca-certificates.crt,
   each certificate or link in /etc/ssl/certs) is one that Debian's ca-certificates
   package ships: a file the package installed, as its dpkg file list names them;
2. /usr/local/share/ca-certificates (where local CAs are added) holds no certificate;
3. no file anywhere holds a certificate given with --forbid (the build host's extra
   CAs: those are compared by their DER bytes, whatever the file's name).

Standard library only: it runs with the host's python3, no virtual environment.
"""

from __future__ import annotations

import argparse
import base64
import hashlib
import os
import re
import sys
import tarfile
from collections.abc import Iterator
from pathlib import Path, PurePosixPath

PEM = re.compile(rb"-----BEGIN CERTIFICATE-----\s+([A-Za-z0-9+/=\s]+?)-----END CERTIFICATE-----")
MARK = b"-----BEGIN CERTIFICATE-----"
BUNDLE = "etc/ssl/certs/ca-certificates.crt"
CERTS_DIR = "etc/ssl/certs"
LOCAL_DIR = "usr/local/share/ca-certificates"
PACKAGE_LIST = "var/lib/dpkg/info/ca-certificates.list"


def certificates(data: bytes) -> set[str]:
    """SHA-256 fingerprints (hex) of the DER bytes of every PEM certificate in `data`."""
    out = set()
    for m in PEM.finditer(data):
        try:
            der = base64.b64decode(b"".join(m.group(1).split()), validate=True)
        except ValueError:
            continue
        out.add(hashlib.sha256(der).hexdigest())
    return out


def _norm(path: str) -> str:
    """A member's path relative to the root, without leading ./ or /."""
    return "/".join(x for x in path.split("/") if x not in ("", "."))


def walk_tar(stream) -> Iterator[tuple[str, str | None, bytes | None]]:
    """(path, symlink target or None, contents or None) of every member of a tar stream."""
    with tarfile.open(fileobj=stream, mode="r|*") as tar:
        for m in tar:
            path = _norm(m.name)
            if m.issym():
                yield path, m.linkname, None
            elif m.isfile():
                f = tar.extractfile(m)
                yield path, None, f.read() if f else b""
            elif m.islnk():
                yield path, "/" + _norm(m.linkname), None


def walk_root(root: Path) -> Iterator[tuple[str, str | None, bytes | None]]:
    """The same for a directory tree (symlinks are not followed)."""
    for dirpath, dirnames, filenames in os.walk(root):
        for name in filenames + [d for d in dirnames if os.path.islink(os.path.join(dirpath, d))]:
            full = os.path.join(dirpath, name)
            rel = os.path.relpath(full, root)
            if os.path.islink(full):
                yield rel, os.readlink(full), None
            elif os.path.isfile(full):
                with open(full, "rb") as f:
                    yield rel, None, f.read()


def check(entries: Iterator[tuple[str, str | None, bytes | None]],
          forbidden: set[str]) -> tuple[list[str], dict[str, int]]:
    """Problems (empty when the trust store is Debian's own) and counts of what was read."""
    files: dict[str, set[str]] = {}  # path -> certificates, for files that hold some
    links: dict[str, str] = {}
    package_files: list[str] | None = None
    problems: list[str] = []
    n = 0
    for path, target, data in entries:
        n += 1
        if target is not None:
            links[path] = target
            continue
        if path == PACKAGE_LIST:
            package_files = [_norm(ln) for ln in data.decode().splitlines() if ln.strip()]
        if MARK in data:
            found = certificates(data)
            if found:
                files[path] = found
                bad = found & forbidden
                if bad:
                    problems.append(f"/{path} holds {len(bad)} of the forbidden certificates")

    def resolve(path: str) -> str:
        for _ in range(40):
            if path not in links:
                return path
            target = links[path]
            base = PurePosixPath("/" + path).parent
            path = _norm(str(base / target) if not target.startswith("/") else target)
        return path

    if package_files is None:
        problems.append(f"no /{PACKAGE_LIST}: cannot tell Debian's certificates")
        debian: set[str] = set()
    else:
        debian = set().union(*(files.get(p, set()) for p in package_files))
        if not debian:
            problems.append("the ca-certificates package's files hold no certificate")
    bundle = files.get(resolve(BUNDLE))
    if not bundle:
        problems.append(f"no certificate in /{BUNDLE}")
    else:
        extra = bundle - debian
        if extra:
            problems.append(f"/{BUNDLE}: {len(extra)} of its {len(bundle)} certificates are "
                            "not among those of the ca-certificates package")
    in_dir = sorted({p for p in files if p.startswith(CERTS_DIR + "/")}
                    | {p for p in links if p.startswith(CERTS_DIR + "/")})
    for p in in_dir:
        if p == BUNDLE:
            continue
        real = resolve(p)
        if real.startswith(LOCAL_DIR + "/") or files.get(real, set()) - debian:
            where = f"/{p}" if real == p else f"/{p} -> /{real}"
            problems.append(f"{where}: not a certificate of the ca-certificates package")
    local = sorted(p for p in set(files) | set(links) if p.startswith(LOCAL_DIR + "/"))
    for p in local:
        problems.append(f"/{p}: a local CA certificate")
    counts = {"entries": n, "debian": len(debian), "bundle": len(bundle or ()),
              "forbidden": len(forbidden)}
    return problems, counts


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    src = p.add_mutually_exclusive_group(required=True)
    src.add_argument("--tar", help="a tar stream of the filesystem ('-': standard input)")
    src.add_argument("--root", type=Path, help="a directory holding the filesystem")
    p.add_argument("--forbid", nargs="*", default=[], metavar="CERT",
                   help="PEM files of certificates that must be nowhere in the filesystem")
    args = p.parse_args(argv)
    forbidden: set[str] = set()
    for f in args.forbid:
        found = certificates(Path(f).read_bytes())
        if not found:
            p.error(f"{f}: no PEM certificate")
        forbidden |= found
    if args.root is not None:
        problems, counts = check(walk_root(args.root), forbidden)
    elif args.tar == "-":
        problems, counts = check(walk_tar(sys.stdin.buffer), forbidden)
    else:
        with open(args.tar, "rb") as f:
            problems, counts = check(walk_tar(f), forbidden)
    for line in problems:
        print(f"trust store: {line}", file=sys.stderr)
    print(f"trust store: {counts['bundle']} certificates in the bundle, all among the "
          f"{counts['debian']} of Debian's ca-certificates package; none of the "
          f"{counts['forbidden']} forbidden anywhere in {counts['entries']} files"
          if not problems else f"trust store: {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
