"""The editor's fields in a real Chromium, as a person uses them: units and
the "did you mean cm?" question, fields a type does not use greyed out,
pallet boundary as a checkbox, the mesh type, tooltips from
docs/schemes.md, errors marked where they are and the pictures marked out
of date, 800 px without sideways scrolling, Tab order and skip links, every
control's accessible name, and previews that do not pile up."""

import json
import re
from pathlib import Path

import pytest
from conftest import rse_gen_release_path
from editor_harness import (
    chromium_page,
    edit,
    gen_summary_says,
    generate,
    generate_refused,
    running_editor,
    save,
    wait_ready,
)
from playwright.sync_api import Page

pytestmark = pytest.mark.thirdparty

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture
def editor(tmp_path: Path):
    """A running `rse-gen edit` on six_obstacles.csv's copy; yields (url, folder)."""
    scheme = tmp_path / "six.csv"
    scheme.write_text((REPO / "schemes/six_obstacles.csv").read_text())
    with running_editor(rse_gen_release_path(), scheme, tmp_path) as url:
        yield url, tmp_path


def is_stale(page: Page) -> bool:
    return page.evaluate("document.getElementById('pictures').classList.contains('stale') && !document.getElementById('stale').hidden")


def test_units_show_and_a_step_in_metres_that_looks_like_cm_is_questioned(editor, page: Page) -> None:
    url, _ = editor
    wait_ready(page, url)
    headers = page.locator("#table thead th:visible").all_inner_texts()  # tread: hidden with no pyramid
    assert [h.split("\n")[:2] for h in headers[2:]] == [
        ["height", "steps"], ["angle", "degrees"], ["x1", "cells"], ["y1", "cells"],
        ["x2", "cells"], ["y2", "cells"], ["sigma", "steps"],
    ]
    # Each column's two fields have a visible name each, right above them.
    for column in ("height", "x1", "sigma"):
        header = page.locator("#table thead th", has_text=column).first
        for part, name in (("lo", "low"), ("hi", "high")):
            label = header.get_by_text(name, exact=True).bounding_box()
            field = page.locator(f'#table tbody tr[data-row="1"] [data-field="{column}"][data-part="{part}"]').bounding_box()
            centre = label["x"] + label["width"] / 2
            assert field["x"] <= centre <= field["x"] + field["width"], f"{column}: '{name}' is not above its field"
    for key, unit in [("step height", "m"), ("block size", "m"), ("base", "m"), ("size", "cells"), ("amount", "worlds")]:
        field = page.get_by_label(key, exact=True).first
        assert field.evaluate("e => e.nextElementSibling.textContent") == unit, key
    step = page.get_by_label("step height", exact=True)
    edit(page, lambda: step.fill("10"))
    question = page.locator("#unit-question")
    assert question.is_visible() and "did you mean 10 cm?" in question.inner_text()
    edit(page, lambda: page.get_by_role("button", name="Use 0.1 m").click())
    assert step.input_value() == "0.1" and question.is_hidden()
    edit(page, lambda: page.get_by_label("block size", exact=True).fill("5"))
    assert "did you mean 5 cm?" in question.inner_text()
    page.get_by_role("button", name="Keep 5 m").click()
    assert question.is_hidden() and page.get_by_label("block size", exact=True).input_value() == "5"


def test_fields_a_type_does_not_use_are_greyed_out_and_emptied_when_it_changes(editor, page: Page) -> None:
    url, _ = editor
    wait_ready(page, url)
    # Row 3 of six_obstacles is a peak: x1, y1 used, x2, y2, sigma not.
    assert page.get_by_label("x1 of obstacle 3", exact=True).is_enabled()
    for name in ["x2 of obstacle 3", "y2 of obstacle 3", "sigma of obstacle 3", "angle of obstacle 1", "sigma of obstacle 1"]:
        assert page.get_by_label(name, exact=True).is_disabled(), name
    assert page.get_by_label("sigma of obstacle 2", exact=True).is_enabled(), "gaussian takes sigma"
    edit(page, lambda: page.get_by_label("type of obstacle 3").select_option("wall"))
    assert page.get_by_label("x2 of obstacle 3", exact=True).is_enabled()
    edit(page, lambda: page.get_by_label("type of obstacle 3").select_option("random"))
    row = page.evaluate("({...window.rseEditor.state.rows[2]})")
    assert row["x1.lo"] == row["angle.lo"] == "" and row["height.lo"] == "6", "unused fields are emptied"
    assert page.get_by_label("x1 of obstacle 3", exact=True).is_disabled()
    assert page.locator("#error").inner_text() == ""
    edit(page, lambda: page.get_by_role("button", name="Undo").click())
    assert page.get_by_label("x1 of obstacle 3", exact=True).input_value() == "10", "Undo brings them back"


def test_tooltips_are_the_words_of_docs_schemes(editor, page: Page) -> None:
    url, _ = editor
    wait_ready(page, url)
    docs = (REPO / "docs/schemes.md").read_text()

    def doc_row(name: str, column: int) -> str:
        line = next(line for line in docs.splitlines() if line.startswith(f"| `{name}` |"))
        return line.strip("|").split(" | ")[column].strip().replace("`", "")

    for column in ["height", "angle", "x1", "sigma"]:
        assert page.get_by_label(f"{column} of obstacle 1", exact=True).get_attribute("title") == doc_row(column, 2)
        header = page.locator("#table thead th", has_text=re.compile(f"^{column}"))
        assert header.get_attribute("title") == doc_row(column, 2)
    for key in ["step_height", "pallets", "seed"]:
        assert page.locator(f'[data-global="{key}"]').get_attribute("title") == doc_row(key, 1)


def test_pallet_boundary_is_a_checkbox_and_mesh_a_choice_both_reach_the_worlds(editor, page: Page) -> None:
    url, folder = editor
    wait_ready(page, url)
    boundary = page.get_by_label("pallet boundary")
    assert boundary.get_attribute("type") == "checkbox"
    assert boundary.is_disabled(), "no pallets, no boundary"
    edit(page, lambda: page.get_by_label("pallets", exact=True).fill("2x2"))
    edit(page, lambda: page.get_by_label("pallet size", exact=True).fill("25"))
    assert boundary.is_enabled() and boundary.is_checked(), "on by default, as the scheme format says"
    assert page.evaluate("window.rseEditor.preview.frame_period") == 26
    edit(page, lambda: boundary.uncheck())
    assert page.evaluate("window.rseEditor.preview.frame_period") is None
    # Generate one world with blocks as its collider.
    page.get_by_label("mesh").select_option(label="blocks (one box each)")
    page.get_by_label("number of worlds").fill("1")
    page.get_by_label("output folder").fill(str(folder / "worlds"))
    page.get_by_role("button", name="Generate").click()
    page.wait_for_function("document.getElementById('gen-check').textContent !== ''", timeout=60_000)
    manifest = json.loads((folder / "worlds/world_0000/rse.json").read_text())
    assert manifest["mesh"] == "blocks", manifest.get("mesh")
    assert "# pallet_boundary: false\n" in manifest["scheme"], manifest["scheme"]


def test_every_world_option_has_a_generate_field_that_reaches_the_worlds(editor, page: Page) -> None:
    """The Generate panel offers every world option of rse-world's table
    (targets and mesh with controls of their own, the rest a field each,
    found by its name): the MuJoCo collider and its oversample reach
    `rse.json`, and a value one refuses is said on its field."""
    import rse._rse as _rse

    url, folder = editor
    wait_ready(page, url)
    for name, *_ in _rse._world_keywords():
        if name not in ("targets", "mesh"):
            assert page.get_by_label(name.replace("_", " "), exact=True).is_visible(), name
    page.check('#gen-targets input[value="mujoco"]')
    page.get_by_label("number of worlds").fill("1")
    page.get_by_label("output folder").fill(str(folder / "worlds"))
    oversample = page.get_by_label("oversample", exact=True)
    oversample.fill("0")
    page.get_by_role("button", name="Generate").click()
    page.wait_for_function("document.getElementById('gen-summary').textContent.startsWith('not started')")
    assert oversample.get_attribute("aria-invalid") == "true"
    assert "oversample" in page.locator("#gen-summary").inner_text()
    page.get_by_label("mujoco collider", exact=True).fill("hfield")
    oversample.fill("2")
    page.get_by_role("button", name="Generate").click()
    page.wait_for_function("document.getElementById('gen-check').textContent !== ''", timeout=60_000)
    manifest = json.loads((folder / "worlds/world_0000/rse.json").read_text())
    assert manifest["mujoco_collider"] == {"type": "hfield", "oversample": 2}, manifest.get("mujoco_collider")
    assert (folder / "worlds/world_0000/mujoco/terrain.bin").is_file()


def test_refused_values_are_marked_in_words_and_the_pictures_marked_out_of_date(editor, page: Page) -> None:
    url, folder = editor
    wait_ready(page, url)
    assert not is_stale(page)
    for label, value, words in [
        ("index", "-1", "the index must be a whole number of 0 or more"),
        ("world seed", "abc", "the world seed must be a whole number of 0 or more"),
    ]:
        field = page.get_by_label(label, exact=True)
        edit(page, lambda field=field, value=value: field.fill(value))
        assert field.get_attribute("aria-invalid") == "true", label
        said = page.locator("#error").inner_text()
        assert said.startswith(f"{label}: {words}") and "expected" not in said and "line 1 column" not in said, said
        assert is_stale(page) and page.locator("#timing").inner_text() == ""
        edit(page, lambda field=field: field.fill(""))
        assert field.get_attribute("aria-invalid") is None and not is_stale(page)
    # A table field: the message is rse-core's, on that field.
    height = page.get_by_label("height of obstacle 1", exact=True)
    edit(page, lambda: height.fill("two"))
    assert height.get_attribute("aria-invalid") == "true"
    assert page.locator("#error").inner_text().startswith("obstacle 1, height: `two` is not a whole number")
    assert is_stale(page)
    edit(page, lambda: height.fill("2"))
    # Generate with an amount that is not a number: refused on that field, nothing written.
    page.get_by_label("number of worlds").fill("abc")
    page.get_by_label("output folder").fill(str(folder / "worlds"))
    generate_refused(page, "number of worlds", "the number of worlds must be a whole number")
    assert not (folder / "worlds").exists()


def test_at_800_px_nothing_scrolls_sideways_and_the_preview_moves_below_the_table(tmp_path: Path) -> None:
    scheme = tmp_path / "six.csv"
    scheme.write_text((REPO / "schemes/six_obstacles.csv").read_text())
    with running_editor(rse_gen_release_path(), scheme, tmp_path) as url:
        for width in (800, 1024, 1200, 1280, 1440, 1920):
            with chromium_page(width, 900) as page:
                wait_ready(page, url)
                scroll, client = page.evaluate("[document.documentElement.scrollWidth, document.documentElement.clientWidth]")
                assert scroll <= client, f"{width} px: the page is {scroll} px wide"
                table_box = page.locator("#table").bounding_box()
                map_box = page.locator("#map-overlay").bounding_box()
                assert map_box["x"] + map_box["width"] <= width and table_box["x"] + table_box["width"] <= width
                if width < 1200:
                    assert map_box["y"] >= table_box["y"] + table_box["height"], f"{width} px: the preview is below the table"
                else:
                    assert map_box["x"] >= table_box["x"] + table_box["width"], f"{width} px: the preview is beside the table"
                    assert map_box["width"] >= 300, f"{width} px: the map is {map_box['width']} px wide"


@pytest.mark.parametrize("width, height", [(1280, 800), (1440, 900), (1920, 1080)])
def test_the_map_stays_in_view_beside_any_row_edited_with_the_toolbar_and_headings(tmp_path: Path, width: int, height: int) -> None:
    """A laptop's 1280×800 or 1440×900, a desktop's 1920×1080: the map
    beside the table, whole on the screen and large (once 347×231 px at
    1440×900, some 6 px a block), whichever row is edited (the 30th too);
    the toolbar (Undo, Save, "unsaved") and the column headings stay on the
    screen above the row (row 30 was unlabelled numbers). The 3D view is
    under the map, in the preview's own scroll."""
    scheme = tmp_path / "long.csv"
    scheme.write_text("# size: 40x40\ntype,height,angle,x1,y1\n" + "".join(f"peak,3,60,{i},{i}\n" for i in range(30)))
    with running_editor(rse_gen_release_path(), scheme, tmp_path) as url, chromium_page(width, height) as page:
        wait_ready(page, url)
        for row in (1, 15, 30):
            field = page.get_by_label(f"height of obstacle {row}", exact=True)
            edit(page, lambda field=field: field.fill("4"))
            field_box = field.bounding_box()
            map_box = page.locator("#map-overlay").bounding_box()
            assert 0 <= field_box["y"] < height, "the edited field is on the screen"
            assert 0 <= map_box["y"] and map_box["y"] + map_box["height"] <= height, f"row {row}: the map is at {map_box}"
            assert map_box["x"] >= field_box["x"] + field_box["width"]
            assert map_box["width"] >= 480, f"row {row}: the map is {map_box['width']} px wide"
            for name in ("Undo", "Save"):
                button = page.get_by_role("button", name=name, exact=True).bounding_box()
                assert 0 <= button["y"] < field_box["y"], f"row {row}: {name} scrolled away"
            heading = page.locator("#table thead th", has_text="height").bounding_box()
            assert heading["y"] + heading["height"] <= field_box["y"] and heading["y"] >= 0, f"row {row}: the heading is at {heading}"
        page.get_by_role("img", name="3D view of the blocks").scroll_into_view_if_needed()
        view = page.get_by_role("img", name="3D view of the blocks").bounding_box()
        assert 0 <= view["y"] and view["y"] + view["height"] <= height, f"the 3D view is at {view}"


def focus_section(page: Page) -> str:
    return page.evaluate(
        "(() => { const e = document.activeElement; const s = e.closest('section, header, nav');"
        " return s ? (s.id || s.tagName.toLowerCase()) : e.tagName.toLowerCase(); })()"
    )


def test_tab_goes_globals_table_preview_generate_and_skip_links_jump(editor, page: Page) -> None:
    url, _ = editor
    wait_ready(page, url)
    page.locator("body").focus()
    seen: list[str] = []
    for _ in range(200):
        page.keyboard.press("Tab")
        where = focus_section(page)
        if not seen or seen[-1] != where:
            seen.append(where)
        if page.evaluate("document.activeElement.id") == "generate":
            break
    assert seen == ["nav", "header", "globals", "table-panel", "view", "generate-panel"], seen
    # The skip link to Generate: two key presses from the top.
    page.reload()
    page.wait_for_function("window.rseEditor?.previews >= 1")
    page.locator("body").focus()
    for _ in range(3):
        page.keyboard.press("Tab")
    assert page.evaluate("document.activeElement.textContent") == "Skip to Generate"
    page.keyboard.press("Enter")
    page.keyboard.press("Tab")
    assert focus_section(page) == "generate-panel"


def test_every_control_has_the_accessible_name_the_issue_lists(editor, page: Page) -> None:
    url, _ = editor
    wait_ready(page, url)
    for name in ["Undo", "Redo", "Save", "Save as", "Download CSV", "Add obstacle", "Copy obstacle", "Delete obstacle", "Move up", "Move down", "Generate"]:
        assert page.get_by_role("button", name=name, exact=True).count() == 1, name
    for label in ["height of obstacle 1", "type of obstacle 1", "angle of obstacle 3", "x2 of obstacle 4", "sigma of obstacle 2", "index", "world seed", "mesh", "pallet boundary"]:
        assert page.get_by_label(label, exact=True).count() == 1, label
    # Nothing focusable without a name.
    nameless = page.evaluate(
        """[...document.querySelectorAll('button, input, select, textarea, [tabindex="0"]')]
             .filter(e => !e.hidden && e.type !== 'file')
             .filter(e => !(e.getAttribute('aria-label') || (e.labels && e.labels.length) || e.textContent.trim() || e.closest('label')))
             .map(e => e.outerHTML.slice(0, 80))"""
    )
    assert nameless == []


def test_typing_a_size_sends_a_few_previews_and_draws_the_last(editor, page: Page) -> None:
    url, _ = editor
    wait_ready(page, url)
    before = page.evaluate("window.rseEditor.requests")
    size = page.get_by_label("size", exact=True)
    size.fill("")
    size.press_sequentially("200x200")
    page.wait_for_function("document.getElementById('timing').textContent.startsWith('200×200')")
    page.wait_for_timeout(300)
    sent = page.evaluate("window.rseEditor.requests") - before
    # One request on its way at a time: keys typed meanwhile go together
    # in the next (how many depends on the machine's speed, never all 8).
    assert page.evaluate("window.rseEditor.mostInFlight") == 1
    assert sent < 8, f"{sent} previews for 8 key presses"
    assert page.evaluate("[window.rseEditor.preview.nx, window.rseEditor.preview.ny]") == [200, 200]
    # The reply is the heights: ≤ 100 kB at 200x200, whatever the terrain.
    reply = page.evaluate(
        """(async () => { const r = await fetch('/api/preview', {method: 'POST', headers: {'Content-Type': 'application/json'},
             body: JSON.stringify({scheme: {globals: {size: '200x200'}, obstacles: [{type: 'random', height: ['200', '']}]}})});
             return (await r.text()).length; })()"""
    )
    assert reply <= 100_000, reply


def test_size_says_the_pallets_set_the_grid_and_saved_goes_with_the_next_edit(editor, page: Page) -> None:
    """With pallets on, the size field is not what the map shows: it says
    the pallets make the grid, and how big; and "saved …" does not stay
    beside "unsaved" once the page is edited again."""
    url, folder = editor
    wait_ready(page, url)
    edit(page, lambda: page.get_by_label("pallets", exact=True).fill("5x5"))
    page.wait_for_function("document.getElementById('grid-note').textContent.includes('56×56')")
    assert page.get_by_text("Size is not used: the pallets make the grid 56×56 cells.").is_visible()
    assert page.get_by_label("size", exact=True).input_value() == "50x50", "the file's value, kept for pallets off"
    edit(page, lambda: page.get_by_label("pallets", exact=True).fill("off"))
    assert page.locator("#grid-note").is_hidden()
    # An empty size under pallets is greyed out, as the pallet keys without.
    edit(page, lambda: page.get_by_label("pallets", exact=True).fill("5x5"))
    edit(page, lambda: page.get_by_label("size", exact=True).fill(""))
    assert page.get_by_label("size", exact=True).is_disabled()
    save(page)
    assert page.locator("#status").inner_text().startswith("saved")
    edit(page, lambda: page.get_by_label("block size", exact=True).fill("0.2"))
    assert page.locator("#unsaved").is_visible() and not page.locator("#status").inner_text().startswith("saved")


# What must never reach the page (crates/rse-edit/src/words.rs holds the
# same list for the server's own test of every scheme fault).
NOT_THE_USERS_WORDS = {
    " --": "a command-line flag",
    "rse-gen ": "a command",
    "`# ": "scheme-file syntax",
    "..=": "Rust range syntax",
    "18446744073709551615": "an integer type's bound",
    "os error": "a system error's text",
    "entity not found": "a system error's text",
    "No such file": "a system error's text",
    "Permission denied": "a system error's text",
    "step_height": "a key's spelling",
    "pallet_size": "a key's spelling",
    "jobs": "a setting the page does not have",
    "lo..hi": "scheme-file syntax of a range",
    "NXxNY": "scheme-file syntax of a size",
    "≥": "a symbol for a sentence",
}


def messages_on_the_page(page: Page) -> str:
    """Every line of the page that says what went wrong, and the tooltips of
    the fields marked."""
    return page.evaluate(
        "['error', 'status', 'gen-summary', 'gen-check', 'dialog-error', 'stale', 'connection']"
        ".map(id => document.getElementById(id).textContent)"
        ".concat([...document.querySelectorAll('[aria-invalid=true]')].map(e => e.title)).join(' | ')"
    )


def test_every_error_is_said_in_the_users_words_naming_the_control_and_the_fix(editor, page: Page) -> None:
    """Walks the refusals the server can give the page — each scheme field,
    each page control, a preview too large, Save as into a new folder, Open
    of a missing file, a batch too large and one into another scheme's
    folder — and reads every message the page shows: no flag, file syntax,
    Rust range, integer bound or system text, and each names its fix."""
    url, folder = editor
    wait_ready(page, url)
    seen = []

    def said(expect: str) -> None:
        page.wait_for_function(
            "text => ['error', 'status', 'gen-summary', 'dialog-error'].some(id => document.getElementById(id).textContent.includes(text))",
            arg=expect,
        )
        text = messages_on_the_page(page)
        seen.append(text)
        for bad, what in NOT_THE_USERS_WORDS.items():
            assert bad not in text, f"{what} (`{bad}`) on the page: {text}"

    pallets, pallet_size = page.get_by_label("pallets", exact=True), page.get_by_label("pallet size", exact=True)
    edit(page, lambda: pallets.fill("2x3"))
    edit(page, lambda: pallet_size.fill("4"))
    edit(page, lambda: pallets.fill(""))
    said("set pallets (e.g. 2x3), or empty this field")
    edit(page, lambda: pallet_size.fill(""))
    edit(page, lambda: page.get_by_label("x1 range high end of obstacle 3").fill("99"))
    said("must be from 0 to 49")
    edit(page, lambda: page.get_by_label("x1 range high end of obstacle 3").fill("40"))
    edit(page, lambda: page.get_by_label("height range high end of obstacle 1").fill("1"))
    said("swap them")
    edit(page, lambda: page.get_by_label("height range high end of obstacle 1").fill(""))
    edit(page, lambda: page.get_by_label("step height", exact=True).fill("-1"))
    said("step height")
    edit(page, lambda: page.get_by_label("step height", exact=True).fill("0.1"))
    edit(page, lambda: page.get_by_label("notes").fill("size: big"))
    said("reword its start")
    edit(page, lambda: page.get_by_label("notes").fill("fine"))
    # A letter in a number's field, a size in words (once "`a` is not a
    # whole number ≥ 0 or a range lo..hi", and "`si` is not a whole number").
    edit(page, lambda: page.get_by_label("height of obstacle 1", exact=True).fill("a"))
    said("`a` is not a whole number of 0 or more: type one")
    edit(page, lambda: page.get_by_label("height of obstacle 1", exact=True).fill("2"))
    size = page.get_by_label("size", exact=True)
    before = size.input_value()
    edit(page, lambda: size.fill("sixty by forty"))
    said("`sixty by forty` is not a size: type two whole numbers, columns x rows")
    edit(page, lambda: size.fill(before))
    for value, expect in (("-1", "a whole number of 0 or more"), ("99999999999999999999999", "is too large")):
        edit(page, lambda value=value: page.get_by_label("index").fill(value))
        said(expect)
    edit(page, lambda: page.get_by_label("index").fill("0"))
    edit(page, lambda: page.get_by_label("size", exact=True).fill("5000x5000"))
    said("Generate writes worlds of any size")

    # A batch larger than any machine's memory: refused before it starts.
    edit(page, lambda: page.get_by_label("size", exact=True).fill("10000x10000"))
    page.get_by_label("output folder").fill(str(folder / "huge"))
    page.get_by_role("button", name="Generate").click()
    said("use a smaller grid or fewer targets")
    assert not (folder / "huge").exists() or not any((folder / "huge").iterdir())
    edit(page, lambda: page.get_by_label("size", exact=True).fill("50x50"))

    # Another scheme's worlds in the output folder: a new folder is offered.
    page.get_by_label("output folder").fill(str(folder / "worlds"))
    generate(page, "worlds written")
    edit(page, lambda: page.get_by_label("height of obstacle 1", exact=True).fill("3"))
    page.get_by_role("button", name="Generate").click()
    said("choose another output folder")
    page.get_by_role("button", name=f"Write into {folder / 'worlds-2'} instead").click()
    gen_summary_says(page, "worlds written")
    assert (folder / "worlds-2").is_dir() and page.get_by_label("output folder").input_value() == str(folder / "worlds-2")

    # Open of a file that is not there, then Save as into a new folder.
    page.get_by_role("button", name="Save", exact=True).click()
    # Saved before Open: an Open while the save is on its way asks about
    # the edits not yet saved, as it should (a loaded machine showed it).
    page.wait_for_function("document.getElementById('status').textContent.startsWith('saved')")
    page.get_by_role("button", name="Open path").click()
    page.get_by_label("file path").fill(str(folder / "missing.csv"))
    page.get_by_role("button", name="OK").click()
    said("there is no such file or folder")
    page.get_by_role("button", name="Save as").click()
    page.get_by_label("file path").fill(str(folder / "new" / "mine.csv"))
    page.get_by_role("button", name="OK").click()
    dialog = page.get_by_role("dialog", name="Create the folder?")
    assert f"The folder {folder / 'new'} does not exist" in dialog.inner_text()
    dialog.get_by_role("button", name="Cancel").click()
    said("does not exist")
    assert not (folder / "new").exists(), "nothing made without asking"
    page.get_by_role("button", name="Save as").click()
    page.get_by_label("file path").fill(str(folder / "new" / "mine.csv"))
    page.get_by_role("button", name="OK").click()
    page.get_by_role("dialog", name="Create the folder?").get_by_role("button", name="Create folder").click()
    page.wait_for_function("document.getElementById('status').textContent.startsWith('saved')")
    assert (folder / "new" / "mine.csv").is_file()
    assert len(seen) == 14, seen
