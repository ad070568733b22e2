"""Takes docs/images/editor.png: `rse-gen edit` on schemes/six_obstacles.csv
in headless Chromium. Run: .venv/bin/python scripts/editor_screenshot.py"""

import shutil
import subprocess
from pathlib import Path

from playwright.sync_api import sync_playwright

REPO = Path(__file__).resolve().parents[1]


def main() -> None:
    editor = subprocess.Popen(
        [str(REPO / "target/release/rse-gen"), "edit", "schemes/six_obstacles.csv"],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        cwd=REPO,
    )
    try:
        url = editor.stdout.readline().strip()
        with sync_playwright() as p:
            browser = p.chromium.launch(
                executable_path=shutil.which("chromium"),
                args=["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
            )
            page = browser.new_page(viewport={"width": 1500, "height": 1050})
            page.goto(url)
            page.wait_for_function("window.rseEditor.previews >= 1")
            page.click('#table tbody tr[data-row="2"]')
            page.screenshot(path=str(REPO / "docs/images/editor.png"), full_page=True)
            browser.close()
    finally:
        editor.terminate()
        editor.wait()
        editor.stdout.close()


if __name__ == "__main__":
    main()
