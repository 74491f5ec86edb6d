"""The compiled kernels (base.kernels): found in the sources, and never loading machine code built from an old
source; the check runs at the first kernel's definition, not when the package is imported."""

import ast
import os
import subprocess
import sys
from pathlib import Path

import lightsail_mbs
from lightsail_mbs.base import kernels

ROOT = Path(lightsail_mbs.__file__).parent


def cached_kernel_files(root: Path) -> set[str]:
    """The files of root with a function decorated by a call of a ...jit(...) with cache=True (read by ast)."""
    found = set()
    for path in root.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.FunctionDef):
                continue
            for d in node.decorator_list:
                if not isinstance(d, ast.Call):
                    continue
                name = d.func.id if isinstance(d.func, ast.Name) else getattr(d.func, "attr", "")
                cached = any(k.arg == "cache" and getattr(k.value, "value", None) is True for k in d.keywords)
                if name.endswith("jit") and cached:
                    found.add(path.relative_to(root).as_posix())
    return found


def test_kernel_sources_are_the_files_that_define_cached_kernels():
    sources = kernels.kernel_sources()
    assert set(sources) == cached_kernel_files(ROOT) and list(sources) == sorted(sources)
    assert {"model/loads.py", "solvers/reduced/dynamics.py"} <= set(sources)


def test_every_kernel_is_decorated_by_the_checking_njit():
    """No kernel source takes njit from numba itself: the stale-kernel check runs before any kernel exists."""
    for name in kernels.kernel_sources():
        tree = ast.parse((ROOT / name).read_text(encoding="utf-8"))
        froms = {(n.module, a.name) for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) for a in n.names}
        assert ("lightsail_mbs.base.kernels", "njit") in froms, name
        assert not any(module and module.startswith("numba") for module, _ in froms), name


def test_a_new_kernel_file_is_found(tmp_path):
    (tmp_path / "deep" / "er").mkdir(parents=True)
    (tmp_path / "deep" / "er" / "new.py").write_text("@njit(cache=True)\ndef f(x):\n    return x\n")
    (tmp_path / "plain.py").write_text("@njit\ndef g(x):\n    return x\n")
    assert kernels.kernel_sources(tmp_path) == ("deep/er/new.py",)


def test_importing_the_package_leaves_the_kernel_cache_alone():
    """Importing the package, the case and the command does no check; defining the first kernel does it once."""
    probe = (
        "import sys\n"
        "import lightsail_mbs, lightsail_mbs.cli, lightsail_mbs.model.parameters\n"
        "print('lightsail_mbs.base.kernels' in sys.modules)\n"
        "import lightsail_mbs.model.loads\n"
        "from lightsail_mbs.base import kernels\n"
        "print(kernels._checked.cache_info().currsize)\n"
    )
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["False", "1"]


def test_cached_kernels_are_dropped_when_any_kernel_source_changes(tmp_path):
    package = tmp_path / "lightsail_mbs"
    cached = []
    for name in kernels.kernel_sources():
        source = package / name
        source.parent.mkdir(parents=True, exist_ok=True)
        source.write_text("@njit(cache=True)\ndef kernel():\n    return 0\n")
        cached += [source.parent / "__pycache__" / f"{source.stem}.kernel-10.py311.nbi"]
    other = package / "solvers" / "reduced" / "__pycache__" / "solver.cpython-311.pyc"

    def cache_everything():
        for path in [*cached, other]:
            path.parent.mkdir(exist_ok=True)
            path.write_bytes(b"machine code")

    cache_everything()
    kernels.drop_stale_kernels(package)  # no record yet: whatever is cached may be stale
    assert not any(p.exists() for p in cached) and other.exists()
    cache_everything()
    kernels.drop_stale_kernels(package)  # sources unchanged: the cache stays
    assert all(p.exists() for p in cached)
    radau = package / "solvers" / "reduced" / "radau.py"
    stamp = radau.stat().st_mtime_ns
    radau.write_text(radau.read_text())  # the same content written anew (as pip installs it): a new time stamp
    os.utime(radau, ns=(radau.stat().st_atime_ns, stamp + 3_000_000_000))
    kernels.drop_stale_kernels(package)  # content as recorded: its time stamp is restored, the cache stays
    assert radau.stat().st_mtime_ns == stamp and all(p.exists() for p in cached)
    dynamics = package / "solvers" / "reduced" / "dynamics.py"
    dynamics.write_text("@njit(cache=True)\ndef kernel():\n    return 1\n")
    os.utime(dynamics, ns=(dynamics.stat().st_atime_ns, dynamics.stat().st_mtime_ns + 1_000_000_000))
    kernels.drop_stale_kernels(package)  # one source edited: every kernel file's cache goes
    assert not any(p.exists() for p in cached) and other.exists()
    cache_everything()
    kernels.drop_stale_kernels(package)
    assert all(p.exists() for p in cached)
    (package / "model" / "new_kernels.py").write_text("@njit(cache=True)\ndef kernel():\n    return 2\n")
    kernels.drop_stale_kernels(package)  # a kernel source added: not in the record, every cache goes
    assert not any(p.exists() for p in cached) and other.exists()
