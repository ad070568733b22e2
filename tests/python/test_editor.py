"""`rse-gen edit` in a real headless Chromium (Debian's, driven by
Playwright): build a scheme by clicking, watch the preview change, save,
reload, generate, and the editor's defences."""

import io
import json
import os
import statistics
import subprocess
import time
import urllib.error
import urllib.request
from pathlib import Path

import numpy as np
import pytest
import rse
from conftest import rse_gen_release_path
from editor_harness import cell, edit, preview_round_trips, running_editor, save, save_as, save_target, table
from PIL import Image
from playwright.sync_api import Page

# Needs what only `make test` installs (Debian packages, a browser, or
# the wheels' build): not in `make test-quick`.
pytestmark = pytest.mark.thirdparty


def previews(page: Page) -> int:
    return page.evaluate("window.rseEditor.previews")


def image_pixels(png_bytes: bytes) -> np.ndarray:
    """A PNG screenshot as (height, width, 4) uint8."""
    return np.asarray(Image.open(io.BytesIO(png_bytes)).convert("RGBA"))


def test_build_a_scheme_by_clicking_save_reload_and_generate(editor, page: Page) -> None:
    url, folder = editor
    page.goto(url)
    page.wait_for_function("window.rseEditor?.previews >= 1")
    first = page.locator("#map").screenshot()

    # Replace the random field by a wall and a peak, then put the peak first.
    edit(page, lambda: page.click("#delete"))
    edit(page, lambda: page.click("#add"))
    edit(page, lambda: page.select_option('#table tbody tr[data-row="0"] select', "wall"))
    for field, value in [("height", "3"), ("angle", "45"), ("x1", "2"), ("y1", "3"), ("x2", "17"), ("y2", "3")]:
        edit(page, lambda f=field, v=value: cell(page, 0, f).fill(v))
    edit(page, lambda: page.click("#add"))
    edit(page, lambda: page.select_option('#table tbody tr[data-row="1"] select', "peak"))
    for field, value in [("height", "2"), ("angle", "30"), ("x1", "10"), ("y1", "10")]:
        edit(page, lambda f=field, v=value: cell(page, 1, f).fill(v))
    page.click('#table tbody tr[data-row="1"]')
    edit(page, lambda: page.click("#up"))
    assert [r["type"] for r in table(page)] == ["peak", "wall"]
    # A random range: the peak's height from 2 to 4.
    edit(page, lambda: cell(page, 0, "height", "hi").fill("4"))
    assert page.locator("#error").inner_text() == ""
    after = page.locator("#map").screenshot()
    assert not np.array_equal(image_pixels(first), image_pixels(after)), "the preview's pixels changed"

    # Save, then load the file back into a fresh page: the same table.
    saved = folder / "saved.csv"
    save_as(page, saved)
    scheme = rse.Scheme.load(saved)
    assert [o.type for o in scheme.obstacles] == ["peak", "wall"]
    assert scheme.obstacles[0].height == (2, 4)
    rows = table(page)
    page.reload()
    page.wait_for_function("window.rseEditor?.previews >= 1")
    before = previews(page)
    page.set_input_files("#load", str(saved))
    page.wait_for_function(f"window.rseEditor.previews > {before}")
    assert table(page) == rows

    # Generate three worlds and see the check summary.
    page.fill("#gen-amount", "3")
    page.fill("#gen-out", str(folder / "worlds"))
    page.check('#gen-targets input[value="mujoco"]')
    page.get_by_label("gazebo-classic", exact=True).check()
    page.click("#generate")
    page.wait_for_function("document.getElementById('gen-check').textContent !== ''", timeout=60_000)
    assert "3 worlds written" in page.locator("#gen-summary").inner_text()
    assert page.locator("#gen-check").inner_text().startswith("checked 3 worlds: 3 good, 0 failed")
    assert (folder / "worlds/world_0002/mujoco/rse.xml").is_file()
    assert (folder / "worlds/world_0002/gazebo-classic/rse_terrain/model.sdf").is_file()


def test_the_3d_view_draws_blocks(editor, page: Page) -> None:
    url, _ = editor
    page.goto(url)
    page.wait_for_function("window.rseEditor?.views >= 1")
    pixels = image_pixels(page.locator("#blocks").screenshot())
    background = np.array([221, 221, 235])  # the clear colour, 0.87 0.87 0.92
    drawn = np.abs(pixels[:, :, :3].astype(int) - background).sum(axis=2) > 30
    assert drawn.mean() > 0.05, f"only {drawn.mean():.1%} of the 3D view is drawn"
    colours = {tuple(c) for c in pixels[drawn][:, :3][::17]}
    assert len(colours) > 5, "shaded faces in several colours"


def test_invalid_values_are_marked_at_the_field(editor, page: Page) -> None:
    url, _ = editor
    page.goto(url)
    page.wait_for_function("window.rseEditor?.previews >= 1")
    page.select_option('#table tbody tr[data-row="0"] select', "peak")
    cell(page, 0, "height").fill("2")
    cell(page, 0, "angle").fill("45")
    cell(page, 0, "y1").fill("3")
    cell(page, 0, "x1").fill("99")
    page.wait_for_function("document.getElementById('error').textContent.includes('outside the grid')")
    assert "invalid" in (cell(page, 0, "x1").get_attribute("class") or "")
    assert page.locator("#error").inner_text().startswith("obstacle 1, x1: ")
    page.fill('[data-global="block_size"]', "-1")
    page.wait_for_function("document.getElementById('error').textContent.startsWith('block size')")
    assert "invalid" in (page.locator('[data-global="block_size"]').get_attribute("class") or "")
    assert "Traceback" not in page.content() and "panicked" not in page.content()


def test_the_preview_round_trip_is_measured(editor, page: Page, capsys) -> None:
    """Measures and prints the round trip, from the browser; the figure is judged against its 50 ms aim in bench/editor.py,
    not here: a timed assertion fails on a busy machine, not on slow code."""
    url, _ = editor
    times = preview_round_trips(page, url, 15)
    assert all(t > 0 for t in times), times
    with capsys.disabled():
        print(f"\n  editor preview round trip, 50x50: median {statistics.median(times):.1f} ms, max {max(times):.1f} ms")


@pytest.mark.parametrize(
    "headers",
    [{"Origin": "http://evil.example"}, {"Host": "evil.example"}, {"Origin": "http://127.0.0.1:1"}],
    ids=["foreign origin", "foreign host", "other port"],
)
def test_foreign_origins_and_hosts_get_403(editor, headers) -> None:
    url, _ = editor
    request = urllib.request.Request(url + "api/state", headers=headers)
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(request)
    assert refused.value.code == 403
    refused.value.close()
    with urllib.request.urlopen(url + "api/state") as ok:
        assert ok.status == 200


def test_oversized_requests_get_413(editor) -> None:
    url, _ = editor
    request = urllib.request.Request(url + "api/preview", data=b"x" * (2 << 20), method="POST")
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(request)
    assert refused.value.code == 413
    refused.value.close()


# --- the editor's defences ------------------------------------------------------


def post(url: str, path: str, body: dict) -> dict:
    request = urllib.request.Request(
        url + path, data=json.dumps(body).encode(), method="POST", headers={"Content-Type": "application/json"}
    )
    with urllib.request.urlopen(request, timeout=60) as answer:
        return json.loads(answer.read())


def test_saving_keeps_the_schemes_notes(tmp_path: Path, page: Page) -> None:
    """The notes of the file opened are on the page and in the file saved;
    notes edited on the page are saved too."""
    scheme = tmp_path / "noted.csv"
    scheme.write_text("# A stepfield for the Husky tests\n# (see lab wiki, 2026)\n# size: 12x10\ntype,height\nrandom,2\n")
    with running_editor(rse_gen_release_path(), scheme, tmp_path) as url:
        page.goto(url)
        page.wait_for_function("window.rseEditor?.previews >= 1")
        assert page.input_value("#notes") == "A stepfield for the Husky tests\n(see lab wiki, 2026)"
        saved = tmp_path / "saved.csv"
        save_as(page, saved)
        assert rse.Scheme.load(saved) == rse.Scheme.load(scheme), "notes and all"
        assert saved.read_text().startswith("# A stepfield for the Husky tests\n# (see lab wiki, 2026)\n")
        page.fill("#notes", "Husky, run 2")
        page.evaluate("document.querySelector('#status').textContent = ''")
        page.click("#save")
        page.wait_for_function("document.querySelector('#status').textContent.includes('saved')")
        assert saved.read_text().startswith("# Husky, run 2\n# size: 12x10\n"), saved.read_text()
        # A note that would read back as a global parameter is refused, by field.
        answer = post(url, "api/save", {"scheme": {"globals": {}, "obstacles": [], "notes": "Author: me"}, "path": str(saved)})
        assert not answer["ok"] and answer["error"]["field"] == "notes", answer


def test_a_huge_preview_is_refused_quickly(editor) -> None:
    url, _ = editor
    scheme = {"globals": {"size": "5000x5000"}, "obstacles": [{"type": "random", "height": "2"}]}
    started = time.monotonic()
    answer = post(url, "api/preview", {"scheme": scheme})
    assert time.monotonic() - started < 2.0
    assert not answer["ok"] and answer["error"]["field"] == "size"
    assert "more than the editor draws" in answer["error"]["message"] and "Generate writes worlds of any size" in answer["error"]["message"]
    scheme["globals"]["size"] = "500x500"
    assert post(url, "api/preview", {"scheme": scheme})["ok"], "the largest previewed grid"


def test_trickling_and_idle_clients_neither_hold_the_editor_nor_stop_it(editor) -> None:
    """Six clients (more than the editor's four work threads) trickle a
    large body one byte every two seconds, and one connects and sends
    nothing: the page and the API are served meanwhile; each trickler gets a
    408 at the body deadline (10 s after its headers), however steadily it
    sends; the silent one is closed at the head timeout (5 s). Then, idle
    past every timeout, the editor still accepts and serves the page (it
    stopped listening after 5 idle seconds once)."""
    import socket
    import threading
    from urllib.parse import urlparse

    url, _ = editor
    where = urlparse(url)
    head = (
        f"POST /api/preview HTTP/1.1\r\nHost: 127.0.0.1:{where.port}\r\n"
        "Content-Type: application/json\r\nContent-Length: 100000\r\n\r\n{"
    ).encode()
    tricklers = [socket.create_connection((where.hostname, where.port)) for _ in range(6)]
    silent = socket.create_connection((where.hostname, where.port))
    started = time.monotonic()
    for s in tricklers:
        s.sendall(head)
    stop = threading.Event()

    def trickle() -> None:
        while not stop.wait(2.0):
            for s in tricklers:
                try:
                    s.sendall(b" ")
                except OSError:
                    pass

    thread = threading.Thread(target=trickle, daemon=True)
    thread.start()
    try:
        time.sleep(1.0)
        asked = time.monotonic()
        with urllib.request.urlopen(url + "api/state", timeout=4) as answer:
            assert answer.status == 200
        assert post(url, "api/preview", {"scheme": {"globals": {"size": "10x10"}, "obstacles": []}})["ok"]
        assert time.monotonic() - asked < 3.0
        # Gentle peaks reaching the whole of a 500x500 grid: refused by the
        # work cap at once (it took 25 s), so it cannot hold a worker either.
        rows = [{"type": "peak", "height": "60", "angle": "0.5", "x1": str(i % 500), "y1": "250"} for i in range(400)]
        refused = post(url, "api/preview", {"scheme": {"globals": {"size": "500x500"}, "obstacles": rows}})
        assert not refused["ok"] and "more than the editor draws" in refused["error"]["message"], refused

        silent.settimeout(15)
        assert silent.recv(4096) == b"", "closed, without an answer"
        assert 4.0 < time.monotonic() - started < 8.0, "at the head timeout"
        for s in tricklers:
            s.settimeout(15)
            answer = b""
            while chunk := s.recv(4096):
                answer += chunk
            assert answer.startswith(b"HTTP/1.1 408 "), answer
        assert 9.5 < time.monotonic() - started < 14.0, "at the body deadline, not after a silent gap"
    finally:
        stop.set()
        thread.join()
        for s in [*tricklers, silent]:
            s.close()
    # Idle past every timeout (head 5 s, body 10 s), then the page loads.
    time.sleep(max(0.0, 16.0 - (time.monotonic() - started)))
    with urllib.request.urlopen(url, timeout=4) as page:
        assert page.status == 200 and b"<html" in page.read().lower()


def test_clients_that_never_read_their_replies_are_cut_off_at_the_write_deadline(editor) -> None:
    """64 clients (every connection slot) send many previews each and never
    read a reply: they held every slot (503 for everyone else) and 1.2 GB of
    unread replies for as long as they stayed. Now each reply must be taken
    within the write deadline (10 s): the slots come back, the editor's
    memory stays bounded."""
    import socket
    from urllib.parse import urlparse

    url, _ = editor
    where = urlparse(url)
    body = json.dumps(
        {"scheme": {"globals": {"size": "300x300"}, "obstacles": [{"type": "random", "height": ["300", ""]}]}}
    ).encode()
    request = (
        f"POST /api/preview HTTP/1.1\r\nHost: 127.0.0.1:{where.port}\r\n"
        f"Content-Type: application/json\r\nContent-Length: {len(body)}\r\n\r\n"
    ).encode() + body
    hogs = []
    for _ in range(64):
        s = socket.create_connection((where.hostname, where.port))
        s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
        s.sendall(request * 12)  # 12 replies of 240 kB: far more than the socket buffers hold
        hogs.append(s)
    started = time.monotonic()
    try:
        served = None
        while time.monotonic() - started < 30:
            try:
                with urllib.request.urlopen(url + "api/state", timeout=5) as answer:
                    served = answer.status
                    break
            except (urllib.error.URLError, ConnectionError, TimeoutError):
                time.sleep(0.5)
        waited = time.monotonic() - started
        assert served == 200, "the editor answers again"
        assert waited < 20, f"served after {waited:.1f} s: the write deadline is 10 s"
    finally:
        for s in hogs:
            s.close()


def test_request_headers_above_the_cap_get_431(editor) -> None:
    url, _ = editor
    request = urllib.request.Request(url + "api/state", headers={"X-Padding": "a" * (20 << 10)})
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(request, timeout=10)
    assert refused.value.code == 431
    refused.value.close()
    with urllib.request.urlopen(url + "api/state", timeout=4) as ok:
        assert ok.status == 200


def test_open_without_a_browser_says_so_in_one_line(tmp_path: Path) -> None:
    """No xdg-open on PATH: one line on stderr; the editor keeps serving."""
    process = subprocess.Popen(
        [str(rse_gen_release_path()), "edit", "--open"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=tmp_path,
        env={**os.environ, "PATH": str(tmp_path)},
    )
    try:
        url = process.stdout.readline().strip()
        lines = [process.stderr.readline(), process.stderr.readline()]
        assert lines[0].startswith("rse-gen: the editor is at "), lines
        assert lines[1] == f"rse-gen: --open: cannot open a browser (no xdg-open here); open {url} yourself\n", lines
        with urllib.request.urlopen(url + "api/state", timeout=10) as ok:
            assert ok.status == 200
    finally:
        process.terminate()
        process.wait(timeout=10)
        process.stdout.close()
        process.stderr.close()


def test_a_reload_keeps_unsaved_edits_asks_before_leaving_and_save_makes_them_the_files(editor, page: Page) -> None:
    url, folder = editor
    page.goto(url)
    page.wait_for_function("window.rseEditor?.previews >= 1")
    assert save_target(page) == str(folder / "start.csv")
    assert page.locator("#unsaved").is_hidden()
    edit(page, lambda: cell(page, 0, "height").fill("3"))
    assert page.locator("#unsaved").is_visible()
    dialogs: list[str] = []
    page.on("dialog", lambda dialog: (dialogs.append(dialog.type), dialog.accept()))
    page.reload()
    page.wait_for_function("window.rseEditor?.previews >= 1")
    assert dialogs == ["beforeunload"], "leaving with unsaved changes asks first"
    assert cell(page, 0, "height").input_value() == "3", "the edit survived the reload"
    assert page.locator("#unsaved").is_visible()
    assert "restored" in page.locator("#status").inner_text()
    # Save: the file holds it, nothing is unsaved, a reload starts from it.
    save(page)
    assert page.locator("#unsaved").is_hidden()
    assert "random,3" in (folder / "start.csv").read_text()
    page.reload()
    page.wait_for_function("window.rseEditor?.previews >= 1")
    assert dialogs == ["beforeunload"], "nothing unsaved: no question"
    assert cell(page, 0, "height").input_value() == "3" and page.locator("#unsaved").is_hidden()


def test_undo_and_redo_by_buttons_and_keys(editor, page: Page) -> None:
    url, _ = editor
    page.goto(url)
    page.wait_for_function("window.rseEditor?.previews >= 1")
    undo, redo = page.get_by_role("button", name="Undo"), page.get_by_role("button", name="Redo")
    assert undo.is_disabled() and redo.is_disabled()
    edit(page, lambda: cell(page, 0, "height").fill("2"))
    edit(page, lambda: page.click("#add"))
    assert len(table(page)) == 2
    edit(page, lambda: undo.click())
    assert len(table(page)) == 1 and cell(page, 0, "height").input_value() == "2"
    edit(page, lambda: undo.click())
    assert cell(page, 0, "height").input_value() == "1" and undo.is_disabled()
    edit(page, lambda: redo.click())
    assert cell(page, 0, "height").input_value() == "2"
    # Outside a text field the keys do the same.
    page.locator("h1").click()
    edit(page, lambda: page.keyboard.press("Control+Shift+Z"))
    assert len(table(page)) == 2 and redo.is_disabled()
    edit(page, lambda: page.keyboard.press("Control+Z"))
    assert len(table(page)) == 1
    edit(page, lambda: page.keyboard.press("Control+Y"))
    assert len(table(page)) == 2


def test_one_action_is_one_undo_step_whatever_mix_of_buttons_keys_and_map_grabs_made_it(editor, page: Page) -> None:
    url, _ = editor
    page.goto(url)
    page.wait_for_function("window.rseEditor?.previews >= 1")
    undo, redo = page.get_by_role("button", name="Undo"), page.get_by_role("button", name="Redo")
    edit(page, lambda: cell(page, 0, "height").fill("2"))  # typed
    edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())  # a button
    edit(page, lambda: page.get_by_label("type of obstacle 2").select_option("peak"))
    edit(page, lambda: page.get_by_label("angle of obstacle 2", exact=True).fill("90"))
    mapped = page.get_by_role("application", name="top-down map")
    mapped.focus()  # the cursor starts mid-grid, (10, 8), where the new peak stands
    edit(page, lambda: page.keyboard.press("Enter"))  # a keyboard grab places the new peak …
    for _ in range(3):
        edit(page, lambda: page.keyboard.press("ArrowRight"))  # … and moves it, still held
    assert table(page)[1]["x1.lo"] == "13"
    # Ctrl+Z mid-grab takes back the grab, and only it.
    edit(page, lambda: page.keyboard.press("Control+Z"))
    assert table(page)[1] == {"type": "peak", "height.lo": "1", "angle.lo": "90", "x1.lo": "10", "y1.lo": "8"}, table(page)
    edit(page, lambda: page.keyboard.press("Control+Shift+Z"))
    assert (table(page)[1]["x1.lo"], table(page)[1]["y1.lo"]) == ("13", "8"), "Redo brings the grab back"
    # A grab, then a button clicked while it is held: two steps.
    mapped.focus()
    edit(page, lambda: page.keyboard.press("Enter"))  # grabs the peak's own point
    for _ in range(2):
        edit(page, lambda: page.keyboard.press("ArrowUp"))
    edit(page, lambda: page.get_by_role("button", name="Copy obstacle").click())
    assert len(table(page)) == 3 and table(page)[2]["y1.lo"] == "10"
    edit(page, lambda: undo.click())
    assert len(table(page)) == 2 and table(page)[1]["y1.lo"] == "10"
    edit(page, lambda: undo.click())
    assert table(page)[1]["y1.lo"] == "8"
    edit(page, lambda: undo.click())
    assert table(page)[1]["x1.lo"] == "10" and table(page)[1]["angle.lo"] == "90"
    edit(page, lambda: undo.click())
    # The type's step: a new peak starts valid, 45° in the middle.
    assert table(page)[1] == {"type": "peak", "height.lo": "1", "angle.lo": "45", "x1.lo": "10", "y1.lo": "8"}, table(page)
    for _ in range(4):
        edit(page, lambda: redo.click())
    assert len(table(page)) == 3 and redo.is_disabled()


def test_delete_acts_on_the_obstacle_being_edited_and_undo_brings_it_back(editor, page: Page) -> None:
    url, _ = editor
    page.goto(url)
    page.wait_for_function("window.rseEditor?.previews >= 1")
    edit(page, lambda: page.click("#add"))
    edit(page, lambda: page.click("#add"))
    edit(page, lambda: cell(page, 2, "height").fill("4"))
    before = table(page)
    assert len(before) == 3
    page.click('#table tbody tr[data-row="0"] td')  # highlight row 1 by pointer …
    cell(page, 1, "height").focus()  # … then edit row 2 by keyboard
    page.keyboard.type("2")
    edit(page, lambda: page.click("#delete"))
    after = table(page)
    assert len(after) == 2 and after[0] == before[0] and after[1]["height.lo"] == "4", after
    edit(page, lambda: page.get_by_role("button", name="Undo").click())
    restored = table(page)
    assert len(restored) == 3 and restored[1]["height.lo"] == "12", restored


def test_the_table_is_edited_by_the_controls_accessible_names(editor, page: Page) -> None:
    """What a screen reader says is what a test finds: buttons and fields
    by their accessible names, never by a selector."""
    url, _ = editor
    page.goto(url)
    page.wait_for_function("window.rseEditor?.previews >= 1")
    edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())
    edit(page, lambda: page.get_by_label("type of obstacle 2").select_option("peak"))
    edit(page, lambda: page.get_by_label("height of obstacle 2", exact=True).fill("3"))
    edit(page, lambda: page.get_by_label("angle of obstacle 2", exact=True).fill("45"))
    edit(page, lambda: page.get_by_label("x1 of obstacle 2", exact=True).fill("5"))
    edit(page, lambda: page.get_by_label("y1 of obstacle 2", exact=True).fill("6"))
    edit(page, lambda: page.get_by_label("height range high end of obstacle 1").fill("2"))
    assert table(page) == [
        {"type": "random", "height.lo": "1", "height.hi": "2"},
        {"type": "peak", "height.lo": "3", "angle.lo": "45", "x1.lo": "5", "y1.lo": "6"},
    ]
    assert page.locator("#error").inner_text() == ""
    edit(page, lambda: page.get_by_role("button", name="Copy obstacle").click())
    edit(page, lambda: page.get_by_role("button", name="Move up").click())
    edit(page, lambda: page.get_by_role("button", name="Delete obstacle").click())
    assert [row["type"] for row in table(page)] == ["random", "peak"]
    assert page.get_by_label("world seed").is_visible() and page.get_by_label("index").is_visible()


def test_download_csv_is_the_file_save_writes(editor, page: Page) -> None:
    url, folder = editor
    page.goto(url)
    page.wait_for_function("window.rseEditor?.previews >= 1")
    edit(page, lambda: page.get_by_label("height of obstacle 1", exact=True).fill("2"))
    with page.expect_download() as download:
        page.get_by_role("button", name="Download CSV").click()
    assert download.value.suggested_filename == "start.csv"
    got = folder / "downloaded.csv"
    download.value.save_as(got)
    assert (folder / "start.csv").read_text() == "# size: 20x16\ntype,height\nrandom,1\n", "a download writes no file"
    save(page)
    assert got.read_text() == (folder / "start.csv").read_text() and "random,2" in got.read_text()


def test_add_and_copy_move_the_focus_to_the_new_rows_type(editor, page: Page) -> None:
    """After Add obstacle or Copy obstacle the keyboard is on the new row's
    first field, not on the button (which left the new row dozens of Tabs
    away)."""
    url, _ = editor
    page.goto(url)
    page.wait_for_function("window.rseEditor?.previews >= 1")
    focused = "document.activeElement.getAttribute('aria-label')"
    edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())
    assert page.evaluate(focused) == "type of obstacle 2"
    page.keyboard.press("End")  # the last type of the list, by keyboard
    page.wait_for_function("document.activeElement.value === 'crossing_ramps'")
    edit(page, lambda: page.get_by_role("button", name="Copy obstacle").click())
    assert page.evaluate(focused) == "type of obstacle 3"
    assert [row["type"] for row in table(page)] == ["random", "crossing_ramps", "crossing_ramps"]
