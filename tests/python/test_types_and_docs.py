"""Every public name is documented (help() shows it) and typed in the package's stub."""
import ast
import pathlib

import airr


def test_every_public_function_has_documentation():
    for name in airr.__all__:
        obj = getattr(airr, name)
        if callable(obj):
            assert obj.__doc__ and len(obj.__doc__.strip()) > 30, name
    for method in ("load", "set", "get", "save", "to_json"):
        assert getattr(airr.Scene, method).__doc__, method
    assert "KeyboardInterrupt" in airr.render.__doc__ and "airr render" in airr.render.__doc__


def test_the_stub_names_what_the_package_holds():
    stub = pathlib.Path(airr.__file__).with_name("__init__.pyi")
    tree = ast.parse(stub.read_text())
    typed = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    typed |= {n.target.id for n in tree.body if isinstance(n, ast.AnnAssign)}
    assert typed == set(airr.__all__)
    scene = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Scene")
    methods = {n.name for n in scene.body if isinstance(n, ast.FunctionDef)}
    public = {m for m in dir(airr.Scene) if not m.startswith("_")}
    assert methods == public
    assert (stub.parent / "py.typed").is_file()
