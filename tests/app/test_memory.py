"""The open sessions are kept out of the garbage collector's walks, and what closed
sessions leave is reclaimed (`app.page.memory.SessionMemory`)."""

from __future__ import annotations

import gc
import weakref

import pytest

from app.page.memory import THRESHOLDS, SessionMemory


class Node:
    """A stand-in for a document's objects: a cycle only the cyclic collector frees."""

    def __init__(self) -> None:
        self.me = self


@pytest.fixture
def memory():
    gc.collect()
    m = SessionMemory(share=0.25, freeze_from=1)
    yield m
    m.stop()
    gc.collect()


def test_a_build_freezes_what_is_alive_and_collections_pass_it_by(memory) -> None:
    doc = Node()
    memory.built()
    assert gc.get_freeze_count() > 0 and not memory.sweeping
    dead = weakref.ref(doc)
    del doc
    gc.collect()  # (walks what is newer than the build only)
    assert dead() is not None


def test_closed_sessions_are_reclaimed_once_a_quarter_of_the_open_have_closed(memory) -> None:
    docs = []
    for _ in range(3):
        docs.append(Node())
        memory.built()
    assert memory.open == 3 and not memory.sweeping
    refs = [weakref.ref(d) for d in docs]
    docs.clear()
    memory.closed()  # 1 closed of 2 open left: at least a quarter, and at least one
    assert memory.sweeping and gc.get_freeze_count() == 0
    gc.collect()  # the full collection the sweep waits for
    assert not memory.sweeping
    assert all(r() is None for r in refs)


def test_with_many_open_one_close_does_not_sweep(memory) -> None:
    for _ in range(40):
        memory.built()
    frozen = gc.get_freeze_count()
    memory.closed()
    assert not memory.sweeping and gc.get_freeze_count() == frozen  # 1 of 39: no sweep
    for _ in range(9):
        memory.closed()
    assert memory.sweeping  # 10 closed since the last sweep, 30 open: a quarter


def test_no_build_freezes_while_a_sweep_waits_for_its_collection(memory) -> None:
    memory.built()
    memory.closed()  # the only one: a sweep
    assert memory.sweeping and gc.get_freeze_count() == 0
    memory.built()
    assert gc.get_freeze_count() == 0  # its garbage would be frozen again
    gc.collect(1)  # (a younger generation's collection does not end it)
    assert memory.sweeping
    gc.collect()
    memory.built()
    assert not memory.sweeping and gc.get_freeze_count() > 0


def test_with_few_open_nothing_is_frozen_and_a_close_needs_no_sweep() -> None:
    """Below `freeze_from` open sessions a build freezes nothing, so a close is
    reclaimed by a collection of the few open sessions (a sweep would walk all that the
    server froze at its start); the build that reaches it freezes them all."""
    gc.collect()
    m = SessionMemory(share=0.25, freeze_from=3)
    try:
        before = gc.get_freeze_count()
        docs = []
        for _ in range(2):
            docs.append(Node())
            m.built()
        assert gc.get_freeze_count() == before
        dead = weakref.ref(docs.pop())
        m.closed()
        assert not m.sweeping and gc.get_freeze_count() == before
        gc.collect()
        assert dead() is None
        for _ in range(2):
            docs.append(Node())
            m.built()  # 2, then 3 open: the third freezes
        assert m.open == 3 and gc.get_freeze_count() > before
        m.closed()  # 1 of 2 left: a quarter: a sweep
        assert m.sweeping and gc.get_freeze_count() == 0
    finally:
        m.stop()
        gc.collect()


def full_collections_over_builds(thresholds: tuple[int, int, int], builds: int = 8) -> int:
    """The full collections Python runs by itself while `builds` pages' worth of objects
    (37,000 each, kept alive: a page's document, `app.page.memory`) are allocated, with
    the collector's `thresholds`."""
    counts = []

    def count(phase: str, info: dict) -> None:
        if phase == "stop" and info["generation"] == 2:
            counts.append(1)

    saved = gc.get_threshold()
    gc.collect()
    gc.freeze()  # (as the server does at its start: what this process holds already is
    gc.collect()  # out of the walks, and of the count by which Python decides on one)
    gc.set_threshold(*thresholds)
    gc.callbacks.append(count)
    try:
        pages = [[Node() for _ in range(37_000)] for _ in range(builds)]
    finally:
        gc.callbacks.remove(count)
        gc.set_threshold(*saved)
        gc.unfreeze()
    del pages
    gc.collect()
    return len(counts)


def test_the_servers_thresholds_keep_pythons_full_collections_out_of_a_run_of_builds() -> None:
    """Eight page builds with fewer than `freeze_from` sessions open (nothing frozen):
    with Python's thresholds the collector walks them in full every other build or so,
    with the server's (`THRESHOLDS`) not once."""
    assert full_collections_over_builds((700, 10, 10)) >= 2
    assert full_collections_over_builds(THRESHOLDS) == 0
