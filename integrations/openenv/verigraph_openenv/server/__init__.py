"""The VeriGraph OpenEnv server: an OpenEnv 0.10 app whose sessions forward to VeriGraph."""
