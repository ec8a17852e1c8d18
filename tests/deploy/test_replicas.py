"""Two explorer replicas behind Debian's nginx with the shipped docker/nginx.conf.

Runs docker/replicas.py's smoke test (also `make replica-smoke`) on loopback ports:
sessions opened through the balancer speaking Bokeh's protocol land on both replicas,
each session's page and websocket reach the same replica (sticky cookie), a foreign
websocket Origin is refused through the balancer, and with one replica killed the
other's sessions and new sessions keep working.  Also checks the TLS variant of the
configuration with `nginx -t`.

nginx is installed with apt-get (Debian's package, no service started) when missing
and this runs as root; otherwise the tests are skipped with the reason.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "docker"))
import replicas  # noqa: E402  (docker/replicas.py)

pytestmark = pytest.mark.slow


def _install_nginx() -> str | None:
    """Why nginx cannot be had, or None once it is installed."""
    if replicas.nginx_exe():
        return None
    if os.geteuid() != 0 or not shutil.which("apt-get"):
        return "nginx is not installed and apt-get is not available as root (make nginx)"
    env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive", "RUNLEVEL": "1"}
    for cmd in (["apt-get", "install", "-y", "-qq", "nginx"],
                ["apt-get", "update", "-qq"],
                ["apt-get", "install", "-y", "-qq", "nginx"]):
        try:
            subprocess.run(cmd, env=env, capture_output=True, timeout=300, check=False)
        except subprocess.TimeoutExpired:
            return f"`{' '.join(cmd)}` timed out"
        if replicas.nginx_exe():
            return None
    return "nginx could not be installed with apt-get"


@pytest.fixture(scope="module")
def nginx() -> str:
    why = _install_nginx()
    if why:
        pytest.skip(why)
    return replicas.nginx_exe()


def test_two_replicas_behind_nginx_are_sticky_and_survive_a_kill(nginx):
    result = replicas.smoke(2)
    assert all(n >= 1 for n in result["sessions_per_replica"].values())
    assert result["sticky_sessions_checked"] >= 6
    assert result["after_kill"]["new_sessions_ok"] == 6


def test_tls_configuration_is_valid(nginx, tmp_path):
    key, cert = tmp_path / "key.pem", tmp_path / "cert.pem"
    if not shutil.which("openssl"):
        pytest.skip("openssl is not installed")
    subprocess.run(["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "1",
                    "-subj", "/CN=localhost", "-keyout", str(key), "-out", str(cert)],
                   capture_output=True, check=True, timeout=60)
    conf = replicas.render((ROOT / "docker" / "nginx-tls.conf").read_text(),
                           SERVER_NAME="localhost", LISTEN_HTTP=f"127.0.0.1:{replicas.free_port()}",
                           LISTEN_HTTPS=f"127.0.0.1:{replicas.free_port()}",
                           UPSTREAM_SERVERS="server 127.0.0.1:9;",
                           TLS_CERT=str(cert), TLS_KEY=str(key))
    (tmp_path / "explorer.conf").write_text(conf)
    (tmp_path / "tmp").mkdir()
    (tmp_path / "nginx.conf").write_text(replicas.TOP.format(d=tmp_path))
    proc = subprocess.run([nginx, "-t", "-c", str(tmp_path / "nginx.conf")],
                          capture_output=True, text=True, timeout=30, check=False)
    assert proc.returncode == 0, proc.stderr


def test_render_refuses_missing_variables():
    with pytest.raises(KeyError, match="UPSTREAM_SERVERS"):
        replicas.render((ROOT / "docker" / "nginx.conf").read_text(), LISTEN="80")
