"""Draw the book's social card, ``_theme/social-card.png`` (1200 x 630 px).

The card is the image a link preview shows (``og:image``, sphinxext-opengraph's
``ogp_image``): the course's title over a planar 3R arm drawn by the library,
with the end effector's velocity from its Jacobian. Run
``python -m tools.social_card`` after changing it and commit the PNG.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import jacobians as jac
from jacobians.plotting.planar import draw_planar_arm

OUT = Path(__file__).resolve().parents[1] / "_theme" / "social-card.png"


def main() -> None:
    arm = jac.robots.planar_3r(l1=1.0, l2=1.0, l3=1.0)
    theta = np.array([0.35, 0.7, 0.6])
    fig = plt.figure(figsize=(12, 6.3), dpi=100, facecolor="white")
    fig.text(0.05, 0.72, "Manipulator Jacobians", fontsize=44, weight="bold", color="#1a1a1a")
    fig.text(0.05, 0.58, "How joint velocities move the end effector", fontsize=22, color="#333333")
    fig.text(0.05, 0.22, "An interactive course: live figures, exercises, slides", fontsize=18, color="#333333")
    ax = fig.add_axes((0.58, 0.06, 0.4, 0.88))
    draw_planar_arm(ax, arm, theta, show_frames=False)
    p = arm.joint_positions(theta)[-1]
    twist = jac.space_jacobian(arm, theta) @ np.array([0.4, 0.3, 0.5])  # V_s = (omega, v_s)
    tip = np.array([p[0], p[1], 0.0])
    v = 0.4 * (twist[3:] + np.cross(twist[:3], tip))  # velocity of the tip point v_s + omega x p, drawn over 0.4 s
    ax.annotate("", xy=(p[0] + v[0], p[1] + v[1]), xytext=(p[0], p[1]),
                arrowprops={"arrowstyle": "-|>", "lw": 3, "color": "#B5470B"})
    ax.set_xlim(-0.6, 3.2)
    ax.set_ylim(-0.4, 3.0)
    ax.set_aspect("equal")
    ax.axis("off")
    fig.savefig(OUT, dpi=100, facecolor="white")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
