"""The package's compiled kernels and numba's on-disk cache of them.

Every numba kernel of the package is decorated with this module's :func:`njit` (numba's own, with the
same arguments). Its first call in a process, before the first kernel is compiled or loaded, runs
:func:`drop_stale_kernels` once; importing the package does no file-system work for it.

numba keys each cached function on its own file's time stamp and size, but a kernel inlines the kernels
it calls from other files (an integrator inlines the right-hand side), so after an edit of one file the
others would load machine code built from the old source. ``__pycache__/numba-kernel-sources`` in the
package folder records the size, time stamp (ns) and SHA-256 of every kernel source (:func:`kernel_sources`:
the files that define kernels cached on disk, found by reading the package's sources) at compilation:

* all sizes and time stamps as recorded: nothing to do;
* a source with another time stamp but the recorded content (an install: pip writes the files anew,
  after the kernels were compiled into the wheel at build time): its recorded time stamp is restored,
  so numba's own check accepts the cache;
* any content changed, or a kernel source added: every ``*.nbi``/``*.nbc`` of the kernel sources is
  removed and the record rewritten; numba compiles afresh.

A read-only install is left as it is.
"""

from __future__ import annotations

import functools
import hashlib
import os
import re
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent
RECORD = Path("__pycache__") / "numba-kernel-sources"  # in the package folder
# a decorator line of a kernel that numba caches on disk: @njit(cache=True), @jit(..., cache=True), ...
CACHED_KERNEL = re.compile(r"^\s*@\w*jit\(.*cache=True", re.M)


def kernel_sources(root: Path | None = None) -> tuple[str, ...]:
    """The package's files that define kernels numba caches on disk, relative to the package folder
    (`root`, default the installed package), sorted."""
    root = PACKAGE if root is None else Path(root)
    found = (p for p in root.rglob("*.py") if CACHED_KERNEL.search(p.read_text(encoding="utf-8")))
    return tuple(sorted(p.relative_to(root).as_posix() for p in found))


def drop_stale_kernels(root: Path | None = None) -> None:
    """Keep numba's cached machine code only while every kernel source is the one it was compiled from
    (module docstring); `root`: the package folder (default the installed package)."""
    root = PACKAGE if root is None else Path(root)
    record = root / RECORD
    try:
        sources = kernel_sources(root)
        stats = {name: (root / name).stat() for name in sources}
        recorded = {}
        for line in record.read_text().splitlines() if record.is_file() else ():
            fields = line.split()
            if len(fields) == 4 and fields[1].isdigit() and fields[2].isdigit():
                recorded[fields[0]] = (int(fields[1]), int(fields[2]), fields[3])
        if all(recorded.get(n, (None, None))[:2] == (st.st_size, st.st_mtime_ns) for n, st in stats.items()):
            return
        digests = {name: hashlib.sha256((root / name).read_bytes()).hexdigest() for name in sources}
        if all(recorded.get(n, (0, 0, None))[2] == d for n, d in digests.items()):
            for name, st in stats.items():
                os.utime(root / name, ns=(st.st_atime_ns, recorded[name][1]))
            return
        for name in sources:
            source = root / name
            for cached in (source.parent / "__pycache__").glob(f"{source.stem}.*.nb[ic]"):
                cached.unlink(missing_ok=True)
        record.parent.mkdir(exist_ok=True)
        lines = (f"{n} {st.st_size} {st.st_mtime_ns} {digests[n]}" for n, st in stats.items())
        record.write_text("\n".join(lines))
    except OSError:
        pass


@functools.cache
def _checked() -> None:
    """drop_stale_kernels of the installed package, once per process."""
    drop_stale_kernels()


def njit(*args, **kwargs):
    """``numba.njit(*args, **kwargs)``, after the cache of the package's kernels has been checked against
    their sources (drop_stale_kernels, at the first call in a process)."""
    _checked()
    import numba

    return numba.njit(*args, **kwargs)
