"""The test suite, laid out like the package (model/, solvers/, analysis/, studies/, viz/, paper/, cli/).

A package so that pytest puts the repository root on sys.path (rootdir-based "prepend" import mode) and
the shared helpers import as ``tests.helpers`` and ``tests.sweep_fake`` without any sys.path edits; sweep
worker processes are forked and import the fake solver by the same module path.
"""
