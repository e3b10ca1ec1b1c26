"""Rotation matrices of any Tait-Bryan order and Euler rates → angular velocity (docs/mathematics.md section 6.2).

An order such as ``"ZYX"`` means R = Rz(a1)·Ry(a2)·Rx(a3), the three angles
taken in the order of the factors; ``"ZYX"`` is docs/mathematics.md section 1's R = Rz(α)·Ry(β)·Rx(γ)
and gives exactly :func:`stgen.reference.geometry.rotation_matrix`. Angles in
radians, everything broadcasts over leading axes ``[...]``.

Angular velocity in the fixed (world) frame of R = R1(a1)·R2(a2)·R3(a3):
ω = e1·ȧ1 + R1·e2·ȧ2 + R1·R2·e3·ȧ3 (ek the unit axis of factor k), so
ω = E(a)·ȧ with the columns of E those three axes. Its derivative
ω̇ = E·ä + Σk ωk−1 × (E[:, k]·ȧk), ωk−1 the part of ω from the factors before k
(the k-th axis turns with them).
"""

from __future__ import annotations

import numpy as np

_AXES = {"X": 0, "Y": 1, "Z": 2}


def axis_rotation(axis: str, angle) -> np.ndarray:
    """The elementary rotation about ``axis`` ("X", "Y" or "Z"), shape ``angle.shape + (3, 3)``."""
    angle = np.asarray(angle, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    one, zero = np.ones_like(angle), np.zeros_like(angle)
    if axis == "X":
        rows = ((one, zero, zero), (zero, c, -s), (zero, s, c))
    elif axis == "Y":
        rows = ((c, zero, s), (zero, one, zero), (-s, zero, c))
    elif axis == "Z":
        rows = ((c, -s, zero), (s, c, zero), (zero, zero, one))
    else:
        raise ValueError(f"unknown rotation axis {axis!r}")
    return np.stack([np.stack(row, axis=-1) for row in rows], axis=-2)


def _factors(order: str, angles) -> list[np.ndarray]:
    angles = np.asarray(angles, dtype=float)
    if len(order) != 3 or sorted(order) != ["X", "Y", "Z"]:
        raise ValueError(f"rotation order must be a permutation of XYZ, got {order!r}")
    return [axis_rotation(axis, angles[..., k]) for k, axis in enumerate(order)]


def rotation(order: str, angles) -> np.ndarray:
    """R = R_order[0](a1)·R_order[1](a2)·R_order[2](a3) for ``angles[..., 3]`` in radians."""
    first, second, third = _factors(order, angles)
    return first @ second @ third


def rotation_partials(order: str, angles) -> np.ndarray:
    """∂R/∂ak for k = 1, 2, 3: shape ``[..., 3, 3, 3]`` (k first after the leading axes)."""
    factors = _factors(order, angles)
    partials = []
    for k, axis in enumerate(order):
        generator = np.zeros((3, 3))
        i = _AXES[axis]
        j, l = (i + 1) % 3, (i + 2) % 3
        generator[l, j], generator[j, l] = 1.0, -1.0  # [e_i]×: dRi/da = [e_i]× · Ri
        changed = list(factors)
        changed[k] = generator @ factors[k]
        partials.append(changed[0] @ changed[1] @ changed[2])
    return np.stack(partials, axis=-3)


def rate_matrix(order: str, angles) -> np.ndarray:
    """E(a) with ω = E·ȧ (ω in the fixed frame), shape ``[..., 3, 3]``; columns are the turned axes."""
    factors = _factors(order, angles)
    columns = []
    carried = np.broadcast_to(np.eye(3), factors[0].shape)
    for k, axis in enumerate(order):
        columns.append(carried[..., :, _AXES[axis]])
        carried = carried @ factors[k]
    return np.stack(columns, axis=-1)


def angular_velocity(order: str, angles, rates) -> np.ndarray:
    """ω = E(a)·ȧ, rad/s, shape ``[..., 3]``."""
    return np.einsum("...ij,...j->...i", rate_matrix(order, angles), np.asarray(rates, dtype=float))


def angular_acceleration(order: str, angles, rates, accelerations) -> np.ndarray:
    """ω̇ = E·ä + Σk ωk−1 × (E[:, k]·ȧk), rad/s², shape ``[..., 3]``."""
    matrix = rate_matrix(order, angles)
    rates = np.asarray(rates, dtype=float)
    result = np.einsum("...ij,...j->...i", matrix, np.asarray(accelerations, dtype=float))
    partial = np.zeros(np.broadcast_shapes(matrix.shape[:-1], rates.shape))
    for k in range(3):
        term = matrix[..., :, k] * rates[..., k, None]
        result = result + np.cross(partial, term)
        partial = partial + term
    return result
