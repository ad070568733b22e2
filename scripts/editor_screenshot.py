"""Takes docs/images/editor.png (a 1440 px laptop window: the preview beside
the table), docs/images/editor-1280.png (a 1280×800 laptop),
docs/images/editor-wide.png (1920 px: globals, table and preview in three
columns) and docs/images/editor-narrow.png (800 px: the preview below the
table): `rse-gen edit` on schemes/six_obstacles.csv in
headless Chromium, the peak selected and the pointer on the map. Run:
.venv/bin/python scripts/editor_screenshot.py"""

import os
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "python"))

from editor_harness import cell_point, chromium_page, edit, running_editor  # noqa: E402


def main() -> None:
    # A state folder of its own: no draft of an earlier session shows.
    os.environ["RSE_STATE_DIR"] = tempfile.mkdtemp(prefix="rse-screenshot-state-")
    scheme = REPO / "schemes/six_obstacles.csv"
    with running_editor(REPO / "target/release/rse-gen", scheme, REPO) as url:
        for width, height, name in [
            (1440, 900, "editor.png"),
            (1280, 800, "editor-1280.png"),
            (1920, 1080, "editor-wide.png"),
            (800, 1000, "editor-narrow.png"),
        ]:
            with chromium_page(width, height) as page:
                page.goto(url)
                page.wait_for_function("window.rseEditor.previews >= 1")
                page.get_by_label("height of obstacle 3", exact=True).click()
                # Draw a few more times: the first previews' times include the page's
                # start (the script's compilation), not what an edit costs.
                for index in ["1", "2", "0"]:
                    views = page.evaluate("window.rseEditor.views")  # before the edit: its view may come at once
                    edit(page, lambda index=index: page.get_by_label("index").fill(index))
                    page.wait_for_function(f"window.rseEditor.views > {views}")  # the 3D view of this draw
                page.mouse.move(*cell_point(page, 20, 31))
                page.screenshot(path=str(REPO / "docs/images" / name), full_page=True)


if __name__ == "__main__":
    main()
