#!/usr/bin/env python3
"""sable_tools/drag/cg_fields.py --layers on a synthetic fix ave/cg file whose answer is known: a bed of
uniform density rho under a vertical stress k * g rho (level - z) (k = 1 hydrostatic,
k < 1 a wall carrying part of the weight), isotropic but on the axis, where P is halved.
Away from the surface the layer means over the N inner nodes must give sigma_zz / weight
= k (N - 1/2) / N and P_axis / P = (1/2) N / (N - 1/2); nodes outside the inner radius
(stress 1e9 there) must not count.
Exit 77 (skipped) without h5py.

    PYTHONPATH=. /usr/bin/python3 tests/cg_layers.py    (from the repository root)"""
import os
import sys
import tempfile

try:
    import h5py
    import numpy as np
except ImportError:
    print("h5py or numpy not installed: skipped")
    sys.exit(77)

from sable_tools.drag import cg_fields  # noqa: E402  (after the skip above)
from sable_tools.readers.h5 import cg_windows  # noqa: E402

G, RHO, LEVEL, SUPPORT, K = 9.81, 1500.0, 0.05, 0.003, 0.7


def synthetic(path):
    n, nz = 21, 30
    x = -0.015 + (np.arange(n) + 0.5) * 0.03 / n
    z = (np.arange(nz) + 0.5) * 0.06 / nz
    X, Y, Z = np.meshgrid(x, x, z, indexing="ij")
    inside = Z < LEVEL
    rho = np.where(inside, RHO, 0.0)
    szz = np.where(inside, K * G * RHO * (LEVEL - Z), 0.0)
    stress = np.zeros(X.shape + (6,))
    stress[..., 0] = stress[..., 1] = stress[..., 2] = szz
    i = np.abs(x).argmin()
    stress[i, i, :, :3] *= 0.5  # the axis
    outer = np.hypot(X, Y) > 0.015 - SUPPORT  # the container wall at the grid's edge, 0.015
    stress[outer] = 1e9  # must be left out of the layer means
    n_inner = (~outer[:, :, 0]).sum()
    with h5py.File(path, "w") as f:
        f.attrs["fields"] = np.array(["rho", "phi", "stress"], dtype=object)
        f.attrs["frame"] = np.array(["world"], dtype=object)
        f["step"], f["samples"], f["support"] = np.array([100]), np.array([1.0]), np.array([SUPPORT])
        f["x"], f["y"], f["z"] = x, x, z
        f["rho"], f["phi"], f["stress"] = rho[None], (rho / 2500.0)[None], stress[None]
    return z, n_inner


def main():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "cg.h5")
        z, N = synthetic(path)
        d = cg_windows(path)
    P, szz, phi, weight, p_axis = cg_fields.layers(d, LEVEL, G)
    deep = z < LEVEL - 2 * SUPPORT
    failures = []
    # The one axis node at half stress pulls each layer's mean to (N - 0.5) / N of K.
    expect = K * (N - 0.5) / N
    for name, got in (("sigma_zz / weight", szz / weight), ("P / weight", P / weight)):
        err = np.abs(got[deep] - expect).max()
        print(f"{name}: expected {expect:.6f}, worst deep layer off by {err:.2e}")
        if not err < 1e-9:
            failures.append(name)
    ratio = p_axis[deep] / P[deep]
    exp_ratio = 0.5 / ((N - 0.5) / N)
    err = np.abs(ratio - exp_ratio).max()
    print(f"P_axis / P: expected {exp_ratio:.6f}, off by {err:.2e}")
    if not err < 1e-9:
        failures.append("P_axis / P")
    if not np.allclose(phi[deep], RHO / 2500.0):
        failures.append("phi")
    if failures:
        sys.exit("FAIL: " + ", ".join(failures))
    print("ok")


if __name__ == "__main__":
    main()
