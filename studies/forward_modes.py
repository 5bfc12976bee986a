"""How often forward kinematics returns another pose than the one whose lengths it was given,
far from home: the thesis platform with joint limits opened to 178 deg and strokes 0.01-5 m,
random poses within every limit over a wide box about home (yaw +-115 deg, roll and pitch
+-69 deg) that the solver takes as the working mode when started at the pose itself; lengths from
the closed form |p + R b_k - a_k|. Prints the counts for rows solved cold and tracked from the row
before. Usage: python studies/forward_modes.py [POSES] (default 20000)."""
import sys

import numpy as np

import stewart


def rotation(roll, pitch, yaw):
    cr, sr, cp, sp, cy, sy = np.cos(roll), np.sin(roll), np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def main(n):
    table = {p["name"]: p["defaults"] for p in stewart.parameters()}
    base, top = (np.reshape(table[k], (6, 3)) for k in ("base_joint", "platform_joint"))
    platform = stewart.Platform(base_joint_limit=np.radians(178.0),
                                platform_joint_limit=np.radians(178.0), stroke_min=0.01, stroke_max=5.0)
    box = np.array([[-0.5, 0.5], [-0.5, 0.5], [0.1, 0.9], [-1.2, 1.2], [-1.2, 1.2], [-2.0, 2.0]])
    rng = np.random.default_rng(2026)
    kept, drawn = [], 0
    while sum(len(k) for k in kept) < n:
        q = rng.uniform(box[:, 0], box[:, 1], (4 * n, 6))
        drawn += len(q)
        q = q[platform.limits(q).within]
        L = np.array([np.linalg.norm(p[:3] + top @ rotation(*p[3:]).T - base, axis=1) for p in q])
        kept.append((q, L)[0][platform.forward(L, guess=q, cold=True).status == 0])
    q = np.concatenate(kept)[:n]
    L = np.array([np.linalg.norm(p[:3] + top @ rotation(*p[3:]).T - base, axis=1) for p in q])
    print(f"{n} poses on the working mode (of {drawn} drawn)")
    for name, found in (("cold", platform.forward(L, cold=True)), ("tracked", platform.forward(L))):
        solved = found.status == 0
        off = np.array([max(np.abs(a[:3] - b[:3]).max(), np.abs(rotation(*a[3:]) - rotation(*b[3:])).max())
                        for a, b in zip(found.pose, q)])
        print(f"{name:8s} solved {solved.sum():6d}  another pose returned {(solved & (off > 1e-7)).sum():4d}"
              f"  refused {(~solved).sum():6d}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 20000)
