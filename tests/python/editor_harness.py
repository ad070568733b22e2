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
def running_editor(binary: Path, scheme: Path, cwd: Path, port: int | None = None, extra: tuple[str, ...] = ()) -> Iterator[str]:
    """`rse-gen edit SCHEME` running in `cwd` (on `port`, else where it
    chooses; `extra`: more of its options); yields the URL it prints."""
    process = subprocess.Popen(
        [str(binary), "edit", str(scheme), *(["--port", str(port)] if port else []), *extra],
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
            # In a context of its own: `page.context.new_page()` opens a
            # second tab of the same browser profile.
            yield browser.new_context(viewport={"width": width, "height": height}).new_page()
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
    # Nothing on its way (a draft restored on load asks for its own
    # preview): each edit below is then answered by its own.
    page.wait_for_function("window.rseEditor.inFlight === 0")
    times = []
    for i in range(1, count + 1):
        drawn = page.evaluate("window.rseEditor.previews")
        edit(page, lambda i=i: page.fill("#index", str(i)))
        assert page.evaluate("window.rseEditor.previews") == drawn + 1, "each edit drew a new preview"
        times.append(page.evaluate("window.rseEditor.lastRoundTripMs"))
    return times


# --- finding things on the page, as the browser tests do -----------------------


def wait_ready(page: Page, url: str) -> None:
    """Opens the editor and waits for its first map."""
    page.goto(url)
    page.wait_for_function("window.rseEditor?.previews >= 1")


def cell(page: Page, row: int, field: str, part: str = "lo"):
    """The table field `field` (its low or high end) of obstacle `row` (0-based)."""
    return page.locator(f'#table tbody tr[data-row="{row}"] [data-field="{field}"][data-part="{part}"]')


def table(page: Page) -> list[dict]:
    """The table's rows: type and every filled field (`height.lo`, `height.hi`, …)."""
    rows = page.evaluate("window.rseEditor.state.rows.map(r => ({...r}))")
    return [{k: v for k, v in row.items() if v != ""} for row in rows]


def gen_summary_says(page: Page, text: str) -> None:
    """Waits until Generate's summary line holds `text`."""
    page.wait_for_function("text => document.getElementById('gen-summary').textContent.includes(text)", arg=text)


def generate(page: Page, until: str) -> None:
    """Clicks Generate and waits until its summary line holds `until`
    ("not started", "worlds written", …)."""
    page.get_by_role("button", name="Generate").click()
    gen_summary_says(page, until)


def generate_refused(page: Page, field: str, words: str) -> None:
    """Clicks Generate and checks it was refused before starting, on the
    control labelled `field` (marked invalid), with `words` in the summary."""
    generate(page, "not started")
    assert page.locator("#gen-summary").inner_text().startswith("not started")
    assert page.get_by_label(field).get_attribute("aria-invalid") == "true"
    assert words in page.locator("#gen-summary").inner_text()


def save_target(page: Page) -> str:
    """The file the header names as the one Save writes, whole (the header
    shows a file in the working folder by its path from there)."""
    return page.locator("#file-name").get_attribute("title") or ""


def status_says(page: Page, start: str) -> None:
    """Waits until the header's status line starts with `start`."""
    page.wait_for_function(f"document.getElementById('status').textContent.startsWith({start!r})")


def save(page: Page) -> None:
    """Save, and waits for this save's "saved" (the status is cleared first:
    an earlier "saved" must not answer for this one)."""
    page.evaluate("document.getElementById('status').textContent = ''")
    page.get_by_role("button", name="Save", exact=True).click()
    status_says(page, "saved")


def save_as(page: Page, path: Path | str) -> None:
    """Save as → the path typed into the dialog → OK, and waits for "saved"."""
    page.evaluate("document.getElementById('status').textContent = ''")
    page.get_by_role("button", name="Save as").click()
    page.get_by_label("file path").fill(str(path))
    page.get_by_role("button", name="OK").click()
    status_says(page, "saved")


def cell_point(page: Page, x: int, y: int) -> tuple[float, float]:
    """The page coordinates of the centre of grid cell (x, y) on the map
    (north up: row 0 at the bottom)."""
    box = page.locator("#map-overlay").bounding_box()
    nx, ny = page.evaluate("[window.rseEditor.preview.nx, window.rseEditor.preview.ny]")
    return box["x"] + (x + 0.5) * box["width"] / nx, box["y"] + (ny - 1 - y + 0.5) * box["height"] / ny


def drag_on_map(page: Page, start: tuple[int, int], end: tuple[int, int]) -> None:
    """Presses the mouse on cell `start`, moves to cell `end` in steps, lets go."""
    page.mouse.move(*cell_point(page, *start))
    page.mouse.down()
    page.mouse.move(*cell_point(page, *end), steps=8)
    page.mouse.up()
