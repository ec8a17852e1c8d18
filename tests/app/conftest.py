"""Fixtures of the browser tests: one explorer server and one Chromium per module."""

from __future__ import annotations

import pytest
from explorer_browser import CHROMIUM_ARGS, chromium_path, explorer_server


@pytest.fixture(scope="module")
def url():
    with explorer_server() as u:
        yield u


@pytest.fixture(scope="module")
def browser():
    path = chromium_path()
    if path is None:
        pytest.skip("/usr/bin/chromium is absent and could not be installed (apt-get)")
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=path, args=CHROMIUM_ARGS)
        yield b
        b.close()
