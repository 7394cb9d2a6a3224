# SPDX-License-Identifier: MIT
"""Writes the type stubs of the sewerplan module (python/sewerplan/__init__.pyi) from the built
module: the signatures pybind11 writes at the head of each docstring, and inspect's for the Python
functions. Run it after a change of the module's API, then read the diff (tests/python/
test_stubs.py fails until the stubs agree with the module):

    PYTHONPATH=build/release/python /usr/bin/python3 python/tools/make_stubs.py \\
        > python/sewerplan/__init__.pyi
"""
import inspect
import re
import sys

import sewerplan

HEADER = '''# SPDX-License-Identifier: MIT
# Type stubs of the sewerplan module, written by python/tools/make_stubs.py from the built module
# and checked against it by tests/python/test_stubs.py (docs/python.md).
from typing import (Any, Callable, ClassVar, Dict, Iterable, Iterator, List, Optional, Tuple, Union,
                    overload)
import os

__version__: str
has_gis: bool
'''

SIGNATURE = re.compile(r"^(?:\d+\. )?(\w+)\((.*)\)(?: -> (.+))?$")


def clean_type(text):
    text = text.replace("sewerplan.", "")
    text = re.sub(r"\bfunction\b", "Callable[[Event], None]", text).replace("os.PathLike", "Union[str, os.PathLike[str]]")
    text = re.sub(r"\bIterator\b(?!\[)", "Iterator[Step]", text)
    return {"iterator": "Iterator[Any]", "handle": "Any", "object": "Any", "slice": "slice",
            "list": "List[Any]", "dict": "Dict[str, Any]"}.get(text, text)


def split_params(text):
    """Splits a parameter list at its top-level commas."""
    params, depth, current = [], 0, ""
    for ch in text:
        depth += ch in "[(" and 1 or 0
        depth -= ch in "])" and 1 or 0
        if ch == "," and depth == 0:
            params.append(current.strip())
            current = ""
        else:
            current += ch
    if current.strip():
        params.append(current.strip())
    return params


def stub_params(text, method):
    out = []
    for i, param in enumerate(split_params(text)):
        if param in ("*", "/"):
            out.append(param)
            continue
        name, _, rest = param.partition(":")
        annotation, has_default, default = rest.partition("=")
        name, annotation = name.strip(), clean_type(annotation.strip())
        if default.strip() == "None" and not annotation.startswith("Optional["):
            annotation = f"Optional[{annotation}]"
        if method and i == 0:
            out.append("self")
            continue
        item = f"{name}: {annotation}" if annotation else name
        out.append(item + (" = ..." if has_default else ""))
    return ", ".join(out)


def pybind_signatures(function):
    """(name, params, return) of each overload, from pybind11's docstring."""
    found = []
    doc = function.__doc__ or ""
    overloaded = "Overloaded function." in doc
    for line in doc.splitlines():
        if overloaded and not re.match(r"^\d+\. ", line.strip()):
            continue  # the overloads' common "name(*args, **kwargs)"
        match = SIGNATURE.match(line.strip())
        if match and match.group(1) == function.__name__:
            found.append(match.groups())
    return found


def function_stub(function, indent="", method=False, static=False):
    lines = []
    if not hasattr(function, "__code__"):  # pybind11
        signatures = pybind_signatures(function)
        for name, params, returns in signatures:
            if len(signatures) > 1:
                lines.append(f"{indent}@overload")
            if static:
                lines.append(f"{indent}@staticmethod")
            returns = clean_type(returns or "None")
            lines.append(f"{indent}def {name}({stub_params(params, method)}) -> {returns}: ...")
        return lines
    signature = inspect.signature(function)
    params, star_done = [], False
    for param in signature.parameters.values():
        if param.kind is param.KEYWORD_ONLY and not star_done:
            params.append("*")
            star_done = True
        text = param.name
        if param.annotation is not param.empty:
            text += ": " + annotation_text(param.annotation)
        if param.default is not param.empty:
            text += " = ..."
        params.append(text)
    returns = annotation_text(signature.return_annotation)
    text = f"({', '.join(params)}) -> {returns}"
    return [f"{indent}def {function.__name__}{text}: ..."]


def annotation_text(annotation):
    if annotation is inspect.Signature.empty:
        return "Any"
    if annotation is None:
        return "None"
    if annotation is dict:
        return "Dict[str, Any]"
    if isinstance(annotation, type):
        return annotation.__name__
    text = str(annotation).replace("typing.", "").replace("sewerplan.", "")
    return re.sub(r"\bdict\b(?!\[)", "Dict[str, Any]", text)


def property_type(prop):
    signatures = pybind_signatures_for_property(prop.fget)
    return clean_type(signatures or "Any")


def pybind_signatures_for_property(fget):
    for line in (fget.__doc__ or "").splitlines():
        match = re.match(r"^\((?:self|arg0): [\w.]+\) -> (.+)$", line.strip())
        if match:
            return match.group(1)
    return None


def class_stub(name, cls):
    if issubclass(cls, BaseException):
        base = cls.__bases__
        names = ", ".join(b.__name__ for b in base)
        if name == "Error":
            return [f"class Error(RuntimeError):", "    code: Optional[str]",
                    "    exit_code: Optional[int]", "    message: str",
                    "    diagnostics: List[Diagnostic]", ""]
        return [f"class {name}({names}): ...", ""]
    lines = [f"class {name}:"]
    if hasattr(cls, "__members__"):  # a pybind11 enum
        for member in cls.__members__:
            lines.append(f"    {member}: ClassVar[{name}]")
        lines.append(f"    __members__: ClassVar[Dict[str, {name}]]")
        lines += ["    def __init__(self, value: int) -> None: ...",
                  "    def __int__(self) -> int: ...", "    def __index__(self) -> int: ...",
                  "    @property", "    def name(self) -> str: ...",
                  "    @property", "    def value(self) -> int: ..."]
    for attr, member in vars(cls).items():
        if attr.startswith("__") and attr not in ("__init__", "__len__", "__getitem__",
                                                  "__iter__", "__bool__", "__eq__"):
            continue
        if attr.startswith("_") and not attr.startswith("__"):
            continue
        if hasattr(cls, "__members__") and (attr in cls.__members__ or attr in (
                "__init__", "name", "value")):
            continue
        if isinstance(member, property):
            lines.append("    @property")
            lines.append(f"    def {attr}(self) -> {property_type(member)}: ...")
            if member.fset is not None:
                lines.append(f"    @{attr}.setter")
                lines.append(f"    def {attr}(self, value: {property_type(member)}) -> None: ...")
        elif isinstance(member, staticmethod):
            lines += function_stub(getattr(cls, attr), "    ", static=True)
        elif callable(member):
            if attr == "__init__" and "No constructor" in (member.__doc__ or ""):
                continue
            lines += function_stub(member, "    ", method=True)
    if len(lines) == 1:
        lines.append("    ...")
    return lines + [""]


def main():
    out = [HEADER]
    names = sorted(n for n in dir(sewerplan) if not n.startswith("_"))
    classes = [n for n in names if isinstance(getattr(sewerplan, n), type)]
    # Base classes before their subclasses (a stub reads them in order).
    ordered = []
    while len(ordered) < len(classes):
        for n in classes:
            cls = getattr(sewerplan, n)
            if n not in ordered and all(b.__name__ in ordered or b.__module__ == "builtins"
                                        for b in cls.__bases__ if b.__name__ != "pybind11_object"):
                ordered.append(n)
    for n in ordered:
        out += class_stub(n, getattr(sewerplan, n))
    for n in names:
        value = getattr(sewerplan, n)
        if callable(value) and not isinstance(value, type):
            out += function_stub(value)
    print("\n".join(out).rstrip() + "\n", end="")


if __name__ == "__main__":
    sys.exit(main())
