"""The Motor card's fixture: a card built and its first results shown."""

from __future__ import annotations

import pytest
from test_motor_scene import wait

from app.motor import MotorScene


@pytest.fixture
def scene() -> MotorScene:
    s = MotorScene()
    wait()
    yield s
    s.close()
