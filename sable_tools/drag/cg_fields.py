#!/usr/bin/python3
"""Reads the coarse-grained fields written by `fix ave/cg` (HDF5; a killed run's
file too), averages the chosen windows (weighted by their samples), and gives
P = tr(sigma)/3 and the principal stresses and directions. Optional figures:
P (and phi) along the vertical line through x = y = 0 of the grid, and
guillard2015 Fig. 7 in a vertical plane: at each node the ellipse sigma n / P
(n a unit vector of the plane), i.e. axes along the in-plane principal
directions with lengths proportional to eigenvalue / P, coloured by P.

    cg_fields.py F.h5 [--windows=A:B] [--line P.png] [--ellipses E.png] [--plane xz|yz] [--at 0]
                      [--layers LEVEL]

--layers LEVEL (the bed's surface height in the grid's frame, m): per horizontal layer of
nodes, the means of P, sigma_zz and phi over the nodes one kernel support or more inside the
side wall (a cylindrical container centred on the grid), against the weight above per area,
g (LEVEL - z) rho_mean (rho_mean: the layer means of rho from z to 2 supports below LEVEL),
and the axis' P over the layer's: how far the bed's pressure is from hydrostatic, and
whether it dips at the cylinder's axis.

Grid coordinates are those of the compute (the mesh body frame with `frame mesh`).
"""
import argparse

import numpy as np

from sable_tools.readers.h5 import cg_windows  # the fix ave/cg file, windows averaged

COMPONENTS = ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))  # xx yy zz xy xz yz


def tensor(s6):
    """[..., 6] (xx yy zz xy xz yz) -> [..., 3, 3] symmetric."""
    t = np.empty(s6.shape[:-1] + (3, 3))
    for c, (a, b) in enumerate(COMPONENTS):
        t[..., a, b] = t[..., b, a] = s6[..., c]
    return t


def pressure(s6):
    return (s6[..., 0] + s6[..., 1] + s6[..., 2]) / 3.0


def principal(s6):
    """Eigenvalues (ascending) and unit eigenvectors (columns) of each node's stress."""
    return np.linalg.eigh(tensor(s6))


def layers(d, level, g=9.81):
    """Per z: (mean P, mean sigma_zz, mean phi over the layer's inner nodes, weight above per
    area, axis P). Inner: radius <= grid half-width + half a cell - the kernel support."""
    x, y, z = d["x"], d["y"], d["z"]
    R = x.max() + 0.5 * (x[1] - x[0])
    X, Y = np.meshgrid(x, y, indexing="ij")
    inner = np.hypot(X, Y) <= R - d["support"]
    mean = lambda f: np.array([f[:, :, k][inner].mean() for k in range(len(z))])
    P, szz, phi, rho = mean(pressure(d["stress"])), mean(d["stress"][..., 2]), mean(d["phi"]), mean(d["rho"])
    deep = z <= level - 2 * d["support"]  # below the kernel-smoothed surface
    weight = np.array([g * (level - zk) * rho[deep & (z >= zk)].mean() if (deep & (z >= zk)).any() else np.nan
                       for zk in z])
    i, j = np.abs(x).argmin(), np.abs(y).argmin()
    return P, szz, phi, weight, pressure(d["stress"][i, j])


def plot_line(d, out, level=None):
    """With `level` (--layers) also the layer means of P and sigma_zz and the weight above."""
    import matplotlib.pyplot as plt
    i, j = np.abs(d["x"]).argmin(), np.abs(d["y"]).argmin()
    P = pressure(d["stress"][i, j])
    fig, ax = plt.subplots(1, 2, figsize=(7, 4), sharey=True)
    ax[0].plot(P, d["z"], "o-", label="P on the axis")
    if level is not None:
        Pl, szz, _, w, _ = layers(d, level)
        ax[0].plot(Pl, d["z"], "-", label="P, layer mean")
        ax[0].plot(szz, d["z"], "--", label="sigma_zz, layer mean")
        ax[0].plot(w, d["z"], "k:", label="weight above per area")
        ax[0].legend(fontsize=7)
    ax[0].set_xlabel("P = tr(sigma)/3 (Pa)")
    ax[0].set_ylabel(f"z (x = {d['x'][i]:.3g}, y = {d['y'][j]:.3g})")
    ax[1].plot(d["phi"][i, j], d["z"], "o-")
    ax[1].set_xlabel("phi")
    fig.suptitle(f"steps {d['step'][0]}..{d['step'][-1]}, frame {d['frame']}")
    fig.tight_layout()
    fig.savefig(out, dpi=150)


def plot_ellipses(d, out, plane="xz", at=0.0, stride=2):
    import matplotlib.pyplot as plt
    from matplotlib.collections import EllipseCollection
    a = "xyz".index(plane[0])  # horizontal axis of the picture; z is vertical
    cut = 1 - a  # the other horizontal axis, held at `at`
    k = np.abs(d["xyz"[cut]] - at).argmin()
    s = np.take(d["stress"], k, axis=cut)[::stride, ::stride]  # [n_a, nz, 6], every stride-th node
    t = tensor(s)[..., [a, 2], :][..., :, [a, 2]]  # in-plane 2x2
    P = pressure(s)
    val, vec = np.linalg.eigh(t)
    ok = P > 1e-3 * P.max()  # empty and surface nodes: no stress to draw
    xa, za = d["xyz"[a]][::stride], d["z"][::stride]
    h = min(np.diff(xa).min(initial=np.inf), np.diff(za).min(initial=np.inf))
    h = h if np.isfinite(h) else 1.0
    X, Z = np.meshgrid(xa, za, indexing="ij")
    # Diameters 0.6 h per unit of eigenvalue / P (at most 1.5: 0.9 h, so that neighbours do not touch).
    widths = 0.6 * h * np.clip(val[..., 1][ok] / P[ok], 0, 1.5)  # major axis: larger eigenvalue
    heights = 0.6 * h * np.clip(val[..., 0][ok] / P[ok], 0, 1.5)
    angles = np.degrees(np.arctan2(vec[..., 1, 1], vec[..., 0, 1]))[ok]
    fig, ax = plt.subplots(figsize=(6, 7))
    ec = EllipseCollection(widths, heights, angles, units="xy", offsets=np.c_[X[ok], Z[ok]],
                           offset_transform=ax.transData, array=P[ok], cmap="viridis")
    ax.add_collection(ec)
    ax.autoscale_view()
    ax.set_aspect("equal")
    ax.set_xlabel(plane[0])
    ax.set_ylabel("z")
    ax.set_title(f"sigma n / P in the {plane} plane at {'xyz'[cut]} = {d['xyz'[cut]][k]:.3g}")
    fig.colorbar(ec, label="P (Pa)", shrink=0.6)
    fig.savefig(out, dpi=150)


def print_layers(d, level):
    P, szz, phi, w, Pax = layers(d, level)
    print(f"# layers (surface z = {level:.6g}): z depth P sigma_zz phi weight_above sigma_zz/weight P/weight P_axis/P")
    for k, z in enumerate(d["z"]):
        if z < level:
            print(f"{z:.6g} {level - z:.6g} {P[k]:.6g} {szz[k]:.6g} {phi[k]:.4f} {w[k]:.6g} "
                  f"{szz[k] / w[k]:.3f} {P[k] / w[k]:.3f} {Pax[k] / P[k]:.3f}")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("file")
    p.add_argument("--windows", default=":", help="python slice of windows to average, e.g. --windows=-10: (default all)")
    p.add_argument("--line", help="figure: P and phi along the vertical line x = y = 0")
    p.add_argument("--ellipses", help="figure: stress ellipses in a vertical plane")
    p.add_argument("--plane", default="xz", choices=("xz", "yz"))
    p.add_argument("--at", type=float, default=0.0, help="coordinate of the plane along the other horizontal axis")
    p.add_argument("--stride", type=int, default=2, help="ellipses at every stride-th node (default 2)")
    p.add_argument("--layers", type=float, metavar="LEVEL", help="layer means against the weight above (LEVEL: surface z)")
    a = p.parse_args()
    d = cg_windows(a.file, slice(*[int(x) if x else None for x in a.windows.split(":")]))
    i, j = np.abs(d["x"]).argmin(), np.abs(d["y"]).argmin()
    P = pressure(d["stress"][i, j])
    val, vec = principal(d["stress"][i, j])
    print(f"# {a.file}: windows ending at steps {d['step'].tolist()}, frame {d['frame']}")
    print(f"# x = {d['x'][i]:.6g} y = {d['y'][j]:.6g}: z P phi sigma1 sigma3 major-direction")
    for k, z in enumerate(d["z"]):
        e = vec[k][:, 2]
        print(f"{z:.6g} {P[k]:.6g} {d['phi'][i, j, k]:.4f} {val[k, 2]:.6g} {val[k, 0]:.6g} "
              f"{e[0]:+.3f} {e[1]:+.3f} {e[2]:+.3f}")
    if a.layers is not None:
        print_layers(d, a.layers)
    if a.line:
        plot_line(d, a.line, a.layers)
    if a.ellipses:
        plot_ellipses(d, a.ellipses, a.plane, a.at, a.stride)


if __name__ == "__main__":
    main()
