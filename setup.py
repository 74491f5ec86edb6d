"""Build hook of lightsail-mbs (the metadata is in pyproject.toml).

The reduced solver's kernels are numba functions cached on disk next to their sources. Compiling them
takes tens of seconds, so `build_py` compiles them when the package is built: after copying the sources
(a regular install: into the build folder, whose __pycache__ then ships in the wheel) or, for an editable
install (`pip install -e .`), in the source tree itself. It runs `python -m
lightsail_mbs.solvers.reduced.warmup` in a subprocess with numba from the build requirements. numba keys
its cache on a hash of each source file, the numba version and the CPU, so the compiled code is used when
the package runs with the same numba on the same machine; otherwise the first run compiles it (and says
so on stderr). Set LIGHTSAIL_MBS_NO_WARMUP=1 to skip the step; a failure of the step never fails the build.
"""

import os
import subprocess
import sys
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

WARMUP = "lightsail_mbs.solvers.reduced.warmup"


class build_py_with_compiled_kernels(build_py):
    """build_py, then compile the reduced solver's kernels into the package's __pycache__ folders."""

    def run(self):
        super().run()
        if os.environ.get("LIGHTSAIL_MBS_NO_WARMUP", "") not in ("", "0"):
            return
        root = Path.cwd() if self.editable_mode else Path(self.build_lib).resolve()
        env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
        env.pop("NUMBA_CACHE_DIR", None)  # numba's default: __pycache__ next to each source file
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(root), env.get("PYTHONPATH")]))
        print(f"lightsail-mbs: compiling the reduced solver's kernels in {root} (about a minute)", flush=True)
        try:
            subprocess.run([sys.executable, "-m", WARMUP], cwd=root, env=env, check=True, timeout=3600)
        except (OSError, subprocess.SubprocessError) as exc:
            print(f"lightsail-mbs: warning: kernels not compiled at install ({exc}); the first run compiles them")


setup(cmdclass={"build_py": build_py_with_compiled_kernels})
