"""The house rules of size: every module of lightsail_mbs at most 450 lines (coefficient tables excepted),
every function at most 100 lines (numba-compiled kernels excepted).

KNOWN_LONG_MODULES and KNOWN_LONG_FUNCTIONS list what is over the limit while it is being shrunk; each
test also fails when a listed entry is within the limit again, so that the lists only ever shrink.
"""

import ast
from pathlib import Path

import pytest

import lightsail_mbs

PACKAGE = Path(lightsail_mbs.__file__).parent
MODULE_LINES = 450
FUNCTION_LINES = 100

# modules over MODULE_LINES by nature: path (relative to the package) -> why
TABLES = {
    "solvers/reduced/tableaus.py": "the Butcher tableaus and dense-output coefficients of DOP853 and Radau IIA, "
    "digits copied from their published sources",
}

# over the limit while they are being shrunk (remove an entry when its module or function is within it)
KNOWN_LONG_MODULES: set = set()
KNOWN_LONG_FUNCTIONS: set = set()

COMPILERS = ("njit", "jit")  # @njit, @numba.njit, @jit, with or without arguments


def modules():
    return sorted(str(p.relative_to(PACKAGE)) for p in PACKAGE.rglob("*.py"))


def lines(name: str) -> int:
    return len((PACKAGE / name).read_text().splitlines())


def compiled(function: ast.FunctionDef) -> bool:
    """True if a decorator of `function` is a numba compiler (COMPILERS)."""
    for decorator in function.decorator_list:
        target = decorator.func if isinstance(decorator, ast.Call) else decorator
        name = target.attr if isinstance(target, ast.Attribute) else getattr(target, "id", None)
        if name in COMPILERS:
            return True
    return False


def functions(name: str):
    """(qualified name, line count, compiled) of every function and method of a module, nested ones too."""
    found = []

    def visit(node, prefix):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)):
                qualified = f"{prefix}{child.name}"
                found.append((qualified, child.end_lineno - child.lineno + 1, compiled(child)))
                visit(child, f"{qualified}.")
            elif isinstance(child, ast.ClassDef):
                visit(child, f"{prefix}{child.name}.")
            else:
                visit(child, prefix)

    visit(ast.parse((PACKAGE / name).read_text()), "")
    return found


def long_functions() -> dict[str, int]:
    """'module:qualified name' -> lines of every function over FUNCTION_LINES that is not compiled."""
    return {
        f"{name}:{qualified}": length
        for name in modules()
        for qualified, length, is_compiled in functions(name)
        if length > FUNCTION_LINES and not is_compiled
    }


def test_modules_are_at_most_450_lines():
    over = {name: lines(name) for name in modules() if lines(name) > MODULE_LINES}
    new = {name: n for name, n in over.items() if name not in TABLES and name not in KNOWN_LONG_MODULES}
    assert not new, f"modules over {MODULE_LINES} lines: {new}; split them along a seam"


def test_functions_are_at_most_100_lines_unless_compiled():
    new = {name: n for name, n in long_functions().items() if name not in KNOWN_LONG_FUNCTIONS}
    assert not new, f"functions over {FUNCTION_LINES} lines: {new}; split them"


def test_the_lists_of_exceptions_are_not_stale():
    existing = set(modules())
    assert set(TABLES) <= existing and KNOWN_LONG_MODULES <= existing
    assert all(lines(name) > MODULE_LINES for name in TABLES), "a table within the limit needs no exception"
    shrunk = {name for name in KNOWN_LONG_MODULES if lines(name) <= MODULE_LINES}
    assert not shrunk, f"within {MODULE_LINES} lines now, remove from KNOWN_LONG_MODULES: {sorted(shrunk)}"
    fixed = KNOWN_LONG_FUNCTIONS - set(long_functions())
    assert not fixed, f"within {FUNCTION_LINES} lines now (or gone), remove from KNOWN_LONG_FUNCTIONS: {sorted(fixed)}"


@pytest.mark.parametrize(
    "source, expected",
    [
        ("@njit\ndef f():\n    pass\n", True),
        ("@njit(cache=True)\ndef f():\n    pass\n", True),
        ("@numba.njit(cache=True)\ndef f():\n    pass\n", True),
        ("@numba.jit\ndef f():\n    pass\n", True),
        ("@property\ndef f():\n    pass\n", False),
        ("@functools.cache\ndef f():\n    pass\n", False),
        ("def f():\n    pass\n", False),
    ],
)
def test_compiled_kernels_are_recognised_by_their_decorator(source, expected):
    assert compiled(ast.parse(source).body[0]) is expected
