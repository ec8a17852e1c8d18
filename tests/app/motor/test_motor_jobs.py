"""The Motor card on the job runner (`app.kit.jobs.RUNNER`): a closed card's waiting job
is dropped and it asks for nothing more; a newer request replaces the waiting one and
only the newest result is shown; a failed job ends the progress and says why."""

from __future__ import annotations

import pytest
from jobs_helpers import Watched, blocked
from test_motor_scene import assert_curve_matches_core, wait

from app.kit.jobs import RUNNER
from app.motor import MotorScene


def test_a_closed_scene_drops_its_waiting_job_and_asks_for_nothing_more() -> None:
    s = MotorScene()
    wait()
    shown = s.results
    gate = blocked(RUNNER)
    try:
        with Watched(RUNNER) as jobs:
            s.inputs["x0"].value = -2.0
            assert jobs.waiting == 1 and s.progress.busy
            s.close()
            assert jobs.waiting == 0  # dropped
            s.inputs["x0"].value = -3.0  # a closed scene asks for nothing more
            assert jobs.waiting == 0
    finally:
        gate.set()
    wait()
    assert s.results is shown  # nothing ran for it


def test_a_newer_request_replaces_the_waiting_one_and_only_it_is_shown() -> None:
    s = MotorScene()
    wait()
    gate = blocked(RUNNER)
    try:
        with Watched(RUNNER) as jobs:
            s.inputs["x0"].value = -2.0
            s.inputs["x0"].value = -4.0  # replaces the waiting request
        assert jobs.waiting == 1 and s.progress.busy
        assert s.status.object == "computing the thrust-speed curve, the load and the wear…"
    finally:
        gate.set()
    assert_curve_matches_core(s)
    assert s.results.at_x0.point.x0 == -0.004
    assert not s.progress.busy
    s.close()


def test_a_failed_job_ends_the_progress_and_says_why(scene: MotorScene,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    import app.motor.data

    def broken(request):
        raise RuntimeError("out of memory")

    monkeypatch.setattr(app.motor.data, "compute", broken)
    scene.inputs["x0"].value = -3.0
    wait()
    assert not scene.progress.busy
    assert scene.status.object == "⚠ could not compute: out of memory"


