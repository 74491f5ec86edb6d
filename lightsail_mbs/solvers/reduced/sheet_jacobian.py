"""The reduced sheet's Jacobian with its dense rows computed apart (option ``jacobian="split"``,
solvers.reduced.sheet_options): :class:`DenseRows`, which solvers.reduced.sheet.SheetModel holds as its ``dense``.

Why. The sheet's Jacobian comes from coloured difference quotients: tiles of one colour of a distance-2
colouring (sheet_radau.distance2_colouring) never share a neighbour, so one right-hand side per colour and
state component gives each of their columns. A polar disc's centre tile touches every tile of the first ring
(56 on a 1009-tile disc), so those all need colours of their own: 57 colours, 741 right-hand sides a Jacobian,
where a rectangular grid takes 5.

How. A tile with more than DENSE_DEGREE neighbours (joined to them by connectors only) is a dense tile; the
colouring lets tiles share a dense tile as their common neighbour (not as a neighbour of one of them: a tile and
its neighbours keep distinct colours), which leaves 7 colours on the 1009-tile disc. Every row except a dense
tile's then comes out of the coloured quotients as before, and so does a dense tile's diagonal block (no
neighbour shares its colour). Its off-diagonal blocks ∂f_r/∂y_k (k a neighbour) depend on y_k only through the
connectors joining r and k: the tile's rates are its own inertia and loads (its own state) plus the sum of its
connectors' forces and moments, each of which reads the states of its two tiles only, and the turning frame's
rates of a tile read its own state and inertial rates only (sheet_turning). So they are the quotients of a *star*
system: for every pair (r, k) a copy of r and a copy of k joined by their connectors and nothing else (no loads,
followers or tethers); perturbing component s of every k-copy at once gives ∂f_r/∂y_{k,s} on every r-copy,
with the increments the coloured quotients use (13 evaluations of 2 × 56 bodies on the 1009-tile disc). The
result equals the coloured Jacobian to the round-off of the quotients (the star's rates lack the terms that do
not depend on y_k; tests/solvers/reduced/test_sheet_jacobian.py).
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.solvers.reduced.sheet_kernels import STATE, rhs_kernel
from lightsail_mbs.solvers.reduced.sheet_turning import frame_rotation, to_inertial, to_turning_rates

DENSE_DEGREE = 8  # a tile with more neighbours than this has its rows computed apart (a grid tile has 4)
CONNECTOR_ARRAYS = ("la", "lb", "gap", "K", "Dm", "off", "frame", "framed")


class DenseRows:
    """The dense tiles of a SheetModel and the star system of their pairs (module docstring)."""

    def __init__(self, model, tiles: np.ndarray, neighbours: list):
        self.model, self.tiles = model, tiles
        pairs = [(r, k) for r in tiles for k in sorted(neighbours[r] - {r})]
        self.pairs = np.array(pairs, dtype=np.int64).reshape(-1, 2)
        self.sources = self.pairs.ravel()  # star body 2p: a copy of tile r of pair p; 2p + 1: of its k
        self.state = (STATE * self.sources[:, None] + np.arange(STATE)).ravel()
        where = {pair: p for p, pair in enumerate(pairs)}
        ta, tb, connectors, ends = model.ta, model.tb, [], []
        for c in range(ta.size):
            for a, b in ((ta[c], tb[c]), (tb[c], ta[c])):
                if (a, b) in where:  # the connector joins the pair's r (a) and k (b)
                    connectors.append(c)
                    p = where[(a, b)]
                    ends.append((2 * p, 2 * p + 1) if a == ta[c] else (2 * p + 1, 2 * p))
        self.connectors = np.array(connectors, dtype=np.int64)
        self.ends = np.array(ends, dtype=np.int64).reshape(-1, 2)
        self.ta, self.tb = np.ascontiguousarray(self.ends[:, 0]), np.ascontiguousarray(self.ends[:, 1])
        self.bodies = tuple(
            np.ascontiguousarray(getattr(model, name)[self.sources])
            for name in ("flat", "masses", "inertia", "inverse", "diagonal")
        )
        self.arrays = tuple(np.ascontiguousarray(getattr(model, name)[self.connectors]) for name in CONNECTOR_ARRAYS)
        self.positions = self._positions()

    @classmethod
    def of(cls, model, neighbours: list) -> DenseRows | None:
        """The dense rows of a model whose tiles' closed neighbourhoods are `neighbours` (None if it has none): the
        tiles with more than DENSE_DEGREE neighbours, none of them joined by a tether or the payload."""
        tethered = set(model.tethers[0].tolist()) | set(range(model.lit, model.count))
        tiles = [k for k in range(model.count) if len(neighbours[k]) - 1 > DENSE_DEGREE and k not in tethered]
        return cls(model, np.array(tiles, dtype=np.int64), neighbours) if tiles else None

    def _positions(self) -> np.ndarray:
        """(pairs, 13 columns, 13 rows): the CSC data index of entry (row of r, column of k) of each pair."""
        m = self.model
        out = np.empty((len(self.pairs), STATE, STATE), dtype=np.int64)
        for p, (r, k) in enumerate(self.pairs):
            for s in range(STATE):
                col = STATE * k + s
                start, stop = m.indptr[col], m.indptr[col + 1]
                out[p, s] = start + np.searchsorted(m.indices[start:stop], STATE * r + np.arange(STATE))
        return out

    def rates(self, t: float, ys: np.ndarray) -> np.ndarray:
        """The star's rates (in the model's frame) of its state ys (13 per star body)."""
        m = self.model
        flat, masses, inertia, inverse, diagonal = self.bodies
        la, lb, gap, K, Dm, off, frame, framed = self.arrays
        state = ys
        if m.turning is not None:
            Q, QmI, qQ = frame_rotation(m.turning.spin, float(t))
            state = np.empty_like(ys)
            to_inertial(ys, flat, m.turning.axis, m.turning.spin, Q, QmI, qQ, state)
        out = np.empty_like(ys)
        none = np.zeros(0, np.int64)
        rhs_kernel(
            state, flat, masses, inertia, inverse, diagonal, self.ta, self.tb, la, lb, gap, K, Dm, off, frame, framed,
            none, np.zeros((0, 3)), np.zeros((0, 3)), m.load, float(t), 0, 0.0,
            none, np.zeros((0, 3)), np.zeros(0), np.zeros(2), out,
        )  # fmt: skip
        if m.turning is not None:
            inertial_rates = out
            out = np.empty_like(ys)
            to_turning_rates(ys, inertial_rates, flat, m.turning.axis, m.turning.spin, Q, out)
        return out

    def fill(self, data: np.ndarray, t: float, y: np.ndarray) -> None:
        """Writes the dense tiles' off-diagonal blocks into the Jacobian's CSC data (the model's pattern) at the
        state y, time t."""
        ys = y[self.state]
        base = self.rates(t, ys).reshape(-1, 2, STATE)[:, 0]
        for s in range(STATE):
            cols = STATE * self.pairs[:, 1] + s
            yp = ys.copy().reshape(-1, 2, STATE)
            yp[:, 1, s] += self.model.increments(y, cols)
            increments = yp[:, 1, s] - y[cols]
            rows = self.rates(t, yp.ravel()).reshape(-1, 2, STATE)[:, 0]
            data[self.positions[:, s]] = (rows - base) / increments[:, None]
