"""Input validators shared by the public functions.

Every public function turns what it is given into a clean float array here,
and raises :class:`ValueError` or :class:`TypeError` that says what was
expected and what came.  Nothing below is part of the public API.
"""

from __future__ import annotations

import numbers

import numpy as np
from numpy.typing import NDArray

#: Tolerance used to decide whether a rotation is orthonormal, an axis is
#: unit length, and so on.  Loose enough for values typed with 6 digits.
UNIT_TOL = 1e-6


def _describe(value: object) -> str:
    """A short description of what came, for error messages."""
    if isinstance(value, np.ndarray):
        return f"array with shape {value.shape} and dtype {value.dtype}"
    if isinstance(value, (list, tuple)):
        try:
            shape: object = np.shape(np.asarray(value, dtype=object))
        except Exception:  # pragma: no cover - exotic ragged input
            shape = "?"
        return f"{type(value).__name__} of shape {shape}"
    return f"{type(value).__name__} {value!r}"[:120]


def as_float_array(value: object, name: str) -> NDArray[np.float64]:
    """Convert ``value`` to a float64 array, or raise ``TypeError``.

    Strings, ``None``, complex numbers, ragged nested lists and arbitrary
    objects are refused with a message naming ``name``.
    """
    if value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"Expected an array-like of real numbers for {name}, got {_describe(value)}")
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "biuf":
            return np.asarray(value, dtype=float)
        if value.dtype.kind == "c":
            raise TypeError(f"Expected real numbers for {name}, got a complex array")
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return np.asarray(float(value))
    try:
        arr = np.asarray(value)
    except (ValueError, TypeError) as exc:
        raise TypeError(
            f"Expected an array-like of real numbers for {name}, got {_describe(value)} ({exc})"
        ) from None
    if arr.dtype.kind == "c":
        raise TypeError(f"Expected real numbers for {name}, got complex values")
    if arr.dtype.kind not in "biuf":
        # Objects such as sympy numbers: try a float conversion element-wise.
        try:
            arr = arr.astype(float)
        except (ValueError, TypeError):
            raise TypeError(
                f"Expected an array-like of real numbers for {name}, got {_describe(value)}"
            ) from None
    return np.asarray(arr, dtype=float)


def check_finite(arr: NDArray[np.float64], name: str) -> NDArray[np.float64]:
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"Expected finite values in {name}, got NaN or inf")
    return arr


def check_shape_tail(
    arr: NDArray[np.float64], tail: tuple[int | None, ...], name: str, batch_allowed: bool = True
) -> NDArray[np.float64]:
    """Require ``arr.shape`` to end with ``tail`` (``None`` entries match any size)."""
    pattern = ", ".join("n" if t is None else str(t) for t in tail)
    want = f"(..., {pattern})" if batch_allowed else f"({pattern})"
    ok = arr.ndim >= len(tail) if batch_allowed else arr.ndim == len(tail)
    if ok:
        for have, need in zip(arr.shape[arr.ndim - len(tail):], tail, strict=True):
            if need is not None and have != need:
                ok = False
    if not ok:
        raise ValueError(f"Expected {name} with shape {want}, got shape {arr.shape}")
    return arr


def real_array(
    value: object, name: str, tail: tuple[int | None, ...], batch_allowed: bool = True
) -> NDArray[np.float64]:
    """Float array with a checked trailing shape and only finite values."""
    arr = as_float_array(value, name)
    check_shape_tail(arr, tail, name, batch_allowed)
    return check_finite(arr, name)


def check_rotation(R: NDArray[np.float64], name: str, tol: float = UNIT_TOL) -> None:
    """Raise ``ValueError`` unless every ``R[..., :, :]`` is in SO(3)."""
    RtR = np.swapaxes(R, -1, -2) @ R
    err = np.abs(RtR - np.eye(3)).max(initial=0.0)
    if err > tol:
        raise ValueError(
            f"Expected {name} to be a rotation matrix (R^T R = I), "
            f"but R^T R differs from I by {err:.3g}"
        )
    det = np.linalg.det(R) if R.size else np.ones(())
    if np.any(det <= 0):
        raise ValueError(f"Expected {name} to be a rotation (det R = +1), got det R = {np.min(det):.3g}")


def transform_array(value: object, name: str = "T", batch_allowed: bool = True) -> NDArray[np.float64]:
    """A checked homogeneous transform (or a batch of them)."""
    T = real_array(value, name, (4, 4), batch_allowed)
    bottom = T[..., 3, :]
    if np.abs(bottom - np.array([0.0, 0.0, 0.0, 1.0])).max(initial=0.0) > UNIT_TOL:
        raise ValueError(
            f"Expected {name} in SE(3) with last row [0, 0, 0, 1], got last row {bottom.reshape(-1, 4)[0]}"
        )
    check_rotation(T[..., :3, :3], f"the rotation part of {name}")
    return T


def rotation_array(value: object, name: str = "R", batch_allowed: bool = True) -> NDArray[np.float64]:
    R = real_array(value, name, (3, 3), batch_allowed)
    check_rotation(R, name)
    return R


def screw_axes_array(value: object, name: str = "screw_axes") -> NDArray[np.float64]:
    """A checked 6 x n matrix whose columns are unit screw axes (omega, v)."""
    S = as_float_array(value, name)
    if S.ndim == 1 and S.shape[0] == 6:
        raise ValueError(
            f"Expected {name} with shape (6, n): one screw axis per column; got a 1-D array of "
            "shape (6,). For one joint pass it as a (6, 1) column, e.g. S.reshape(6, 1)"
        )
    if S.ndim != 2 or S.shape[0] != 6:
        hint = ""
        if S.ndim == 2 and S.shape[1] == 6:
            hint = " (it looks transposed: the axes must be the columns, use S.T)"
        raise ValueError(f"Expected {name} with shape (6, n), got shape {S.shape}{hint}")
    if S.shape[1] == 0:
        raise ValueError(f"Expected {name} with at least one column, got shape {S.shape}")
    check_finite(S, name)
    w_norm = np.linalg.norm(S[:3], axis=0)
    v_norm = np.linalg.norm(S[3:], axis=0)
    for i in range(S.shape[1]):
        if w_norm[i] > UNIT_TOL:
            if abs(w_norm[i] - 1.0) > UNIT_TOL:
                raise ValueError(
                    f"Expected column {i} of {name} (a revolute joint) to have a unit angular part, "
                    f"got |omega| = {w_norm[i]:.6g}"
                )
        elif v_norm[i] <= UNIT_TOL:
            raise ValueError(f"Column {i} of {name} is zero: a screw axis must not be zero")
        elif abs(v_norm[i] - 1.0) > UNIT_TOL:
            raise ValueError(
                f"Expected column {i} of {name} (a prismatic joint, omega = 0) to have a unit linear "
                f"part, got |v| = {v_norm[i]:.6g}"
            )
    return S


def theta_array(value: object, dof: int, name: str = "theta") -> NDArray[np.float64]:
    """Joint values with shape (..., dof): one configuration (dof,), or a batch of them along leading axes.

    A column of shape (dof, 1) (as the Robotics Toolbox and MATLAB accept) is
    refused with a message that says to pass a flat vector: the last axis is
    always the joint axis, so reading a column as one configuration would make
    (1, 1)-shaped input mean two things for a one-joint chain.
    """
    th = as_float_array(value, name)
    if th.ndim == 0:
        if dof == 1:
            th = th.reshape(1)
        else:
            raise ValueError(f"Expected {name} with shape (..., {dof}), got a scalar")
    if dof > 1 and th.ndim >= 2 and th.shape[-1] == 1 and th.shape[-2] == dof:
        raise ValueError(
            f"Expected {name} as {dof} joint values in a flat array of shape ({dof},), got a column of shape "
            f"{th.shape}: pass np.ravel({name}) (a 2-D array is read as a batch of configurations, one per row, "
            f"shape (k, {dof}))"
        )
    if th.shape[-1] != dof:
        raise ValueError(
            f"Expected {name} with shape (..., {dof}) for a chain with {dof} joints, got shape {th.shape}"
        )
    return check_finite(th, name)


def jacobian_array(value: object, name: str = "J") -> NDArray[np.float64]:
    return real_array(value, name, (6, None))


def broadcast_leading(
    a: NDArray[np.float64], a_core: int, b: NDArray[np.float64], b_core: int, names: tuple[str, str]
) -> tuple[int, ...]:
    """Check that the batch (leading) shapes of two arrays broadcast, or raise."""
    sa = a.shape[: a.ndim - a_core]
    sb = b.shape[: b.ndim - b_core]
    try:
        return np.broadcast_shapes(sa, sb)
    except ValueError:
        raise ValueError(
            f"The batch shapes of {names[0]} {sa} and {names[1]} {sb} do not match "
            "(they must be equal, or broadcast by numpy's rules)"
        ) from None


def positive_int(value: object, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"Expected an integer for {name}, got {_describe(value)}")
    return int(value)


def positive_float(value: object, name: str, allow_zero: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"Expected a real number for {name}, got {_describe(value)}")
    v = float(value)
    if not np.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        kind = "non-negative" if allow_zero else "positive"
        raise ValueError(f"Expected a {kind} finite number for {name}, got {v!r}")
    return v
