"""Every global option of a scheme, walked through every skin that carries
it: the constructor's keyword, `Scheme.replace`, the scheme file both ways,
the world's `rse.json`, the templates' context, the framework adapters'
tile fitting, the command line's flag; and a value of each outside its
range, which every skin refuses naming the key. The keys and a value of each other
than its default come from the library itself (`Scheme().fields()`, the
examples of rse-core's table of keys), so a key added to core that a skin
drops fails here by name, with no edit of this file. (The editor's schema
lists every key by the same table: rse-edit's `api::tests`.)"""

import json
import subprocess
from pathlib import Path

import pytest
import rse
import rse._rse as _rse
from conftest import rse_gen_path
from rse._adapters import tiles

# A value of each key other than its default, as Python gives it and as a
# scheme file writes it: the example rse-core's table declares with the key
# (read back through the scheme file, with pallets on for the pallet keys).
def _sample(key: str, text: str) -> tuple[object, str]:
    pallets = "# pallets: 1x1\n" if key in NEEDS_PALLETS else ""
    value = rse.Scheme.from_csv(f"{pallets}# {key}: {text}\ntype\n").fields()[key]
    return value, text


KEYS = [key for key in rse.Scheme().fields() if key != "obstacles"]
# The pallet keys need pallets on; fitting a tile sets the grid itself.
NEEDS_PALLETS = {"pallet_size", "pallet_boundary"}
SAMPLES: dict[str, tuple[object, str]] = {key: _sample(key, text) for key, _, text, _ in _rse._global_keywords()}
# A value of each key outside its range, as a scheme file writes it: the
# one rse-core's table declares with the key's range (keys any value of
# whose type will do have none).
OUTSIDE: dict[str, str] = {key: outside for key, _, _, outside in _rse._global_keywords() if outside is not None}
THE_GRID = {"size", "pallets"} | NEEDS_PALLETS


def scheme_with(key: str) -> rse.Scheme:
    value, _ = SAMPLES[key]
    base: dict[str, object] = {"pallets": (2, 1)} if key in NEEDS_PALLETS else {}
    return rse.Scheme(**base, **{key: value})


def test_every_key_has_a_sample_value() -> None:
    missing = [key for key in KEYS if key not in SAMPLES]
    assert not missing, f"keys with no example in rse-core's table: {missing}"
    assert set(SAMPLES) == set(KEYS), f"keys no longer in the library: {set(SAMPLES) - set(KEYS)}"
    defaults = rse.Scheme().fields()
    for key, (value, _) in SAMPLES.items():
        assert defaults[key] != value, f"{key}: the sample is the default"


@pytest.mark.parametrize("key", KEYS)
def test_the_constructor_and_replace_carry_it(key: str) -> None:
    value, _ = SAMPLES[key]
    assert scheme_with(key).fields()[key] == value
    base: dict[str, object] = {"pallets": (2, 1)} if key in NEEDS_PALLETS else {}
    assert rse.Scheme(**base).replace(**{key: value}).fields()[key] == value


@pytest.mark.parametrize("key", KEYS)
def test_the_scheme_file_carries_it_both_ways(key: str) -> None:
    scheme = scheme_with(key)
    _, text = SAMPLES[key]
    csv = scheme.to_csv()
    assert f"# {key}: {text}\n" in csv, csv
    assert rse.Scheme.from_csv(csv).fields() == scheme.fields()


@pytest.mark.parametrize("key", KEYS)
def test_rse_json_records_it(key: str, tmp_path: Path) -> None:
    _, text = SAMPLES[key]
    rse.write_worlds(scheme_with(key), tmp_path, amount=1, targets="obj")
    manifest = json.loads((tmp_path / "world_0000" / "rse.json").read_text())
    assert f"# {key}: {text}\n" in manifest["scheme"], manifest["scheme"]


# How the templates' `scheme` value prints the pallet keys' samples (inside
# `scheme.pallets`); minijinja prints the others as Python's repr does.
IN_TEMPLATES = {"pallets": "'count': (2, 1)", "pallet_size": "'size': 7", "pallet_boundary": "'boundary': False"}


@pytest.mark.parametrize("key", KEYS)
def test_the_templates_see_it(key: str, tmp_path: Path) -> None:
    folder = tmp_path / "templates" / "urdf"
    folder.mkdir(parents=True)
    (folder / "scheme.txt.j2").write_text("{% for key, value in scheme|items %}{{ key }}={{ value }}\n{% endfor %}")
    rse.write_worlds(scheme_with(key), tmp_path / "out", amount=1, targets="urdf", template=tmp_path / "templates")
    text = (tmp_path / "out" / "world_0000" / "urdf" / "scheme.txt").read_text()
    seen = dict(line.split("=", 1) for line in text.splitlines())
    value, _ = SAMPLES[key]
    holder = "pallets" if key in IN_TEMPLATES else key
    assert holder in seen, f"the templates' `scheme` has no {holder}: {text}"
    assert IN_TEMPLATES.get(key, repr(value)) in seen[holder], text


@pytest.mark.parametrize("key", sorted(set(KEYS) - THE_GRID))
def test_a_fitted_tile_keeps_it(key: str) -> None:
    value, _ = SAMPLES[key]
    # A size the scheme does not span, so the tile is refitted.
    fitted = tiles.fit(scheme_with(key), (3.0, 2.0))
    assert fitted.grid != scheme_with(key).grid
    assert fitted.fields()[key] == value


@pytest.mark.parametrize("key", KEYS)
def test_the_command_line_has_its_flag(key: str) -> None:
    usage = subprocess.run(
        [str(rse_gen_path()), "batch", "--help"], check=True, capture_output=True, text=True
    ).stdout
    flag = "--" + key.replace("_", "-")
    assert f"{flag} " in usage or f"{flag}\n" in usage, f"rse-gen batch has no {flag}"


@pytest.mark.parametrize("key", sorted(set(KEYS) - {"amount", "seed"}))
def test_the_command_lines_flag_reaches_the_scheme(key: str, tmp_path: Path) -> None:
    # amount and seed are the batch's own flags (how many worlds, which
    # seed), recorded as the batch, not as the scheme's text.
    _, text = SAMPLES[key]
    scheme = tmp_path / "s.csv"
    scheme.write_text(rse.Scheme(pallets=(2, 1) if key in NEEDS_PALLETS else None).to_csv())
    flag = "--" + key.replace("_", "-")
    subprocess.run(
        [str(rse_gen_path()), "batch", str(scheme), "-o", str(tmp_path / "out"), "--target", "obj", flag, text],
        check=True,
        capture_output=True,
    )
    manifest = json.loads((tmp_path / "out" / "world_0000" / "rse.json").read_text())
    assert f"# {key}: {text}\n" in manifest["scheme"], manifest["scheme"]


def _python_value(key: str, text: str) -> object:
    """`text` as Python gives the key, by the key's type (core's parser
    would refuse it: it is outside the range)."""
    kind = {name: kind for name, kind, *_ in _rse._global_keywords()}[key]
    if "_Pair" in kind:
        return tuple(int(n) for n in text.split("x"))
    if kind == "_Int":
        return int(text)
    if kind == "_Float":
        return float(text)
    if kind.startswith("Union[tuple[_Float"):
        return tuple(float(c) for c in text.split())
    raise AssertionError(f"{key}: no Python form for type {kind}")


def test_most_keys_have_a_range() -> None:
    assert {"size", "pallets", "pallet_size", "block_size", "step_height", "base", "color", "ground_color", "amount"} <= set(OUTSIDE)


def _refusal_names(key: str, error: BaseException) -> None:
    assert key in str(error), f"{key}: the refusal does not name it: {error}"


@pytest.mark.parametrize("key", sorted(OUTSIDE))
def test_the_constructor_and_replace_refuse_a_value_outside_its_range(key: str) -> None:
    value = _python_value(key, OUTSIDE[key])
    base: dict[str, object] = {"pallets": (2, 1)} if key in NEEDS_PALLETS else {}
    with pytest.raises(ValueError) as refused:
        rse.Scheme(**base, **{key: value})
    _refusal_names(key, refused.value)
    with pytest.raises(ValueError) as refused:
        rse.Scheme(**base).replace(**{key: value})
    _refusal_names(key, refused.value)


@pytest.mark.parametrize("key", sorted(OUTSIDE))
def test_the_scheme_file_refuses_a_value_outside_its_range(key: str) -> None:
    pallets = "# pallets: 1x1\n" if key in NEEDS_PALLETS else ""
    with pytest.raises(ValueError) as refused:
        rse.Scheme.from_csv(f"{pallets}# {key}: {OUTSIDE[key]}\ntype\n")
    _refusal_names(key, refused.value)


@pytest.mark.parametrize("key", sorted(OUTSIDE))
def test_a_world_whose_record_holds_a_value_outside_its_range_fails_check(key: str, tmp_path: Path) -> None:
    base: dict[str, object] = {"pallets": (2, 1)} if key in NEEDS_PALLETS else {}
    rse.write_worlds(rse.Scheme(**base), tmp_path, amount=1, targets="obj")
    record = tmp_path / "world_0000" / "rse.json"
    manifest = json.loads(record.read_text())
    manifest["scheme"] = f"# {key}: {OUTSIDE[key]}\n" + manifest["scheme"]
    record.write_text(json.dumps(manifest))
    report = rse.check(tmp_path / "world_0000")
    assert not report.ok
    faults = [fault for world in report.worlds for fault in world.faults] + report.batch_faults
    _refusal_names(key, "\n".join(str(fault) for fault in faults))


@pytest.mark.parametrize("key", sorted(set(OUTSIDE) - {"amount", "seed"}))
def test_the_command_line_refuses_a_value_outside_its_range(key: str, tmp_path: Path) -> None:
    scheme = tmp_path / "s.csv"
    scheme.write_text(rse.Scheme(pallets=(2, 1) if key in NEEDS_PALLETS else None).to_csv())
    flag = "--" + key.replace("_", "-")
    run = subprocess.run(
        [str(rse_gen_path()), "batch", str(scheme), "-o", str(tmp_path / "out"), "--target", "obj", f"{flag}={OUTSIDE[key]}"],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 2, run.stderr
    assert flag in run.stderr, run.stderr
    assert not (tmp_path / "out").exists(), "nothing written"


def test_a_colour_is_drawn_by_the_simulators(tmp_path: Path) -> None:
    """`color` reaches MuJoCo's material and USD's display colour as the
    simulators load them, and `check` rebuilds the world from its record."""
    import mujoco
    from pxr import Usd, UsdGeom

    scheme = rse.Scheme.load(Path(__file__).parents[2] / "schemes" / "six_obstacles.csv").replace(color=(0.1, 0.2, 0.3))
    rse.write_worlds(scheme, tmp_path, amount=1, targets="mujoco,usd")
    world = tmp_path / "world_0000"
    model = mujoco.MjModel.from_xml_path(str(world / "mujoco" / "rse.xml"))
    rgba = model.mat("rse_wood").rgba
    assert [round(float(c), 6) for c in rgba] == [0.1, 0.2, 0.3, 1.0]
    stage = Usd.Stage.Open(str(world / "usd" / "terrain.usda"))
    colors = UsdGeom.Mesh(stage.GetPrimAtPath("/terrain")).GetDisplayColorAttr().Get()
    assert [round(float(c), 6) for c in colors[0]] == [0.1, 0.2, 0.3]
    assert rse.check(world).ok
    assert json.loads((world / "rse.json").read_text())["globals"]["color"] == [0.1, 0.2, 0.3]


def test_the_ground_colour_is_drawn_by_the_simulators(tmp_path: Path) -> None:
    """`ground_color` reaches the ground as MuJoCo (its floor's checker, two
    shades around the colour), usd-core and PyBullet load it; the terrain
    keeps its own colour, and `check` rebuilds the world from its record."""
    import mujoco
    import pybullet
    from pxr import Usd, UsdGeom

    scheme = rse.Scheme.load(Path(__file__).parents[2] / "schemes" / "six_obstacles.csv").replace(ground_color=(0.3, 0.5, 0.98))
    rse.write_worlds(scheme, tmp_path, amount=1, targets="mujoco,usd,urdf")
    world = tmp_path / "world_0000"
    spec = mujoco.MjSpec.from_file(str(world / "mujoco" / "rse.xml"))
    grid = spec.texture("grid")
    assert [round(float(c), 6) for c in grid.rgb1] == [0.35, 0.55, 1.0], "lightened, within 0 to 1"
    assert [round(float(c), 6) for c in grid.rgb2] == [0.25, 0.45, 0.93]
    model = spec.compile()
    assert model.mat_texid[model.mat("grid").id].max() == model.tex("grid").id
    stage = Usd.Stage.Open(str(world / "usd" / "rse.usda"))
    ground = UsdGeom.Cube(stage.GetPrimAtPath("/World/ground")).GetDisplayColorAttr().Get()
    assert [round(float(c), 6) for c in ground[0]] == [0.3, 0.5, 0.98]
    client = pybullet.connect(pybullet.DIRECT)
    try:
        body = pybullet.loadURDF(str(world / "urdf" / "rse.urdf"), useFixedBase=True, physicsClientId=client)
        shapes = pybullet.getVisualShapeData(body, physicsClientId=client)
        colours = {round(s[7][0], 6): [round(c, 6) for c in s[7]] for s in shapes}
        assert colours[0.3] == [0.3, 0.5, 0.98, 1.0], shapes
        assert colours[0.72] == [0.72, 0.58, 0.42, 1.0], "the terrain keeps its colour"
    finally:
        pybullet.disconnect(client)
    assert rse.check(world).ok


# Every world option (rse-world's table): its keyword, type as the stubs
# write it, an example other than its default and a value every writer
# refuses, as text.
WORLD_OPTIONS = {name: (kind, example, outside) for name, kind, example, outside in _rse._world_keywords()}
# What an option needs beside it to be taken: an oversample is the height
# field's.
WORLD_NEEDS = {"oversample": {"mujoco_collider": "hfield"}}


def _world_value(name: str, text: str) -> object:
    return int(text) if WORLD_OPTIONS[name][0] == "int" else text


def _world_keywords(name: str, text: str) -> dict[str, object]:
    return {"targets": "obj,mujoco", **WORLD_NEEDS.get(name, {}), name: _world_value(name, text)}


def _flags(keywords: dict[str, object]) -> list[str]:
    flag = {name: "--" + name.replace("_", "-") for name in WORLD_OPTIONS} | {"targets": "--target"}
    return [f"{flag[name]}={value}" for name, value in keywords.items()]


def test_every_world_option_is_in_every_writers_signature() -> None:
    import inspect

    scheme = rse.Scheme(size=(4, 4))
    writers = [rse.write_worlds, rse.write_world, rse.Atlas([scheme], rows=1, cols=1).write]
    for writer in writers:
        parameters = inspect.signature(writer).parameters
        for name in WORLD_OPTIONS:
            assert parameters[name].kind is inspect.Parameter.KEYWORD_ONLY, (writer, name)
            assert parameters[name].default is None, (writer, name)


@pytest.mark.parametrize("name", sorted(WORLD_OPTIONS))
def test_a_world_option_reaches_rse_json_from_python_and_the_command_line_alike(name: str, tmp_path: Path) -> None:
    """The example of each option, given to `write_worlds`, `write_world`
    and `rse-gen batch`, writes the same world, byte for byte, and not the
    world of the default."""
    scheme_file = tmp_path / "s.csv"
    scheme_file.write_text(rse.Scheme(size=(6, 5)).to_csv())
    scheme = rse.Scheme.load(scheme_file)
    keywords = _world_keywords(name, WORLD_OPTIONS[name][1])
    rse.write_worlds(scheme, tmp_path / "py", amount=1, **keywords)
    rse.write_world(scheme.generate(0, 0), tmp_path / "one" / "world_0000", **keywords)
    # The same keywords but this option's: its default.
    rse.write_worlds(scheme, tmp_path / "default", amount=1, **{k: v for k, v in keywords.items() if k != name})
    subprocess.run(
        [str(rse_gen_path()), "batch", str(scheme_file), "-o", str(tmp_path / "cli"), "--amount", "1", *_flags(keywords)],
        check=True,
        capture_output=True,
    )
    record = (tmp_path / "py" / "world_0000" / "rse.json").read_text()
    assert (tmp_path / "cli" / "world_0000" / "rse.json").read_text() == record
    assert (tmp_path / "one" / "world_0000" / "rse.json").read_text() == record
    assert (tmp_path / "default" / "world_0000" / "rse.json").read_text() != record, f"{name}: its example is the default"


@pytest.mark.parametrize("name", sorted(WORLD_OPTIONS))
def test_every_writer_refuses_a_world_option_outside_what_it_takes(name: str, tmp_path: Path) -> None:
    scheme_file = tmp_path / "s.csv"
    scheme_file.write_text(rse.Scheme(size=(6, 5)).to_csv())
    scheme = rse.Scheme.load(scheme_file)
    keywords = _world_keywords(name, WORLD_OPTIONS[name][2])
    writers = [
        lambda: rse.write_worlds(scheme, tmp_path / "py", amount=1, **keywords),
        lambda: rse.write_world(scheme.generate(0, 0), tmp_path / "py", **keywords),
        lambda: rse.Atlas([scheme], rows=1, cols=1).write(tmp_path / "py", **keywords),
    ]
    for write in writers:
        with pytest.raises(ValueError) as refused:
            write()
        _refusal_names(name, refused.value)
    run = subprocess.run(
        [str(rse_gen_path()), "batch", str(scheme_file), "-o", str(tmp_path / "cli"), *_flags(keywords)],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 2, run.stderr
    assert _flags({name: ""})[0].rstrip("=") in run.stderr, run.stderr
    assert not (tmp_path / "py").exists() and not (tmp_path / "cli").exists(), "nothing written"


# Every per-env option of `EnvTerrains` (rse-core's table): its keyword,
# type as the stubs write it, default, example, a value it refuses (or
# None) and what it needs beside it, as text.
ENV_OPTIONS = {row[0]: row[1:] for row in _rse._env_keywords()}


def _env_value(name: str, text: str) -> object:
    kind = ENV_OPTIONS[name][0]
    return int(text) if kind == "int" else float(text) if kind == "float" else text


def _env_keywords(name: str, text: str) -> dict[str, object]:
    needs = ENV_OPTIONS[name][4]
    beside = dict([needs.split("=", 1)]) if needs else {}
    return {**beside, name: _env_value(name, text)}


def _pool_state(envs: rse.EnvTerrains) -> tuple[object, ...]:
    return (envs.layout, envs.field_shape, envs.oversample, envs.samples.tobytes(), envs.origins.tobytes(), envs.difficulty.tobytes())


def test_every_env_option_is_in_the_signature() -> None:
    import inspect

    parameters = inspect.signature(rse.EnvTerrains).parameters
    for name in ENV_OPTIONS:
        assert parameters[name].kind is inspect.Parameter.KEYWORD_ONLY, name


@pytest.mark.parametrize("name", sorted(ENV_OPTIONS))
def test_an_env_option_changes_the_envs_and_one_outside_its_range_is_refused(name: str) -> None:
    scheme = rse.Scheme.load(Path(__file__).parents[2] / "schemes" / "six_obstacles.csv")
    _, _, example, outside, needs = ENV_OPTIONS[name]
    beside = _env_keywords(name, example)
    del beside[name]
    default = rse.EnvTerrains(scheme, 9, **beside)
    given = rse.EnvTerrains(scheme, 9, **_env_keywords(name, example))
    assert _pool_state(given) != _pool_state(default), f"{name}={example} changes nothing"
    if outside is not None:
        with pytest.raises(ValueError) as refused:
            rse.EnvTerrains(scheme, 4, **_env_keywords(name, outside))
        _refusal_names(name, refused.value)


@pytest.mark.parametrize("name", sorted(WORLD_OPTIONS))
def test_the_templates_see_every_world_option(name: str, tmp_path: Path) -> None:
    """A user's template prints `options`: at its example the option shows,
    as it differs from the default (the oversample inside its collider's
    record), and every option is there at its default too."""
    folder = tmp_path / "templates" / "urdf"
    folder.mkdir(parents=True)
    (folder / "options.txt.j2").write_text("{% for key, value in options|items %}{{ key }}={{ value }}\n{% endfor %}")
    keywords = _world_keywords(name, WORLD_OPTIONS[name][1])
    printed = {}
    for run, given in (("example", keywords), ("default", {k: v for k, v in keywords.items() if k != name})):
        targets = ",".join(sorted(set(str(given.get("targets", "obj")).split(",")) | {"urdf"}))
        rse.write_worlds(rse.Scheme(size=(4, 3)), tmp_path / run, amount=1, template=tmp_path / "templates", **{**given, "targets": targets})
        printed[run] = (tmp_path / run / "world_0000" / "urdf" / "options.txt").read_text()
    assert printed["example"] != printed["default"], f"{name}: the templates do not see it\n{printed['example']}"
    shown = dict(line.split("=", 1) for line in printed["default"].splitlines())
    assert {"targets", "mesh", "mujoco_collider"} <= set(shown), shown
