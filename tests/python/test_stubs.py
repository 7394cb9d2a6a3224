# SPDX-License-Identifier: MIT
# The type stubs shipped next to the module (sewerplan/__init__.pyi) against the module itself:
# the same public names, the same members of each class (properties as properties), the same base
# classes, and the same parameters (names, keyword-only, with a default or not) of every function
# and method, each overload included. A change of the API fails here until the stubs follow
# (python/tools/make_stubs.py rewrites them).
import ast
import inspect
import pathlib
import re

import pytest

import sewerplan
from conftest import SOURCE

SHIPPED = pathlib.Path(sewerplan.__file__).with_name("__init__.pyi")
PYBIND_SIGNATURE = re.compile(r"^(?:\d+\. )?(\w+)\((.*)\)(?: -> .+)?$")
KEPT_DUNDERS = {"__init__", "__len__", "__getitem__", "__iter__", "__bool__", "__eq__"}


@pytest.fixture(scope="module")
def stub():
    return ast.parse(SHIPPED.read_text(), str(SHIPPED))


def top_level(tree):
    names = {}
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            names.setdefault(node.name, []).append(node)
        elif isinstance(node, ast.AnnAssign):
            names[node.target.id] = [node]
    return names


def stub_params(node, method):
    """(name, keyword-only, has a default) of each parameter of a stub's def."""
    args = node.args
    positional = args.posonlyargs + args.args
    if method and not is_static(node):
        positional = positional[1:]  # self
    defaults = [False] * (len(positional) - len(args.defaults)) + [True] * len(args.defaults)
    params = [(a.arg, False, d) for a, d in zip(positional, defaults)]
    params += [(a.arg, True, d is not None) for a, d in zip(args.kwonlyargs, args.kw_defaults)]
    return tuple(params)


def is_static(node):
    return any(isinstance(d, ast.Name) and d.id == "staticmethod" for d in node.decorator_list)


def is_property(node):
    return any((isinstance(d, ast.Name) and d.id == "property") for d in node.decorator_list)


def split_params(text):
    params, depth, current = [], 0, ""
    for ch in text:
        depth += (ch in "[(") - (ch in "])")
        if ch == "," and depth == 0:
            params.append(current.strip())
            current = ""
        else:
            current += ch
    return params + ([current.strip()] if current.strip() else [])


def runtime_params(function, method):
    """The parameter lists of a function, one per overload, as stub_params gives them."""
    if hasattr(function, "__code__"):  # Python
        params = list(inspect.signature(function).parameters.values())
        return {tuple((p.name, p.kind is p.KEYWORD_ONLY, p.default is not p.empty)
                      for p in params)}
    doc = function.__doc__ or ""
    overloaded = "Overloaded function." in doc
    found = set()
    for line in doc.splitlines():
        line = line.strip()
        if overloaded and not re.match(r"^\d+\. ", line):
            continue
        match = PYBIND_SIGNATURE.match(line)
        if not match or match.group(1) != function.__name__:
            continue
        params, keyword_only = [], False
        for param in split_params(match.group(2))[1 if method else 0:]:
            if param == "*":
                keyword_only = True
                continue
            params.append((param.split(":")[0].strip(), keyword_only, "=" in param))
        found.add(tuple(params))
    assert found, f"{function.__name__}: no signature in its docstring"
    return found


def test_the_stubs_ship_next_to_the_module():
    assert SHIPPED.read_text() == (SOURCE / "python" / "sewerplan" / "__init__.pyi").read_text()
    assert SHIPPED.with_name("py.typed").exists()


def test_the_same_public_names(stub):
    module = {n for n in dir(sewerplan) if not n.startswith("_")} | {"__version__"}
    assert set(top_level(stub)) == module


def test_the_same_functions_and_parameters(stub):
    for name, nodes in top_level(stub).items():
        value = getattr(sewerplan, name)
        if isinstance(nodes[0], ast.FunctionDef):
            assert callable(value) and not isinstance(value, type), name
            assert {stub_params(n, False) for n in nodes} == runtime_params(value, False), name


def test_the_same_classes_members_and_methods(stub):
    for name, nodes in top_level(stub).items():
        cls = getattr(sewerplan, name)
        if not isinstance(nodes[0], ast.ClassDef):
            continue
        assert isinstance(cls, type), name
        node = nodes[0]
        assert [ast.unparse(b) for b in node.bases] == [
            b.__name__ for b in cls.__bases__ if b.__name__ != "pybind11_object"], name
        if issubclass(cls, BaseException):
            continue
        members = {}
        for item in node.body:
            if isinstance(item, ast.FunctionDef):
                members.setdefault(item.name, []).append(item)
            elif isinstance(item, ast.AnnAssign):
                members[item.target.id] = [item]
        runtime = {a for a in vars(cls) if not a.startswith("_") or a in KEPT_DUNDERS}
        if "__init__(" not in (cls.__init__.__doc__ or ""):
            runtime.discard("__init__")  # no constructor from Python: the base type's slot
        if hasattr(cls, "__members__"):  # an enum: its values, name and value too
            runtime |= set(cls.__members__) | {"name", "value", "__members__"}
        assert set(members) - {"__int__", "__index__"} == runtime, name
        for attr, defs in members.items():
            if not isinstance(defs[0], ast.FunctionDef) or attr in ("__int__", "__index__"):
                continue
            member = inspect.getattr_static(cls, attr)
            where = f"{name}.{attr}"
            assert is_property(defs[0]) == isinstance(member, property), where
            if isinstance(member, property):
                setter = any(isinstance(d, ast.Attribute) and d.attr == "setter"
                             for n in defs for d in n.decorator_list)
                assert setter == (member.fset is not None), where
                continue
            if hasattr(cls, "__members__") and attr == "__init__":
                continue
            static = isinstance(member, staticmethod)
            assert all(is_static(n) == static for n in defs), where
            expected = runtime_params(getattr(cls, attr), method=not static)
            assert {stub_params(n, True) for n in defs} == expected, where


def test_a_stale_stub_is_caught(stub, monkeypatch):
    # The checks see a drift: a parameter renamed in the module, a function added.
    monkeypatch.setattr(sewerplan, "plan", lambda mission, algo="auto": None)
    with pytest.raises(AssertionError):
        test_the_same_functions_and_parameters(stub)
    monkeypatch.setattr(sewerplan, "brand_new", lambda: None, raising=False)
    with pytest.raises(AssertionError):
        test_the_same_public_names(stub)
