#!/usr/bin/python3
"""Evaluate pliant on the third generator's logs (experiments/third_generator/generate.py).

For each variant: generate; identify (auto, plus --method smoother / paper and the auto fit on
per-joint logs, for comparison); K(L) and delta against the truth in sigma units; filter (with
the tip_fixed hint and without) and correct (equation 2) on the test log and on the calibration
log's clamps; the same with the TRUE parameters written as a pliant parameters file.

Usage: evaluate.py [--pliant build/cli/pliant] [--work /tmp/third] [--only NAME ...]
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import physics as ph  # noqa: E402

VARIANTS = [
    ("default", []),
    ("soft_k", ["--k-scale", "0.7", "1.35", "--clearance", "0.003", "0.011"]),
    ("noisy100", ["--noise-scale", "3", "--rate", "100"]),
    ("rate1000", ["--rate", "1000"]),
]
LOG = []  # every command: (variant, command, exit status, stderr lines worth reading)


def run(variant, cmd, cwd):
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    name = "_".join(os.path.basename(c).replace(".", "_") for c in cmd[1:4] if not c.startswith("-"))
    with open(os.path.join(cwd, f"stderr_{name}_{len(LOG)}.txt"), "w") as f:
        f.write(" ".join(cmd) + "\n" + p.stderr + p.stdout)
    notes = [ln.strip() for ln in (p.stderr + p.stdout).splitlines()
             if any(w in ln.lower() for w in ("warning", "error", "diverg", "ended", "note"))
             and "tip error against" not in ln]
    LOG.append((variant, " ".join(cmd), p.returncode, notes))
    return p


def read_csv(path):
    with open(path) as f:
        lines = [ln for ln in f.read().splitlines() if ln and not ln.startswith("#")]
    head = lines[0].split(",")
    data = np.array([[float(v) if v else np.nan for v in ln.split(",")] for ln in lines[1:]])
    return {h: data[:, i] for i, h in enumerate(head)}


def write_without(src, dst, drop):
    with open(src) as f, open(dst, "w") as g:
        idx = None
        for ln in f:
            if ln.startswith("#"):
                g.write(ln)
                continue
            parts = ln.rstrip("\n").split(",")
            if idx is None:
                idx = [i for i, h in enumerate(parts) if h not in drop]
            g.write(",".join(parts[i] for i in idx) + "\n")


def split_per_joint(src, dst_pattern):
    """The calibration as two logs that record only the joint under test (JHU-style)."""
    d = read_csv(src)
    meta = [ln for ln in open(src) if ln.startswith("#")]
    seg, tf = d["segment"].astype(int), d["tip_fixed"]
    for j in (1, 2):
        other = 2 if j == 1 else 1
        # a segment belongs to joint j when joint j's angle moves more than the other's
        keep = np.zeros(len(seg), bool)
        for s in np.unique(seg):
            m = seg == s
            keep |= m & (np.ptp(d[f"q{j}"][m]) > np.ptp(d[f"q{other}"][m]))
        with open(dst_pattern % j, "w") as g:
            g.writelines(meta)
            g.write(f"t,q{j},q3,tau{j},q{j}_true,tip_fixed,segment\n")
            for i in np.nonzero(keep)[0]:
                g.write(f"{i},{d[f'q{j}'][i]:.12g},{d['q3'][i]:.12g},{d[f'tau{j}'][i]:.12g},"
                        f"{d[f'q{j}_true'][i]:.12g},{int(tf[i])},{seg[i]}\n")


def truth_params(truth, path):
    """The true parameters in pliant's format: 1/K(L) as a cubic fitted on the clamp range,
    the bias as an exact Fourier series (joint 1 at q2 = 0: its cos(q2) factor has no place)."""
    lo, hi = 0.08, 0.23
    Ls = np.linspace(lo, hi, 61)
    b = truth["bias"]
    Lr = 0.155
    joints, maxerr = {}, []
    for j in (1, 2):
        K = ph.compliance(j, Ls, truth["k_scale"][j - 1])
        c = np.polyfit(Ls, 1.0 / K, 3)  # pliant's inverse_cubic: 1/K(L) a cubic in L
        maxerr.append(float(np.max(np.abs(1.0 / np.polyval(c, Ls) / K - 1))))
        if j == 1:
            bias = dict(form="fourier", coefficients=[b["c1"] + b["b1"], b["a1"] * np.sin(b["phi1"]),
                                                      b["a1"] * np.cos(b["phi1"])],
                        depth_slope_nm_per_m=0.0, reference_depth_m=Lr)
        else:
            m = b["m"] * (Lr - b["Lcw"])
            bias = dict(form="fourier",
                        coefficients=[b["c2"], b["a2"] * np.sin(b["phi2"]) + m * np.sin(b["phi3"]),
                                      b["a2"] * np.cos(b["phi2"]) + m * np.cos(b["phi3"]), 0.0, b["e2"]],
                        depth_slope_nm_per_m=0.0,
                        depth_harmonic_nm_per_m=[b["m"] * np.sin(b["phi3"]), b["m"] * np.cos(b["phi3"])],
                        reference_depth_m=Lr)
        w = truth["full_load"][j - 1]
        joints[f"joint{j}"] = dict(
            bias_torque={k: (list(map(float, v)) if isinstance(v, list) else v if isinstance(v, str) else float(v))
                         for k, v in bias.items()},
            compliance=dict(form="inverse_cubic", coefficients=[float(x) for x in c]),
            backlash_rad=dict(value=truth["delta"][j - 1]), tau_min_nm=dict(value=w),
            deadzone_width_nm=dict(value=w), depth_range_m=dict(value=[lo, hi]))
    doc = dict(format="pliant-parameters", version=1, description="third_generator truth") | joints
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
    return maxerr


def id_table(pl, variant, wd, truth, files):
    """K at every clamp depth and delta against the truth: error % and z = (est - truth)/sd."""
    got = {}
    for tag, pj in files:
        if not os.path.exists(os.path.join(wd, pj)):
            continue
        for d in truth["clamp"]:
            p = run(variant, [pl, "params", pj, "--depth", str(d["L"]), "--json"], wd)
            got[tag, d["L"]] = json.loads(p.stdout)
    tags = [t for t, _ in files if (t, truth["clamp"][0]["L"]) in got]
    print("  identification: K error % (z = (est - truth)/sd; * |z|>=2, !! |z|>=3), joint 1 | joint 2")
    print("    L (m)  " + "".join(f"{t:>34s}" for t in tags))
    zs = {t: [] for t in tags}

    def cell(t, est, sd, true):
        z = (est - true) / max(sd, 1e-300)
        zs[t].append(abs(z))
        return f"{100 * (est / true - 1):+6.2f}% {z:+7.1f}{mark(z):2s}"
    for d in truth["clamp"]:
        line = f"    {d['L']:.3f}  "
        for t in tags:
            r = got[t, d["L"]]
            line += "  " + cell(t, r["K1"], r["K1_sd"], d["K1"]) + "|" + cell(t, r["K2"], r["K2_sd"], d["K2"])
        print(line)
    line = "    delta  "
    for t in tags:
        r = got[t, truth["clamp"][0]["L"]]
        for j in (1, 2):
            z = (r[f"delta{j}"] - truth["delta"][j - 1]) / max(r[f"delta{j}_sd"], 1e-300)
            line += f"  {1e3 * r[f'delta{j}']:5.2f}±{1e3 * r[f'delta{j}_sd']:.2f} {z:+6.1f}{mark(z):2s}"
    print(line + f"   (mrad; truth {1e3 * truth['delta'][0]:.2f}, {1e3 * truth['delta'][1]:.2f})")
    print("    share of K with |z|<2: " + ", ".join(f"{t} {100 * np.mean(np.array(zs[t]) < 2):.0f}% (max |z| {max(zs[t]):.1f})"
                                           for t in tags))


def mark(z):
    return "!!" if abs(z) >= 3 else ("*" if abs(z) >= 2 else "")


def metrics(out, orig, truth_rows, full_load, sd=True):
    """RMS of corrected - q_true (mrad) on held rows, held rows on a wall, free rows; coverage."""
    held = orig["tip_fixed"] == 1
    res = {}
    for j in (1, 2):
        e = out[f"q{j}_corr"] - orig[f"q{j}_true"]
        wall = held & (np.abs(truth_rows[f"tau{j}_ext"]) > full_load[j - 1])
        r = dict(held=rms(e[held]), wall=rms(e[wall]), free=rms(e[~held]),
                 unc=rms((orig[f"q{j}"] - orig[f"q{j}_true"])[held]),
                 hmax=1e3 * np.nanmax(np.abs(e[held])), fmax=1e3 * np.nanmax(np.abs(e[~held])) if np.any(~held) else np.nan)
        if sd and f"q{j}_sd" in out:
            s = out[f"q{j}_sd"]
            r["cov"] = 100 * np.mean(np.abs(e[held]) < 1.96 * s[held])
            r["cov_wall"] = 100 * np.mean(np.abs(e[wall]) < 1.96 * s[wall])
            r["cov_free"] = 100 * np.mean(np.abs(e[~held]) < 1.96 * s[~held]) if np.any(~held) else np.nan
            r["maxz"] = np.nanmax(np.abs(e) / s)
        res[j] = r
    return res


def rms(x):
    return 1e3 * float(np.sqrt(np.nanmean(x**2))) if len(x) else float("nan")


def downstream(pl, variant, wd, pj, tag, truth, logs):
    print(f"  with {tag} parameters ({pj}): corrected - q_true, mrad, joint 1/joint 2: RMS on held rows, on held rows"
          f" past the take-up (wall), on free rows; max |error| held, free; coverage of 1.96 sd on held (wall, free)"
          f" rows; max |error|/sd over all rows; rows rejected by the gate / flagged model mismatch")
    for logname, hint, nohint, truthcsv in logs:
        orig, tr = read_csv(os.path.join(wd, hint)), read_csv(os.path.join(wd, truthcsv))
        jobs = [("filter+hint", ["filter", "--params", pj, hint], True),
                ("filter online", ["filter", "--params", pj, nohint], True),
                ("correct eq.2", ["correct", "--params", pj, nohint], False)]
        if tag == "TRUE":
            jobs.append(("correct dz", ["correct", "--model", "deadzone", "--params", pj, nohint], False))
        for name, cmd, sd in jobs:
            outp = f"out_{tag}_{logname}_{name.split()[0]}{'_h' if 'hint' in name else ''}{'_dz' if 'dz' in name else ''}.csv"
            p = run(variant, [pl] + cmd + ["-o", outp], wd)
            if p.returncode != 0:
                print(f"    {logname:5s} {name:13s} EXIT {p.returncode}: {p.stderr.strip()[:300]}")
                continue
            m = metrics(read_csv(os.path.join(wd, outp)), orig, tr, truth["full_load"], sd)
            s = (f"    {logname:5s} {name:13s} held {m[1]['held']:5.2f}/{m[2]['held']:5.2f} wall "
                 f"{m[1]['wall']:5.2f}/{m[2]['wall']:5.2f} free {m[1]['free']:5.2f}/{m[2]['free']:5.2f} "
                 f"max {m[1]['hmax']:5.1f}/{m[2]['hmax']:5.1f}, {m[1]['fmax']:5.1f}/{m[2]['fmax']:5.1f}")
            if sd:
                fl = [ln for ln in (p.stderr + p.stdout).splitlines() if "rows flagged" in ln]
                rej = mis = "?"
                if fl:
                    w = fl[0].replace(",", "").split()
                    rej, mis = w[w.index("rejected") + 1], w[w.index("mismatch") + 1]
                s += (f" cov {m[1]['cov']:5.1f}/{m[2]['cov']:5.1f}% ({m[1]['cov_wall']:5.1f}/{m[2]['cov_wall']:5.1f},"
                      f" {m[1]['cov_free']:5.1f}/{m[2]['cov_free']:5.1f}) e/sd {m[1]['maxz']:5.1f}/{m[2]['maxz']:5.1f}"
                      f" rej {rej} mis {mis}")
            print(s)
        print(f"    {logname:5s} {'uncorrected':13s} held {m[1]['unc']:5.2f}/{m[2]['unc']:5.2f}")


def python_truth_check(wd, truth, logname, truthcsv):
    """Independent of pliant: does the docs' q_hat = q - delta*S - K*tau_ext give q_true here?"""
    d, tr = read_csv(os.path.join(wd, logname)), read_csv(os.path.join(wd, truthcsv))
    b = ph.Bias.__new__(ph.Bias)
    b.__dict__.update(truth["bias"])
    t0 = b.tau0(d["q1"], d["q2"], d["q3"])
    held = d["tip_fixed"] == 1
    out = []
    for j in (1, 2):
        exact = d[f"q{j}"] - tr[f"b{j}"] - tr[f"K{j}"] * tr[f"tau{j}_ext"] - d[f"q{j}_true"]
        w, dl = truth["full_load"][j - 1], truth["delta"][j - 1]
        tm = d[f"tau{j}"] - t0[j - 1]
        x = np.clip(tm / w, -1, 1)
        S = (15 * x - 10 * x**3 + 3 * x**5) / 8
        eq = d[f"q{j}"] - dl * S - tr[f"K{j}"] * tm - d[f"q{j}_true"]
        wall = held & (np.abs(tr[f"tau{j}_ext"]) > w)
        out.append(f"j{j}: exact max {1e3 * np.max(np.abs(exact)):.4f} mrad; deadzone eq. with true params: "
                   f"on-wall RMS {rms(eq[wall]):.3f}, held RMS {rms(eq[held]):.3f} mrad")
    return f"  python check on {logname}: " + "; ".join(out)


def evaluate(pl, work, name, extra):
    wd = os.path.join(work, name)
    os.makedirs(wd, exist_ok=True)
    print(f"\n=== variant {name}: generate.py {' '.join(extra)}")
    p = run(name, [sys.executable, os.path.join(HERE, "generate.py"), "--out", wd] + extra, wd)
    print("  " + p.stdout.strip())
    truth = json.load(open(os.path.join(wd, "truth.json")))
    print("  truth: K scale %.3f/%.3f  delta %.2f/%.2f mrad  take-up ends %.3f/%.3f N·m  effort sd %.1f/%.1f mN·m tc %.0f/%.0f ms"
          % (*truth["k_scale"], 1e3 * truth["delta"][0], 1e3 * truth["delta"][1], *truth["full_load"],
             1e3 * truth["effort_sigma"][0], 1e3 * truth["effort_sigma"][1],
             1e3 * truth["effort_tc"][0], 1e3 * truth["effort_tc"][1]))
    write_without(os.path.join(wd, "test.csv"), os.path.join(wd, "test_nohint.csv"), {"tip_fixed"})
    write_without(os.path.join(wd, "calibration.csv"), os.path.join(wd, "calibration_nohint.csv"), {"tip_fixed"})
    split_per_joint(os.path.join(wd, "calibration.csv"), os.path.join(wd, "calib_j%d.csv"))
    maxerr = truth_params(truth, os.path.join(wd, "TRUE.json"))
    print(f"  TRUE.json: K(L) as an inverse cubic, largest error {100 * maxerr[0]:.3f}/{100 * maxerr[1]:.3f} % of K")
    for logname, tcsv in (("test.csv", "test_truth.csv"), ("calibration.csv", "calibration_truth.csv")):
        print(python_truth_check(wd, truth, logname, tcsv))
    files = []
    for tag, args, pj in (("auto", [], "P.json"), ("smoother", ["--method", "smoother"], "P_smoother.json"),
                          ("paper", ["--method", "paper"], "P_paper.json")):
        p = run(name, [pl, "identify"] + args + ["calibration.csv", "-o", pj], wd)
        if p.returncode:
            print(f"  identify {tag}: EXIT {p.returncode}: {p.stderr.strip()[:300]}")
        files.append((tag, pj))
    p = run(name, [pl, "identify", "calib_j1.csv", "calib_j2.csv", "-o", "P_split.json"], wd)
    files.append(("auto-split", "P_split.json"))
    id_table(pl, name, wd, truth, files)
    logs = [("test", "test.csv", "test_nohint.csv", "test_truth.csv"),
            ("calib", "calibration.csv", "calibration_nohint.csv", "calibration_truth.csv")]
    for tag, pj in (("TRUE", "TRUE.json"), ("auto", "P.json"), ("smoother", "P_smoother.json")):
        downstream(pl, name, wd, pj, tag, truth, logs)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pliant", default=os.path.join(HERE, "..", "..", "build", "cli", "pliant"))
    ap.add_argument("--work", default="/tmp/third")
    ap.add_argument("--only", nargs="*")
    a = ap.parse_args()
    pl = os.path.abspath(a.pliant)
    for name, extra in VARIANTS:
        if not a.only or name in a.only:
            evaluate(pl, a.work, name, extra)
    print("\n=== commands with a non-zero exit or warnings/notes on stderr")
    for variant, cmd, rc, notes in LOG:
        if rc or notes:
            print(f"  [{variant}] exit {rc}: {cmd.replace(pl, 'pliant')}")
            for n in dict.fromkeys(notes):
                print(f"      {n[:240]}")


if __name__ == "__main__":
    main()
