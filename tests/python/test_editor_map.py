"""The editor's map and 3D view in a real Chromium: the map is `preview.png`
pixel for pixel, a click places a peak and a drag draws a wall on the cells
pointed at, points and ranges move by dragging (and by the keyboard), the
readout and legend say what rse-core generated, and the 3D view shares the
map's colours, has no holes, shows pallet frames and turns by keyboard."""

import io
from pathlib import Path

import numpy as np
import pytest
import rse
from conftest import rse_gen_release_path
from editor_harness import cell, cell_point, drag_on_map, edit, running_editor, table, wait_ready
from PIL import Image
from playwright.sync_api import Page

pytestmark = pytest.mark.thirdparty

REPO = Path(__file__).resolve().parents[2]


def map_pixels(page: Page) -> np.ndarray:
    """The map canvas's own pixels (not a screenshot: no scaling), RGB."""
    width, height, data = page.evaluate(
        "(() => { const c = document.getElementById('map'); const d = c.getContext('2d').getImageData(0, 0, c.width, c.height);"
        " return [c.width, c.height, Array.from(d.data)]; })()"
    )
    return np.array(data, dtype=np.uint8).reshape(height, width, 4)[:, :, :3]


def heights_on_page(page: Page) -> np.ndarray:
    """The heights of the map shown, (ny, nx)."""
    nx, ny, heights = page.evaluate("[window.rseEditor.preview.nx, window.rseEditor.preview.ny, Array.from(window.rseEditor.preview.heights)]")
    return np.array(heights).reshape(ny, nx)


@pytest.mark.parametrize(
    "scheme_text",
    [
        (REPO / "schemes/six_obstacles.csv").read_text(),
        "# pallets: 2x3\n# pallet_size: 6\ntype,height,angle,x1,y1\nrandom,3,,,\npeak,9,30,7,10\n",
        "# size: 300x120\ntype,height\nrandom,300\n",  # two bytes a cell, one pixel a cell
    ],
    ids=["six obstacles", "pallets", "tall and wide"],
)
def test_the_map_is_preview_png_pixel_for_pixel(tmp_path: Path, page: Page, scheme_text: str) -> None:
    scheme_file = tmp_path / "scheme.csv"
    scheme_file.write_text(scheme_text)
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        wait_ready(page, url)
        edit(page, lambda: page.get_by_label("index").fill("3"))
        png = rse.Scheme.load(scheme_file).generate(index=3).preview()
        got = map_pixels(page)
        # The PNG's map, above its legend.
        want = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))[: got.shape[0]]
        assert got.shape == want.shape
        assert np.array_equal(got, want), f"{(got != want).any(axis=2).sum()} pixels differ"


def test_a_drag_moves_the_peak_and_draws_the_new_wall_on_the_cells_pointed_at(tmp_path: Path, page: Page) -> None:
    scheme_file = tmp_path / "start.csv"
    scheme_file.write_text("# size: 20x16\ntype,height,angle,x1,y1\npeak,4,90,1,1\n")
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        wait_ready(page, url)
        # A click on empty ground moves nothing (it once moved the selection there).
        page.mouse.click(*cell_point(page, 5, 7))
        assert table(page)[0] == {"type": "peak", "height.lo": "4", "angle.lo": "90", "x1.lo": "1", "y1.lo": "1"}
        # A drag of the peak's point (90°: one block) takes it to the cell let go on.
        drag_on_map(page, (1, 1), (5, 7))
        page.wait_for_function("window.rseEditor.preview.heights[7 * 20 + 5] === 4")
        assert table(page)[0] == {"type": "peak", "height.lo": "4", "angle.lo": "90", "x1.lo": "5", "y1.lo": "7"}
        heights = heights_on_page(page)
        assert heights[7, 5] == 4 and heights.sum() == 4, "the block is where the drag ended, and only there"

        # A new wall, drawn by a drag from (2, 3) to (15, 3).
        edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())
        edit(page, lambda: page.get_by_label("type of obstacle 2").select_option("wall"))
        edit(page, lambda: page.get_by_label("height of obstacle 2", exact=True).fill("3"))
        edit(page, lambda: page.get_by_label("angle of obstacle 2", exact=True).fill("90"))
        before_drag = table(page)
        drag_on_map(page, (2, 3), (15, 3))
        page.wait_for_function("!window.rseEditor.state.rows[1] || window.rseEditor.state.rows[1]['x2.lo'] === '15'")
        page.wait_for_function(f"window.rseEditor.preview.heights[3 * 20 + 15] === 3")
        assert {k: table(page)[1][k] for k in ("x1.lo", "y1.lo", "x2.lo", "y2.lo")} == {"x1.lo": "2", "y1.lo": "3", "x2.lo": "15", "y2.lo": "3"}
        heights = heights_on_page(page)
        assert (heights[3, 2:16] == 3).all() and heights[3, :2].sum() == 0 and heights[3, 16:].sum() == 0
        assert heights[2].sum() == 0 and heights[4].sum() == 0, "a 90° wall is one cell wide"
        # The whole drag is one edit.
        edit(page, lambda: page.get_by_role("button", name="Undo").click())
        assert table(page) == before_drag
        edit(page, lambda: page.get_by_role("button", name="Redo").click())
        assert table(page)[1]["x2.lo"] == "15"

        # Drag the peak's point (it is on another row: the drag selects it).
        drag_on_map(page, (5, 7), (9, 10))
        page.wait_for_function("window.rseEditor.state.rows[0]['x1.lo'] === '9'")
        assert (table(page)[0]["x1.lo"], table(page)[0]["y1.lo"]) == ("9", "10")
        assert page.evaluate("window.rseEditor.state.selected") == 0

        # A random range is a rectangle: dragging it moves both ends, kept on the grid.
        edit(page, lambda: cell(page, 0, "x1").fill("4"))
        edit(page, lambda: cell(page, 0, "x1", "hi").fill("6"))
        edit(page, lambda: cell(page, 0, "y1").fill("4"))
        edit(page, lambda: cell(page, 0, "y1", "hi").fill("6"))
        drag_on_map(page, (5, 5), (10, 8))
        page.wait_for_function("window.rseEditor.state.rows[0]['x1.lo'] === '9'")
        row = table(page)[0]
        assert (row["x1.lo"], row["x1.hi"], row["y1.lo"], row["y1.hi"]) == ("9", "11", "7", "9")
        drag_on_map(page, (10, 8), (19, 15))
        page.wait_for_function("window.rseEditor.state.rows[0]['x1.hi'] === '19'")
        row = table(page)[0]
        assert (row["x1.lo"], row["x1.hi"], row["y1.lo"], row["y1.hi"]) == ("17", "19", "13", "15")
        assert page.locator("#error").inner_text() == ""


def test_a_new_obstacle_is_placed_by_the_next_click_wherever_others_lie(tmp_path: Path, page: Page) -> None:
    """On a busy map (six obstacles, their random ranges covering the
    middle) a new pit starts valid in the middle, and the next click places
    it where it is, and says so first: it never selects another obstacle
    there. By the keyboard, Enter next to another's point places it too."""
    scheme_file = tmp_path / "six.csv"
    scheme_file.write_text((REPO / "schemes/six_obstacles.csv").read_text())
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        wait_ready(page, url)
        edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())
        edit(page, lambda: page.get_by_label("type of obstacle 7").select_option("pit"))
        assert table(page)[6] == {"type": "pit", "height.lo": "1", "angle.lo": "45", "x1.lo": "25", "y1.lo": "25"}, "valid from the start"
        assert page.locator("#error").inner_text() == ""
        edit(page, lambda: page.get_by_label("angle of obstacle 7", exact=True).fill("60"))
        assert page.evaluate("window.rseEditor.state.selected") == 6
        # (20, 30) lies inside the peak's, the wall's and the other pit's ranges.
        page.mouse.move(*cell_point(page, 20, 30))
        hint = page.locator("#map-hint")
        assert hint.inner_text().startswith("Click: place pit 7 here"), hint.inner_text()
        assert page.locator("#map-overlay").evaluate("e => e.style.cursor") == "crosshair"
        edit(page, lambda: page.mouse.click(*cell_point(page, 20, 30)))
        assert (table(page)[6]["x1.lo"], table(page)[6]["y1.lo"]) == ("20", "30")
        assert page.evaluate("window.rseEditor.state.selected") == 6, "the pit stays selected"
        assert table(page)[2]["x1.lo"] == "10" and table(page)[2]["x1.hi"] == "40", "the peak did not move"
        # Placed: a click there now picks what is under the pointer.
        page.mouse.move(*cell_point(page, 20, 30))
        assert hint.inner_text().startswith("Click: drag to move pit 7"), hint.inner_text()

        # The keyboard: a second new pit, Enter on the cell next to the long
        # pit's end (25, 0) places it there.
        edit(page, lambda: page.get_by_role("button", name="Copy obstacle").click())
        assert "click on the map to place it" in page.locator("#status").inner_text()
        page.get_by_role("application", name="top-down map").focus()  # the cursor starts mid-grid, (25, 25)
        page.keyboard.press("ArrowRight")
        for _ in range(24):
            page.keyboard.press("ArrowDown")
        assert hint.inner_text().startswith("Click: place pit 8 here"), hint.inner_text()
        edit(page, lambda: page.keyboard.press("Enter"))
        page.keyboard.press("Enter")
        assert (table(page)[7]["x1.lo"], table(page)[7]["y1.lo"]) == ("26", "1")
        assert (table(page)[5]["x1.lo"], table(page)[5]["y1.lo"]) == ("25", "0"), "the long pit stayed"
        assert page.evaluate("window.rseEditor.state.selected") == 7


def test_pointing_picks_what_is_under_the_pointer(tmp_path: Path, page: Page) -> None:
    """A busy map of 12 obstacles: a click exactly on another obstacle's
    point picks it though the selected one's point is a block away (the
    selection's handle once won); a wall is picked by the middle of its
    line and dragged whole; clicking again on one spot goes through every
    obstacle under the pointer in turn; a plain click on empty ground moves
    nothing; picking records no Undo step."""
    scheme_file = tmp_path / "busy.csv"
    rows = ["random,1,,,,,", "wall,3,90,4,10,20,10", "long_pit,2,90,10,2,10,8"]
    rows += [f"peak,4,45,{x},{y},," for x, y in [(30, 20), (31, 21), (5, 30), (6, 30), (15, 25), (15, 25), (35, 5), (36, 6), (20, 30)]]
    scheme_file.write_text("# size: 40x36\ntype,height,angle,x1,y1,x2,y2\n" + "\n".join(rows) + "\n")
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        wait_ready(page, url)
        selected = lambda: page.evaluate("window.rseEditor.state.selected")  # noqa: E731
        undo = page.get_by_role("button", name="Undo")
        # Peak 4 at (30, 20) selected; a click exactly on peak 5's point (31, 21).
        page.mouse.click(*cell_point(page, 30, 20))
        assert selected() == 3
        page.mouse.click(*cell_point(page, 31, 21))
        assert selected() == 4, "the point clicked on wins over the selected one a block away"
        # A wall by the middle of its line, dragged whole: both ends move.
        drag_on_map(page, (12, 10), (12, 14))
        page.wait_for_function("window.rseEditor.state.rows[1]['y1.lo'] === '14'")
        wall = table(page)[1]
        assert (wall["x1.lo"], wall["y1.lo"], wall["x2.lo"], wall["y2.lo"]) == ("4", "14", "20", "14")
        assert selected() == 1
        # Two peaks on one spot, (15, 25): click, click again: each in turn.
        page.mouse.click(*cell_point(page, 15, 25))
        first = selected()
        page.mouse.click(*cell_point(page, 15, 25))
        second = selected()
        page.mouse.click(*cell_point(page, 15, 25))
        assert {first, second} == {7, 8} and selected() == first, (first, second, selected())
        # Empty ground: nothing moves, nothing is selected anew.
        before = table(page)
        page.mouse.click(*cell_point(page, 25, 33))
        assert table(page) == before and selected() == first
        assert page.locator("#map-hint").inner_text().startswith("Click: nothing here")
        # Picks recorded nothing: one Undo takes back the wall's drag.
        edit(page, lambda: undo.click())
        assert table(page)[1]["y1.lo"] == "10" and undo.is_disabled()


def test_the_map_zooms_and_pans_by_wheel_buttons_and_keys(tmp_path: Path, page: Page) -> None:
    """A 120×80 grid is some 4 px a block: the map zooms to 24 px a block
    and more (wheel over it, the buttons, + and − on it), pans by a drag on
    empty ground and with the keyboard's cursor, and clicks still land on
    the cell under the pointer."""
    scheme_file = tmp_path / "wide.csv"
    scheme_file.write_text("# size: 120x80\ntype,height,angle,x1,y1\nrandom,1,,,\npeak,5,45,60,40\n")
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        wait_ready(page, url)
        level = page.locator("#zoom-level")
        assert level.inner_text().startswith("whole grid")
        box = page.locator(".map-box").bounding_box()
        block = lambda: page.locator("#map-overlay").bounding_box()["width"] / 120  # noqa: E731
        assert block() < 8
        for _ in range(6):
            page.get_by_role("button", name="Zoom in").click()
        assert block() >= 24, f"{block()} px a block"
        assert "px a block" in level.inner_text() and level.inner_text().startswith("zoom")
        # The peak, zoomed: dragged by its point to a cell clicked on.
        centre = page.locator("#map-overlay").bounding_box()
        assert centre["x"] < box["x"], "zoomed about the middle"
        page.mouse.move(*cell_point(page, 60, 40))
        assert page.locator("#map-hint").inner_text().startswith("Click: select peak 2")
        drag_on_map(page, (60, 40), (62, 41))
        page.wait_for_function("window.rseEditor.state.rows[1]['x1.lo'] === '62'")
        assert table(page)[1]["y1.lo"] == "41"
        # A drag on empty ground pans.
        before = page.locator("#map-overlay").bounding_box()
        page.mouse.move(box["x"] + 20, box["y"] + 20)
        page.mouse.down()
        page.mouse.move(box["x"] + 120, box["y"] + 60, steps=5)
        page.mouse.up()
        after = page.locator("#map-overlay").bounding_box()
        assert after["x"] > before["x"] and after["y"] > before["y"], (before, after)
        assert table(page)[1]["x1.lo"] == "62", "panning moved nothing"
        # The keys: − out, 0 the whole grid, + in; the wheel.
        page.get_by_role("application", name="top-down map").focus()
        page.keyboard.press("0")
        assert level.inner_text().startswith("whole grid")
        page.keyboard.press("+")
        assert level.inner_text().startswith("zoom")
        page.keyboard.press("-")
        page.keyboard.press("-")
        assert level.inner_text().startswith("whole grid")
        page.mouse.move(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
        page.mouse.wheel(0, -600)
        assert block() > 8
        page.get_by_role("button", name="Whole grid").click()
        assert level.inner_text().startswith("whole grid")


def test_the_keyboard_draws_on_the_map(tmp_path: Path, page: Page) -> None:
    scheme_file = tmp_path / "start.csv"
    scheme_file.write_text("# size: 20x16\ntype,height,angle,x1,y1,x2,y2\nrandom,1,,,,,\n")
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        wait_ready(page, url)
        edit(page, lambda: page.get_by_label("type of obstacle 1").select_option("wall"))
        edit(page, lambda: page.get_by_label("height of obstacle 1", exact=True).fill("2"))
        edit(page, lambda: page.get_by_label("angle of obstacle 1", exact=True).fill("90"))
        page.get_by_role("application", name="top-down map").focus()  # the cursor starts mid-grid, (10, 8)
        for key, times in [("ArrowRight", 7), ("ArrowUp", 5)]:
            for _ in range(times):
                page.keyboard.press(key)
        assert page.locator("#readout").inner_text().startswith("column 17, row 13")
        page.keyboard.press("Enter")  # the new wall's first end …
        for _ in range(10):
            page.keyboard.press("ArrowDown")
        edit(page, lambda: page.keyboard.press("Enter"))  # … and its second
        row = table(page)[0]
        assert (row["x1.lo"], row["y1.lo"], row["x2.lo"], row["y2.lo"]) == ("17", "13", "17", "3")
        heights = heights_on_page(page)
        assert (heights[3:14, 17] == 2).all() and heights[:, :17].sum() == 0, "the wall is where the keys drew it"
        # Enter on its line grabs it whole; the arrows move it.
        page.keyboard.press("ArrowUp")
        page.keyboard.press("Enter")
        for _ in range(3):
            page.keyboard.press("ArrowLeft")
        edit(page, lambda: page.keyboard.press("Enter"))
        row = table(page)[0]
        assert (row["x1.lo"], row["y1.lo"], row["x2.lo"], row["y2.lo"]) == ("14", "13", "14", "3")


def test_the_readout_and_legend_say_what_rse_core_generated(tmp_path: Path, page: Page) -> None:
    scheme_file = REPO / "schemes/six_obstacles.csv"
    heights = rse.Scheme.load(scheme_file).generate().heights
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        wait_ready(page, url)
        for x, y in [(3, 4), (25, 30), (49, 0)]:
            page.mouse.move(*cell_point(page, x, y))
            h = int(heights[y, x])
            want = f"column {x}, row {y}: height {h} {'step' if h == 1 else 'steps'} ({round(h * 0.1, 4):g} m)"
            page.wait_for_function(f"document.getElementById('readout').textContent === {want!r}")
        legend = page.locator("#legend li").all_inner_texts()
        lo, hi = int(heights.min()), int(heights.max())
        assert legend[0] == f"{lo} steps, {lo * 0.1:g} m" and legend[-1] == f"{hi} steps, {hi * 0.1:g} m", legend
        assert len(legend) == hi - lo + 1


def screenshot(page: Page, selector: str) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(page.locator(selector).screenshot())).convert("RGB")).astype(int)


def test_the_3d_view_shares_the_maps_colours_has_no_holes_shows_frames_and_turns_by_keyboard(tmp_path: Path, page: Page) -> None:
    # Floor 0 (blue), a wall of 2 (red), frames (wood), nothing in between:
    # the map's scale has no green, so green in 3D is another scale.
    scheme_file = tmp_path / "frames.csv"
    scheme_file.write_text("# pallets: 2x2\n# pallet_size: 8\ntype,height,angle,x1,y1,x2,y2\nwall,2,90,1,5,17,5\n")
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        page.goto(url)
        page.wait_for_function("window.rseEditor?.views >= 1")
        flat = screenshot(page, "#map")
        view = screenshot(page, "#blocks")
        r, g, b = view[..., 0], view[..., 1], view[..., 2]
        red = (r > 150) & (g < 60) & (b < 60)
        blue = (b > 150) & (r < 60) & (g < 60)
        wood = (r > g + 15) & (g > b + 15) & (r < 170) & (r > 60)
        green = (g > r + 40) & (g > b + 40)
        assert red.sum() > 100 and blue.sum() > 1000 and wood.sum() > 200, (red.sum(), blue.sum(), wood.sum())
        assert green.sum() == 0, f"{green.sum()} green pixels: the 3D view is on another scale than the map"
        fr, fg, fb = flat[..., 0], flat[..., 1], flat[..., 2]
        assert ((fg > fr + 40) & (fg > fb + 40)).sum() == 0, "nor is there green on the map"
        # No holes: around the grid's centre (the view's centre) every pixel is terrain.
        h, w = view.shape[:2]
        middle = view[h // 2 - 20 : h // 2 + 20, w // 2 - 20 : w // 2 + 20]
        background = (np.abs(middle - np.array([221, 221, 235])).sum(axis=2) < 12).sum()
        assert background == 0, f"{background} background pixels show through the ground"
        # The keyboard turns it.
        page.get_by_role("img", name="3D view of the blocks").focus()
        for _ in range(3):
            page.keyboard.press("ArrowLeft")
        page.keyboard.press("+")
        assert not np.array_equal(screenshot(page, "#blocks"), view)


def test_a_drag_draws_a_flight_of_stairs_corner_to_corner_and_the_map_outlines_it(tmp_path: Path, page: Page) -> None:
    """Stairs are drawn as walls are, by a drag from one corner to the
    other: the flight climbs from the first corner's side, one step every
    tread, and the overlay outlines its rectangle."""
    scheme_file = tmp_path / "start.csv"
    scheme_file.write_text("# size: 20x16\ntype,height,angle,x1,y1\npeak,1,90,19,15\n")
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        wait_ready(page, url)
        edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())
        edit(page, lambda: page.get_by_label("type of obstacle 2").select_option("stairs"))
        edit(page, lambda: page.get_by_label("height of obstacle 2", exact=True).fill("4"))
        assert page.get_by_label("angle of obstacle 2", exact=True).is_disabled(), "stairs have no slope angle"
        assert page.get_by_label("tread of obstacle 2", exact=True).count() == 0, "a flight's tread follows from its run: no column"
        drag_on_map(page, (2, 3), (9, 6))
        page.wait_for_function("window.rseEditor.preview.heights[6 * 20 + 9] === 4")
        assert {k: table(page)[1][k] for k in ("x1.lo", "y1.lo", "x2.lo", "y2.lo")} == {"x1.lo": "2", "y1.lo": "3", "x2.lo": "9", "y2.lo": "6"}
        heights = heights_on_page(page)
        # A run of 8 cells, 4 steps: treads of 2 cells, every row of the flight alike.
        assert (heights[3:7, 2:10] == [1, 1, 2, 2, 3, 3, 4, 4]).all()
        assert heights[2].sum() == 0 and heights[7].sum() == 0 and heights[3:7, 10:].sum() == 0
        # A pyramid with its tread (the column shows with it), on the same rectangle.
        edit(page, lambda: page.get_by_label("type of obstacle 2").select_option("pyramid"))
        assert page.get_by_label("tread of obstacle 2", exact=True).is_enabled()
        assert page.get_by_label("tread of obstacle 1", exact=True).is_disabled(), "the peak leaves it unused"
        edit(page, lambda: page.get_by_label("tread of obstacle 2", exact=True).fill("1"))
        page.wait_for_function("window.rseEditor.preview.heights[4 * 20 + 4] === 2")
        heights = heights_on_page(page)
        assert (heights[3, 2:10] == 1).all() and (heights[4, 3:9] == 2).all()
        assert page.locator("#error").inner_text() == ""
        page.screenshot(path=str(tmp_path / "pyramid.png"))
        # The overlay outlines the rectangle: white pixels on its border cells.
        overlay = page.evaluate(
            "(() => { const c = document.getElementById('map-overlay'); const d = c.getContext('2d').getImageData(0, 0, c.width, c.height);"
            " return [c.width, c.height, Array.from(d.data)]; })()"
        )
        width, height, data = overlay
        alpha = np.array(data, dtype=np.uint8).reshape(height, width, 4)[:, :, 3]
        cp = width // 20
        top, left = (16 - 1 - 6) * cp, 2 * cp  # the rectangle's top-left corner, pixels (north up)
        assert alpha[top, left + 3 * cp] > 0 and alpha[top + 2 * cp, left] > 0, "the outline is drawn"
        # A ramp on the same rectangle: its staircase under the plane, the
        # tread column gone again, the rectangle still outlined.
        edit(page, lambda: page.get_by_label("type of obstacle 2").select_option("ramp"))
        assert page.get_by_label("tread of obstacle 2", exact=True).count() == 0, "a ramp has no tread"
        page.wait_for_function("window.rseEditor.preview.heights[4 * 20 + 9] === 3")
        heights = heights_on_page(page)
        # 8 cells rising 4 steps: floor(i·4/8), every row alike.
        assert (heights[3:7, 2:10] == [0, 0, 1, 1, 2, 2, 3, 3]).all()
        assert page.locator("#error").inner_text() == ""
        # The 3D view gets the ramp to draw as a wedge over its staircase.
        ramps = page.evaluate("window.rseEditor.preview.ramps")
        assert ramps == [{"cells": [2, 3, 9, 6], "along_y": False, "ascending": True, "rise": 4}]
        page.screenshot(path=str(tmp_path / "ramp.png"))
