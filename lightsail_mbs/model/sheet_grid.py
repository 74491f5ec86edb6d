"""The sheet's grid of tiles (model "sheet", :mod:`lightsail_mbs.model.sheet`): their geometry, mass and
inertia, and the rotations of a tile (Tait–Bryan xyz angles, quaternions, the tilt to a normal).

Geometry
--------
The flat sail spans 0 ≤ x ≤ L, 0 ≤ y ≤ W in the plane z = 0; the beam travels along +z. It is cut
into nx × ny rectangular tiles of a × b (a = L/nx, b = W/ny, nx = params.n). Tile (i, j) (flat index
k = j·nx + i) has its centre at x_i = (i + ½)a, y_j = (j + ½)b in the flat state, mass m = ρhab and
the centroidal inertia of a thin cuboid, diag(m(b² + h²), m(a² + h²), m(a² + b²))/12.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model.parameters import SailParameters


def require_sheet(p: SailParameters) -> None:
    if p.model != "sheet":
        raise ParameterError(f"model={p.model!r} is invalid here: allowed 'sheet'")


@dataclass(frozen=True)
class Tiles:
    """Derived quantities of a sheet case.

    Attributes
    ----------
    nx, ny : int
        Tiles along L and across W.
    a, b : float
        Tile length L/nx and width W/ny (m).
    mass : float
        m = ρ h a b (kg).
    inertia : ndarray (3,)
        Principal centroidal inertia of the thin cuboid tile (kg m²).
    bending_rigidity : float
        D = E h³/12 (ν_p = 0; 0 with bending off) (N m).
    membrane_modulus : float
        E_m of the in-plane springs (Pa).
    membrane_damping : float
        β_m on the stiff springs (s).
    """

    nx: int
    ny: int
    a: float
    b: float
    mass: float
    inertia: np.ndarray
    bending_rigidity: float
    membrane_modulus: float
    membrane_damping: float

    @classmethod
    def of(cls, p: SailParameters) -> Tiles:
        require_sheet(p)
        a, b, h = p.length / p.n, p.width / p.ny, p.thickness
        m = p.density * h * a * b
        em = float(p.youngs_modulus if p.membrane_modulus is None else p.membrane_modulus)
        if p.membrane_damping is None:
            omega_max = math.sqrt(4.0 * em * h * (b / a + a / b) / m)
            beta = 2.0 / omega_max
        else:
            beta = float(p.membrane_damping)
        return cls(
            nx=p.n,
            ny=p.ny,
            a=a,
            b=b,
            mass=m,
            inertia=m / 12.0 * np.array([b * b + h * h, a * a + h * h, a * a + b * b]),
            bending_rigidity=p.youngs_modulus * h**3 / 12.0 if p.bending else 0.0,
            membrane_modulus=em,
            membrane_damping=beta,
        )

    @property
    def count(self) -> int:
        return self.nx * self.ny

    @property
    def area(self) -> float:
        return self.a * self.b


def flat_centres(p: SailParameters) -> np.ndarray:
    """(N, 3) tile centres of the flat sail, k = j·nx + i (m)."""
    i, j = np.meshgrid(np.arange(p.n), np.arange(p.ny), indexing="xy")
    x = (i.ravel() + 0.5) * p.length / p.n
    y = (j.ravel() + 0.5) * p.width / p.ny
    return np.column_stack([x, y, np.zeros_like(x)])


def rotation_xyz(angles: np.ndarray) -> np.ndarray:
    """R = R_x(φ₀) R_y(φ₁) R_z(φ₂) (Exudyn's Tait–Bryan convention) of (..., 3) angles, (..., 3, 3)."""
    a = np.asarray(angles, float)
    c0, c1, c2 = np.cos(a[..., 0]), np.cos(a[..., 1]), np.cos(a[..., 2])
    s0, s1, s2 = np.sin(a[..., 0]), np.sin(a[..., 1]), np.sin(a[..., 2])
    R = np.empty(a.shape[:-1] + (3, 3))
    R[..., 0, 0] = c1 * c2
    R[..., 0, 1] = -c1 * s2
    R[..., 0, 2] = s1
    R[..., 1, 0] = c0 * s2 + s0 * s1 * c2
    R[..., 1, 1] = c0 * c2 - s0 * s1 * s2
    R[..., 1, 2] = -s0 * c1
    R[..., 2, 0] = s0 * s2 - c0 * s1 * c2
    R[..., 2, 1] = s0 * c2 + c0 * s1 * s2
    R[..., 2, 2] = c0 * c1
    return R


def angles_xyz(R: np.ndarray) -> np.ndarray:
    """The xyz angles of rotation matrices (..., 3, 3), the inverse of rotation_xyz away from φ₁ = ±π/2."""
    R = np.asarray(R, float)
    phi1 = np.arctan2(R[..., 0, 2], np.hypot(R[..., 1, 2], R[..., 2, 2]))
    phi0 = np.arctan2(-R[..., 1, 2], R[..., 2, 2])
    phi2 = np.arctan2(-R[..., 0, 1], R[..., 0, 0])
    return np.stack([phi0, phi1, phi2], axis=-1)


def normal_xyz(angles: np.ndarray) -> np.ndarray:
    """Tile normal n = R ẑ = (sin φ₁, −sin φ₀ cos φ₁, cos φ₀ cos φ₁) of (..., 3) xyz angles."""
    a = np.asarray(angles, float)
    c1 = np.cos(a[..., 1])
    return np.stack([np.sin(a[..., 1]), -np.sin(a[..., 0]) * c1, np.cos(a[..., 0]) * c1], axis=-1)


def tilt_rotation(normal: np.ndarray) -> np.ndarray:
    """(..., 3, 3): the rotation about the axis ẑ × n that takes ẑ to the unit normal n (no twist).

    Rodrigues' formula with K built from the unnormalised axis ẑ × n (|ẑ × n| = sin θ):
    R = I + K + K²/(1 + cos θ)."""
    n = np.asarray(normal, float)
    n = n / np.linalg.norm(n, axis=-1, keepdims=True)
    axis = np.stack([-n[..., 1], n[..., 0], np.zeros_like(n[..., 0])], axis=-1)
    K = np.zeros(n.shape[:-1] + (3, 3))
    K[..., 0, 1], K[..., 0, 2] = -axis[..., 2], axis[..., 1]
    K[..., 1, 0], K[..., 1, 2] = axis[..., 2], -axis[..., 0]
    K[..., 2, 0], K[..., 2, 1] = -axis[..., 1], axis[..., 0]
    return np.eye(3) + K + K @ K / (1.0 + n[..., 2])[..., None, None]


def rotation_minus_identity(q: np.ndarray) -> np.ndarray:
    """R − I of the rotations of (not necessarily unit) quaternions q (..., 4), scalar first, from small
    products only (accurate to the ulps of its own entries, not of 1), (..., 3, 3)."""
    q = np.asarray(q, float)
    q0, q1, q2, q3 = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    n = 2.0 / np.sum(q * q, axis=-1)
    out = np.empty(q.shape[:-1] + (3, 3))
    out[..., 0, 0] = -(q2 * q2 + q3 * q3) * n
    out[..., 0, 1] = (q1 * q2 - q0 * q3) * n
    out[..., 0, 2] = (q1 * q3 + q0 * q2) * n
    out[..., 1, 0] = (q1 * q2 + q0 * q3) * n
    out[..., 1, 1] = -(q1 * q1 + q3 * q3) * n
    out[..., 1, 2] = (q2 * q3 - q0 * q1) * n
    out[..., 2, 0] = (q1 * q3 - q0 * q2) * n
    out[..., 2, 1] = (q2 * q3 + q0 * q1) * n
    out[..., 2, 2] = -(q1 * q1 + q2 * q2) * n
    return out


def quaternion_rotation(q: np.ndarray) -> np.ndarray:
    """The rotation matrices (..., 3, 3) of quaternions q (..., 4), scalar first."""
    return np.eye(3) + rotation_minus_identity(q)


def tilt_quaternion(normal: np.ndarray) -> np.ndarray:
    """(..., 4) unit quaternions of the twist-free rotations taking ẑ to the (not necessarily unit) normals:
    q ∝ (|n| + n_z, −n_y, n_x, 0), the half-angle form of the rotation about ẑ × n."""
    n = np.asarray(normal, float)
    q = np.stack([np.linalg.norm(n, axis=-1) + n[..., 2], -n[..., 1], n[..., 0], np.zeros_like(n[..., 0])], axis=-1)
    return q / np.linalg.norm(q, axis=-1, keepdims=True)
