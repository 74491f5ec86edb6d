"""The package's import-time housekeeping: numba kernels never load machine code built from an old source."""

import os
import re
from pathlib import Path

import lightsail_mbs


def test_kernel_sources_list_every_file_with_cached_kernels():
    root = Path(lightsail_mbs.__file__).parent
    decorated = re.compile(r"^\s*@\w*jit\(.*cache=True", re.M)
    holding = {str(p.relative_to(root)) for p in root.rglob("*.py") if decorated.search(p.read_text())}
    assert holding == set(lightsail_mbs.KERNEL_SOURCES)


def test_cached_kernels_are_dropped_when_any_kernel_source_changes(tmp_path, monkeypatch):
    package = tmp_path / "lightsail_mbs"
    cached = []
    for name in lightsail_mbs.KERNEL_SOURCES:
        source = package / name
        source.parent.mkdir(parents=True, exist_ok=True)
        source.write_text("# kernel\n")
        cached += [source.parent / "__pycache__" / f"{source.stem}.kernel-10.py311.nbi"]
    other = package / "solvers" / "reduced" / "__pycache__" / "solver.cpython-311.pyc"
    monkeypatch.setattr(lightsail_mbs, "__file__", str(package / "__init__.py"))

    def cache_everything():
        for path in [*cached, other]:
            path.parent.mkdir(exist_ok=True)
            path.write_bytes(b"machine code")

    cache_everything()
    lightsail_mbs._drop_stale_kernels()  # no record yet: whatever is cached may be stale
    assert not any(p.exists() for p in cached) and other.exists()
    cache_everything()
    lightsail_mbs._drop_stale_kernels()  # sources unchanged: the cache stays
    assert all(p.exists() for p in cached)
    radau = package / "solvers" / "reduced" / "radau.py"
    stamp = radau.stat().st_mtime_ns
    radau.write_text(radau.read_text())  # the same content written anew (as pip installs it): a new time stamp
    os.utime(radau, ns=(radau.stat().st_atime_ns, stamp + 3_000_000_000))
    lightsail_mbs._drop_stale_kernels()  # content as recorded: its time stamp is restored, the cache stays
    assert radau.stat().st_mtime_ns == stamp and all(p.exists() for p in cached)
    dynamics = package / "solvers" / "reduced" / "dynamics.py"
    dynamics.write_text("# kernel, edited\n")
    os.utime(dynamics, ns=(dynamics.stat().st_atime_ns, dynamics.stat().st_mtime_ns + 1_000_000_000))
    lightsail_mbs._drop_stale_kernels()  # one source edited: every kernel file's cache goes
    assert not any(p.exists() for p in cached) and other.exists()
