"""Files written whole or not at all."""

from __future__ import annotations

import functools
import os
import tempfile
from pathlib import Path


def write_atomically(path: Path, write) -> None:
    """write(binary handle) into a temporary file beside path, flushed to disk, then renamed to path
    (with the permissions a new file gets from the umask): a reader sees the old file or the whole new one."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        os.chmod(tmp, 0o666 & ~_umask())
        with os.fdopen(fd, "wb") as handle:
            write(handle)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


@functools.cache
def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask
