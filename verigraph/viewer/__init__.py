"""The episode viewer: per-step renders and graphs of a plan or an episode, shown by one
self-contained HTML page that works as an MCP App (inside chat clients), as the page of
`verigraph view`, and as the `verigraph validate --html` report file.

Everything it shows comes from the same tool functions the MCP server and the CLI call
(`validate_plan`, `render_scene`, the episode store); this package only lays the
results out per step and draws them.
"""

from verigraph.viewer.page import APP_HTML_PATH, app_html, report_html
from verigraph.viewer.views import (
    VIEW_SPEC,
    EpisodeView,
    StepView,
    ViewInput,
    episode_view,
    plan_view,
    view,
)

__all__ = ["APP_HTML_PATH", "VIEW_SPEC", "EpisodeView", "StepView", "ViewInput", "app_html",
           "episode_view", "plan_view", "report_html", "view"]
