"""The editor's third pass, points 3 to 5 and 8, in a real Chromium, found
by accessible names: one Undo wherever the focus is, errors beside the
field they name and never over the map, a new obstacle of any type valid
from the start, and no old status line after a reload."""

from pathlib import Path

import pytest
from conftest import rse_gen_release_path
from editor_harness import cell, cell_point, edit, running_editor, table, wait_ready
from playwright.sync_api import Page

pytestmark = pytest.mark.thirdparty


def test_ctrl_z_is_the_editors_undo_wherever_the_focus_is(editor, page: Page) -> None:
    """Ctrl+Z inside a text field was the browser's text undo: after an
    edit elsewhere it did nothing, or undid another field letter by letter
    as new edits, wiping Redo. Now it is the editor's Undo in a field too,
    a field's typing is one step however slowly it is typed, and selecting
    records no step."""
    url, _ = editor
    wait_ready(page, url)
    undo, redo = page.get_by_role("button", name="Undo"), page.get_by_role("button", name="Redo")
    # Typed slowly (pauses longer than any merge window): one step.
    height = page.get_by_label("height of obstacle 1", exact=True)
    height.fill("")
    edit(page, lambda: height.press_sequentially("123", delay=800))
    edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())
    assert len(table(page)) == 2
    # Selections by the table and the map: no steps.
    page.get_by_label("height of obstacle 1", exact=True).click()
    page.get_by_label("height of obstacle 2", exact=True).click()
    # In a field, Ctrl+Z takes back the last edit (the Add), not the field's text.
    field = page.get_by_label("height of obstacle 1", exact=True)
    field.click()
    edit(page, lambda: page.keyboard.press("Control+Z"))
    assert len(table(page)) == 1 and cell(page, 0, "height").input_value() == "123"
    assert redo.is_enabled(), "Redo is kept"
    # The focus stays in the field, and the next Ctrl+Z takes back the
    # field's typing whole (its emptying and the three digits).
    assert page.evaluate("document.activeElement.getAttribute('aria-label')") == "height of obstacle 1"
    edit(page, lambda: page.keyboard.press("Control+Z"))
    assert cell(page, 0, "height").input_value() == "1" and undo.is_disabled()
    # Redo from within the field, both ways of saying it.
    edit(page, lambda: page.keyboard.press("Control+Y"))
    assert cell(page, 0, "height").input_value() == "123"
    edit(page, lambda: page.keyboard.press("Control+Shift+Z"))
    assert len(table(page)) == 2 and redo.is_disabled()
    # In the notes too.
    notes = page.get_by_label("notes")
    notes.click()
    edit(page, lambda: notes.press_sequentially("a test", delay=50))
    edit(page, lambda: page.keyboard.press("Control+Z"))
    assert notes.input_value() == "" and len(table(page)) == 2


def test_errors_stand_beside_their_field_never_over_the_map(tmp_path: Path, page: Page) -> None:
    """With 30 rows the message was under the table, off the screen, and
    the "Out of date" banner was drawn over the map's top rows. Now the
    words stand right under the row (or under the global) they name, and
    the banner stands under the map."""
    scheme = tmp_path / "long.csv"
    scheme.write_text("# size: 40x40\ntype,height,angle,x1,y1\n" + "".join(f"peak,3,60,{i},{i}\n" for i in range(30)))
    with running_editor(rse_gen_release_path(), scheme, tmp_path) as url:
        wait_ready(page, url)
        field = page.get_by_label("x1 of obstacle 28", exact=True)
        edit(page, lambda: field.fill("99"))
        said = page.locator("#table td.field-error-text")
        said.wait_for()
        assert said.inner_text().startswith("obstacle 28, x1: ") and said.get_attribute("role") == "alert"
        box, words = field.bounding_box(), said.bounding_box()
        assert 0 <= words["y"] - (box["y"] + box["height"]) < 20, f"right under the row: {box} {words}"
        assert 0 <= words["y"] + words["height"] <= 900, "on the screen"
        assert field.get_attribute("aria-invalid") == "true"
        assert page.evaluate("document.getElementById(document.activeElement.getAttribute('aria-describedby') || 'x')?.textContent || ''")
        stale = page.locator("#stale").bounding_box()
        chart = page.locator(".map-box").bounding_box()
        assert stale["y"] >= chart["y"] + chart["height"], f"the banner is over the map: {stale} {chart}"
        edit(page, lambda: field.fill("9"))
        assert page.get_by_role("alert").filter(has_text="obstacle 28").count() == 0
        # A global's error under the global.
        block = page.get_by_label("block size", exact=True)
        edit(page, lambda: block.fill("-1"))
        said = page.locator("p.field-error")
        said.wait_for()
        assert said.inner_text().startswith("block size")
        below = block.bounding_box()
        assert 0 <= said.bounding_box()["y"] - (below["y"] + below["height"]) < 20


TYPES = ["peak", "pit", "wall", "long_pit", "stairs", "pyramid", "pyramid_pit", "ramp", "crossing_ramps", "gaussian"]


@pytest.mark.parametrize("kind", TYPES)
def test_a_new_obstacle_of_any_type_starts_valid(editor, page: Page, kind: str) -> None:
    """A new pit or wall started with empty required fields (angle, a
    position): red errors at once, one at a time. Now each type starts with
    values that work on this grid, and is drawn on the map."""
    url, _ = editor
    wait_ready(page, url)
    edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())
    before = page.evaluate("Array.from(window.rseEditor.preview.heights).join()")
    edit(page, lambda: page.get_by_label("type of obstacle 2").select_option(kind))
    assert page.locator("#error").inner_text() == "", page.locator("#error").inner_text()
    assert page.locator("[aria-invalid=true]").count() == 0
    assert not page.locator("#pictures").evaluate("e => e.classList.contains('stale')")
    row = table(page)[1]
    assert row["type"] == kind and row.get("height.lo") == "1", row
    if kind != "gaussian":
        after = page.evaluate("Array.from(window.rseEditor.preview.heights).join()")
        assert after != before, "drawn on the map"


def test_no_old_status_line_after_a_reload(editor, page: Page) -> None:
    """'nothing here to select' stayed in the header after a reload: what
    the map says of a click is said under the map, never in the header."""
    url, _ = editor
    wait_ready(page, url)
    page.mouse.click(*cell_point(page, 3, 3))
    assert page.locator("#status").inner_text() == ""
    assert page.locator("#map-hint").inner_text().startswith("Click: nothing here")
    page.reload()
    page.wait_for_function("window.rseEditor?.previews >= 1")
    assert page.locator("#status").inner_text() in ("", "unsaved changes restored")


def test_after_generate_the_folder_whole_a_way_to_open_it_and_each_worlds_preview(editor, page: Page) -> None:
    """After Generate there was no link to the worlds or their previews, and
    the path was shown as typed (relative). Now the summary names the folder
    whole, Open folder opens it (or says where it is, with no file manager),
    and each world's preview is shown with its legend."""
    from PIL import Image

    url, folder = editor
    wait_ready(page, url)
    page.get_by_label("number of worlds").fill("2")
    page.get_by_label("output folder").fill("worlds")
    page.get_by_role("button", name="Generate").click()
    page.wait_for_function("document.getElementById('gen-check').textContent !== ''", timeout=60_000)
    whole = str((folder / "worlds").resolve())
    assert whole in page.locator("#gen-summary").inner_text()
    assert page.locator("#gen-folder-path").inner_text() == whole
    page.get_by_role("button", name="Open folder").click()
    page.wait_for_function("document.getElementById('status').textContent.includes('opened')")
    status = page.locator("#status").inner_text()
    assert status.startswith("opened") or whole in status, status
    for name in ("world_0000", "world_0001"):
        image = page.get_by_role("img", name=f"preview of {name}")
        image.wait_for()
        page.wait_for_function("n => document.querySelector(`img[alt='preview of ${n}']`).naturalWidth > 0", arg=name)
        width = image.evaluate("e => e.naturalWidth")
        with Image.open(folder / "worlds" / name / "preview.png") as png:
            assert width == png.width
        legend = page.get_by_role("list", name=f"legend of {name}: colour of each height")
        assert legend.get_by_role("listitem").count() >= 2
        assert "steps" in legend.inner_text() and " m" in legend.inner_text()
