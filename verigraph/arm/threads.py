"""Driver calls that must not hold up their caller: motions and status polls.

A motion runs in its own daemon thread so the controller can time it out and stop it;
a status poll runs in one too, so `arm_status` and the stop path never wait on a driver
whose `status()` hangs (a stalled controller socket, a wedged SDK call).
"""

from __future__ import annotations

import threading
from collections.abc import Callable

from verigraph.arm.models import DriverStatus
from verigraph.arm.protocols import ArmDriver

STATUS_WAIT_S = 0.5  # how long a caller waits for a driver's status


def start(name: str, call: Callable[[], None]) -> tuple[threading.Thread, list[BaseException]]:
    """Run `call` in a daemon thread; the list receives what it raised, if anything."""
    errors: list[BaseException] = []

    def body() -> None:
        try:
            call()
        except BaseException as exc:
            errors.append(exc)

    worker = threading.Thread(target=body, name=name, daemon=True)
    worker.start()
    return worker, errors


class StatusPoll:
    """`driver.status()` bounded by a wait; at most one poll in flight per driver."""

    def __init__(self, driver: ArmDriver) -> None:
        self._driver = driver
        self._lock = threading.Lock()
        self._worker: threading.Thread | None = None

    def __call__(self, wait_s: float = STATUS_WAIT_S) -> DriverStatus:
        """The driver's status; TimeoutError if it does not answer within `wait_s`."""
        box: list[DriverStatus] = []
        with self._lock:
            if self._worker is not None and self._worker.is_alive():
                raise TimeoutError("an earlier status request has not returned")
            worker, errors = start("arm-status", lambda: box.append(self._driver.status()))
            self._worker = worker
        worker.join(wait_s)
        if worker.is_alive():
            raise TimeoutError(f"no answer within {wait_s:g} s")
        if errors:
            raise errors[0]
        return box[0]
