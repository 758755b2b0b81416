"""Tests of the bridges to linear-first conventions and to Pinocchio."""

import numpy as np
import pytest

import jacobians as jac
from jacobians import interop
from jacobians.testing import close, random_chain, random_theta


def test_swap_is_an_involution():
    J = np.random.default_rng(0).normal(size=(3, 6, 4))
    assert np.array_equal(interop.to_angular_first(interop.to_linear_first(J)), J)
    assert np.allclose(interop.SWAP @ J, interop.to_linear_first(J))
    V = np.arange(6.0)
    assert np.array_equal(interop.to_linear_first(V), [3, 4, 5, 0, 1, 2])


def test_pinocchio_reference_frames():
    pin = pytest.importorskip("pinocchio")
    rng = np.random.default_rng(1)
    for chain in [jac.robots.ur5(), jac.robots.spatial_rrp(), jac.robots.scara()] + [
            random_chain(rng, pitch_probability=0.0) for _ in range(5)]:
        model, fid = interop.to_pinocchio_model(chain)
        data = model.createData()
        for _ in range(3):
            q = random_theta(chain, rng)
            pin.forwardKinematics(model, data, q)
            pin.updateFramePlacements(model, data)
            assert close(data.oMf[fid].homogeneous, chain.fk(q))   # well-conditioned: 1e-12 (jacobians.testing.close)
            pin.computeJointJacobians(model, data, q)
            get = lambda ref, model=model, data=data, fid=fid: pin.getFrameJacobian(model, data, fid, ref)
            P = interop.SWAP
            assert close(get(pin.ReferenceFrame.WORLD), P @ jac.space_jacobian(chain, q))
            assert close(get(pin.ReferenceFrame.LOCAL), P @ jac.body_jacobian(chain, q))
            assert close(get(pin.ReferenceFrame.LOCAL_WORLD_ALIGNED), P @ jac.geometric_jacobian(chain, q))


def test_pitch_refused():
    pytest.importorskip("pinocchio")
    S = np.array([[0, 0, 1, 0, 0, 0.5]], dtype=float).T
    with pytest.raises(ValueError, match="pitch"):
        interop.to_pinocchio_model(jac.SerialChain(S, np.eye(4)))
