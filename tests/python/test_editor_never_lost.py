"""The editor's third pass, point 1 and 7, in a real Chromium: work is
never lost. A scheme in no file yet (New, a sample, a file from this
computer) keeps its draft and history through a reload and a restart on any
port; two tabs on one scheme never overwrite each other's work silently;
`rse-gen edit FILE` on a file not there yet starts a new scheme there."""

from pathlib import Path

import pytest
from conftest import rse_gen_release_path
from editor_harness import cell, chromium_page, edit, running_editor, save, status_says, table, wait_ready
from playwright.sync_api import Page
from test_editor_files import free_port, wait_for_kept_draft

pytestmark = pytest.mark.thirdparty

START = "# size: 20x16\ntype,height\nrandom,1\n"


def start_new(page: Page, how: str, folder: Path) -> None:
    """Starts a scheme in no file yet the way `how` says, as a user does."""
    if how == "New":
        edit(page, lambda: page.get_by_role("button", name="New", exact=True).click())
    elif how == "Open sample":
        page.get_by_role("button", name="Open sample").click()
        samples = page.get_by_role("dialog", name="Open a sample scheme")
        edit(page, lambda: samples.get_by_role("button", name="six_obstacles.csv").click())
    else:
        picked = folder / "picked.csv"
        picked.write_text("# size: 9x9\ntype,height\nrandom,4\nrandom,2\n")
        edit(page, lambda: page.set_input_files("#load", str(picked)))


@pytest.mark.parametrize("how", ["New", "Open sample", "Open file"])
def test_a_scheme_in_no_file_yet_survives_a_reload_and_a_restart(tmp_path: Path, how: str) -> None:
    """New (or a sample, or a file from this computer), edits, a reload:
    the edits were gone, back to the command line's 20×20, with no word
    and no Undo. Now the page comes back on that scheme, its edits, its
    name and its history, after a reload and after the editor restarted on
    another port."""
    scheme = tmp_path / "start.csv"
    scheme.write_text(START)
    with running_editor(rse_gen_release_path(), scheme, tmp_path) as url, chromium_page() as page:
        wait_ready(page, url)
        start_new(page, how, tmp_path)
        name = page.locator("#file-name").inner_text()
        before = len(table(page))
        edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())
        edit(page, lambda: cell(page, before, "height").fill("7"))
        edited = table(page)
        wait_for_kept_draft(page)
        page.reload()
        page.wait_for_function("window.rseEditor?.previews >= 1")
        assert table(page) == edited, f"{how}: the edits after a reload"
        assert page.locator("#file-name").inner_text() == name
        assert page.locator("#unsaved").is_visible()
        status_says(page, "unsaved changes restored")
        # The history came back too: Undo takes back the height, then the row.
        undo = page.get_by_role("button", name="Undo")
        edit(page, lambda: undo.click())
        assert cell(page, before, "height").input_value() != "7"
        edit(page, lambda: undo.click())
        assert len(table(page)) == before
        edit(page, lambda: page.get_by_role("button", name="Redo").click())
        edit(page, lambda: page.get_by_role("button", name="Redo").click())
        assert table(page) == edited
        wait_for_kept_draft(page)
    with running_editor(rse_gen_release_path(), scheme, tmp_path, port=free_port()) as again, chromium_page() as page:
        wait_ready(page, again)
        assert table(page) == edited, f"{how}: the edits after a restart on another port"
        assert page.locator("#file-name").inner_text() == name
        # Saved where the user says, it is that file's from then on.
        page.get_by_role("button", name="Save", exact=True).click()
        page.get_by_label("file path").fill(str(tmp_path / "kept.csv"))
        page.get_by_role("button", name="OK").click()
        status_says(page, "saved")
        assert page.locator("#unsaved").is_hidden()
    assert scheme.read_text() == START, "the command line's file was never touched"


def test_a_restart_on_the_same_port_loses_nothing(tmp_path: Path) -> None:
    """The page stays open while the editor restarts on its port: it said
    the server was gone, came back, and the stored draft was a blank
    scheme. Now the page's work is what a reload finds after it."""
    scheme = tmp_path / "start.csv"
    scheme.write_text(START)
    port = free_port()
    with chromium_page() as page:
        with running_editor(rse_gen_release_path(), scheme, tmp_path, port=port) as url:
            wait_ready(page, url)
            start_new(page, "New", tmp_path)
            edit(page, lambda: cell(page, 0, "height").fill("5"))
            wait_for_kept_draft(page)
        # An edit while it is gone: said, kept in the browser.
        cell(page, 0, "height").fill("6")
        page.wait_for_function("!document.getElementById('connection').hidden")
        with running_editor(rse_gen_release_path(), scheme, tmp_path, port=port):
            page.wait_for_function("document.getElementById('connection').hidden", timeout=15_000)
            wait_for_kept_draft(page)
            page.reload()
            page.wait_for_function("window.rseEditor?.previews >= 1")
            assert cell(page, 0, "height").input_value() == "6"
            assert page.locator("#unsaved").is_visible()


def test_two_tabs_on_one_scheme_never_overwrite_each_other_silently(tmp_path: Path) -> None:
    """A second tab on the same scheme overwrote the stored draft. Now a
    tab that writes over another tab's later work is told, and offered
    both: keep its own, or take the other's (its own one Undo away)."""
    scheme = tmp_path / "start.csv"
    scheme.write_text(START)
    with running_editor(rse_gen_release_path(), scheme, tmp_path) as url, chromium_page() as first:
        second = first.context.new_page()
        wait_ready(first, url)
        edit(first, lambda: cell(first, 0, "height").fill("2"))
        wait_for_kept_draft(first)
        wait_ready(second, url)
        assert cell(second, 0, "height").input_value() == "2", "the second tab starts from the first's work"
        edit(second, lambda: cell(second, 0, "height").fill("3"))
        wait_for_kept_draft(second)
        # The first tab edits on from its older copy: asked, nothing lost.
        first.bring_to_front()
        cell(first, 0, "height").fill("4")
        asked = first.get_by_role("dialog", name="Changed in another tab")
        asked.wait_for()
        edit(first, lambda: asked.get_by_role("button", name="Take the other tab's").click())
        assert cell(first, 0, "height").input_value() == "3"
        edit(first, lambda: first.get_by_role("button", name="Undo").click())
        assert cell(first, 0, "height").input_value() == "4", "its own work is one Undo away"
        wait_for_kept_draft(first)
        # The second tab now is behind: it keeps its own, on purpose.
        second.bring_to_front()
        cell(second, 0, "height").fill("9")
        asked = second.get_by_role("dialog", name="Changed in another tab")
        asked.wait_for()
        asked.get_by_role("button", name="Keep this tab's").click()
        status_says(second, "kept this tab's version")
        wait_for_kept_draft(second)
        third = first.context.new_page()
        wait_ready(third, url)
        assert cell(third, 0, "height").input_value() == "9"


def test_editing_a_file_not_there_yet_starts_a_new_scheme_there(tmp_path: Path, page: Page) -> None:
    """`rse-gen edit new.csv` refused a file that did not exist yet ("cannot
    read … No such file or directory"); a desktop program starts it."""
    target = tmp_path / "plans" / "new.csv"
    target.parent.mkdir()
    with running_editor(rse_gen_release_path(), target, tmp_path) as url:
        wait_ready(page, url)
        status_says(page, "a new scheme: Save writes")
        assert table(page) == [{"type": "random", "height.lo": "1"}]
        assert page.locator("#unsaved").is_visible(), "not on disk yet"
        assert not target.exists()
        edit(page, lambda: cell(page, 0, "height").fill("3"))
        save(page)
        assert "random,3" in target.read_text()
        assert page.locator("#unsaved").is_hidden()
    # The command line's scheme options apply to the new scheme too.
    other = tmp_path / "plans" / "wide.csv"
    with running_editor(rse_gen_release_path(), other, tmp_path, extra=("--size", "30x12")) as url:
        wait_ready(page, url)
        assert page.get_by_label("size", exact=True).input_value() == "30x12"
        assert not other.exists()
