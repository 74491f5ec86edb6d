"""The block triangular solves (solvers.reduced.block_lu) against the scalar factorisation they copy and the
matrix itself: a random structurally symmetric block matrix on a grid of bodies, dominated by its diagonal."""

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from lightsail_mbs.solvers.reduced import block_lu


def grid_matrix(nx: int, ny: int, seed: int = 0, dtype=np.float64, diagonal: float = 60.0) -> sp.csc_matrix:
    """6 × 6 dense random blocks on the 5-point stencil of an nx × ny grid of bodies, `diagonal` I added."""
    rng = np.random.default_rng(seed)
    index = np.arange(nx * ny).reshape(ny, nx)
    pairs = [(k, k) for k in range(nx * ny)]
    pairs += [(a, b) for a, b in zip(index[:, :-1].ravel(), index[:, 1:].ravel())]
    pairs += [(a, b) for a, b in zip(index[:-1, :].ravel(), index[1:, :].ravel())]
    pairs += [(b, a) for a, b in pairs if a != b]
    blocks = rng.normal(size=(len(pairs), 6, 6))
    if np.dtype(dtype).kind == "c":
        blocks = blocks + 1j * rng.normal(size=blocks.shape)
    rows = np.concatenate([6 * a + np.repeat(np.arange(6), 6) for a, _ in pairs])
    cols = np.concatenate([6 * b + np.tile(np.arange(6), 6) for _, b in pairs])
    S = sp.csc_matrix((blocks.ravel(), (rows, cols)), shape=(6 * nx * ny, 6 * nx * ny))
    return (S + diagonal * sp.identity(S.shape[0])).tocsc().astype(dtype)


def factored(S: sp.csc_matrix):
    pattern = block_lu.BlockPattern(block_lu.body_graph(S))
    order = (6 * pattern.order[:, None] + np.arange(6)).ravel()
    lu = splu(S[order][:, order], permc_spec="NATURAL", diag_pivot_thresh=0.0, options=dict(SymmetricMode=True))
    return pattern, order, lu


@pytest.mark.parametrize("dtype", [np.float64, np.complex128])
def test_block_solve_is_superlus_solve_and_solves_the_matrix(dtype):
    S = grid_matrix(7, 5, dtype=dtype)
    pattern, order, lu = factored(S)
    blocks = block_lu.BlockFactors.from_superlu(lu, pattern)
    assert blocks is not None
    b = np.random.default_rng(1).normal(size=S.shape[0]).astype(dtype)
    x = blocks.solve(b)
    reference = np.empty_like(x)
    reference[order] = lu.solve(b[order])
    assert np.max(np.abs(x - reference)) < 1e-12 * np.max(np.abs(reference))
    assert np.max(np.abs(S @ x - b)) < 1e-11 * np.max(np.abs(b))


def test_the_symbolic_pattern_holds_every_entry_of_the_factors():
    """The block pattern of L and U from the elimination tree covers SuperLU's fill exactly: as many
    off-diagonal blocks as the scalar factor has."""
    S = grid_matrix(9, 8)
    pattern, _, lu = factored(S)
    L = lu.L.tocoo()
    below = L.row // 6 > L.col // 6
    assert len(set(zip(L.row[below] // 6, L.col[below] // 6))) == pattern.Li.size


def test_single_precision_solve_is_accurate_to_single_precision():
    S = grid_matrix(6, 6)
    pattern, order, _ = factored(S)
    single = S.astype(np.float32)
    lu = splu(single[order][:, order], permc_spec="NATURAL", diag_pivot_thresh=0.0, options=dict(SymmetricMode=True))
    blocks = block_lu.BlockFactors.from_superlu(lu, pattern)
    b = np.random.default_rng(2).normal(size=S.shape[0])
    x = blocks.solve(b)
    assert x.dtype == np.float64  # the result in the right-hand side's precision
    assert np.max(np.abs(S @ x - b)) < 1e-5 * np.max(np.abs(b))


def test_factors_with_row_interchanges_are_refused():
    S = grid_matrix(4, 3, diagonal=0.0)  # no dominant diagonal: partial pivoting interchanges rows
    pattern, order, _ = factored(S)
    lu = splu(S[order][:, order], permc_spec="NATURAL", diag_pivot_thresh=1.0)
    assert not np.array_equal(lu.perm_r, np.arange(S.shape[0]))
    assert block_lu.BlockFactors.from_superlu(lu, pattern) is None


def test_small_pages_restores_numpys_huge_page_advice():
    """The factors and samples are allocated without numpy's huge-page advice (sheet_radau.small_pages); the
    advice is numpy's own setting again afterwards, also after an error."""
    from numpy._core import multiarray

    from lightsail_mbs.solvers.reduced.sheet_radau import empty_small_pages, small_pages

    before = multiarray._set_madvise_hugepage(True)
    try:
        with pytest.raises(RuntimeError), small_pages():
            assert multiarray._set_madvise_hugepage(False) is False  # off inside
            raise RuntimeError
        assert multiarray._set_madvise_hugepage(True) is True  # on again
        a = empty_small_pages((3, 4), np.float32)
        assert a.shape == (3, 4) and a.dtype == np.float32
        assert multiarray._set_madvise_hugepage(True) is True
    finally:
        multiarray._set_madvise_hugepage(before)
