"""Random chains and transforms for tests, exercises and property checks.

>>> import numpy as np
>>> chain = random_chain(np.random.default_rng(0), dof=4)
>>> chain.dof
4
"""

from __future__ import annotations

from typing import TypeAlias

import numpy as np
from numpy.typing import NDArray

from ._validation import positive_int
from .chain import SerialChain
from .lie import _exp_se3, _exp_so3

__all__ = ["random_rotation", "random_transform", "random_chain", "random_theta"]

#: What the ``rng`` arguments accept: a generator, a seed, or None for a fresh one.
RngLike: TypeAlias = "np.random.Generator | int | None"
#: A batch shape: ``()`` for one sample, an int or a tuple of ints.
Size: TypeAlias = "int | tuple[int, ...]"


def _rng(rng: RngLike) -> np.random.Generator:
    if isinstance(rng, np.random.Generator):
        return rng
    return np.random.default_rng(rng)


def random_rotation(rng: RngLike = None, size: Size = ()) -> NDArray[np.float64]:
    """Rotations from exponential coordinates drawn in a ball of radius pi."""
    rng = _rng(rng)
    size = (size,) if isinstance(size, int) else tuple(size)
    w = rng.normal(size=size + (3,))
    w /= np.linalg.norm(w, axis=-1, keepdims=True)
    return _exp_so3(w * rng.uniform(0, np.pi, size=size + (1,)))


def random_transform(rng: RngLike = None, size: Size = (), scale: float = 1.0) -> NDArray[np.float64]:
    """Random rigid transforms with translations of about ``scale``."""
    rng = _rng(rng)
    size = (size,) if isinstance(size, int) else tuple(size)
    return _exp_se3(np.concatenate([rng.normal(size=size + (3,)), scale * rng.normal(size=size + (3,))], -1))


def random_chain(rng: RngLike = None, dof: int | None = None, prismatic_probability: float = 0.25,
                 pitch_probability: float = 0.1) -> SerialChain:
    """A random chain: revolute joints (some with a pitch), prismatic joints, a random home pose."""
    rng = _rng(rng)
    n = int(rng.integers(1, 8)) if dof is None else positive_int(dof, "dof")
    if n < 1:
        raise ValueError(f"Expected dof >= 1, got {n}")
    S = np.zeros((6, n))
    for i in range(n):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        if rng.uniform() < prismatic_probability:
            S[3:, i] = axis
        else:
            q = rng.normal(size=3)
            S[:3, i] = axis
            S[3:, i] = -np.cross(axis, q)
            if rng.uniform() < pitch_probability:
                S[3:, i] += rng.normal() * axis
    return SerialChain(S, random_transform(rng))


def random_theta(chain: SerialChain, rng: RngLike = None, size: Size = ()) -> NDArray[np.float64]:
    """Joint values in [-pi, pi] (revolute) or [-1, 1] (prismatic), shape size + (n,)."""
    rng = _rng(rng)
    size = (size,) if isinstance(size, int) else tuple(size)
    scale: NDArray[np.float64] = np.array([np.pi if t == "R" else 1.0 for t in chain.joint_types])
    return rng.uniform(-1, 1, size=size + (chain.dof,)) * scale
