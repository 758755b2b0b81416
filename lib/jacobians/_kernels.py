"""Numerical kernels behind the chain and Jacobian functions.

Two paths compute the same thing:

* ``single``: one configuration ``theta`` of shape ``(n,)``. The n joint
  exponentials are formed at once as an ``(n, 3, 3)`` stack and composed with
  ``n - 1`` small matrix products; a few dozen numpy calls in all.
* ``batch``: ``N`` configurations. The 3x3 algebra is written out entry by
  entry on whole arrays of length ``N`` (layout ``(3, 3, N)``, batch last, so
  every operation is one contiguous vector operation), terms whose constant
  factor is zero are skipped (axis-aligned joints, the common case, cost a
  fraction of a general one), and the batch is processed in chunks that stay
  in cache.

Both are private; the tests check them against each other and against
finite differences of the forward kinematics.
"""

from __future__ import annotations

from typing import Literal, TypeAlias, overload

import numpy as np
from numpy.typing import NDArray

_Array: TypeAlias = NDArray[np.float64]
#: Entry (k, j) of one joint's rotation in the batch path: a constant (1.0 or 0.0) or a chunk-long array.
_Entry: TypeAlias = "float | _Array"

CHUNK = 4096
_EPS = 0.0  # constants are compared with exact zero: skip only true zeros


class ChainConstants:
    """Per-joint constants derived once from the screw axes."""

    def __init__(self, S: _Array) -> None:
        self.n = S.shape[1]
        self.w = np.ascontiguousarray(S[:3].T)  # (n, 3)
        self.v = np.ascontiguousarray(S[3:].T)  # (n, 3)
        w = self.w
        K = np.zeros((self.n, 3, 3))
        K[:, 0, 1], K[:, 0, 2] = -w[:, 2], w[:, 1]
        K[:, 1, 0], K[:, 1, 2] = w[:, 2], -w[:, 0]
        K[:, 2, 0], K[:, 2, 1] = -w[:, 1], w[:, 0]
        self.K = K
        self.K2 = K @ K
        self.Kv = (K @ self.v[:, :, None])[..., 0]
        self.K2v = (self.K2 @ self.v[:, :, None])[..., 0]
        # Sparse descriptions for the batch path.
        # R_i[k, j] = delta_kj + K[k, j] * s + K2[k, j] * (1 - c)
        self.rot_terms: list[list[tuple[int, int, float, float, float]]] = []
        for i in range(self.n):
            terms: list[tuple[int, int, float, float, float]] = []
            for k in range(3):
                for j in range(3):
                    d = 1.0 if k == j else 0.0
                    a, b = K[i, k, j], self.K2[i, k, j]
                    if d or a or b:
                        terms.append((k, j, d, a, b))
            self.rot_terms.append(terms)
        # p_i[k] = v[k] * theta + Kv[k] * (1 - c) + K2v[k] * (theta - s)
        self.trans_terms: list[list[tuple[int, float, float, float]]] = []
        for i in range(self.n):
            tterms: list[tuple[int, float, float, float]] = []
            for k in range(3):
                a, b, c = self.v[i, k], self.Kv[i, k], self.K2v[i, k]
                if a or b or c:
                    tterms.append((k, a, b, c))
            self.trans_terms.append(tterms)


# ---------------------------------------------------------------- single

def exp_stack(C: ChainConstants, theta: _Array) -> tuple[_Array, _Array]:
    """Rotations (n, 3, 3) and translations (n, 3) of e^{[S_i] theta_i}."""
    c = np.cos(theta)
    s = np.sin(theta)
    omc = 1.0 - c
    R = np.eye(3) + s[:, None, None] * C.K + omc[:, None, None] * C.K2
    p = theta[:, None] * C.v + omc[:, None] * C.Kv + (theta - s)[:, None] * C.K2v
    return R, p


def prefixes_single(C: ChainConstants, theta: _Array) -> tuple[_Array, _Array]:
    """R[i], p[i] of e^{[S_1]theta_1} ... e^{[S_i]theta_i} for i = 0..n (i = 0: identity)."""
    Re, pe = exp_stack(C, theta)
    n = C.n
    Rs = np.empty((n + 1, 3, 3))
    ps = np.empty((n + 1, 3))
    Rs[0] = np.eye(3)
    ps[0] = 0.0
    R = Re[0]
    p = pe[0]
    Rs[1] = R
    ps[1] = p
    for i in range(1, n):
        p = R @ pe[i] + p
        R = R @ Re[i]
        Rs[i + 1] = R
        ps[i + 1] = p
    return Rs, ps


def _cross_rows(a: _Array, b: _Array) -> _Array:
    """Row-wise cross product of (m, 3) arrays without np.cross's overhead."""
    out = np.empty_like(b)
    out[:, 0] = a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1]
    out[:, 1] = a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2]
    out[:, 2] = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    return out


def space_columns_single(C: ChainConstants, Rs: _Array, ps: _Array) -> _Array:
    """J_s (6, n) from the prefixes of :func:`prefixes_single`."""
    Rp = Rs[:-1]
    ws = (Rp @ C.w[:, :, None])[..., 0]
    vs = (Rp @ C.v[:, :, None])[..., 0] + _cross_rows(ps[:-1], ws)
    J = np.empty((6, C.n))
    J[:3] = ws.T
    J[3:] = vs.T
    return J


# ---------------------------------------------------------------- batch

def _compose(
    R: _Array | None, p: _Array | None, C: ChainConstants, i: int, th: _Array, s: _Array, omc: _Array, tms: _Array
) -> tuple[_Array, _Array]:
    """Return (R @ R_i, R @ p_i + p) for the chunk; R, p may be None (identity)."""
    # Build the entries of R_i and p_i that are not zero.
    Ri: dict[tuple[int, int], _Entry] = {}
    for k, j, d, a, b in C.rot_terms[i]:
        if a == 0.0 and b == 0.0:
            Ri[(k, j)] = d
        else:
            e: _Array | None = None
            if a:
                e = s * a
            if b:
                e = omc * b if e is None else e + omc * b
            assert e is not None  # a or b is non-zero here
            if d:
                e = e + d
            Ri[(k, j)] = e
    pi: dict[int, _Array] = {}
    for k, a, b, c in C.trans_terms[i]:
        e = None
        if a:
            e = th * a
        if b:
            e = omc * b if e is None else e + omc * b
        if c:
            e = tms * c if e is None else e + tms * c
        assert e is not None  # the constants keep only terms with a, b or c non-zero
        pi[k] = e
    m = th.shape[0]
    if R is None or p is None:  # (both or neither)
        R_new = np.zeros((3, 3, m))
        for (k, j), entry in Ri.items():
            R_new[k, j] = entry
        p_new = np.zeros((3, m))
        for k, pk in pi.items():
            p_new[k] = pk
        return R_new, p_new
    R_new = np.empty((3, 3, m))
    for j in range(3):
        acc: _Array | None = None
        for k in range(3):
            rkj = Ri.get((k, j))
            if rkj is None:
                continue
            term = R[:, k] if (isinstance(rkj, float) and rkj == 1.0) else R[:, k] * rkj
            acc = term if acc is None else acc + term
        if acc is None:
            R_new[:, j] = 0.0
        else:
            R_new[:, j] = acc
    p_new = p.copy()
    for k, pk in pi.items():
        p_new += R[:, k] * pk
    return R_new, p_new


def _rotate_const(R: _Array, vec: _Array) -> _Array:
    """R @ vec for a chunk R (3, 3, m) and a constant 3-vector, skipping zeros."""
    acc: _Array | None = None
    for k in range(3):
        if vec[k]:
            term = R[:, k] * vec[k] if vec[k] != 1.0 else R[:, k]
            acc = term if acc is None else acc + term
    if acc is None:
        return np.zeros((3, R.shape[-1]))
    return acc


_Prefixes: TypeAlias = "list[tuple[_Array, _Array]]"


@overload
def sweep_batch(
    C: ChainConstants, thT: _Array, want_columns: Literal[True], want_prefixes: bool = False, want_final: bool = True
) -> tuple[_Array, _Array | None, _Array | None, _Prefixes | None]: ...


@overload
def sweep_batch(
    C: ChainConstants, thT: _Array, want_columns: bool, want_prefixes: bool = False, want_final: bool = True
) -> tuple[_Array | None, _Array | None, _Array | None, _Prefixes | None]: ...


def sweep_batch(
    C: ChainConstants, thT: _Array, want_columns: bool, want_prefixes: bool = False, want_final: bool = True
) -> tuple[_Array | None, _Array | None, _Array | None, _Prefixes | None]:
    """Run along the chain for one chunk.

    Parameters
    ----------
    thT : (n, m) joint values, batch last.

    Returns
    -------
    J : (6, n, m) space Jacobian columns, or None
    R, p : (3, 3, m), (3, m) the full product e^{[S_1]θ_1}...e^{[S_n]θ_n}
        (when ``want_final`` is false and no prefixes are asked for, the
        product stops before the last joint and R, p are not meaningful)
    prefixes : list of (R, p) for i = 1..n (only when asked)
    """
    n, m = thT.shape
    c = np.cos(thT)
    s = np.sin(thT)
    omc = 1.0 - c
    tms = thT - s
    J = np.empty((6, n, m)) if want_columns else None
    R: _Array | None = None
    p: _Array | None = None
    pref: _Prefixes | None = [] if want_prefixes else None
    for i in range(n):
        if J is not None:
            w, v = C.w[i], C.v[i]
            if R is None or p is None:  # (both or neither)
                J[:3, i] = w[:, None]
                J[3:, i] = v[:, None]
            else:
                ws = _rotate_const(R, w)
                vs = _rotate_const(R, v)
                J[:3, i] = ws
                J[3, i] = vs[0] + p[1] * ws[2] - p[2] * ws[1]
                J[4, i] = vs[1] + p[2] * ws[0] - p[0] * ws[2]
                J[5, i] = vs[2] + p[0] * ws[1] - p[1] * ws[0]
        if i == n - 1 and not (want_final or want_prefixes):
            break  # the columns need only the products before the last joint
        R, p = _compose(R, p, C, i, thT[i], s[i], omc[i], tms[i])
        if pref is not None:
            pref.append((R, p))
    return J, R, p, pref


def product_batch(C: ChainConstants, thT: _Array) -> tuple[_Array, _Array]:
    """R (3, 3, m) and p (3, m) of the full product e^{[S_1]θ_1}...e^{[S_n]θ_n} for one chunk."""
    _, R, p, _ = sweep_batch(C, thT, want_columns=False)
    assert R is not None and p is not None  # want_final: the product over n >= 1 joints is formed
    return R, p


def times_home(R: _Array, p: _Array, M: _Array) -> tuple[_Array, _Array]:
    """(R, p) composed with a constant transform M, batch last: returns (3,3,m), (3,m)."""
    RM = np.empty_like(R)
    for j in range(3):
        RM[:, j] = _rotate_const(R, M[:3, j])
    pM = _rotate_const(R, M[:3, 3]) + p
    return RM, pM
