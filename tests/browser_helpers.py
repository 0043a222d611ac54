"""Headless Chromium (Debian's binary, driven by Playwright) for the viewer tests, with
every request the page makes recorded and anything off loopback blocked."""

from __future__ import annotations

import os
import shutil
from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import urlsplit

import pytest

CHROMIUM = os.environ.get("VERIGRAPH_CHROMIUM", "/usr/bin/chromium")
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu",
                 "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--no-first-run"]
LOOPBACK = {"127.0.0.1", "localhost", "::1", "[::1]"}
SCREENSHOTS = Path(os.environ.get("VERIGRAPH_SCREENSHOTS", "out/screenshots"))


def require_browser() -> None:
    """The browser tests need Debian's chromium and Playwright (scripts/test.sh installs
    both); say so instead of failing obscurely."""
    pytest.importorskip("playwright.async_api", reason="pip install playwright")
    if shutil.which(CHROMIUM) is None and not Path(CHROMIUM).exists():
        pytest.skip(f"{CHROMIUM} missing: apt-get install -y chromium")


@dataclass
class RequestLog:
    """Every URL the page asked for, and those refused for leaving loopback."""

    urls: list[str] = field(default_factory=list)
    blocked: list[str] = field(default_factory=list)

    def off_loopback(self) -> list[str]:
        out = []
        for url in self.urls:
            parts = urlsplit(url)
            if parts.scheme in ("data", "about", "file", "blob"):
                continue
            if parts.hostname not in LOOPBACK:
                out.append(url)
        return out


@asynccontextmanager
async def browser_page() -> AsyncIterator[tuple[object, RequestLog]]:
    from playwright.async_api import Route, async_playwright

    log = RequestLog()
    async with async_playwright() as pw:
        browser = await pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        context = await browser.new_context(viewport={"width": 1100, "height": 980})

        async def guard(route: Route) -> None:
            url = route.request.url
            log.urls.append(url)
            host = urlsplit(url).hostname
            if urlsplit(url).scheme in ("http", "https", "ws", "wss") and host not in LOOPBACK:
                log.blocked.append(url)
                await route.abort()
                return
            await route.continue_()

        await context.route("**/*", guard)
        page = await context.new_page()
        page.on("request", lambda request: log.urls.append(request.url)
                if request.url not in log.urls else None)
        try:
            yield page, log
        finally:
            await browser.close()


def screenshot_path(name: str) -> Path:
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    return SCREENSHOTS / name
