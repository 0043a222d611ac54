"""Detection: pixels to colour classes, regions and objects (side view and top view),
and what an occluder hides.
"""
