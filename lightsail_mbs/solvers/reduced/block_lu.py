"""The triangular solves of the sheet's reduced Newton matrix (sheet_radau) in dense 6 × 6 blocks, one block row
and column per body.

The reduced matrix S = μ I − A_V − A_X B/μ couples each body's 6 velocity unknowns with its own and its
neighbours' (its body graph is the mesh's adjacency). SuperLU factors it with the bodies in a fill-reducing
order (minimum degree on the body graph, each body's unknowns kept together) and no row interchanges (μ I
dominates the diagonal), S = L U. Its factors are scalar sparse matrices, but their fill is block-dense: a
body's 6 unknowns couple to the same bodies, so each factor is a set of dense 6 × 6 blocks on the block
pattern of the elimination (BlockPattern, from the body graph once per run: the elimination tree and the row
subtrees, Liu's algorithm, Davis, *Direct Methods for Sparse Linear Systems*, Sec. 4.1–4.2). BlockFactors copies
them into that pattern and solves

    L y = b forward: y_j ← (L_jj)⁻¹ y_j, then y_i −= L_ij y_j (i > j);
    U x = y backward: x_k = (U_kk)⁻¹ y_k, then y_j −= U_jk x_k (j < k),

every operation a dense 6 × 6 product on contiguous memory with one index per 36 entries. SuperLU's own solve of
the same factors walks its supernodes with a BLAS-2 call each; at 100 × 100 tiles (single precision, one core
of this machine, loaded) it takes 14 ms (real) and 25 ms (complex) a solve where the blocks take 7.5 and 14 ms.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from lightsail_mbs.base.kernels import njit

WIDTH = 6  # unknowns per body


def body_graph(S: sp.spmatrix, width: int = WIDTH) -> sp.csc_matrix:
    """The symmetric body pattern (bodies × bodies, ones, the diagonal included, sorted) of the scalar matrix
    S with `width` consecutive unknowns per body."""
    bodies = S.shape[0] // width
    coo = S.tocoo()
    T = sp.csc_matrix((np.ones(coo.nnz), (coo.row // width, coo.col // width)), shape=(bodies, bodies))
    T = (T + T.T + sp.identity(bodies)).tocsc()
    T.data[:] = 1.0
    T.sort_indices()
    return T


def minimum_degree(T: sp.csc_matrix) -> np.ndarray:
    """A fill-reducing elimination order of the bodies of pattern T: SuperLU's minimum degree (MMD on the
    pattern of Tᵀ + T), order[new] = old. Minimum degree on the scalar unknowns interleaves bodies: at 100 × 100
    tiles its factors need 1.4× (real) and 1.2× (complex) SuperLU's time per triangular solve of this order's,
    for the same fill (12.5 M entries)."""
    bodies = T.shape[0]
    D = (T + (2 * np.diff(T.indptr).max() + 1) * sp.identity(bodies)).tocsc()  # diagonally dominant
    return splu(D, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options=dict(SymmetricMode=True)).perm_c.argsort()


@njit(cache=True)
def _symbolic(Ap, Ai, n):
    """The block patterns of L (by columns, rows ascending) and U (by columns, rows ascending) of the
    symmetric pattern (Ap, Ai) (CSC, n bodies, in elimination order): U's column k holds the rows of the
    row subtree of k (its row pattern of L), L's column j the k with j in that subtree."""
    parent = np.full(n, -1, np.int64)
    ancestor = np.full(n, -1, np.int64)
    for k in range(n):  # the elimination tree (Liu)
        for p in range(Ap[k], Ap[k + 1]):
            i = Ai[p]
            while i != -1 and i < k:
                following = ancestor[i]
                ancestor[i] = k
                if following == -1:
                    parent[i] = k
                i = following
    mark = np.full(n, -1, np.int64)
    counts = np.zeros(n + 1, np.int64)
    lcounts = np.zeros(n + 1, np.int64)
    for k in range(n):  # pass 1: sizes of the row subtrees
        mark[k] = k
        for p in range(Ap[k], Ap[k + 1]):
            i = Ai[p]
            while i < k and mark[i] != k:
                mark[i] = k
                counts[k + 1] += 1
                lcounts[i + 1] += 1
                i = parent[i]
    Up = np.cumsum(counts)
    Lp = np.cumsum(lcounts)
    Ui = np.empty(Up[n], np.int64)
    Li = np.empty(Lp[n], np.int64)
    fill = Lp[:n].copy()
    mark[:] = -1
    for k in range(n):  # pass 2: the rows, U's sorted, L's ascending by construction
        mark[k] = k
        top = Up[k]
        for p in range(Ap[k], Ap[k + 1]):
            i = Ai[p]
            while i < k and mark[i] != k:
                mark[i] = k
                Ui[top] = i
                top += 1
                i = parent[i]
        Ui[Up[k] : Up[k + 1]] = np.sort(Ui[Up[k] : Up[k + 1]])
        for q in range(Up[k], Up[k + 1]):
            j = Ui[q]
            Li[fill[j]] = k
            fill[j] += 1
    return Lp, Li, Up, Ui


class BlockPattern:
    """The elimination order and symbolic factorisation of a body pattern T (body_graph): order[new] = old,
    the permuted pattern (Ap, Ai) and the block patterns (Lp, Li), (Up, Ui) of the factors."""

    def __init__(self, T: sp.csc_matrix):
        self.T = T
        self.bodies = T.shape[0]
        self.order = minimum_degree(T)
        self.rank = np.argsort(self.order)  # rank[old] = new
        P = T[self.order][:, self.order].tocsc()
        P.sort_indices()
        self.Ap, self.Ai = P.indptr.astype(np.int64), P.indices.astype(np.int64)
        self.Lp, self.Li, self.Up, self.Ui = _symbolic(self.Ap, self.Ai, self.bodies)

    def matches(self, T: sp.csc_matrix) -> bool:
        """T has this pattern."""
        return (
            T.shape == self.T.shape
            and np.array_equal(T.indptr, self.T.indptr)
            and np.array_equal(T.indices, self.T.indices)
        )


@njit(cache=True)
def _invert(A, out):
    """out = A⁻¹ of a 6 × 6 block, Gauss–Jordan with partial pivoting."""
    M = np.empty((WIDTH, 2 * WIDTH), A.dtype)
    for i in range(WIDTH):
        for j in range(WIDTH):
            M[i, j] = A[i, j]
            M[i, WIDTH + j] = 1.0 if i == j else 0.0
    for c in range(WIDTH):
        pivot = c
        for r in range(c + 1, WIDTH):
            if abs(M[r, c]) > abs(M[pivot, c]):
                pivot = r
        if pivot != c:
            for j in range(2 * WIDTH):
                M[c, j], M[pivot, j] = M[pivot, j], M[c, j]
        d = 1.0 / M[c, c]
        for j in range(2 * WIDTH):
            M[c, j] *= d
        for r in range(WIDTH):
            if r != c:
                f = M[r, c]
                for j in range(2 * WIDTH):
                    M[r, j] -= f * M[c, j]
    for i in range(WIDTH):
        for j in range(WIDTH):
            out[i, j] = M[i, WIDTH + j]


@njit(cache=True)
def _gather_factor(indptr, indices, data, lower, Bp, Bi, blocks, diagonal):
    """Scatter one scalar triangular factor (CSC, in elimination order; lower: L, else U) into its dense
    diagonal blocks and the off-diagonal blocks of the block pattern (Bp, Bi) (block columns). Returns False
    when a nonzero lies outside the pattern."""
    n = Bp.size - 1
    where = np.full(n, -1, np.int64)
    blocks[:] = 0.0
    diagonal[:] = 0.0
    for k in range(n):
        for q in range(Bp[k], Bp[k + 1]):
            where[Bi[q]] = q
        for s in range(WIDTH):
            c = WIDTH * k + s
            for p in range(indptr[c], indptr[c + 1]):
                r = indices[p]
                i = r // WIDTH
                if i == k:
                    diagonal[k, r % WIDTH, s] = data[p]
                elif where[i] >= 0 and (i > k) == lower:
                    blocks[where[i], r % WIDTH, s] = data[p]
                elif data[p] != 0:
                    return False
        for q in range(Bp[k], Bp[k + 1]):
            where[Bi[q]] = -1
    return True


@njit(cache=True)
def _invert_diagonal(diagonal, out):
    """out[k] = diagonal[k]⁻¹ (formed in the precision of `out`)."""
    A = np.empty((WIDTH, WIDTH), out.dtype)
    for k in range(diagonal.shape[0]):
        A[:] = diagonal[k]
        _invert(A, out[k])


@njit(cache=True)
def _apply(blocks, q, y, k, t):
    """t = M y[k] for the 6 × 6 block M = blocks[q]."""
    for a in range(WIDTH):
        s = blocks[q, a, 0] * y[k, 0]
        for c in range(1, WIDTH):
            s += blocks[q, a, c] * y[k, c]
        t[a] = s


@njit(cache=True)
def _subtract(blocks, q, t, y, i):
    """y[i] −= M t for the 6 × 6 block M = blocks[q]."""
    for a in range(WIDTH):
        s = y[i, a]
        for c in range(WIDTH):
            s -= blocks[q, a, c] * t[c]
        y[i, a] = s


@njit(cache=True)
def _solve(order, Lp, Li, Up, Ui, Lx, Ux, Linv, Uinv, b, out):
    """out = S⁻¹ b with S's factors in block form (b and out in the bodies' original order, 6 entries per
    body; the arithmetic in the factors' precision): L y = b forward, U x = y backward."""
    n = order.size
    y = np.empty((n, WIDTH), Lx.dtype)
    t = np.empty(WIDTH, Lx.dtype)
    for k in range(n):
        for a in range(WIDTH):
            y[k, a] = b[WIDTH * order[k] + a]
    for j in range(n):
        _apply(Linv, j, y, j, t)
        y[j] = t
        for q in range(Lp[j], Lp[j + 1]):
            _subtract(Lx, q, t, y, Li[q])
    for k in range(n - 1, -1, -1):
        _apply(Uinv, k, y, k, t)
        y[k] = t
        for u in range(Up[k], Up[k + 1]):
            _subtract(Ux, u, t, y, Ui[u])
    for k in range(n):
        for a in range(WIDTH):
            out[WIDTH * order[k] + a] = y[k, a]


class BlockFactors:
    """The factors L, U of a SuperLU factorisation of S (rows and columns in the pattern's elimination order,
    no row interchanges) in 6 × 6 blocks on the BlockPattern, the diagonal blocks inverted (in double, stored
    in the factors' precision); solve(b) → S⁻¹ b in the bodies' original order. from_superlu(lu, pattern) is None when
    the factorisation does not fit the pattern (row interchanges, an entry outside it)."""

    def __init__(self, pattern: BlockPattern, Lx, Ux, Linv, Uinv):
        self.pattern, self.Lx, self.Ux, self.Linv, self.Uinv = pattern, Lx, Ux, Linv, Uinv
        self.dtype = Lx.dtype

    @classmethod
    def from_superlu(cls, lu, pattern: BlockPattern) -> BlockFactors | None:
        n = WIDTH * pattern.bodies
        if not (np.array_equal(lu.perm_r, np.arange(n)) and np.array_equal(lu.perm_c, np.arange(n))):
            return None
        p = pattern
        factors = []
        for M, lower, (Bp, Bi) in ((lu.L, True, (p.Lp, p.Li)), (lu.U, False, (p.Up, p.Ui))):
            M = M.tocsc()
            blocks = np.empty((Bi.size, WIDTH, WIDTH), M.dtype)
            diagonal = np.empty((p.bodies, WIDTH, WIDTH), M.dtype)
            if not _gather_factor(
                M.indptr.astype(np.int64), M.indices.astype(np.int64), M.data, lower, Bp, Bi, blocks, diagonal
            ):
                return None
            inverse = np.empty(diagonal.shape, np.complex128 if M.dtype.kind == "c" else np.float64)
            _invert_diagonal(diagonal, inverse)
            factors.append((blocks, inverse.astype(M.dtype)))
        (Lx, Linv), (Ux, Uinv) = factors
        return cls(pattern, Lx, Ux, Linv, Uinv)

    @property
    def nnz(self) -> int:
        """Stored entries of the factors' blocks (the inverted diagonal blocks included)."""
        return WIDTH * WIDTH * (self.Lx.shape[0] + self.Ux.shape[0] + 2 * self.Linv.shape[0])

    def solve(self, b: np.ndarray) -> np.ndarray:
        """S⁻¹ b: b rounded to the factors' precision, the solve in it, the result in b's."""
        p = self.pattern
        out = np.empty(b.shape, np.result_type(b, self.dtype))
        rounded = b.astype(self.dtype, copy=False)
        _solve(p.order, p.Lp, p.Li, p.Up, p.Ui, self.Lx, self.Ux, self.Linv, self.Uinv, rounded, out)
        return out
