"""Headless Chromium for the report tests: render a page offline, screenshot, DOM, netlog.

Every host resolves to nothing (``--host-resolver-rules="MAP * ~NOTFOUND"``), the browser's
own background traffic is switched off as far as flags allow, and the network log
(``--log-net-log``) tells which requests the *page* started: URL requests whose network
isolation key is the page's ``file://`` origin. The browser's own requests (update checks,
accounts) carry other keys and are not the page's.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

BROWSERS = ("chromium", "chromium-browser", "google-chrome", "chrome")


def find_browser() -> str | None:
    """The path of a Chromium-like browser, or None."""
    for name in BROWSERS:
        path = shutil.which(name)
        if path:
            return path
    return None


def _run(browser, page: Path, tmp: Path, action: list[str], tag: str) -> tuple[str, Path]:
    profile = tmp / f"profile-{tag}"
    netlog = tmp / f"netlog-{tag}.json"
    cmd = [
        browser,
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--disable-default-apps",
        "--disable-extensions",
        "--no-first-run",
        "--hide-scrollbars",
        f"--user-data-dir={profile}",
        "--host-resolver-rules=MAP * ~NOTFOUND",
        f"--log-net-log={netlog}",
        *action,
        page.resolve().as_uri(),
    ]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=120, check=False)
    assert r.returncode == 0, f"{browser} failed ({r.returncode}): {r.stderr[-2000:]}"
    return r.stdout, netlog


def page_requests(netlog: Path) -> list[str]:
    """The URLs the page itself requested (not file: or data:), from a Chromium netlog."""
    text = netlog.read_text()
    try:
        log = json.loads(text)
    except json.JSONDecodeError:  # a log cut short at exit: close its event list
        log = json.loads(text.rstrip().rstrip(",") + "]}")
    types = {v: k for k, v in log["constants"]["logEventTypes"].items()}
    urls = []
    for event in log.get("events", []):
        p = event.get("params") or {}
        if types.get(event.get("type")) != "URL_REQUEST_START_JOB" or "url" not in p:
            continue
        if "file://" not in str(p.get("network_isolation_key", "")):
            continue  # the browser's own traffic, not the page's
        if not p["url"].startswith(("file:", "data:")):
            urls.append(p["url"])
    return urls


def render(page: Path, tmp: Path, *, width=1100, height=2400) -> dict:
    """Render ``page`` offline: ``{"dom": str, "screenshot": Path, "requests": [urls]}``."""
    browser = find_browser()
    assert browser, "no browser"
    tmp.mkdir(parents=True, exist_ok=True)
    shot = tmp / f"{page.stem}.png"
    _, log1 = _run(browser, page, tmp, [f"--window-size={width},{height}",
                                        f"--screenshot={shot}"], "shot")  # fmt: skip
    dom, log2 = _run(browser, page, tmp, ["--dump-dom"], "dom")
    return {"dom": dom, "screenshot": shot, "requests": page_requests(log1) + page_requests(log2)}


def pixel_spread(png: Path) -> float:
    """The standard deviation of the screenshot's grey levels in 0-255 (0: one flat colour)."""
    import numpy as np
    from matplotlib.image import imread

    img = np.asarray(imread(png), dtype=float) * 255  # PNG: floats in [0, 1]
    grey = img[..., :3].mean(axis=-1) if img.ndim == 3 else img
    return float(grey.std())


_REF = re.compile(r"""(?:\b(?:src|href|srcset|action|poster|data)\s*=\s*["']?([^"'\s>]+))"""
                  r"""|(?:url\(\s*["']?([^"')]+))|(?:@import\s+["']([^"']+))""", re.I)  # fmt: skip


def external_references(html: str) -> list[str]:
    """Every src/href/url()/@import target in ``html`` that is not ``data:`` or ``#...``."""
    found = []
    for m in _REF.finditer(html):
        target = next(g for g in m.groups() if g is not None)
        if not target.startswith(("data:", "#")):
            found.append(target)
    return found
