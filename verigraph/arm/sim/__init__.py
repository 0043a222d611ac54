"""PyBullet simulation of a Franka Panda cell: physics scene, kinematics and camera."""
