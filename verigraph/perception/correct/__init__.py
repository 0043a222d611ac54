"""Correction before detection: colour constancy, lighting, noise and blur, camera roll.

Everything here turns the camera's picture back towards what the renderer drew,
so that the detectors can read palette colours and level floors.
"""
