"""The leaf layer: what every room of the package builds on, importing nothing of the package.

* :mod:`~lightsail_mbs.base.constants`: physical constants and the package's version;
* :mod:`~lightsail_mbs.base.validation`: :class:`ParameterError` and the checks that raise it (one line
  naming the parameter, its value and what is allowed);
* :mod:`~lightsail_mbs.base.settings`: :class:`RunSettings`, the run control every solver and every Result
  carries;
* :mod:`~lightsail_mbs.base.kernels`: the decorator of the package's compiled kernels and the check that
  keeps numba's on-disk cache true to their sources.

The other rooms import from here; this package imports only the standard library and numpy
(the import contract in pyproject.toml holds it to that).
"""
