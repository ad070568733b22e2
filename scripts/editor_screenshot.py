"""Takes docs/images/editor.png: `rse-gen edit` on schemes/six_obstacles.csv
in headless Chromium. Run: .venv/bin/python scripts/editor_screenshot.py"""

import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "python"))

from editor_harness import chromium_page, edit, running_editor  # noqa: E402


def main() -> None:
    scheme = REPO / "schemes/six_obstacles.csv"
    with running_editor(REPO / "target/release/rse-gen", scheme, REPO) as url, chromium_page(1500, 1050) as page:
        page.goto(url)
        page.wait_for_function("window.rseEditor.previews >= 1")
        page.click('#table tbody tr[data-row="2"]')
        # Draw a few more times: the first previews' times include the page's
        # start (WebGL shaders, the script's compilation), not what an edit costs.
        for index in ["1", "2", "0"]:
            edit(page, lambda index=index: page.fill("#index", index))
        page.screenshot(path=str(REPO / "docs/images/editor.png"), full_page=True)


if __name__ == "__main__":
    main()
