"""The chapters that call ``lie.exp_se3`` must notice when it is wrong.

A check such as det[Ad_{exp(X)}] = 1 holds for any rotation-and-translation, right or wrong, so it
cannot catch a wrong exponential. Here only the public ``jacobians.lie.exp_se3`` is replaced by a
classic mistake (the sign of the :math:`(\\theta - \\sin\\theta)[\\omega]^2v` term of the translation
flipped; the rotation stays right, and the forward kinematics, which has its own kernel, is untouched).
Chapters 10, 11 and 12 are then executed in this process: each must stop in a hidden check cell.
"""

from pathlib import Path

import numpy as np
import pytest

from jacobians import lie

ROOT = Path(__file__).resolve().parents[1]
_RIGHT = lie.exp_se3


def _wrong_exp_se3(twist_theta):
    xi = np.asarray(twist_theta, dtype=float)
    T = _RIGHT(xi)
    w, v = xi[..., :3], xi[..., 3:]
    _, _, C = lie._coefficients(np.linalg.norm(w, axis=-1))
    K = lie._skew(w)
    T[..., :3, 3] -= 2 * ((C[..., None, None] * (K @ K)) @ v[..., None])[..., 0]
    return T


def _run_until_a_check_fails(path):
    """Execute the chapter's code cells here; return (index, is a hidden cell) of the first AssertionError."""
    import jupytext
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    nb = jupytext.read(path)
    namespace: dict = {}
    printoptions = np.get_printoptions()
    rc = matplotlib.rc_context()
    rc.__enter__()
    try:
        for k, cell in enumerate(c for c in nb.cells if c.cell_type == "code"):
            try:
                exec(compile(cell.source, f"{path.name} code cell {k}", "exec"), namespace)
            except AssertionError:
                return k, "remove-cell" in cell.metadata.get("tags", [])
    finally:
        plt.close("all")
        rc.__exit__(None, None, None)
        np.set_printoptions(**printoptions)
    return None


def test_the_mutant_is_wrong_and_the_kernel_untouched():
    rng = np.random.default_rng(0)
    X = rng.normal(size=6)
    assert np.abs(_wrong_exp_se3(X) - _RIGHT(X)).max() > 1e-2
    assert np.allclose(_wrong_exp_se3(X)[:3, :3], _RIGHT(X)[:3, :3])


@pytest.mark.parametrize("chapter", ["10_inverse_kinematics", "11_redundancy", "12_jacobian_derivative"])
def test_chapter_fails_with_a_wrong_exp_se3(chapter, monkeypatch):
    pytest.importorskip("modern_robotics")
    pytest.importorskip("pinocchio")
    monkeypatch.setattr(lie, "exp_se3", _wrong_exp_se3)
    failed = _run_until_a_check_fails(ROOT / "chapters" / f"{chapter}.md")
    assert failed is not None, f"chapter {chapter} ran to the end with a wrong exp_se3"
    assert failed[1], f"the failing cell {failed[0]} is not a hidden check cell"
