r"""Serial chains described by screw axes, and their forward kinematics.

A chain of n one-degree-of-freedom joints is given, as in Modern Robotics, by
the screw axes :math:`\mathcal S_1,\dots,\mathcal S_n` of its joints, expressed
in the space frame {s} with the robot at its home pose, and the home pose
:math:`M` of the end-effector frame {b}. The forward kinematics is the product
of exponentials

.. math:: T_{sb}(\theta) = e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_n]\theta_n} M
          = M e^{[\mathcal B_1]\theta_1}\cdots e^{[\mathcal B_n]\theta_n},

with body axes :math:`\mathcal B_i = [\mathrm{Ad}_{M^{-1}}]\mathcal S_i`.

>>> import numpy as np
>>> import jacobians as jac
>>> arm = jac.robots.planar_2r(l1=1.0, l2=1.0)
>>> arm.fk([np.pi / 2, 0.0])[:3, 3].round(12) + 0.0
array([0., 2., 0.])
"""

from __future__ import annotations

import os

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _kernels as K
from ._validation import (
    UNIT_TOL,
    real_array,
    screw_axes_array,
    theta_array,
    transform_array,
)
from .lie import _adjoint, _exp_se3, _inverse_transform, rotation_about

__all__ = ["SerialChain"]


class SerialChain:
    r"""An open chain of revolute and prismatic joints in product-of-exponentials form.

    Parameters
    ----------
    screw_axes : array_like, shape (6, n)
        Column i is the screw axis :math:`\mathcal S_i = (\omega_i, v_i)` of joint i
        in {s} at the home pose. Revolute: :math:`\|\omega_i\| = 1`
        (:math:`v_i = -\omega_i \times q_i` for a point :math:`q_i` on the axis, plus
        :math:`h\omega_i` for a screw of pitch h). Prismatic: :math:`\omega_i = 0`,
        :math:`\|v_i\| = 1`.
    home : array_like, shape (4, 4)
        :math:`M`, the pose of {b} in {s} at :math:`\theta = 0`.
    link_homes : array_like, shape (n, 4, 4), optional
        Home poses :math:`M_i` of a frame fixed to each link i (for the link
        Jacobians and the mass matrix). If omitted, frame i sits on joint
        axis i, at the point closest to the origin of {s} (for a prismatic
        joint, at the origin of the previous frame), with the orientation of {s};
        the frame of the last link is then replaced by {b}.
    joint_points : array_like, shape (n, 3), optional
        A point of each joint's axis at home, where the joint is drawn (the
        screw axis fixes the line, not where on it the joint sits). Default:
        the point of the axis closest to the origin of {s} (for a prismatic
        joint, its link frame's origin). A point off its revolute axis raises.
    name : str, optional
        Shown in ``repr`` and in figures.

    Notes
    -----
    MR: the ``Slist``, ``M`` arguments of ``FKinSpace`` / ``JacobianSpace``.

    >>> import numpy as np
    >>> S = np.array([[0, 0, 1, 0, 0, 0], [0, 0, 1, 0, -1, 0]]).T
    >>> M = np.eye(4); M[0, 3] = 2.0
    >>> chain = SerialChain(S, M)
    >>> chain.dof, chain.joint_types
    (2, 'RR')
    >>> chain.body_axes[:, 0]
    array([0., 0., 1., 0., 2., 0.])
    """

    def __init__(
        self,
        screw_axes: ArrayLike,
        home: ArrayLike,
        link_homes: ArrayLike | None = None,
        name: str | None = None,
        joint_points: ArrayLike | None = None,
    ) -> None:
        S = screw_axes_array(screw_axes, "screw_axes")
        M = transform_array(home, "home", batch_allowed=False)
        # Re-orthonormalise tiny typing errors away so products stay in SE(3).
        U, _, Vt = np.linalg.svd(M[:3, :3])
        M = M.copy()
        M[:3, :3] = U @ Vt
        self._S = S.copy()
        self._S.setflags(write=False)
        self._M = M
        self._M.setflags(write=False)
        B = _adjoint(_inverse_transform(M)) @ S
        B[np.abs(B) < 1e-15] = 0.0
        self._B = B
        self._B.setflags(write=False)
        n = S.shape[1]
        self._types = "".join("R" if np.linalg.norm(S[:3, i]) > UNIT_TOL else "P" for i in range(n))
        if link_homes is None:
            link_homes = self._default_link_homes()
        else:
            link_homes = transform_array(link_homes, "link_homes")
            if link_homes.shape != (n, 4, 4):
                raise ValueError(f"Expected link_homes with shape ({n}, 4, 4), got shape {link_homes.shape}")
        self._link_homes = np.array(link_homes, dtype=float)
        self._link_homes.setflags(write=False)
        self._joint_points = self._check_joint_points(joint_points)
        self._joint_points.setflags(write=False)
        if name is not None and not isinstance(name, str):
            raise TypeError(f"Expected a str for name, got {type(name).__name__}")
        self.name = name
        self._C = K.ChainConstants(self._S)
        # The body Jacobian is the space Jacobian of the reversed chain with axes -B_n, ..., -B_1:
        # J_bi = Ad_{e^{-[B_n]θ_n}...e^{-[B_{i+1}]θ_{i+1}}} B_i (columns reversed, sign flipped).
        self._C_rev = K.ChainConstants(-self._B[:, ::-1])

    # ------------------------------------------------------------ properties
    @property
    def dof(self) -> int:
        """Number of joints n."""
        return int(self._S.shape[1])

    @property
    def screw_axes(self) -> NDArray[np.float64]:
        """(6, n) space-frame screw axes at home (read-only)."""
        return self._S

    @property
    def body_axes(self) -> NDArray[np.float64]:
        r"""(6, n) body-frame screw axes (read-only): :math:`\mathcal B_i = [\mathrm{Ad}_{M^{-1}}]\mathcal S_i`."""
        return self._B

    @property
    def home(self) -> NDArray[np.float64]:
        """(4, 4) home pose M of {b} (read-only)."""
        return self._M

    @property
    def link_homes(self) -> NDArray[np.float64]:
        """(n, 4, 4) home poses of the link frames (read-only)."""
        return self._link_homes

    @property
    def joint_types(self) -> str:
        """One letter per joint: ``'R'`` revolute, ``'P'`` prismatic."""
        return self._types

    def __repr__(self) -> str:
        label = f" {self.name!r}" if self.name else ""
        return f"<SerialChain{label}: {self.dof} joints {self._types}>"

    # ------------------------------------------------------------ helpers
    def _default_link_homes(self) -> NDArray[np.float64]:
        n = self.dof
        homes = np.tile(np.eye(4), (n, 1, 1))
        prev = np.zeros(3)
        for i in range(n):
            w, v = self._S[:3, i], self._S[3:, i]
            if self._types[i] == "R":
                q = np.cross(w, v)  # point on the axis closest to the origin
                prev = q
            else:
                q = prev
            homes[i, :3, 3] = q
        homes[-1] = self._M
        return homes

    def _check_joint_points(self, joint_points: ArrayLike | None) -> NDArray[np.float64]:
        n = self.dof
        if joint_points is None:
            out = np.empty((n, 3))
            for i in range(n):
                w, v = self._S[:3, i], self._S[3:, i]
                out[i] = np.cross(w, v) if self._types[i] == "R" else self._link_homes[i, :3, 3]
            return out
        pts = real_array(joint_points, "joint_points", (n, 3), batch_allowed=False)
        for i in range(n):
            if self._types[i] == "R":
                w, v = self._S[:3, i], self._S[3:, i]
                q = pts[i]
                off = (q - w * np.dot(w, q)) - np.cross(w, v)  # perpendicular offset from the axis line
                if np.linalg.norm(off) > 1e-6 * max(1.0, float(np.linalg.norm(q))):
                    raise ValueError(
                        f"joint_points[{i}] = {q} is not on the axis of revolute joint {i} "
                        f"(it is {np.linalg.norm(off):.3g} away from the line)"
                    )
        return pts.copy()

    def axis_points(self) -> NDArray[np.float64]:
        """(n, 3) the point of each joint axis where the joint sits at home (``joint_points``)."""
        return self._joint_points.copy()

    # ------------------------------------------------------------ kinematics
    def fk(self, theta: ArrayLike) -> NDArray[np.float64]:
        r"""Forward kinematics :math:`T_{sb}(\theta)`. MR: ``FKinSpace`` / ``FKinBody``.

        Parameters
        ----------
        theta : array_like, shape (..., n)
            One configuration, shape (n,), or a batch of them along leading
            axes (one per row for shape (k, n)). A column of shape (n, 1) is
            refused: pass ``np.ravel(theta)``.

        Returns
        -------
        T_sb : ndarray, shape (..., 4, 4)
        """
        th = theta_array(theta, self.dof)
        if th.ndim == 1:
            Rs, ps = K.prefixes_single(self._C, th)
            T = np.eye(4)
            T[:3, :3] = Rs[-1] @ self._M[:3, :3]
            T[:3, 3] = Rs[-1] @ self._M[:3, 3] + ps[-1]
            return T
        batch = th.shape[:-1]
        flat = th.reshape(-1, self.dof)
        N = flat.shape[0]
        out = np.zeros((N, 4, 4))
        out[:, 3, 3] = 1.0
        for a in range(0, N, K.CHUNK):
            thT = np.ascontiguousarray(flat[a:a + K.CHUNK].T)
            R, p = K.product_batch(self._C, thT)
            RM, pM = K.times_home(R, p, self._M)
            out[a:a + K.CHUNK, :3, :3] = RM.transpose(2, 0, 1)
            out[a:a + K.CHUNK, :3, 3] = pM.T
        return out.reshape(batch + (4, 4))

    def joint_transforms(self, theta: ArrayLike) -> NDArray[np.float64]:
        r"""The exponentials :math:`e^{[\mathcal S_i]\theta_i}`, shape (..., n, 4, 4)."""
        th = theta_array(theta, self.dof)
        return _exp_se3(np.swapaxes(self._S, 0, 1) * th[..., :, None])

    def prefix_transforms(self, theta: ArrayLike) -> NDArray[np.float64]:
        r"""Partial products :math:`e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_i]\theta_i}`, i = 0..n.

        Returns shape (..., n + 1, 4, 4); entry 0 is the identity. Column i of the
        space Jacobian is :math:`[\mathrm{Ad}]` of entry i - 1 applied to :math:`\mathcal S_i`.
        """
        E = self.joint_transforms(theta)
        out = np.empty(E.shape[:-3] + (self.dof + 1, 4, 4))
        out[..., 0, :, :] = np.eye(4)
        for i in range(self.dof):
            out[..., i + 1, :, :] = out[..., i, :, :] @ E[..., i, :, :]
        return out

    def link_poses(self, theta: ArrayLike) -> NDArray[np.float64]:
        r"""Poses :math:`T_{s,i}(\theta)` of the link frames, shape (..., n, 4, 4).

        :math:`T_{s,i}(\theta) = e^{[\mathcal S_1]\theta_1}\cdots e^{[\mathcal S_i]\theta_i} M_i`.
        """
        P = self.prefix_transforms(theta)
        poses: NDArray[np.float64] = P[..., 1:, :, :] @ self._link_homes
        return poses

    def joint_positions(self, theta: ArrayLike) -> NDArray[np.float64]:
        """Where each joint's axis point is at ``theta``, followed by the origin of {b}: shape (..., n + 1, 3).

        Joint i is carried by the joints before it, so its point is
        ``prefix[i - 1] @ q_i``. Used to draw the arm.
        """
        P = self.prefix_transforms(theta)
        q = self.axis_points()
        pts = (P[..., :-1, :3, :3] @ q[:, :, None])[..., 0] + P[..., :-1, :3, 3]
        tip = (P[..., -1, :, :] @ self._M)[..., None, :3, 3]
        return np.concatenate([pts, tip], axis=-2)

    # ------------------------------------------------------------ constructors
    @classmethod
    def from_dh(
        cls,
        a: ArrayLike,
        alpha: ArrayLike,
        d: ArrayLike,
        offset: ArrayLike | None = None,
        joint_types: str | None = None,
        convention: str = "classical",
        tool: ArrayLike | None = None,
        name: str | None = None,
    ) -> SerialChain:
        r"""A chain from a Denavit–Hartenberg table, in either DH convention.

        A DH table has four numbers per joint, :math:`a_i, \alpha_i, d_i, \theta_i`;
        one of :math:`\theta_i` (revolute) or :math:`d_i` (prismatic) is the joint
        variable and the other three are constants. ``convention`` says how the
        table is read (both are taken; the default is the classical one):

        * ``"classical"`` (standard, Denavit–Hartenberg; the Robotics Toolbox's
          ``RevoluteDH``/``PrismaticDH``):
          :math:`{}^{i-1}T_i = R_z(\theta_i)\,T_z(d_i)\,T_x(a_i)\,R_x(\alpha_i)`, and
          joint i moves along or about the z axis of frame i - 1;
        * ``"modified"`` (Craig; the Toolbox's ``RevoluteMDH``/``PrismaticMDH``):
          :math:`{}^{i-1}T_i = R_x(\alpha_{i-1})\,T_x(a_{i-1})\,R_z(\theta_i)\,T_z(d_i)`,
          where the i-th entries of ``a`` and ``alpha`` are :math:`a_{i-1}, \alpha_{i-1}`,
          and joint i moves along or about the z axis of frame i.

        ``d`` and ``offset`` are the d and θ columns of the table at the home pose
        (all joint values zero), in both conventions and for both joint types:

        * revolute joint: :math:`\theta_i = q_i + \text{offset}_i` and :math:`d_i`
          is constant;
        * prismatic joint: :math:`d_i = q_i + d` (``d`` is its length at home) and
          :math:`\theta_i = \text{offset}_i` is constant.

        So a Toolbox ``PrismaticDH(theta=t, a=a, alpha=al, offset=o)`` is
        ``a=a, alpha=al, d=o, offset=t`` here, and ``RevoluteDH(d=d, a=a,
        alpha=al, offset=o)`` is ``a=a, alpha=al, d=d, offset=o``. The screw
        axis of joint i is the z axis it moves along or about, at the home pose.

        Parameters
        ----------
        a, alpha, d : array_like, shape (n,)
        offset : array_like, shape (n,), optional
            The θ column at the home pose: a revolute joint's angle at
            :math:`q_i = 0`, a prismatic joint's constant angle. Default zeros.
        joint_types : str, optional
            One letter per joint, ``'R'`` or ``'P'``; default all revolute.
        convention : {"classical", "modified"}
        tool : array_like, shape (4, 4), optional
            Constant transform from the last DH frame to {b}.
        name : str, optional

        Returns
        -------
        SerialChain
            Its ``link_homes`` are the DH frames 1..n at the home pose.

        >>> arm = SerialChain.from_dh(a=[1.0, 1.0], alpha=[0, 0], d=[0, 0])
        >>> arm.screw_axes[:, 1]
        array([ 0.,  0.,  1.,  0., -1.,  0.])

        A prismatic joint keeps its constant θ (here 90°, so it slides along z
        of a frame turned by 90° about z):

        >>> arm = SerialChain.from_dh([1.0, 0.0], [0, 0], [0, 0], offset=[np.pi / 2, 0.0], joint_types="PR")
        >>> arm.fk([0.5, 0.0])[:3, 3].round(12) + 0.0
        array([0. , 1. , 0.5])
        """
        if convention not in ("classical", "modified"):
            raise ValueError(f"Expected convention 'classical' or 'modified', got {convention!r}")
        a = real_array(a, "a", (None,), batch_allowed=False)
        n = a.shape[0]
        alpha = real_array(alpha, "alpha", (n,), batch_allowed=False)
        d = real_array(d, "d", (n,), batch_allowed=False)
        offset = np.zeros(n) if offset is None else real_array(offset, "offset", (n,), batch_allowed=False)
        if joint_types is None:
            joint_types = "R" * n
        if not isinstance(joint_types, str):
            raise TypeError(f"Expected joint_types as a str such as 'RRP', got {type(joint_types).__name__}")
        if len(joint_types) != n or set(joint_types) - {"R", "P"}:
            raise ValueError(f"Expected joint_types of {n} letters 'R' or 'P', got {joint_types!r}")

        def trans(axis: str, x: float) -> NDArray[np.float64]:
            T = np.eye(4)
            T["xyz".index(axis), 3] = x
            return T

        def rot(axis: str, x: float) -> NDArray[np.float64]:
            T = np.eye(4)
            T[:3, :3] = rotation_about(axis, x)
            return T

        S = np.zeros((6, n))
        frames = []
        points = []
        T = np.eye(4)
        for i in range(n):
            th_i = offset[i]  # the θ column at home: a revolute joint's home angle, a prismatic joint's constant
            if convention == "classical":
                z_frame = T  # joint i turns about z of frame i-1
                T = T @ rot("z", th_i) @ trans("z", d[i]) @ trans("x", a[i]) @ rot("x", alpha[i])
            else:
                z_frame = T @ rot("x", alpha[i]) @ trans("x", a[i])
                T = z_frame @ rot("z", th_i) @ trans("z", d[i])
            z = z_frame[:3, 2]
            q = z_frame[:3, 3]
            points.append(q.copy())
            if joint_types[i] == "R":
                S[:3, i] = z
                S[3:, i] = -np.cross(z, q)
            else:
                S[3:, i] = z
            frames.append(T.copy())
        M = T.copy()
        if tool is not None:
            M = M @ transform_array(tool, "tool", batch_allowed=False)
        S[np.abs(S) < 1e-15] = 0.0
        return cls(S, M, link_homes=np.array(frames), name=name, joint_points=np.array(points))


    @classmethod
    def from_urdf(cls, path: str | os.PathLike[str], base: str, tip: str, name: str | None = None) -> SerialChain:
        r"""The chain from link ``base`` to link ``tip`` of a URDF file.

        {s} is the base link's frame and {b} the tip link's frame. Revolute,
        continuous and prismatic joints become the chain's joints, in order
        from base to tip; fixed joints are folded in. The link frames
        (``link_homes``) are the child links of the moving joints and the joint
        points are the joint frames' origins. See :mod:`jacobians.urdf` for the
        conversion and :func:`jacobians.urdf.read_chain` for the joint names
        and limits. Needs the optional package yourdfpy
        (``pip install 'jacobians[urdf]'``), imported only here.

        Raises ``ValueError`` for a link the file does not have, a tip that is
        not below the base, and floating, planar or mimic joints on the way.

        >>> from jacobians.robots import urdf_path
        >>> arm = SerialChain.from_urdf(urdf_path("panda"), "panda_link0", "panda_link8")
        >>> arm.dof, arm.joint_types
        (7, 'RRRRRRR')
        """
        from .urdf import read_chain

        data = read_chain(path, base, tip)
        label = name if name is not None else f"{data.robot_name or 'URDF'} ({base} to {tip})"
        return cls(data.screw_axes, data.home, link_homes=data.link_homes, name=label,
                   joint_points=data.joint_points)


def _as_chain(chain: object) -> SerialChain:
    if not isinstance(chain, SerialChain):
        raise TypeError(f"Expected a jacobians.SerialChain, got {type(chain).__name__}")
    return chain
