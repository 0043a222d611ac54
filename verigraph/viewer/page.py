"""The viewer's single HTML file (built from viewer/ by scripts/build_viewer.sh and
shipped as package data) and the three ways it is served: as the MCP App resource, as
the `verigraph view` page, and as a self-contained report with the view embedded.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

from verigraph.viewer.views import EpisodeView

APP_HTML_PATH = Path(__file__).parent / "static" / "episode.html"
# The report and the page run without a host, so they carry their own policy: inline
# script and style, data: images, nothing fetched (the page may call its own origin).
REPORT_CSP = ("default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
              "img-src data:; connect-src 'none'; base-uri 'none'; form-action 'none'")
PAGE_CSP = REPORT_CSP.replace("connect-src 'none'", "connect-src 'self'")


@cache
def app_html() -> str:
    """The viewer HTML as built (the MCP App resource serves it unchanged)."""
    return APP_HTML_PATH.read_text(encoding="utf-8")


def _with_head(html: str, extra: str) -> str:
    return html.replace("<!--HEAD-->", extra, 1)


def page_html() -> str:
    """The `verigraph view` page: the viewer in form mode."""
    return _with_head(app_html(), '<meta name="verigraph-mode" content="page">')


def report_html(view: EpisodeView) -> str:
    """One self-contained file: the viewer with `view` embedded (renders as data URLs)."""
    data = view.model_dump_json(exclude_none=True)
    # JSON inside a script element: escape what could end the element or open a comment.
    data = data.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")
    head = f'<meta http-equiv="Content-Security-Policy" content="{REPORT_CSP}">'
    script = f'<script id="verigraph-data" type="application/json">{data}</script>'
    return _with_head(app_html(), head).replace("<!--DATA-->", script, 1)
