"""rigsim from Python: start rigsimd on a rig and steer it through its control API.

Standard library only (pyserial where a test opens a device's pty or socket:// URL).

    from rigsim import Rigsim
    with Rigsim(rig="config/examples/gripper.json", rigsimd="build/release/rigsimd") as rig:
        rig.pause()
        ...                       # a client drives rig.endpoint("mcs0").tcp
        rig.step(100)             # exactly 100 ms of clock time
        rig.run_until_idle(30000)

The pytest plugin (rigsim.pytest_plugin) gives tests a `rigsim` fixture factory.
"""

from rigsim.control import ControlClient, ControlError, NotIdle, Placement, Pose
from rigsim.daemon import Endpoint, Rigsim, RigsimError

__all__ = ["ControlClient", "ControlError", "Endpoint", "NotIdle", "Placement", "Pose", "Rigsim", "RigsimError"]
