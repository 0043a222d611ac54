"""Every exit status of the `verigraph` commands, in one table.

  status    name                  meaning (commands)
  0         EXIT_OK               done: valid, goal reached, a plan found (every command)
  1         EXIT_NEGATIVE         a negative answer: invalid plan, goal missed, unreachable,
                                  audit chain broken (validate, solve, demo, agent, arm)
  2         EXIT_BAD_INPUT        a file, argument or id that cannot be used: a VeriGraphError
                                  without an `exit_code` of its own (every command)
  3         EXIT_BUDGET           the search budget ran out; JSON `reason` (solve)
  3         EXIT_PLANNER_FAILED   the planner failed (agent)
  3, 4, 5   (VeriGraphError       no server at the URL, a token needed, a token refused: the
            .exit_code)           `exit_code` of ServerUnreachableError, MissingTokenError,
                                  TokenRejectedError (verigraph.errors, below this package)
  130       EXIT_INTERRUPTED      interrupted by Ctrl-C (every command)
  1..254    MAX_FAILED_STATUS     VAL's: the number of failed plans, capped (val)
  255       EXIT_FATAL            VAL's exit(-1): the domain, problem or arguments cannot be
                                  used (val, verigraph-val)

README.md's command table states them per command; the statuses are the process's
interface, so a script may test them: they do not change.
"""

from __future__ import annotations

EXIT_OK = 0
EXIT_NEGATIVE = 1
EXIT_BAD_INPUT = 2
EXIT_BUDGET = 3
EXIT_PLANNER_FAILED = 3
EXIT_INTERRUPTED = 130
MAX_FAILED_STATUS = 254  # a count of failed plans never wraps to 0 nor reads as 255
EXIT_FATAL = 255
