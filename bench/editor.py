"""The editor's preview round trip: from an edit in
the page to the new top-down picture and 3D view, for a 50x50 scheme, in
Debian's headless Chromium against the release `rse-gen edit`. Aim: under
50 ms. Prints the median, the 90th percentile and the worst of 100 edits,
and the median's ratio to the aim.

Run: .venv/bin/python bench/editor.py   (make bench runs it; needs
target/release/rse-gen and chromium, which `make test` installs)
"""

import statistics
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "python"))

from editor_harness import chromium_page, preview_round_trips, running_editor  # noqa: E402

AIM_MS = 50.0
EDITS = 100


def main() -> None:
    with tempfile.TemporaryDirectory() as folder:
        scheme = Path(folder) / "start.csv"
        scheme.write_text("# size: 20x16\ntype,height\nrandom,1\n")
        with running_editor(REPO / "target/release/rse-gen", scheme, Path(folder)) as url, chromium_page() as page:
            preview_round_trips(page, url, 10)  # warm up: JIT, shader compile, connection
            times = sorted(preview_round_trips(page, url, EDITS))
    median = statistics.median(times)
    p90 = times[int(0.9 * (len(times) - 1))]
    print(f"editor preview round trip, 50x50, {EDITS} edits (ms):")
    print(f"  median {median:6.1f}   p90 {p90:6.1f}   max {times[-1]:6.1f}")
    print(f"  aim < {AIM_MS:.0f} ms: median is {median / AIM_MS:.2f}x the aim ({'met' if median < AIM_MS else 'NOT met'})")


if __name__ == "__main__":
    main()
