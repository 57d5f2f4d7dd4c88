"""The package itself: a lazy ``import flyopt``, public names that are what they say, no import cycles."""

import ast
import subprocess
import sys
from pathlib import Path

from sources import parsed

import flyopt

SRC = Path(flyopt.__file__).resolve().parent


def test_import_flyopt_loads_no_heavy_dependency():
    code = (
        "import sys, flyopt; heavy = [m for m in ('pandas', 'pyarrow', 'casadi', 'scipy', 'matplotlib', 'pint') "
        "if m in sys.modules]; print(','.join(heavy))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == ""


def test_public_names_are_the_functions_not_modules():
    import flyopt.studies.sweep  # noqa: F401  (importing the module must not shadow the function)

    assert callable(flyopt.sweep) and flyopt.sweep.__module__ == "flyopt.studies.sweep"
    assert callable(flyopt.design_scene) and callable(flyopt.solve)
    for name in flyopt.__all__:
        assert getattr(flyopt, name) is not None


def _imports(path, modules):
    """Modules of flyopt that a file imports, at its top level or inside a function, if it runs.

    A lazy import inside a function still makes the two modules depend on each
    other, so it counts. ``from package import module`` counts as an import of the module, not of the
    package's ``__init__`` (which Python runs first, but which only gathers names).
    """
    tree = parsed(path)
    found = set()
    # an import under ``if TYPE_CHECKING:`` never runs (flyopt/__init__.py names the public types so)
    skipped = {
        id(inner)
        for node in ast.walk(tree)
        if isinstance(node, ast.If) and getattr(node.test, "id", getattr(node.test, "attr", None)) == "TYPE_CHECKING"
        for inner in ast.walk(node)
    }
    for node in ast.walk(tree):
        if id(node) in skipped:
            continue
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("flyopt"):
            submodules = {f"{node.module}.{a.name}" for a in node.names} & set(modules)
            found.update(submodules or {node.module})
        elif isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name.startswith("flyopt"))
    return found


def test_no_import_cycle_between_modules():
    """Imports form a DAG (before, flyopt.batch and flyopt.optimize imported each other)."""
    modules = {}
    for path in SRC.rglob("*.py"):
        parts = path.relative_to(SRC.parent).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        modules[name] = path
    graph = {name: {m for m in _imports(path, modules) if m in modules and m != name} for name, path in modules.items()}
    cycles = []
    state = {}

    def visit(node, stack):
        state[node] = "open"
        for nxt in sorted(graph[node]):
            if state.get(nxt) == "open":
                cycles.append(stack[stack.index(nxt) :] + [nxt])
            elif nxt not in state:
                visit(nxt, stack + [nxt])
        state[node] = "done"

    for name in sorted(graph):
        if name not in state:
            visit(name, [name])
    assert not cycles, cycles


def test_type_checking_imports_name_the_same_api():
    """flyopt/__init__.py names each public type twice (the lazy table and, for type checkers, an
    import under TYPE_CHECKING): the two must name the same objects in the same modules."""
    tree = ast.parse((SRC / "__init__.py").read_text())
    block = next(n for n in tree.body if isinstance(n, ast.If) and getattr(n.test, "id", None) == "TYPE_CHECKING")
    typed = {}
    for node in block.body:
        if isinstance(node, ast.ImportFrom):
            for alias in node.names:
                assert alias.asname == alias.name, f"{alias.name} must be imported as itself to be re-exported"
                typed[alias.name] = node.module
    assert typed == flyopt._API


def test_no_module_imports_a_private_name_of_another():
    """A leading underscore means "this module's own": what another module needs is public where it is owned.

    (A private *module* whose names are public, such as ``flyopt._toml``, is imported by name as usual.)
    """
    reached = []
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(parsed(path)):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("flyopt"):
                reached += [
                    f"{path.relative_to(SRC)}:{node.lineno} imports {node.module}.{alias.name}"
                    for alias in node.names
                    if alias.name.startswith("_") and not alias.name.startswith("__")
                ]
    assert not reached, "\n".join(reached)


def _public_functions(tree, module):
    """(name, node) of every public function and method of a module (methods of public classes only)."""

    def visit(node, prefix, public):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.ClassDef):
                yield from visit(child, f"{prefix}{child.name}.", public and not child.name.startswith("_"))
            elif isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                dunder = child.name.startswith("__") and child.name.endswith("__")
                if public and (dunder or not child.name.startswith("_")):
                    yield f"{module}:{prefix}{child.name}", child, bool(prefix)

    yield from visit(tree, "", True)


def test_every_public_function_is_annotated():
    """Issue 24: every public function, method and property says what it takes and gives (mypy then
    checks its body); a private module's functions count when its names are public (``_toml``)."""
    missing = []
    for path in sorted(SRC.rglob("*.py")):
        module = str(path.relative_to(SRC))
        for name, node, is_method in _public_functions(parsed(path), module):
            args = node.args.posonlyargs + node.args.args + node.args.kwonlyargs
            if is_method and args and args[0].arg in ("self", "cls"):
                args = args[1:]
            args += [a for a in (node.args.vararg, node.args.kwarg) if a is not None]
            if any(a.annotation is None for a in args) or (node.returns is None and node.name != "__init__"):
                missing.append(name)
    assert not missing, f"{len(missing)} public functions without annotations: {missing[:20]}"
