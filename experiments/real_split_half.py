#!/usr/bin/python3
"""Are the stated σ honest on real recordings? Split-half agreement (docs/validation.md §3).

Nothing tells the truth of a real arm, but two halves of one recording identify the same arm:
their difference, in σ of the difference √(σ_a² + σ_b²), should be N(0, 1) if the σ are honest
(|z| > 3 on a handful of numbers says the σ are too small).

- JHU 2017 clamped beam (data/real/, imported from ../shared/data/jhu-2017/): `pliant identify`
  on both bias sweeps and the even insertion depths of both clamps (5 mm bins of q3, as
  ../shared/tools/clamped_cv.py splits them), then the odd ones; K1, K2 at five depths and δ1
  (`pliant params --compare`).
- The dVRK 2.x PSM2 bag in free motion (data/real/crtk2022_psm2_free.csv): `pliant identify
  --effect joint_inertia --effect joint_friction` on its first and second half in time; J, the
  Coulomb and viscous levels of both joints.

Usage: real_split_half.py PLIANT OUT_DIR   (a few seconds)
"""
import json
import os
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REAL = os.path.join(REPO, "data", "real")
DEPTHS_M = (0.10, 0.13, 0.16, 0.19, 0.22)


def run(command):
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (done.returncode, " ".join(command), done.stderr[-600:]))
    return done.stdout


def split(path, keep, out):
    """Copies a canonical log's comment lines, header and the rows keep(row, header) accepts."""
    with open(path) as f, open(out, "w") as g:
        header = None
        rows = []
        for line in f:
            if header is None and line.startswith("#"):
                g.write(line)
            elif header is None:
                header = line.strip().split(",")
                g.write(line)
            else:
                rows.append(line)
        values = [dict(zip(header, r.rstrip("\n").split(","))) for r in rows]
        for line, row in zip(rows, keep(values)):
            if row:
                g.write(line)


def depth_parity(parity):
    def keep(values):
        bins = [round(float(v["q3"]) / 0.005) for v in values]
        levels = sorted(set(bins))
        chosen = {b for i, b in enumerate(levels) if i % 2 == parity}
        return [b in chosen for b in bins]
    return keep


def time_half(first):
    def keep(values):
        t = [float(v["t"]) for v in values]
        middle = 0.5 * (t[0] + t[-1])
        return [(x < middle) == first for x in t]
    return keep


def clamps(pliant, out_dir):
    files = []
    for parity in (0, 1):
        halves = []
        for j in (1, 2):
            half = os.path.join(out_dir, "clamped_j%d_%d.csv" % (j, parity))
            split(os.path.join(REAL, "jhu2017_clamped_j%d.csv" % j), depth_parity(parity), half)
            halves.append(half)
        params = os.path.join(out_dir, "clamps_%d.json" % parity)
        run([pliant, "identify", "--quiet", os.path.join(REAL, "jhu2017_bias_j1.csv"),
             os.path.join(REAL, "jhu2017_bias_j2.csv")] + halves + ["-o", params])
        files.append(params)
    rows = []
    for depth in DEPTHS_M:
        out = run([pliant, "params", files[0], "--compare", files[1], "--depth", str(depth)])
        for line in out.splitlines():
            words = line.split()
            if words and words[0] in ("K1", "K2", "δ1") and words[-1] == "σ":
                if words[0] == "δ1" and depth != DEPTHS_M[0]:
                    continue  # δ does not depend on the depth
                name = words[0] + ("" if words[0] == "δ1" else " at %.2f m" % depth)
                rows.append((name, "%s ± %s" % (words[1], words[3]),
                             "%s ± %s" % (words[4], words[6]), float(words[-2])))
    return rows


def bag(pliant, out_dir):
    fits = []
    for first in (True, False):
        half = os.path.join(out_dir, "bag_%s.csv" % ("first" if first else "second"))
        split(os.path.join(REAL, "crtk2022_psm2_free.csv"), time_half(first), half)
        params = half.replace(".csv", ".json")
        run([pliant, "identify", "--quiet", half, "--effect", "joint_inertia", "--effect",
             "joint_friction", "-o", params])
        with open(params) as f:
            fits.append(json.load(f)["effects"])
    rows = []
    for effect, names in (("joint_inertia", ("inertia1", "inertia2")),
                          ("joint_friction", ("coulomb1", "coulomb2", "viscous1", "viscous2"))):
        for name in names:
            a, b = fits[0][effect][name], fits[1][effect][name]
            z = (a["value"] - b["value"]) / (a["sd"] ** 2 + b["sd"] ** 2) ** 0.5
            rows.append((name, "%.4g ± %.2g" % (a["value"], a["sd"]),
                         "%.4g ± %.2g" % (b["value"], b["sd"]), z))
    return rows


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    pliant, out_dir = sys.argv[1], sys.argv[2]
    os.makedirs(out_dir, exist_ok=True)
    studies = (("JHU 2017 clamped beam: even depths | odd depths", clamps(pliant, out_dir)),
               ("PSM2 bag, free motion: first half | second half", bag(pliant, out_dir)))
    for title, rows in studies:
        print(title)
        for name, a, b, z in rows:
            print("  %-14s %-24s %-24s %+5.1f σ" % (name, a, b, z))
        worst = max(abs(r[3]) for r in rows)
        rms = (sum(r[3] ** 2 for r in rows) / len(rows)) ** 0.5
        print("  %d numbers, %d beyond 2 σ, largest |z| %.1f, RMS z %.2f (1 if the σ are exact)" %
              (len(rows), sum(abs(r[3]) > 2.0 for r in rows), worst, rms))


if __name__ == "__main__":
    main()
