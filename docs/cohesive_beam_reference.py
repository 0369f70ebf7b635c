#!/usr/bin/env python3
"""The converged answer for Petersson's beam of docs/cohesive_beam.py: its cohesive crack along the
symmetry line, solved by Petersson's (1981) own fictitious-crack method on a fine mesh.

    python3 docs/cohesive_beam_reference.py OUT.csv [--h 0.0025]   # needs NumPy and SciPy

The same beam, material and law as the scene (span 2 m between supports, 2.2 m long, depth 0.2 m,
a slot 10 mm wide and 0.1 m deep at mid-span, E 30 GPa, nu 0.2, plane stress, sigma_t 3.33 MPa,
G_f 124 N/m, the linear law t = sigma_t (1 - w/w_c), w_c = 2 G_f/sigma_t), but with the crack's
path known: by symmetry it runs straight up the ligament from the slot's end, so the half beam
x <= 1.1 m is solved with bilinear squares of side h (2x2 Gauss points), a roller at (0.1, 0) and
the load point (1.1, 0.2) moved down by delta, and on the symmetry line x = 1.1 m above the slot:
- below the crack's tip the faces open by w = -2 u_x and carry t(w) (0 beyond w_c),
- at and above the tip u_x = 0.
Instead of stepping delta, the tip is moved up one node at a time and delta follows from the tip's
condition (Petersson 1981, Hillerborg et al. 1976): the tip node's reaction across the line equals
sigma_t times its length. Everything is linear at a given tip and set of faces past w_c:
u = u_sigma + delta * u_delta. The ligament's unknowns are condensed once (Schur complement of the
rest, one sparse factorisation), so each tip is a small dense solve. The top node is the load
point, pressed shut: once the tip is one node below it, the last face opens too and the top node
is the hinge the halves turn about; the opening at the slot's end then drives the steps until
every face is past w_c and the load is zero (full separation: G_f x the ligament less the hinge
node's h/2).

Writes OUT.csv: tip_y_m, deflection_mm, load_kn_per_m, dissipated_j_per_m (sum of L_i D(w_i), D(w) =
sigma_t w - sigma_t w^2/(2 w_c), G_f at w >= w_c), opening_at_slot_um; and prints the peak, the load
work at 1 mm (the curve integrated, straight from the origin to the first point) and the
dissipation there, and RILEM's work of fracture: the load work, the dissipation and the strain
energy left (their difference) until the load has fallen to 1 % of its peak and to zero.
"""
import argparse

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl

E, NU, FT, GF = 3e10, 0.2, 3.33e6, 124.0
WC = 2 * GF / FT


def solve(h):
    nx, ny = round(1.1 / h), round(0.2 / h)
    node = lambda i, j: j * (nx + 1) + i
    ii, jj = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    ii, jj = ii.ravel(), jj.ravel()
    keep = ~(((ii + 0.5) * h > 1.095) & ((jj + 0.5) * h < 0.1))  # the slot's half taken out
    ii, jj = ii[keep], jj[keep]
    els = np.stack([node(ii, jj), node(ii + 1, jj), node(ii + 1, jj + 1), node(ii, jj + 1)], axis=1)
    d = E / (1 - NU * NU) * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])
    ke = np.zeros((8, 8))
    g = 1 / np.sqrt(3)
    for xi in (-g, g):
        for eta in (-g, g):
            dn = 0.5 / h * np.array([[-(1 - eta), 1 - eta, 1 + eta, -(1 + eta)],
                                     [-(1 - xi), -(1 + xi), 1 + xi, 1 - xi]])
            b = np.zeros((3, 8))
            b[0, 0::2], b[1, 1::2], b[2, 0::2], b[2, 1::2] = dn[0], dn[1], dn[1], dn[0]
            ke += b.T @ d @ b * h * h / 4
    dofs = np.empty((len(els), 8), dtype=np.int64)
    dofs[:, 0::2], dofs[:, 1::2] = 2 * els, 2 * els + 1
    n = 2 * (nx + 1) * (ny + 1)
    k = sp.csr_matrix((np.tile(ke.ravel(), len(els)), (np.repeat(dofs, 8, axis=1).ravel(), np.tile(dofs, 8).ravel())),
                      shape=(n, n))
    used = np.zeros(n, bool)
    used[dofs.ravel()] = True
    j0 = round(0.1 / h)
    lig = np.array([node(nx, j) for j in range(j0, ny + 1)])  # slot's end to the top
    length = np.full(len(lig), h)
    length[0] = length[-1] = h / 2
    load = 2 * lig[-1] + 1
    # Boundary unknowns: the ligament's u_x and the load point's u_y; the roller's u_y is 0.
    bnd = np.concatenate([2 * lig, [load]])
    roller = 2 * node(round(0.1 / h), 0) + 1
    inner = np.setdiff1d(np.nonzero(used)[0], np.concatenate([bnd, [roller]]))
    kii = k[inner][:, inner].tocsc()
    kib = k[inner][:, bnd].toarray()
    s = k[bnd][:, bnd].toarray() - kib.T @ spl.splu(kii).solve(kib)  # condensed stiffness
    m = len(lig)
    rows = []
    opened = np.zeros(m, bool)
    for tip in range(1, m - 1):  # the top node is the load point: pressed shut, it is no tip
        for _ in range(m):
            # Unknowns: u_x of the faces below the tip (cohesive or open); known: u_x = 0 at and
            # above it, u_y = -delta at the load. Faces: f_i = L_i sigma_t (1 + 2 u_i / w_c).
            faces = np.arange(tip)
            a = s[np.ix_(faces, faces)].copy()
            coh = ~opened[:tip]
            a[faces[coh], faces[coh]] -= 2 * length[:tip][coh] * FT / WC
            f_const = np.where(coh, length[:tip] * FT, 0.0)
            u_sig = np.linalg.solve(a, f_const)
            u_del = np.linalg.solve(a, s[faces, m])  # per unit delta (u_load = -delta moves rhs by +s[:, m])
            # Reactions at the tip's u_x and the load's u_y: r = S u (no external force there).
            r_tip = (s[tip, faces] @ u_sig, s[tip, faces] @ u_del - s[tip, m])
            delta = (FT * length[tip] - r_tip[0]) / r_tip[1]
            u = u_sig + delta * u_del
            w = -2 * u
            past = (w > WC) & ~opened[:tip]
            if not past.any():
                break
            opened[:tip] |= past
        r_load = s[m, faces] @ u - s[m, m] * delta
        wk = np.clip(w, 0, WC)
        dissipated = float(np.sum(length[:tip] * (FT * wk - FT * wk * wk / (2 * WC))))
        rows.append((lig[tip] // (nx + 1) * h, 1e3 * delta, -2 * r_load / 1e3, dissipated, 1e6 * w[0]))
    # To full separation: the last node below the top opens too, and the top node (the load
    # point, pressed shut) is the hinge the halves turn about (u_x = 0 there, its reaction across
    # the line compressive). The opening at the slot's end w_0 drives the steps (the load falls,
    # and the deflection need not rise: w_0 does), up to w_c, where every face has let go and
    # the halves carry no moment.
    faces = np.arange(m - 1)
    for w0 in np.geomspace(rows[-1][4] * 1e-6, WC * 0.2 / length[m - 2], 400)[1:]:
        for _ in range(m):
            a = s[np.ix_(faces, faces)].copy()
            coh = ~opened[:m - 1]
            a[faces[coh], faces[coh]] -= 2 * length[:m - 1][coh] * FT / WC
            f_const = np.where(coh, length[:m - 1] * FT, 0.0)
            u_sig = np.linalg.solve(a, f_const)
            u_del = np.linalg.solve(a, s[faces, m])
            delta = (-w0 / 2 - u_sig[0]) / u_del[0]
            u = u_sig + delta * u_del
            w = -2 * u
            past = (w > WC) & ~opened[:m - 1]
            if not past.any():
                break
            opened[:m - 1] |= past
        r_load = s[m, faces] @ u - s[m, m] * delta
        r_top = s[m - 1, faces] @ u - s[m - 1, m] * delta  # across the line at the hinge: < 0 pressed
        wk = np.clip(w, 0, WC)
        dissipated = float(np.sum(length[:m - 1] * (FT * wk - FT * wk * wk / (2 * WC))))
        assert r_top <= 0, "the hinge at the load point pulled open"
        rows.append((0.2, 1e3 * delta, -2 * r_load / 1e3, dissipated, 1e6 * w0))
        if opened[:m - 1].all():
            break
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--h", type=float, default=0.0025, help="element side, m (0.1 and 0.005 m multiples of it)")
    a = ap.parse_args()
    rows = [r for r in solve(a.h) if r[1] > 0]
    with open(a.out, "w") as f:
        f.write("tip_y_m,deflection_mm,load_kn_per_m,dissipated_j_per_m,opening_at_slot_um\n")
        for r in rows:
            f.write(",".join(f"{v:.6g}" for v in r) + "\n")
    x = np.array([0.0] + [r[1] for r in rows])
    p = np.array([0.0] + [r[2] for r in rows])
    peak = int(np.argmax(p))
    xs = np.linspace(0, 1.0, 4001)
    work = float(np.trapz(np.interp(xs, x, p), xs))  # kN/m x mm = J/m
    diss = float(np.interp(1.0, x[1:], [r[3] for r in rows]))
    print(f"h {a.h} m: peak {p[peak]:.4g} kN/m at {x[peak]:.3f} mm (tip at y {rows[peak - 1][0]:.4f} m); "
          f"load work at 1 mm {work:.4g} J/m, dissipated there {diss:.4g} J/m; "
          f"last row: {rows[-1][1]:.3f} mm, {rows[-1][2]:.3g} kN/m, dissipated {rows[-1][3]:.4g} J/m")
    # RILEM's work of fracture: the load work until the load has fallen to ~zero (1 % of the peak)
    low = next(i for i in range(peak, len(p)) if p[i] < 0.01 * p[peak])
    for name, end in (("1 % of the peak", low), ("separation", len(p) - 1)):
        wk = float(np.trapz(p[:end + 1], x[:end + 1]))
        print(f"to {name} ({x[end]:.3f} mm, {p[end]:.3g} kN/m): load work {wk:.4g} J/m ({100 * (wk / (GF * 0.1) - 1):+.1f} % "
              f"of G_f x ligament {GF * 0.1:.4g}), dissipated {rows[end - 1][3]:.4g}, strain left {wk - rows[end - 1][3]:.3g} J/m")


if __name__ == "__main__":
    main()
