"""Test helpers shipped with the adapter: stand-ins for what cannot run on a dev machine.

Each is named for what it is (`...ForTests`, `...StandIn`): they exist so the real
client code (roslibpy, the driver logic) can be exercised without a robot.
"""
