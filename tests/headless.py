"""Headless Chromium for the tests that look at pages in a real browser (the report, the docs).

Networking is off in every run: all http(s) requests go to a proxy on the discard port
(127.0.0.1:9), which refuses them, so a page that needs the internet shows it.
"""

import shutil
import subprocess
from collections.abc import Callable
from pathlib import Path

BROWSERS = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
WINDOW = (1280, 900)
"""Width and height of the browser window, in CSS pixels."""


def find_chromium() -> str | None:
    """The path of the first Chromium on PATH (None: none is installed)."""
    return next((path for name in BROWSERS if (path := shutil.which(name))), None)


def chromium(found: str, profile: Path) -> Callable[..., str]:
    """A function running the Chromium at ``found`` headless with the given arguments (and
    ``profile`` as its user data folder); it returns the browser's stdout."""

    def run(*arguments: str) -> str:
        flags = [
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-dev-shm-usage",
            "--hide-scrollbars",
            "--proxy-server=127.0.0.1:9",  # no network: every http(s) request is refused
            f"--user-data-dir={profile}",
            f"--window-size={WINDOW[0]},{WINDOW[1]}",
        ]
        completed = subprocess.run(
            [found, *flags, *arguments],
            capture_output=True,
            text=True,
            timeout=180,
            check=False,
        )
        assert completed.returncode == 0, completed.stderr[-2000:]
        return completed.stdout

    return run
