#!/usr/bin/env python3
"""Reflection of an absorbing boundary against the angle of incidence (docs/absorbing-boundaries.md).

    python3 docs/absorbing_reflection.py BIN_DIR OUT_DIR [--angles 0,15,30,45,60] [--table-only]

A plane wave meets the absorbing boundary at the angle theta: the wave travels straight down a
column 100 m wide whose base is the boundary, inclined at theta (from (0, 0) to (100, 100 tan
theta)). The column's sides on rollers keep the incident wave exactly plane (x held for a P
wave, y held for an S wave: the symmetry planes of a laterally unbounded plane wave); a Hann
pulse of T = 0.04 s put on its top (100 kPa, normal for P, shear for S) starts it. Rock: rho 2000
kg/m3, E 1.667 GPa, nu 0.25, plane strain: cp = 1000 m/s, cs = 577 m/s; mesh h = 1 m (23 elements
per S wavelength), dt = 0.2 ms.
Two runs per angle and wave, on the same mesh lattice (anchored at the origin):
  A  the column above the inclined absorbing base;
  B  the same column continued below it (its own base absorbing), deep enough that what B's
     base sends back reaches the receiver only after every window below has closed.
All but the boundary is the same in A and B, so v_A - v_B at a receiver is what the boundary
sent back. The receiver R = (40, 40 tan theta + 25) m, 25 m above the base. The reflected
waves' arrival times at R follow from Snell's law (the slowness along the base is the incident
one's); the same-type reflection (P for P) and the converted one (S for P) arrive within less
than a pulse of each other, so v_A - v_B is split into the two by their polarisations (a P wave
moves along its direction of travel, an S wave across it: two equations for the two
amplitudes), each read in a window of [-0.1 T, 1.1 T] about its arrival, as its largest
magnitude there over the incident particle velocity (read from B at R).
Writes OUT_DIR/reflection.csv (the measured columns) and prints the table (--table-only: prints
the table of an OUT_DIR/reflection.csv already written, running nothing).
"""
import argparse
import cmath
import csv
import json
import math
import pathlib
import subprocess

RHO, YOUNG, NU = 2000.0, 1.0 / 0.6 * 1e9, 0.25
LAM = YOUNG * NU / ((1 + NU) * (1 - 2 * NU))
G = YOUNG / (2 * (1 + NU))
CP, CS = math.sqrt((LAM + 2 * G) / RHO), math.sqrt(G / RHO)
T, DT, WIDTH, ABOVE, RX, RD = 0.04, 2e-4, 100.0, 40.0, 40.0, 25.0
EARLY, LATE = 0.1 * T, 1.1 * T  # the window about an arrival
STRESS = 1e5


def hann():
    return [[T * i / 40, math.sin(math.pi * i / 40) ** 2] for i in range(41)]


def geometry(theta):
    rise = WIDTH * math.tan(theta)
    top = max(rise, 0.0) + ABOVE + RD
    return rise, top, (RX, RX * math.tan(theta) + RD)


def scene(theta, p_wave, continued):
    rise, top, r = geometry(theta)
    drop = below(theta, p_wave) if continued else 0.0
    held = "x" if p_wave else "y"
    return {
        "name": "reflection",
        "materials": {"rock": {"density": RHO, "young": YOUNG, "poisson": NU}},
        "bodies": [{"material": "rock", "outer": [[0, -drop], [WIDTH, rise - drop], [WIDTH, top], [0, top]]}],
        "mesh": {"size": 1.0},
        "supports": [{"points": [[0, -drop], [0, top]], "fix": held},
                     {"points": [[WIDTH, rise - drop], [WIDTH, top]], "fix": held}],
        "tractions": [{"points": [[0, top], [WIDTH, top]], ("normal" if p_wave else "shear"): -STRESS,
                       "table": hann()}],
        "absorbing": [{"points": [[0, -drop], [WIDTH, rise - drop]]}],
        "measure_points": [list(r)],
        "solver": {"time_step": DT, "steps": steps(theta, p_wave), "output_every": 100000, "history_every": 1},
    }


def directions(theta, p_wave):
    """Unit propagation directions of the incident wave and the reflected P and S waves (None past
    their critical angle), the base's tangent t and normal n (into the rock)."""
    c_in = CP if p_wave else CS
    t, n = (math.cos(theta), math.sin(theta)), (-math.sin(theta), math.cos(theta))
    d_in = (0.0, -1.0)
    p_t = (d_in[0] * t[0] + d_in[1] * t[1]) / c_in  # slowness along the base, kept by every wave
    out = {}
    for name, c in (("P", CP), ("S", CS)):
        a = p_t * c
        out[name] = None if abs(a) > 1 else (a * t[0] + math.sqrt(1 - a * a) * n[0], a * t[1] + math.sqrt(1 - a * a) * n[1])
    return out


def arrival(theta, p_wave, wave, x):
    """s: when the reflected `wave` (P or S) reaches point x: its trace on the base is the
    incident wave's, which reaches the corner (0, 0) at top/c_in."""
    c_in = CP if p_wave else CS
    _, top, _ = geometry(theta)
    k = directions(theta, p_wave)[wave]
    c = CP if wave == "P" else CS
    return top / c_in + (x[0] * k[0] + x[1] * k[1]) / c


def below(theta, p_wave):
    """m: how far B continues below A's base. B's base is A's moved down by D, so each of its
    reflections reaches R D·(1/c_in + k_y/c) later than A's; D puts every one of them 0.1 T past
    the last window's end (at least 30 m)."""
    c_in = CP if p_wave else CS
    _, _, r = geometry(theta)
    waves = [w for w in ("P", "S") if directions(theta, p_wave)[w]]
    end = max(arrival(theta, p_wave, w, r) for w in waves) + LATE + 0.1 * T
    need = 30.0
    for w in waves:
        rate = 1 / c_in + directions(theta, p_wave)[w][1] / (CP if w == "P" else CS)
        need = max(need, (end - arrival(theta, p_wave, w, r)) / rate)
    return math.ceil(need)


def steps(theta, p_wave):
    _, _, r = geometry(theta)
    last = max(arrival(theta, p_wave, w, r) for w in ("P", "S") if directions(theta, p_wave)[w])
    return int(round((last + LATE + 0.2 * T) / DT))


def run(bin_dir, out, doc):
    out.mkdir(parents=True, exist_ok=True)
    (out / "scene.json").write_text(json.dumps(doc))
    subprocess.run([bin_dir / "nmm-preprocess", out / "scene.json", "-o", out / "scene.nmm", "-q"], check=True)
    subprocess.run([bin_dir / "nmm-solve", out / "scene.nmm", "-o", out / "run", "-q"], check=True)
    v, last = [], None
    for r in csv.DictReader(open(out / "run" / "history.csv")):
        t, ux, uy = float(r["time"]), float(r["ux"]), float(r["uy"])
        if last:
            v.append((t, (ux - last[1]) / (t - last[0]), (uy - last[2]) / (t - last[0])))
        last = (t, ux, uy)
    return v


def peak(a, t0, t1):
    """Largest |v| of the trace a over t0 <= t <= t1."""
    return max(math.hypot(vx, vy) for t, vx, vy in a if t0 <= t <= t1)


def reflected(va, vb, theta, p_wave):
    """The largest amplitude of the reflected P and S waves at R (m/s; None for a wave past its
    critical angle): v_A - v_B = a·k_P + b·k_S⊥ solved at every sample, |a| and |b| read in their
    windows. With one reflected wave only, |v_A - v_B| in its window."""
    _, _, r = geometry(theta)
    d = directions(theta, p_wave)
    pol = {w: (None if d[w] is None else (d[w] if w == "P" else (-d[w][1], d[w][0]))) for w in ("P", "S")}
    out = {}
    for w in ("P", "S"):
        if d[w] is None:
            out[w] = None
            continue
        t_r = arrival(theta, p_wave, w, r)
        best = 0.0
        for (t, ax, ay), (_, bx, by) in zip(va, vb):
            if not t_r - EARLY <= t <= t_r + LATE:
                continue
            dx, dy = ax - bx, ay - by
            other = pol["S" if w == "P" else "P"]
            if other is None:
                amp = math.hypot(dx, dy)
            else:  # Cramer's rule for dx,dy = a·pol[w] + b·other
                p = pol[w]
                amp = abs((dx * other[1] - dy * other[0]) / (p[0] * other[1] - p[1] * other[0]))
            best = max(best, amp)
        out[w] = best
    return out


def plane_wave(theta, p_wave):
    """Reflected P and S amplitudes (per unit incident amplitude) and the reflected share of the
    incident energy flux of a plane wave meeting the viscous boundary z = 0 of the solid z > 0 at
    `theta` from its normal. Waves u = A·d·exp(iω(t − k·x/c)) share the incident horizontal
    slowness; a reflected wave past its critical angle is evanescent (k_z imaginary, decaying into
    the solid) and carries no energy away."""
    c_in = CP if p_wave else CS
    s = math.sin(theta) / c_in

    def wave(c, is_p, down):
        sx = s * c
        kz = cmath.sqrt(1 - sx * sx) if sx <= 1 else -1j * math.sqrt(sx * sx - 1)
        k = (sx, -kz if down else kz)
        return c, k, (k if is_p else (k[1], -k[0]))

    def bc(w):  # σzz − ρcp·vz and σxz − ρcs·vx of the wave, per unit amplitude and iω
        c, k, d = w
        exx, ezz, exz = -d[0] * k[0] / c, -d[1] * k[1] / c, -(d[0] * k[1] + d[1] * k[0]) / (2 * c)
        return (LAM * (exx + ezz) + 2 * G * ezz - RHO * CP * d[1], 2 * G * exz - RHO * CS * d[0])

    inc, rp, rs = bc(wave(c_in, p_wave, True)), bc(wave(CP, True, False)), bc(wave(CS, False, False))
    det = rp[0] * rs[1] - rs[0] * rp[1]
    a_p = (-inc[0] * rs[1] + rs[0] * inc[1]) / det
    a_s = (-rp[0] * inc[1] + inc[0] * rp[1]) / det
    flux = lambda c, a: c * wave(c, c == CP, False)[1][1].real * abs(a) ** 2
    energy = (flux(CP, a_p) + flux(CS, a_s)) / (c_in * math.cos(theta))
    return {w: (None if directions(theta, p_wave)[w] is None else abs(a)) for w, a in (("P", a_p), ("S", a_s))}, energy


def table(rows):
    """The markdown table of docs/absorbing-boundaries.md; the plane-wave columns computed afresh."""
    fmt = lambda x: "—" if x is None or x == "" else f"{float(x):.1f} %"
    lines = ["| incident | angle | measured: same type | converted | plane wave: same type | converted | energy back |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        p_wave, deg = r["wave"] == "P", float(r["angle_deg"])
        amp, energy = plane_wave(math.radians(deg), p_wave)
        same, other = ("P", "S") if p_wave else ("S", "P")
        lines.append(f"| {r['wave']} | {deg:.0f}° | {fmt(r['measured_same_percent'])} | "
                     f"{fmt(r['measured_converted_percent'])} | {fmt(100 * amp[same])} | "
                     f"{'— (evanescent)' if amp[other] is None else fmt(100 * amp[other])} | {100 * energy:.2f} % |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bin", type=pathlib.Path)
    ap.add_argument("out", type=pathlib.Path)
    ap.add_argument("--angles", default="0,15,30,45,60")
    ap.add_argument("--table-only", action="store_true", help="print the table of OUT/reflection.csv, run nothing")
    a = ap.parse_args()
    if a.table_only:
        print(table(list(csv.DictReader(open(a.out / "reflection.csv")))))
        return
    rows = []
    for p_wave in (True, False):
        label, other = ("P", "S") if p_wave else ("S", "P")
        for deg in (float(x) for x in a.angles.split(",")):
            theta = math.radians(deg)
            tag = f"{label}_{int(deg)}"
            va = run(a.bin, a.out / f"{tag}_A", scene(theta, p_wave, False))
            vb = run(a.bin, a.out / f"{tag}_B", scene(theta, p_wave, True))
            _, top, r = geometry(theta)
            c_in = CP if p_wave else CS
            t_in = (top - r[1]) / c_in
            incident = peak(vb, t_in - EARLY, t_in + LATE)
            measured = {w: (None if x is None else x / incident) for w, x in reflected(va, vb, theta, p_wave).items()}
            rows.append({"wave": label, "angle_deg": deg, "incident_m_s": incident,
                         "measured_same_percent": 100 * measured[label],
                         "measured_converted_percent": None if measured[other] is None else 100 * measured[other]})
            print(rows[-1], flush=True)
    with open(a.out / "reflection.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(table(rows))


if __name__ == "__main__":
    main()
