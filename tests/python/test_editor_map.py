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
        want = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))
        got = map_pixels(page)
        assert got.shape == want.shape
        assert np.array_equal(got, want), f"{(got != want).any(axis=2).sum()} pixels differ"


def test_a_click_places_the_peak_and_a_drag_draws_the_wall_on_the_cells_pointed_at(tmp_path: Path, page: Page) -> None:
    scheme_file = tmp_path / "start.csv"
    scheme_file.write_text("# size: 20x16\ntype,height,angle,x1,y1\npeak,4,90,1,1\n")
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        wait_ready(page, url)
        # A click places the selected peak (90°: one block) on the cell clicked.
        edit(page, lambda: page.mouse.click(*cell_point(page, 5, 7)))
        assert table(page)[0] == {"type": "peak", "height.lo": "4", "angle.lo": "90", "x1.lo": "5", "y1.lo": "7"}
        heights = heights_on_page(page)
        assert heights[7, 5] == 4 and heights.sum() == 4, "the block is where the click was, and only there"

        # A wall, drawn by a drag from (2, 3) to (15, 3).
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


def test_a_click_places_the_selected_obstacle_even_inside_another_ones_range(tmp_path: Path, page: Page) -> None:
    """On a busy map (six obstacles, their random ranges covering the middle)
    a click places the selected new pit where it is, and says so first;
    another obstacle is picked with Shift; Enter next to another's point
    places too (it no longer grabs the neighbour)."""
    scheme_file = tmp_path / "six.csv"
    scheme_file.write_text((REPO / "schemes/six_obstacles.csv").read_text())
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        wait_ready(page, url)
        edit(page, lambda: page.get_by_role("button", name="Add obstacle").click())
        edit(page, lambda: page.get_by_label("type of obstacle 7").select_option("pit"))
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

        # Shift+click picks the obstacle whose range is there: the peak.
        page.keyboard.down("Shift")
        page.mouse.move(*cell_point(page, 21, 31))
        assert hint.inner_text() == "Click: select peak 3 and move it", hint.inner_text()
        page.mouse.click(*cell_point(page, 21, 31))
        page.keyboard.up("Shift")
        assert page.evaluate("window.rseEditor.state.selected") == 2

        # The keyboard: the pit again, Enter on the cell next to the long
        # pit's end (25, 0) places the pit there.
        page.get_by_label("type of obstacle 7").focus()
        page.get_by_role("application", name="top-down map").focus()  # the cursor starts mid-grid, (25, 25)
        page.keyboard.press("ArrowRight")
        for _ in range(24):
            page.keyboard.press("ArrowDown")
        assert hint.inner_text().startswith("Click: place pit 7 here"), hint.inner_text()
        edit(page, lambda: page.keyboard.press("Enter"))
        page.keyboard.press("Enter")
        assert (table(page)[6]["x1.lo"], table(page)[6]["y1.lo"]) == ("26", "1")
        assert (table(page)[5]["x1.lo"], table(page)[5]["y1.lo"]) == ("25", "0"), "the long pit stayed"
        assert page.evaluate("window.rseEditor.state.selected") == 6


def test_the_keyboard_draws_on_the_map(tmp_path: Path, page: Page) -> None:
    scheme_file = tmp_path / "start.csv"
    scheme_file.write_text("# size: 20x16\ntype,height,angle,x1,y1,x2,y2\nwall,2,90,0,0,1,0\n")
    with running_editor(rse_gen_release_path(), scheme_file, tmp_path) as url:
        wait_ready(page, url)
        page.get_by_role("application", name="top-down map").focus()  # the cursor starts mid-grid, (10, 8)
        for key, times in [("ArrowRight", 7), ("ArrowUp", 5)]:
            for _ in range(times):
                page.keyboard.press(key)
        assert page.locator("#readout").inner_text().startswith("column 17, row 13")
        page.keyboard.press("Enter")  # the wall's first end …
        for _ in range(10):
            page.keyboard.press("ArrowDown")
        edit(page, lambda: page.keyboard.press("Enter"))  # … and its second
        row = table(page)[0]
        assert (row["x1.lo"], row["y1.lo"], row["x2.lo"], row["y2.lo"]) == ("17", "13", "17", "3")
        heights = heights_on_page(page)
        assert (heights[3:14, 17] == 2).all() and heights[0, :2].sum() == 0, "the wall moved to where the keys drew it"


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
