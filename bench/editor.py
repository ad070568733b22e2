"""The editor's preview round trip: from an edit in the page to the new
top-down map drawn, on the page's own timer, in Debian's headless Chromium
against the release `rse-gen edit`, at 50x50 and 200x200 (the aims:
a median of at most 20 ms and 40 ms). Prints the median and the worst of
EDITS edits two ways, the reply's size, and the 3D view's build time,
beside the figures of the editor before the page drew from heights (a PNG
and a box list per preview, measured on this machine the same way).

- "typed in the page": the edit is made by the page's own script (an input
  event on the index field), as a person's key press is: nothing else runs.
- "through Playwright": the test driver fills the field over its protocol,
  which itself keeps the browser busy; the figure the tests print.

Run: .venv/bin/python bench/editor.py   (make bench runs it; needs
target/release/rse-gen and chromium, which `make test` installs)
"""

import json
import statistics
import sys
import tempfile
import urllib.request
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "python"))

from editor_harness import chromium_page, preview_round_trips, running_editor  # noqa: E402

AIM_MS = {50: 20.0, 200: 40.0}
# Before the page drew from heights (commit 1971ffb), this machine, through Playwright: median, max (ms), reply (bytes).
BEFORE = {50: (27.2, 55.9, 58_392), 200: (208.1, 271.8, 440_252)}
EDITS = 60

TYPED_IN_PAGE = """async (count) => {
  // An index typed (its input event, as a key press makes), then the page's
  // `counter` waited for; the figure it timed.
  const pause = (ms) => new Promise((r) => setTimeout(r, ms));
  const typed = async (index, counter, figure, poll) => {
    const before = window.rseEditor[counter];
    const input = document.getElementById('index');
    input.value = String(index);
    input.dispatchEvent(new Event('input', { bubbles: true }));
    while (window.rseEditor[counter] === before) await pause(poll);
    return window.rseEditor[figure];
  };
  const times = [], views = [];
  for (let i = 0; i < count; i++) {
    times.push(await typed(1000 + i, 'previews', 'lastRoundTripMs', 1));
    await pause(40);
  }
  // The 3D view, built once edits pause: a few, each waited for.
  for (let i = 0; i < 5; i++) views.push(await typed(2000 + i, 'views', 'lastViewMs', 5));
  return [times, views];
}"""


def reply_bytes(url: str, size: int) -> int:
    body = {"scheme": {"globals": {"size": f"{size}x{size}"}, "obstacles": [{"type": "random", "height": ["1", ""]}]}}
    request = urllib.request.Request(f"{url}api/preview", data=json.dumps(body).encode(), headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(request) as answer:
        return len(answer.read())


def main() -> None:
    with tempfile.TemporaryDirectory() as folder:
        scheme = Path(folder) / "start.csv"
        scheme.write_text("# size: 20x16\ntype,height\nrandom,1\n")
        with running_editor(REPO / "target/release/rse-gen", scheme, Path(folder)) as url, chromium_page() as page:
            print(f"editor preview round trip, {EDITS} edits each, ms (before: the PNG-per-preview page, same machine)")
            print(f"{'grid':>8} {'how':>20} {'median':>7} {'max':>7}   {'before':>13} {'faster':>7}   aim           reply (before)")
            for size in (50, 200):
                preview_round_trips(page, url, 10, size)  # warm up: JIT, shaders, connection
                driven = sorted(preview_round_trips(page, url, EDITS, size))
                typed, views = page.evaluate(TYPED_IN_PAGE, EDITS)
                typed.sort()
                before_median, before_max, before_reply = BEFORE[size]
                reply = reply_bytes(url, size)
                aim = AIM_MS[size]
                for how, times in [("typed in the page", typed), ("through Playwright", driven)]:
                    median = statistics.median(times)
                    verdict = "met" if median <= aim else "NOT met"
                    print(
                        f"{size}x{size:<4} {how:>20} {median:7.1f} {times[-1]:7.1f}   {before_median:6.1f} {before_max:6.1f}"
                        f" {before_median / median:6.1f}x   ≤{aim:.0f} {verdict:7}  {reply / 1e3:6.1f} kB ({before_reply / 1e3:.1f} kB)"
                    )
                print(f"{'':>8} {'3D view built':>20} {statistics.median(views):7.1f} {max(views):7.1f}   (once edits pause 150 ms; before, part of every preview)")


if __name__ == "__main__":
    main()
