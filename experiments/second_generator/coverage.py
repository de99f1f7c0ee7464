#!/usr/bin/python3
"""Coverage of `pliant identify`'s stated sigma against a known truth.

For each seed: identify, then read K1, K2 at 0.10 / 0.155 / 0.20 m and
delta1, delta2 with their sd (`pliant params --json`), and z = (estimate -
truth) / sd. Prints per-seed z and, per quantity, the share of |z| <= 1.96
(the 95 % interval covers the truth) and the median sd.

Families:
  second     experiments/second_generator/generate.py --case none (timed
             metadata absent: the rows are one per pose); truth K x0.85 /
             x1.10 of PAPER_INVERSE_K, delta 7.0 / 9.0 mrad
  second_qs  the same logs with '# timing: quasi-static' added
  own        pliant's simulated paper protocol (bench/make_identify_logs.sh
             LOGS): sweep_SEED.csv + beam_SEED.csv; truth data/paper.json

Usage: coverage.py PLIANT FAMILY FIRST LAST [--logs DIR] [--json OUT] [--method M]
(--method: pliant identify's, default auto)
"""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import generate  # noqa: E402

DEPTHS = (0.10, 0.155, 0.20)


def params(pliant, path, depth):
    out = subprocess.run([pliant, "params", path, "--depth", str(depth), "--json"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def truth(family, pliant, repo, depth):
    if family == "own":
        p = params(pliant, os.path.join(repo, "data/paper.json"), depth)
        return {"K1": p["K1"], "K2": p["K2"], "delta1": p["delta1"], "delta2": p["delta2"]}
    return {"K1": generate.compliance(0, depth), "K2": generate.compliance(1, depth),
            "delta1": generate.DELTA[0], "delta2": generate.DELTA[1]}


def logs(family, seed, work, logs_dir):
    if family == "own":
        return [os.path.join(logs_dir, "sweep_%d.csv" % seed),
                os.path.join(logs_dir, "beam_%d.csv" % seed)]
    out = os.path.join(work, "seed%d" % seed)
    subprocess.run([sys.executable, os.path.join(HERE, "generate.py"), out, "--seed", str(seed),
                    "--case", "none"], check=True, capture_output=True)
    path = os.path.join(out, "none", "calibration.csv")
    if family == "second_qs":
        with open(path) as f:
            text = f.read()
        with open(path, "w") as f:
            f.write("# timing: quasi-static\n" + text)
    return [path]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("pliant")
    parser.add_argument("family", choices=["second", "second_qs", "own"])
    parser.add_argument("first", type=int)
    parser.add_argument("last", type=int)
    parser.add_argument("--logs", default="/tmp/pliant_identify")
    parser.add_argument("--work", default="/tmp/pliant_coverage")
    parser.add_argument("--json")
    parser.add_argument("--method", default="auto")
    a = parser.parse_args()
    repo = os.path.dirname(os.path.dirname(HERE))
    rows = []
    for seed in range(a.first, a.last + 1):
        files = logs(a.family, seed, os.path.join(a.work, a.family), a.logs)
        out = os.path.join(a.work, "%s_%d.json" % (a.family, seed))
        subprocess.run([a.pliant, "identify", *files, "-o", out, "--method", a.method], check=True,
                       capture_output=True)
        row = {"seed": seed}
        for depth in DEPTHS:
            p, t = params(a.pliant, out, depth), truth(a.family, a.pliant, repo, depth)
            for j in ("1", "2"):
                key = "K%s@%g" % (j, depth)
                row[key] = ((p["K" + j] - t["K" + j]) / p["K" + j + "_sd"], p["K" + j + "_sd"])
            if depth == DEPTHS[0]:
                for j in ("1", "2"):
                    key = "delta" + j
                    row[key] = ((p[key] - t[key]) / p[key + "_sd"], p[key + "_sd"])
        rows.append(row)
        print("seed %2d  " % seed + "  ".join("%s %+6.1f" % (k, v[0]) for k, v in row.items()
                                               if k != "seed"), flush=True)
    keys = [k for k in rows[0] if k != "seed"]
    print("%-10s %9s %11s %9s" % ("quantity", "covered", "median sd", "max |z|"))
    for k in keys:
        z = [r[k][0] for r in rows]
        sd = sorted(r[k][1] for r in rows)
        print("%-10s %4d/%-4d %11.3g %9.1f" % (k, sum(abs(x) <= 1.959964 for x in z), len(z),
                                            sd[len(sd) // 2], max(abs(x) for x in z)))
    allz = [r[k][0] for r in rows for k in keys]
    print("all: %d/%d inside the 95 %% interval (%.0f %%)" %
          (sum(abs(x) <= 1.959964 for x in allz), len(allz),
           100.0 * sum(abs(x) <= 1.959964 for x in allz) / len(allz)))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f)


if __name__ == "__main__":
    main()
