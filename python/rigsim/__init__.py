"""rigsim from Python: start rigsimd on a rig and steer it through its control API.

Standard library only (pyserial where a test opens a device's pty or socket:// URL).

    from rigsim import Rigsim
    with Rigsim(rig="config/examples/gripper.json", rigsimd="build/release/rigsimd") as rig:
        rig.pause()
        ...                       # a client drives rig.endpoint("mcs0").tcp
        rig.step(100)             # exactly 100 ms of clock time
        rig.run_until_idle(30000)

The pytest plugin (rigsim.pytest_plugin) gives tests the `rigsim` and `rigsim_session` fixture
factories and the ready `rigsim_rig`. modem_lines_shim() finds the RTS/DTR shim for LD_PRELOAD.
"""

from rigsim.control import (DEFAULT_CONTROL, ControlClient, ControlError, NoControlAnswer, NotControlApi, NotIdle,
                            Placement, Pose)
from rigsim.daemon import Endpoint, Noted, Rigsim, RigsimError, modem_lines_preloaded, modem_lines_shim

__all__ = ["DEFAULT_CONTROL", "ControlClient", "ControlError", "Endpoint", "NoControlAnswer", "NotControlApi",
           "NotIdle", "Noted", "Placement", "Pose", "Rigsim", "RigsimError", "modem_lines_preloaded", "modem_lines_shim"]
