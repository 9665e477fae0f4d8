# The package over the extension (src/python/polarview/__init__.py): the scheme lists from the C++
# table, one scheme-name parser, and the arguments checked before they reach C++.
import pathlib

import numpy as np
import pytest

import polarview as pv
from conftest import asset


def test_the_package_wraps_the_extension():
    assert pathlib.Path(pv.__file__).name == "__init__.py"
    assert pv.Mesh is pv._core.Mesh and pv.Patches is pv._core.Patches
    for name in pv.__all__:
        assert getattr(pv, name).__doc__ if callable(getattr(pv, name)) else getattr(pv, name)


def test_scheme_lists_come_from_the_scheme_table():
    assert pv.SCHEMES == ("cc", "c2ps", "c2ps-u", "rts", "rts-u", "bps")
    assert pv.POLAR_SCHEMES == ("c2ps", "c2ps-u", "rts", "rts-u", "bps")
    rows = {row["name"]: row for row in pv.schemes()}
    assert rows["c2ps-u"]["label"] == "C2PS-U" and rows["c2ps-u"]["uniform_first_step"]
    assert rows["rts"]["min_valence"] == 5 and not rows["cc"]["polar"]


def test_one_parser_takes_every_spelling_the_cli_takes():
    assert [pv.scheme_name(s) for s in ("catmull-clark", "CC", "C2PS-Uniform", "rtsu")] == ["cc", "cc", "c2ps-u", "rts-u"]
    with pytest.raises(ValueError, match=r"unknown scheme 'bps-u' \(cc, c2ps, c2ps-u, rts, rts-u, bps\)"):
        pv.scheme_name("bps-u")
    mesh = pv.load(asset("globe"))
    assert np.array_equal(pv.refine(mesh, "catmull-clark", 1).vertices, pv.refine(mesh, "cc", 1).vertices)


def test_paths_may_be_path_objects():
    assert pv.load(pathlib.Path(asset("default"))).vertex_count == pv.load(asset("default")).vertex_count


@pytest.mark.parametrize("call,message", [
    (lambda m: pv.refine("default.obj"), "mesh must be a polarview.Mesh, not str"),
    (lambda m: pv.refine(m, 3), "scheme must be a str"),
    (lambda m: pv.refine(m, "cc", 2.5), "levels must be an int, not float"),
    (lambda m: pv.refine(m, "cc", True), "levels must be an int, not bool"),
    (lambda m: pv.refine(m, "cc", 1, memory_budget="1G"), "memory_budget must be an int"),
    (lambda m: pv.limit_patches(m, "c2ps", 2, uniform="yes"), "uniform must be a bool"),
    (lambda m: pv.evaluate(m, [0], [[0.0, 0.0]]), "patches must be a polarview.Patches, not Mesh"),
    (lambda m: pv.load(3), "path must be a str or os.PathLike, not int"),
    (lambda m: pv.shape("cap", height=None), "height must be a str, not NoneType"),
])
def test_wrong_types_raise_type_error_naming_the_argument(call, message):
    with pytest.raises(TypeError, match=message):
        call(pv.load(asset("default")))


@pytest.mark.parametrize("call,message", [
    (lambda m: pv.refine(m, "cc", -1), r"levels must be in 0\.\.64"),
    (lambda m: pv.refine(m, "cc", 2**40), "levels = 1099511627776 is out of range"),
    (lambda m: pv.refine(m, "cc", 1, memory_budget=-1), "memory_budget must be a number of bytes >= 0"),
    (lambda m: pv.pole(m, "c2ps", rings=21), r"rings must be in 0\.\.20"),
    (lambda m: pv.pole(m, "catmull-clark"), "pole analysis needs a polar scheme"),
    (lambda m: pv.spectrum("rts", 4), r"rts takes valence 5\.\.64"),
    (lambda m: pv.spectrum("c2ps", 6, steps=0), r"steps must be in 1\.\.12"),
    (lambda m: pv.spectrum("rts", 6, count=0), "count must be at least 1"),
])
def test_values_out_of_range_raise_value_error(call, message):
    with pytest.raises(ValueError, match=message):
        call(pv.load(asset("default")))


def test_numpy_integers_are_ints():
    mesh = pv.load(asset("default"))
    assert pv.refine(mesh, "cc", np.int64(1)).vertex_count == pv.refine(mesh, "cc", 1).vertex_count


def test_save_takes_a_path_like(tmp_path):
    mesh = pv.shape("cube")
    out = tmp_path / "cube.obj"
    mesh.save(out)
    assert pv.load(out).face_count == mesh.face_count
    with pytest.raises(TypeError):
        mesh.save(42)


def test_measure_is_the_cli_report(tmp_path):
    import json
    import os
    import subprocess
    mesh = pv.load(asset("cube_cc2"))
    ours = pv.measure(mesh, scheme="cc", level=2)
    cli = json.loads(subprocess.run([os.environ["POLARVIEW_BIN"], "measure", asset("cube_cc2"), "--scheme", "cc",
                                     "--level", "2", "--json"], check=True, capture_output=True, text=True).stdout)
    assert ours["closed"] and ours["area"] == cli["area"] and ours["volume"] == cli["volume"]
    assert np.array_equal(ours["centroid"], cli["centroid"]) and np.array_equal(ours["inertia"], cli["inertia"])
    assert ours["inertia"].shape == (3, 3)
    cap = pv.measure(pv.load(asset("cap6_saddle")), scheme="rts", level=2)
    assert not cap["closed"] and cap["volume"] is None and cap["area"] > 0
    with pytest.raises(ValueError):
        pv.measure(mesh, points=1)


# --- type stubs (src/python/polarview/*.pyi): the names, parameters and defaults editors see are the
# package's and the extension's own ---

def _stub_tree(name):
    import ast
    return ast.parse((pathlib.Path(pv.__file__).parent / name).read_text())


def _stub_parameters(node):
    """(name, default source or None) of a stub function's parameters, self left out."""
    import ast
    args = node.args
    positional = args.args
    defaults = [None] * (len(positional) - len(args.defaults)) + [ast.literal_eval(d) for d in args.defaults]
    return [(a.arg, d) for a, d in zip(positional, defaults) if a.arg != "self"]


def _runtime_parameters(function):
    """The same for a Python function, or a pybind11 function from its signature line."""
    import inspect
    try:
        signature = inspect.signature(function)
        return [(p.name, None if p.default is inspect.Parameter.empty else p.default)
                for p in signature.parameters.values() if p.name != "self"]
    except ValueError:  # pybind11: "name(a: T, b: T = default) -> R"
        import ast
        line = function.__doc__.split("\n")[0]
        tree = ast.parse("def f(" + line[line.index("(") + 1:line.rindex(")")] + "): pass").body[0]
        return _stub_parameters(tree)


@pytest.mark.parametrize("stub, module", [("__init__.pyi", pv), ("_core.pyi", pv._core)])
def test_type_stubs_match_the_package(stub, module):
    import ast
    tree = _stub_tree(stub)
    functions = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    public = {n for n in dir(module) if not n.startswith("_") and callable(getattr(module, n))
              and not isinstance(getattr(module, n), type(pv))}
    public -= {"Mesh", "Patches"} if module is pv else set()
    public = {n for n in public if getattr(getattr(module, n), "__module__", module.__name__) in (module.__name__, None)
              or module is pv._core}
    assert set(functions) - {"Mesh", "Patches"} == public - set(classes), (set(functions), public)
    for name, node in functions.items():
        assert _stub_parameters(node) == _runtime_parameters(getattr(module, name)), name
    for name, node in classes.items():
        runtime = getattr(module, name)
        stubbed = {n.name for n in node.body if isinstance(n, ast.FunctionDef) and n.name != "__init__"}
        stubbed |= {n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
        members = {n for n in dir(runtime) if not n.startswith("_")}
        assert stubbed == members, (name, stubbed ^ members)
    if module is pv:
        assert ast.literal_eval(next(n.value for n in ast.parse(pathlib.Path(pv.__file__).read_text()).body
                                     if isinstance(n, ast.Assign) and n.targets[0].id == "__all__")) == pv.__all__
        exported = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
        exported |= {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
        exported |= {a.asname or a.name for n in tree.body if isinstance(n, ast.ImportFrom) for a in n.names}
        assert set(pv.__all__) <= exported, set(pv.__all__) - exported
