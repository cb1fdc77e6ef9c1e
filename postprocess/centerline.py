"""Centerline of a boom from a results file's coordinates: ANCF beams
(cubic Hermite, node-major (x, y, dx/ds, dy/ds)) and rigid bodies
((x_c, y_c, theta), axis through the centre). Used to evaluate positions at
any material coordinate, e.g. for boom 3's moving frame (paper Fig. 9)."""
import numpy as np


def position(q, first, ncoords, length, s):
    """Position r(s) of a body whose coordinates are q[first:first+ncoords]."""
    if ncoords == 3:  # rigid body
        xc, yc, th = q[first:first + 3]
        a = s - 0.5 * length
        return np.array([xc + a * np.cos(th), yc + a * np.sin(th)])
    n_el = ncoords // 4 - 1
    l = length / n_el
    el = min(int(np.floor(s / l)), n_el - 1)
    xi = (s - el * l) / l
    e = q[first + 4 * el: first + 4 * el + 8]
    sh = [1 - 3 * xi**2 + 2 * xi**3, l * (xi - 2 * xi**2 + xi**3), 3 * xi**2 - 2 * xi**3, l * (-xi**2 + xi**3)]
    return sum(sh[k] * e[2 * k: 2 * k + 2] for k in range(4))


def moving_frame_deflection(q, first, ncoords, length, s_axis, s_point):
    """Deflection of material point s_point normal to the axis from r(0) to r(s_axis) (paper Fig. 9)."""
    o = position(q, first, ncoords, length, 0.0)
    x = position(q, first, ncoords, length, s_axis) - o
    x /= np.linalg.norm(x)
    n = np.array([-x[1], x[0]])
    return float(np.dot(position(q, first, ncoords, length, s_point) - o, n))
