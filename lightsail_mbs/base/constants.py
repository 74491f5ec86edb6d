"""Physical constants (SI) and the package's version."""

SPEED_OF_LIGHT = 299_792_458.0  # c, m/s (exact)
VERSION = "0.1.0"  # the package's version (pyproject.toml's)
