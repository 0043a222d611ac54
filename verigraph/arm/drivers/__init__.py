"""Drivers behind the ArmDriver protocol: pybullet (simulated Panda), rosbridge, xarm.

Each is imported lazily by `verigraph.arm.factory`, so the adapter works without the
optional packages of the drivers that are not used; `verigraph.extras` names the
install command when a driver's package is missing.
"""
