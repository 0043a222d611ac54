"""Stop every arm before the process goes: SIGTERM and SIGINT stop motion, then exit.

`verigraph serve` installs this when it serves an arm. The handler sends each open
controller's stop (which never waits: see ArmController.stop), latches and logs it,
and then lets the signal do what it did before: SIGINT raises KeyboardInterrupt,
SIGTERM ends the process.
"""

from __future__ import annotations

import os
import signal
from types import FrameType

from verigraph.arm.controller import stop_every_arm

SIGNALS = (signal.SIGTERM, signal.SIGINT)


def install_stop_on_signals(signals: tuple[signal.Signals, ...] = SIGNALS) -> None:
    """Make `signals` stop every arm of this process first (call from the main thread)."""
    for sig in signals:
        previous = signal.getsignal(sig)

        def handler(signum: int, frame: FrameType | None,
                    previous: object = previous) -> None:
            stop_every_arm(f"the server received {signal.Signals(signum).name}")
            if callable(previous):
                previous(signum, frame)
            elif previous != signal.SIG_IGN:
                signal.signal(signum, signal.SIG_DFL)
                os.kill(os.getpid(), signum)

        signal.signal(sig, handler)
