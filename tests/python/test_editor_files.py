"""The editor opens and saves like a desktop program, in a real Chromium:
open by path and from this computer, Save writes the file opened last,
Save as, failed saves said in words, and a lost server that comes back."""

import socket
import subprocess
from pathlib import Path

import pytest
from conftest import rse_gen_release_path
from editor_harness import (
    cell,
    edit,
    generate,
    generate_refused,
    running_editor,
    save,
    save_as,
    save_target,
    status_says,
    table,
    wait_ready,
)
from playwright.sync_api import Page

pytestmark = pytest.mark.thirdparty

REPO = Path(__file__).resolve().parents[2]
START = "# size: 20x16\ntype,height\nrandom,1\n"


def open_path(page: Page, path: Path) -> None:
    page.evaluate("document.getElementById('status').textContent = ''")
    page.get_by_role("button", name="Open path").click()
    page.get_by_label("file path").fill(str(path))
    edit(page, lambda: page.get_by_role("button", name="OK").click())
    status_says(page, "opened")


def test_open_by_path_then_save_writes_the_opened_file_and_save_as_moves_on(editor, page: Page) -> None:
    url, folder = editor
    other = folder / "other.csv"
    other.write_text("# size: 12x9\ntype,height,angle,x1,y1\npeak,3,45,4,4\n")
    wait_ready(page, url)
    open_path(page, other)
    assert save_target(page) == str(other), "the page shows which file Save writes"
    assert table(page) == [{"type": "peak", "height.lo": "3", "angle.lo": "45", "x1.lo": "4", "y1.lo": "4"}]
    edit(page, lambda: page.get_by_label("height of obstacle 1", exact=True).fill("5"))
    save(page)
    assert "peak,5,45,4,4" in other.read_text()
    assert (folder / "start.csv").read_text() == START, "the file the editor started on is untouched"
    # A reload starts from the file opened last, not the one on the command line.
    page.reload()
    page.wait_for_function("window.rseEditor?.previews >= 1")
    assert save_target(page) == str(other)
    assert cell(page, 0, "height").input_value() == "5"
    # Save as: a third file, which Save then writes.
    third = folder / "third.csv"
    save_as(page, third)
    assert save_target(page) == str(third)
    edit(page, lambda: page.get_by_label("angle of obstacle 1", exact=True).fill("60"))
    save(page)
    assert "peak,5,60,4,4" in third.read_text() and "peak,5,45,4,4" in other.read_text()


def test_a_file_from_this_computer_is_edited_and_save_asks_where(editor, page: Page) -> None:
    url, folder = editor
    picked = folder / "picked.csv"
    picked.write_text("# size: 9x9\ntype,height\nrandom,4\n")
    wait_ready(page, url)
    edit(page, lambda: page.set_input_files("#load", str(picked)))
    assert table(page) == [{"type": "random", "height.lo": "4"}]
    assert save_target(page).startswith("picked.csv (from this computer")
    assert page.locator("#unsaved").is_visible(), "not written anywhere the editor knows yet"
    page.get_by_role("button", name="Save", exact=True).click()
    assert page.get_by_label("file path").input_value() == "picked.csv", "Save asks, offering the picked name"
    page.get_by_label("file path").fill(str(folder / "kept.csv"))
    page.get_by_role("button", name="OK").click()
    status_says(page, "saved")
    assert "random,4" in (folder / "kept.csv").read_text() and page.locator("#unsaved").is_hidden()


def test_a_failed_save_or_open_says_why_in_words(editor, page: Page) -> None:
    url, folder = editor
    wait_ready(page, url)
    save_as_button = page.get_by_role("button", name="Save as")
    for path, words in [(folder / "no/such/folder/x.csv", "does not exist"), (folder / "x.txt", ".csv")]:
        page.evaluate("document.getElementById('status').textContent = ''")
        save_as_button.click()
        page.get_by_label("file path").fill(str(path))
        page.get_by_role("button", name="OK").click()
        if "folder" in str(path):  # asked whether to create it: no
            page.get_by_role("dialog", name="Create the folder?").get_by_role("button", name="Cancel").click()
        status_says(page, "not saved")
        said = page.locator("#status").inner_text()
        assert words in said and "bad request" not in said, said
        assert not path.exists()
    page.get_by_role("button", name="Open path").click()
    page.get_by_label("file path").fill(str(folder / "missing.csv"))
    page.get_by_role("button", name="OK").click()
    status_says(page, "not opened")
    assert "cannot open" in page.locator("#status").inner_text()
    assert save_target(page) == str(folder / "start.csv"), "still the same file"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_editor(scheme: Path, port: int) -> subprocess.Popen:
    process = subprocess.Popen(
        [str(rse_gen_release_path()), "edit", str(scheme), "--port", str(port)],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
        cwd=scheme.parent,
    )
    assert process.stdout.readline().startswith("http://127.0.0.1:")
    return process


def stop(process: subprocess.Popen) -> None:
    process.terminate()
    process.wait(timeout=10)
    process.stdout.close()


def test_a_lost_server_is_said_retried_and_the_edits_kept(tmp_path: Path, page: Page) -> None:
    scheme = tmp_path / "start.csv"
    scheme.write_text(START)
    port = free_port()
    server = start_editor(scheme, port)
    try:
        wait_ready(page, f"http://127.0.0.1:{port}/")
        stop(server)
        # The server is gone: an edit, a save, all said, nothing lost.
        cell(page, 0, "height").fill("2")
        page.wait_for_function("!document.getElementById('connection').hidden")
        assert "not answering" in page.locator("#connection").inner_text()
        assert page.locator("#pictures").evaluate("e => e.classList.contains('stale')"), "the pictures are marked out of date"
        # ... because of the server, not of the scheme, which is fine.
        out_of_date = page.get_by_role("status").filter(has_text="Out of date").inner_text()
        assert "server is not answering" in out_of_date and "scheme has an error" not in out_of_date, out_of_date
        page.get_by_role("button", name="Save", exact=True).click()
        status_says(page, "not saved")
        assert "did not answer" in page.locator("#status").inner_text()
        assert START == scheme.read_text()
        # It comes back: the page notices by itself, draws the edit, saves.
        server = start_editor(scheme, port)
        page.wait_for_function("document.getElementById('connection').hidden", timeout=15_000)
        page.wait_for_function("!document.getElementById('pictures').classList.contains('stale')")
        assert cell(page, 0, "height").input_value() == "2"
        save(page)
        assert "random,2" in scheme.read_text()
    finally:
        if server.poll() is None:
            stop(server)


def test_open_asks_before_replacing_unsaved_edits_and_starts_a_new_history(editor, page: Page) -> None:
    """With edits not saved, Open asks: Cancel keeps them, Discard drops
    them, Save writes them first; an opened file is a new document (Undo
    does not bring the other file back under its name), and the header
    names the file Save writes."""
    url, folder = editor
    start = folder / "start.csv"
    other = folder / "other.csv"
    other.write_text("# size: 9x9\ntype,height\nrandom,4\n")
    wait_ready(page, url)
    edit(page, lambda: cell(page, 0, "height").fill("3"))
    assert page.locator("#unsaved").is_visible()

    def open_answering(choice: str) -> None:
        page.get_by_role("button", name="Open path").click()
        dialog = page.get_by_role("dialog", name="Save your edits first?")
        assert "not saved" in dialog.inner_text()
        dialog.get_by_role("button", name=choice).click()

    open_answering("Cancel")
    assert not page.get_by_role("dialog").is_visible(), "no path is asked for"
    assert cell(page, 0, "height").input_value() == "3" and page.locator("#unsaved").is_visible()
    open_answering("Discard them")
    page.get_by_label("file path").fill(str(other))
    edit(page, lambda: page.get_by_role("button", name="OK").click())
    assert table(page) == [{"type": "random", "height.lo": "4"}]
    assert save_target(page) == str(other) and page.locator("#unsaved").is_hidden()
    assert page.get_by_role("button", name="Undo").is_disabled(), "the open starts a new history"
    assert "random,1" in start.read_text(), "discarded, not written"
    # Save them first: written, then the other file opened.
    edit(page, lambda: cell(page, 0, "height").fill("5"))
    open_answering("Save them first")
    status_says(page, "saved")
    page.get_by_label("file path").fill(str(start))
    edit(page, lambda: page.get_by_role("button", name="OK").click())
    assert "random,5" in other.read_text()
    assert save_target(page) == str(start)
    assert table(page) == [{"type": "random", "height.lo": "1"}]


def wait_for_kept_draft(page: Page) -> None:
    """Waits until the page has sent its last edit's draft to the server."""
    page.wait_for_function("window.rseEditor.draftsSent > 0 && window.rseEditor.draftPending === false")


def test_the_draft_and_its_undo_history_belong_to_the_file_not_the_port_or_browser(tmp_path: Path) -> None:
    """Edits not saved, the editor stopped: started again the README way (no
    --port) it comes back on the same port; started on another port (a new
    origin) in a browser that never saw the page, the edits and their undo
    history are there, kept by the server for the file."""
    from editor_harness import chromium_page

    scheme = tmp_path / "start.csv"
    scheme.write_text(START)
    with running_editor(rse_gen_release_path(), scheme, tmp_path) as first_url, chromium_page() as page:
        wait_ready(page, first_url)
        edit(page, lambda: cell(page, 0, "height").fill("2"))
        edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())
        wait_for_kept_draft(page)
    with running_editor(rse_gen_release_path(), scheme, tmp_path) as again:
        assert again == first_url, "the file's last port, free again, is reused"
    with running_editor(rse_gen_release_path(), scheme, tmp_path, port=free_port()) as url, chromium_page() as page:
        assert url != first_url
        wait_ready(page, url)
        assert len(table(page)) == 2 and cell(page, 0, "height").input_value() == "2"
        assert page.locator("#unsaved").is_visible() and "restored" in page.locator("#status").inner_text()
        assert scheme.read_text() == START, "nothing was written to the file"
        undo = page.get_by_role("button", name="Undo")
        edit(page, lambda: undo.click())
        assert len(table(page)) == 1 and cell(page, 0, "height").input_value() == "2"
        edit(page, lambda: undo.click())
        assert cell(page, 0, "height").input_value() == "1" and undo.is_disabled()
        edit(page, lambda: page.get_by_role("button", name="Redo").click())
        assert cell(page, 0, "height").input_value() == "2"
        # Saved, the draft is the file's: a reload shows the file, not "unsaved".
        save(page)
        wait_for_kept_draft(page)
        page.reload()
        page.wait_for_function("window.rseEditor?.previews >= 1")
        assert page.locator("#unsaved").is_hidden() and cell(page, 0, "height").input_value() == "2"


def test_download_csv_works_with_the_server_gone(tmp_path: Path, page: Page) -> None:
    import rse

    scheme = tmp_path / "start.csv"
    scheme.write_text("# size: 20x16\n# step_height: 0.05\ntype,height,angle,x1,y1\nrandom,1,,,\n")
    port = free_port()
    server = start_editor(scheme, port)
    try:
        wait_ready(page, f"http://127.0.0.1:{port}/")
        edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())
        edit(page, lambda: page.get_by_label("type of obstacle 2").select_option("peak"))
        edit(page, lambda: page.get_by_label("angle of obstacle 2", exact=True).fill("45"))
        edit(page, lambda: page.get_by_label("x1 of obstacle 2", exact=True).fill("3"))
        edit(page, lambda: page.get_by_label("x1 range high end of obstacle 2").fill("9"))
        edit(page, lambda: page.get_by_label("y1 of obstacle 2", exact=True).fill("4"))
        page.get_by_label("notes").fill("made offline")
        with page.expect_download() as online:
            page.get_by_role("button", name="Download CSV").click()
        stop(server)
        with page.expect_download() as offline:
            page.get_by_role("button", name="Download CSV").click()
        assert offline.value.suggested_filename == "start.csv"
        status_says(page, "downloaded as typed")
        got = tmp_path / "offline.csv"
        offline.value.save_as(got)
        want = tmp_path / "online.csv"
        online.value.save_as(want)
        assert rse.Scheme.load(got).to_csv() == rse.Scheme.load(want).to_csv(), got.read_text()
        assert "random,1" in got.read_text() and "peak,1,45,3..9,4" in got.read_text()
    finally:
        if server.poll() is None:
            stop(server)


def test_files_like_a_desktop_program_new_samples_working_folder_and_base_files(editor, page: Page) -> None:
    """New (asking first), the working folder shown, the sample schemes to
    open, Save of a sample into that folder, and Generate with the user's
    own base files (templates), each world's check listed."""
    import rse

    url, folder = editor
    wait_ready(page, url)
    assert page.locator("#work-folder").inner_text() == str(folder)
    # The file the editor started on, in that folder, by its path from there.
    assert page.locator("#file-name").inner_text() == "start.csv" and save_target(page) == str(folder / "start.csv")
    edit(page, lambda: cell(page, 0, "height").fill("3"))
    page.get_by_role("button", name="New", exact=True).click()
    page.get_by_role("dialog", name="Save your edits first?").get_by_role("button", name="Discard them").click()
    page.wait_for_function("document.getElementById('status').textContent === 'a new scheme'")
    assert table(page) == [{"type": "random", "height.lo": "1"}]
    assert save_target(page) == "(not saved yet)"
    assert page.get_by_role("button", name="Undo").is_disabled()

    # The samples, each a button named by its file.
    page.get_by_role("button", name="Open sample").click()
    samples = page.get_by_role("dialog", name="Open a sample scheme")
    names = sorted(p.name for p in (REPO / "schemes").glob("*.csv"))
    assert [b for b in samples.get_by_role("button").all_inner_texts() if b != "Cancel"] == names
    assert "One obstacle of each of the six types" in samples.inner_text()
    edit(page, lambda: samples.get_by_role("button", name="six_obstacles.csv").click())
    assert len(table(page)) == 6 and "six_obstacles.csv (a sample" in save_target(page)
    page.get_by_role("button", name="Save", exact=True).click()
    assert str(folder) in page.get_by_role("dialog", name="Save as").inner_text(), "the dialog says where a relative path starts"
    assert page.get_by_label("file path").input_value() == "six_obstacles.csv"
    page.get_by_role("button", name="OK").click()
    status_says(page, "saved")
    saved = folder / "six_obstacles.csv"
    assert rse.Scheme.load(saved).to_csv() == rse.Scheme.load(REPO / "schemes/six_obstacles.csv").to_csv()
    assert save_target(page) == "six_obstacles.csv"
    assert page.locator("#work-folder").inner_text() == str(folder)

    # Base files of one's own: a Gazebo world template with a mark in it.
    subprocess.run([str(rse_gen_release_path()), "templates", "export", str(folder / "mine")], check=True, capture_output=True)
    world_template = folder / "mine/gazebo/rse.world.j2"
    world_template.write_text("<!-- made with my base files -->\n" + world_template.read_text())
    page.get_by_label("number of worlds").fill("2")
    page.get_by_label("output folder").fill("worlds")
    page.get_by_label("base files").fill(str(folder / "nowhere"))
    generate_refused(page, "base files", "nowhere")
    page.get_by_label("base files").fill(str(folder / "mine"))
    generate(page, "worlds written")
    worlds = sorted((folder / "worlds").glob("world_*"))
    assert len(worlds) == 2
    for world in worlds:
        assert (world / "gazebo/rse.world").read_text().startswith("<!-- made with my base files -->")
    assert page.locator("#gen-check").inner_text().startswith("checked 2 worlds: 2 good")
    page.get_by_text("Each world's check").click()
    rows = page.locator("#gen-worlds tbody tr").all_inner_texts()
    assert [r.split("\t") for r in rows] == [[w.name, "good"] for w in worlds], rows
