#!/usr/bin/python3
"""What gathering the light after an event would gain over counting photons at the sensors.

Issue 37's CPU goal is decided by the light that reaches a sensor after a reflection: with
`direct = "shadow_rays"` the photons count it over each sensor's disc, and a disc of radius
0.25 m catches few of them. The same photons also land on every triangle of the room, and
the surface map counts them there. A sensor's light after an event is the luminance of the
surfaces it sees, integrated over its hemisphere:

    E_s = sum over triangles t of K_st L_t,   K_st = integral over t of cos(theta_s) cos(theta_t) / r^2 dA,
    L_t = rho_t E_t / pi  (a Lambertian surface of reflectance rho_t lit by E_t)

This script computes that sum offline from a result's map (the year's exposure of every
triangle side, E_t in lx h) for upward sensors in a room whose walls, floor and ceiling are
Lambertian and whose window is one plane of glass (the pane reflects the room with its
Fresnel reflectance; what it lets through from outside is direct light, the shadow rays'),
with K_st by quadrature over each triangle (every interior triangle is seen: a convex room).
It prints, for each run given, the RMS relative error of the gathered year and of the
photons' own disc values, both against the reference run, and for the reference the ratio of
the two estimates (the gather's bias, within the reference's own noise).

Usage (the files bench/annual_direct_speed.sh writes):

  /usr/bin/python3 bench/annual_gather_potential.py DIR/ref_shadow.h5 DIR/shadow_2M_1.h5 DIR/shadow_10M_1.h5

Only for the example's kind of room: a measurement, not a part of luxtrace
(docs/PERFORMANCE.md "A path to ten times: gathering the light after an event").
"""
import sys

import h5py
import numpy as np

# The example's materials (examples/annual/annual_office.toml).
REFLECTANCE = {b"wall": 0.5, b"floor": 0.2, b"ceiling": 0.8}
GLASS = b"clear_glass"
REFRACTIVE_INDEX = 1.52


def load(path):
    f = h5py.File(path, "r")
    r = {k: f[k][:] for k in ("mesh/vertices", "mesh/triangles", "mesh/material", "mesh/material_names",
                              "detectors/sensors/positions")}
    r["E"] = f["global/illuminance"][:, :, 0]
    r["disc"] = f["detectors/sensors/value"][0, :, 0]
    r["disc_sigma_rel"] = f["detectors/sensors/sigma_rel"][0, :, 0]
    return r


def quadrature(sub=4):
    """Barycentric centres of the sub x sub subdivision of a triangle (equal areas)."""
    pts = []
    for i in range(sub):
        for j in range(sub - i):
            pts.append(((i + 1 / 3) / sub, (j + 1 / 3) / sub))
            if i + j < sub - 1:
                pts.append(((i + 2 / 3) / sub, (j + 2 / 3) / sub))
    return pts


def pane_reflectance(cos_i, n=REFRACTIVE_INDEX):
    """Unpolarised reflectance of a non-absorbing pane (two surfaces, their interreflections)."""
    sin_t = np.sqrt(np.maximum(0.0, 1.0 - cos_i ** 2)) / n
    cos_t = np.sqrt(1.0 - sin_t ** 2)
    rs = ((cos_i - n * cos_t) / (cos_i + n * cos_t)) ** 2
    rp = ((n * cos_i - cos_t) / (n * cos_i + cos_t)) ** 2
    return 0.5 * (2 * rs / (1 + rs) + 2 * rp / (1 + rp))


class Room:
    def __init__(self, ref):
        V, T = ref["mesh/vertices"], ref["mesh/triangles"]
        names, mat = ref["mesh/material_names"], ref["mesh/material"]
        self.A, self.B, self.C = V[T[:, 0]], V[T[:, 1]], V[T[:, 2]]
        n = np.cross(self.B - self.A, self.C - self.A)
        self.area = np.linalg.norm(n, axis=1) / 2
        self.normal = n / np.linalg.norm(n, axis=1)[:, None]
        self.rho = np.array([REFLECTANCE.get(names[m], 0.0) for m in mat])
        glass = np.array([names[m] == GLASS for m in mat])
        corners = V[T[glass].ravel()]
        self.lo, self.hi = corners.min(0), corners.max(0)
        self.axis = int(np.argmin(self.hi - self.lo))
        if self.hi[self.axis] - self.lo[self.axis] > 1e-9:
            sys.exit("the glass is not one plane: this estimate is for one window")
        self.plane = self.lo[self.axis]
        self.sensors = ref["detectors/sensors/positions"]

    def weights(self, viewpoints, through_window):
        """W[s, t, side]: K_st (times the pane's reflectance when seen in the window)."""
        W = np.zeros((len(viewpoints), len(self.area), 2))
        others = [k for k in range(3) if k != self.axis]
        for (u, v) in quadrature():
            X = self.A + u * (self.B - self.A) + v * (self.C - self.A)
            d = X[None, :, :] - viewpoints[:, None, :]
            r2 = (d * d).sum(-1)
            r = np.sqrt(r2)
            cos_s = d[:, :, 2] / r
            cos_t = -(d * self.normal[None, :, :]).sum(-1) / r
            k = np.where((cos_s > 0) & (self.rho[None, :] > 0), cos_s * np.abs(cos_t) / r2, 0.0)
            if through_window:
                along = d[:, :, self.axis]
                s = (self.plane - viewpoints[:, None, self.axis]) / np.where(np.abs(along) > 1e-12, along, 1e-12)
                Y = viewpoints[:, None, :] + s[:, :, None] * d
                inside = (s > 0) & (s < 1)
                for a in others:
                    inside &= (Y[:, :, a] >= self.lo[a]) & (Y[:, :, a] <= self.hi[a])
                k = np.where(inside, k * pane_reflectance(np.abs(along) / r), 0.0)
            k = k * (self.area / len(quadrature()))[None, :]
            side = np.where(cos_t >= 0, 0, 1)
            for sd in (0, 1):
                W[:, :, sd] += np.where(side == sd, k, 0.0)
        return W

    def kernel(self):
        mirrored = self.sensors.copy()
        mirrored[:, self.axis] = 2 * self.plane - self.sensors[:, self.axis]
        return self.weights(self.sensors, False) + self.weights(mirrored, True)

    def gather(self, W, E):
        L = self.rho[:, None] * E / np.pi
        return (W * L[None, :, :]).sum((1, 2))


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    ref = load(sys.argv[1])
    room = Room(ref)
    W = room.kernel()
    g_ref = room.gather(W, ref["E"])
    ratio = g_ref / ref["disc"]
    print(f"reference {sys.argv[1]}: gathered / photons' disc values, mean {ratio.mean():.4f}, "
          f"by sensor {ratio.min():.3f}-{ratio.max():.3f} (the disc values' own error "
          f"{ref['disc_sigma_rel'].mean() * 100:.2f} %)")
    print("run                                  gathered RMS error   photons' disc RMS error   ratio of variances")
    for path in sys.argv[2:]:
        run = load(path)
        g = room.gather(W, run["E"])
        e_gather = np.sqrt(np.mean((g / g_ref - 1) ** 2))
        e_disc = np.sqrt(np.mean((run["disc"] / ref["disc"] - 1) ** 2))
        print(f"{path[-36:]:36s} {e_gather * 100:17.3f} % {e_disc * 100:22.3f} % {(e_disc / e_gather) ** 2:20.0f}")


if __name__ == "__main__":
    main()
