"""The type stubs (hullcheck/_hullcheck.pyi) describe the compiled module: the same public
names, the same members per class and the same parameter names per function; and every public
function and class has a docstring for help()."""

import ast
import inspect
import pathlib
import re

import pytest

import hullcheck
from hullcheck import _hullcheck

STUB = pathlib.Path(hullcheck.__file__).with_name("_hullcheck.pyi")
ALIASES = {"ArrayLike", "FloatArray", "BoolArray", "PoseLike", "ShapeLike"}


def stub_tree():
    return ast.parse(STUB.read_text())


def stub_functions(body):
    """name -> list of parameter-name lists (one per overload), without self."""
    out = {}
    for node in body:
        properties = [d for d in getattr(node, "decorator_list", [])
                      if isinstance(d, ast.Name) and d.id == "property"]
        if isinstance(node, ast.FunctionDef) and not properties:
            names = [a.arg for a in node.args.args if a.arg != "self"]
            out.setdefault(node.name, []).append(names)
    return out


def stub_members(cls):
    names = set()
    for node in cls.body:
        if isinstance(node, ast.FunctionDef):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
    return names


def public(obj):
    return {n for n in dir(obj) if not n.startswith("_")}


def runtime_parameters(function):
    """Parameter-name lists of a pybind11 function, from its signature lines."""
    out = []
    for line in (function.__doc__ or "").splitlines():
        m = re.match(rf"^(?:\d+\. )?{function.__name__}\((.*)\) ->", line)
        if m:
            names = re.findall(r"(\w+): ", m.group(1))
            out.append([n for n in names if n != "self"])
    return out


def test_top_level_names_match():
    tree = stub_tree()
    names = {n.name for n in tree.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    assert names == public(_hullcheck)


def test_functions_have_the_stub_parameters():
    for name, overloads in stub_functions(stub_tree().body).items():
        runtime = runtime_parameters(getattr(_hullcheck, name))
        assert runtime == overloads, name


def test_classes_have_the_stub_members():
    for cls in (n for n in stub_tree().body if isinstance(n, ast.ClassDef)):
        runtime = getattr(_hullcheck, cls.name)
        if cls.name == "InputError":
            continue
        expected = stub_members(cls) - {"__init__", "__len__"}
        members = public(runtime)
        if isinstance(getattr(runtime, "__members__", None), dict):  # pybind11 enums
            members = set(runtime.__members__) | {"name", "value"}
        assert members == expected, cls.name
        for fname, overloads in stub_functions(cls.body).items():
            if fname.startswith("__") and fname != "__init__":
                continue
            assert runtime_parameters(getattr(runtime, fname)) == overloads, f"{cls.name}.{fname}"


@pytest.mark.parametrize("name", sorted(hullcheck.__all__))
def test_public_names_have_docstrings(name):
    obj = getattr(hullcheck, name)
    doc = inspect.getdoc(obj) or ""
    if inspect.isclass(obj) and name != "InputError":
        assert obj.__doc__, name
    assert len(doc) > 20, name


def test_package_exports_everything():
    assert public(_hullcheck) <= set(hullcheck.__all__)
    assert "benchmark" in hullcheck.__all__
