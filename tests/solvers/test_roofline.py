"""validation/roofline.py's operation counts: the structural count of a sparse LU is the dense LU's 2n³/3 on a
dense matrix, and the Exudyn chain's work grows with its evaluations and its coordinates as counted."""

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from lightsail_mbs import paper_case
from tests.helpers import validation_script


def test_factor_count_of_a_dense_matrix_is_two_thirds_n_cubed():
    n = 60
    a = np.random.default_rng(0).normal(size=(n, n)) + n * np.eye(n)
    lu = splu(sp.csc_matrix(a), permc_spec="NATURAL", diag_pivot_thresh=0.0)
    nnz, flops = validation_script("roofline").factor_work(lu)
    assert nnz == n * n + n  # L with its unit diagonal, U with its diagonal
    assert abs(flops - 2.0 * n**3 / 3.0) < 0.1 * 2.0 * n**3 / 3.0


def test_exudyn_chain_work_counts_evaluations_and_factorisations():
    roofline = validation_script("roofline")
    p = paper_case("torsion-stable")
    info = {"coordinates": p.n + 2, "method": "generalized-alpha", "njev": 0}
    one, _ = roofline.exudyn_chain_work(p, info, 1)
    assert roofline.exudyn_chain_work(p, info, 10)[0] == 10 * one
    with_jacobian, _ = roofline.exudyn_chain_work(p, {**info, "njev": 1}, 1)
    assert with_jacobian - one >= (2.0 / 3.0) * (p.n + 2) ** 3
    explicit, _ = roofline.exudyn_chain_work(p, {**info, "method": "DOPRI5"}, 1)
    assert explicit > one  # a dense LU at every stage
