"""The .pyi stubs name what the module has, with the same arguments, and every call has a docstring."""
import ast
import inspect
import pathlib
import re

import pytest

import vs11
import vs11.irradiance

PACKAGE = pathlib.Path(vs11.__file__).parent


def stub_functions(stub, owner):
    """(qualified name, object in the module, argument names) of every def in a .pyi file."""
    tree = ast.parse((PACKAGE / stub).read_text())
    for node in tree.body:
        members = [(node.name, n) for n in node.body if isinstance(n, ast.FunctionDef)] \
            if isinstance(node, ast.ClassDef) else [(None, node)] if isinstance(node, ast.FunctionDef) else []
        for class_name, function in members:
            if any(isinstance(d, ast.Name) and d.id == "property" for d in function.decorator_list):
                continue
            scope = getattr(owner, class_name) if class_name else owner
            names = [a.arg for a in function.args.args if a.arg not in ("self", "cls")]
            yield "%s.%s" % (class_name or owner.__name__, function.name), getattr(scope, function.name), names


def pybind_arguments(function):
    """The argument names of a pybind11 function, from the signature line its docstring starts with
    (or of a Python function, from its signature)."""
    if inspect.isfunction(function) or inspect.ismethod(function):
        return [name for name in inspect.signature(function).parameters if name != "self"]
    signature = function.__doc__.splitlines()[0]
    inside = signature[signature.index("(") + 1: signature.rindex(") ->")]
    names = [part.split(":")[0].strip() for part in re.split(r",\s*(?![^\[]*\])", inside) if part.strip()]
    return [name for name in names if name != "self"]


@pytest.mark.parametrize("stub,owner", [("__init__.pyi", vs11), ("irradiance.pyi", vs11.irradiance)])
def test_stubs_match_the_module_and_every_call_is_documented(stub, owner):
    checked = 0
    for name, function, stub_names in stub_functions(stub, owner):
        assert pybind_arguments(function) == stub_names, name
        # pybind11's docstrings start with the signature line; a Python function's with its summary.
        python = inspect.isfunction(function) or inspect.ismethod(function)
        description = function.__doc__ if python else function.__doc__.split("\n", 1)[1]
        assert len(description.strip()) > 20, "%s has no docstring" % name
        checked += 1
    assert checked >= 4
