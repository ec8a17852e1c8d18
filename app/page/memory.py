"""When the server's cyclic garbage collector walks the open sessions: rarely.

A page's document is ~37,000 objects that Python's cyclic garbage collector tracks, and
a full collection walks every one alive, holding the interpreter for a time that grows
with the sessions open (``python -m benchmarks.app.gc_pause`` measures it), during which
the process serves no one.  Panel collects in full 5 s after a session closes, and
Python by itself whenever the objects that survived its younger collections have grown
by a quarter: unmanaged, a class joining or leaving stalls every session on the process
once per student or two.

`SessionMemory` keeps the open sessions out of those walks.  After each page build
with `freeze_from` sessions open or more, everything alive is frozen (`gc.freeze`:
moved where no collection looks, at no cost), so that a collection walks only what is
newer.  What a closed session leaves frozen is reclaimed by a *sweep*: everything is
unfrozen (`gc.unfreeze`) and the next full collection (Panel's, after the close, or
Python's own) reclaims it; builds freeze again once that collection has run.  A sweep
is due when the closed sessions since the last reach a quarter of those open: a few
full collections a lesson instead of one per student, and at most a quarter of the
open sessions' memory held by closed ones.  (A build's own garbage, frozen with it, is
a few hundred objects; the next sweep takes it.)

A sweep's collection walks everything, the modules' objects that the server froze at
its start among them: with fewer than `freeze_from`
sessions open, builds freeze nothing and a close needs no sweep, so that a collection
walks the few open sessions only (and the modules' objects too once a
sweep has unfrozen them, until a build with `freeze_from` open freezes them again).

Python's own full collections come rarely too (`THRESHOLDS`, set by `app.serve`): a
build's objects survive the young collections, and with Python's thresholds a page
loaded every second or so set off a full walk of the unfrozen sessions about every
other build, and with `THRESHOLDS` a few times a class (``python -m
benchmarks.app.gc_pause`` counts the full collections Python runs while a class joins,
and their time).  What the sessions leave is
reclaimed by Panel's collection after each close, whatever the thresholds.
"""

from __future__ import annotations

import gc
import threading

#: The collector's thresholds in a server process (`gc.set_threshold`; Python's are
#: (700, 10, 10)): a full collection after every 100th collection of the middle
#: generation, about 700,000 objects allocated and kept, a dozen page builds' worth.
THRESHOLDS = (700, 10, 100)


class SessionMemory:
    """The freezing and sweeping of one server process's sessions (see the module).

    `built()` is called after each page build (on its worker thread), `closed()` when a
    session built with it is destroyed (on the event loop)."""

    def __init__(self, share: float = 0.25, freeze_from: int = 8) -> None:
        self.share, self.freeze_from = share, freeze_from
        self.open = 0  # sessions built and not yet destroyed
        self._closed = 0  # sessions destroyed since the last sweep
        self._sweeping = False  # unfrozen until the next full collection has run
        self._holds = False  # sessions' objects frozen since the last sweep
        self._lock = threading.Lock()
        gc.callbacks.append(self._collected)

    @property
    def sweeping(self) -> bool:
        """Whether a sweep waits for its full collection (nothing is frozen meanwhile)."""
        return self._sweeping

    def built(self) -> None:
        """A page was built: freeze what is alive, with `freeze_from` sessions open or
        more, unless a sweep is waiting."""
        with self._lock:
            self.open += 1
            if not self._sweeping and self.open >= self.freeze_from:
                gc.freeze()
                self._holds = True

    def closed(self) -> None:
        """A session was destroyed: sweep once a `share` of the open ones have closed
        (if sessions were frozen since the last sweep: else a collection reclaims it)."""
        with self._lock:
            self.open = max(0, self.open - 1)
            self._closed += 1
            if not self._holds:
                self._closed = 0
            elif self._closed >= max(1.0, self.share * self.open):
                self._sweep()

    def _sweep(self) -> None:
        gc.unfreeze()
        self._sweeping, self._closed, self._holds = True, 0, False

    def _collected(self, phase: str, info: dict) -> None:
        # (gc's own callback: called at every collection's start and stop, on the thread
        # that collects; a full one, generation 2, ends a sweep)
        if phase == "stop" and info.get("generation") == 2:
            self._sweeping = False

    def stop(self) -> None:
        """Leave the collector as Python runs it: nothing frozen, no callback."""
        with self._lock:
            if self._collected in gc.callbacks:
                gc.callbacks.remove(self._collected)
            gc.unfreeze()
            self._sweeping = self._holds = False
