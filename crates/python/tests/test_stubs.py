"""The type stubs (crates/python/flexdem.pyi, installed as flexdem/__init__.pyi with
py.typed) cover every public name of the module, with the runtime's parameters."""

import ast
import inspect
import pathlib

import pytest

import flexdem

STUB = pathlib.Path(__file__).resolve().parents[1] / "flexdem.pyi"
# keyword arguments spelled out in the stub, `**load` at run time
SPELLED_OUT = {"add_load"}


def public(names):
    return {n for n in names if not n.startswith("_")}


def stub_tree():
    return ast.parse(STUB.read_text())


def stub_class(tree, name):
    [cls] = [n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == name]
    return cls


def test_the_stubs_are_installed_with_py_typed():
    package = pathlib.Path(flexdem.__file__).parent
    assert (package / "py.typed").is_file()
    assert (package / "__init__.pyi").read_text() == STUB.read_text()


def test_every_public_name_has_a_stub():
    tree = stub_tree()
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
    # `flexdem.flexdem` is the extension module that maturin's __init__.py imports from
    runtime = public(dir(flexdem)) - {"flexdem"}
    assert public(names) == runtime
    assert "__version__" in names

    methods = {n.name: n for n in stub_class(tree, "Simulation").body
               if isinstance(n, ast.FunctionDef)}
    assert public(methods) == public(dir(flexdem.Simulation))


def stub_parameters(function):
    a = function.args
    positional = [p.arg for p in a.posonlyargs + a.args]
    return positional, [p.arg for p in a.kwonlyargs]


@pytest.mark.parametrize("name", sorted(public(dir(flexdem.Simulation))))
def test_stub_signatures_match_the_runtime(name):
    [method] = [n for n in stub_class(stub_tree(), "Simulation").body
                if isinstance(n, ast.FunctionDef) and n.name == name]
    decorators = {d.id for d in method.decorator_list if isinstance(d, ast.Name)}
    attribute = inspect.getattr_static(flexdem.Simulation, name)
    if "property" in decorators:
        assert inspect.isgetsetdescriptor(attribute), name
        return
    if name in SPELLED_OUT:
        return
    positional, keyword = stub_parameters(method)
    runtime = inspect.signature(getattr(flexdem.Simulation, name))
    kinds = inspect.Parameter
    rt_positional = [p.name for p in runtime.parameters.values()
                     if p.kind in (kinds.POSITIONAL_ONLY, kinds.POSITIONAL_OR_KEYWORD)]
    rt_keyword = [p.name for p in runtime.parameters.values() if p.kind == kinds.KEYWORD_ONLY]
    if "staticmethod" in decorators:
        assert isinstance(attribute, staticmethod), name
    else:
        positional = positional[1:]  # self
        rt_positional = [p for p in rt_positional if p != "self"]
    assert (positional, keyword) == (rt_positional, rt_keyword), name


def test_module_function_signatures_match_the_runtime():
    functions = {n.name: n for n in stub_tree().body if isinstance(n, ast.FunctionDef)}
    for name, function in functions.items():
        runtime = inspect.signature(getattr(flexdem, name))
        assert stub_parameters(function)[0] == list(runtime.parameters), name
