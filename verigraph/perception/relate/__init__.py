"""Relations and the graph: supports (`on`, `in`) by the simulator's readback rules,
ids, and a confidence per node and edge.
"""
