"""The Motor feature: the rod of Fig. 1 driving a rotor (docs/motor.md, the card's
section of docs/app.md).  `fields`: the inputs, units, presets and their check; `state`:
`MotorState` and the URL codec; `data`: what is shown, from `core.motor`, no Bokeh;
`figures`: the figures and named sources; `plots`: the job's results drawn; `downloads`:
the CSV files; `view`: `MotorScene`, the card."""

from app.motor.fields import FIELDS, PREFIX
from app.motor.state import QUERY_KEYS, URL_PARAMS, MotorState
from app.motor.view import MotorScene

__all__ = ["FIELDS", "PREFIX", "QUERY_KEYS", "URL_PARAMS", "MotorScene", "MotorState"]
