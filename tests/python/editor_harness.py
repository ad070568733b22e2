"""Driving `rse-gen edit` in Debian's headless Chromium: one place for the
browser tests, the editor benchmark (bench/editor.py) and the README
screenshot (scripts/editor_screenshot.py)."""

import shutil
import subprocess
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from playwright.sync_api import Page, sync_playwright

CHROMIUM_FLAGS = [
    "--no-sandbox",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-quic",
    # WebGL without a GPU: SwiftShader renders the 3D view on the CPU.
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
]


@contextmanager
def running_editor(binary: Path, scheme: Path, cwd: Path) -> Iterator[str]:
    """`rse-gen edit SCHEME` running in `cwd`; yields the URL it prints."""
    process = subprocess.Popen(
        [str(binary), "edit", str(scheme)],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        cwd=cwd,
    )
    try:
        url = process.stdout.readline().strip()
        assert url.startswith("http://127.0.0.1:"), f"rse-gen edit printed {url!r}"
        yield url
    finally:
        process.terminate()
        process.wait(timeout=10)
        process.stdout.close()


@contextmanager
def chromium_page(width: int = 1500, height: int = 1000) -> Iterator[Page]:
    """A page in Debian's Chromium (`chromium` on PATH), headless."""
    chromium = shutil.which("chromium")
    assert chromium, "Debian chromium is installed by the test command (scripts/test.sh)"
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium, args=CHROMIUM_FLAGS)
        try:
            yield browser.new_page(viewport={"width": width, "height": height})
        finally:
            browser.close()


def edit(page: Page, action) -> None:
    """Does `action` and waits for the preview answer it causes (a picture
    or a refusal)."""
    before = page.evaluate("window.rseEditor.answers")
    action()
    page.wait_for_function(f"window.rseEditor?.answers > {before}")


def preview_round_trips(page: Page, url: str, count: int, size: int = 50) -> list[float]:
    """Milliseconds from an edit to its new picture and 3D view, as the page
    times them, for `count` new draws of a `size`×`size` scheme."""
    page.goto(url)
    page.wait_for_function("window.rseEditor?.previews >= 1")
    page.fill('[data-global="size"]', f"{size}x{size}")
    page.wait_for_function(f"document.getElementById('timing').textContent.startsWith('{size}×{size}')")
    times = []
    for i in range(1, count + 1):
        drawn = page.evaluate("window.rseEditor.previews")
        edit(page, lambda i=i: page.fill("#index", str(i)))
        assert page.evaluate("window.rseEditor.previews") == drawn + 1, "each edit drew a new preview"
        times.append(page.evaluate("window.rseEditor.lastRoundTripMs"))
    return times
