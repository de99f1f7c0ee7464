#!/usr/bin/python3
"""Hit rate of pliant's missing-effect diagnosis on the third generator's hidden effects.

For the control ("none") and each effect of physics.EFFECT_NAMES, with one fixed seed S:
  * calibration.csv WITHOUT the effect (generate.py --effect none --seed S), identified once:
        pliant identify calibration.csv -o P.json
    (the calibration log and hence P.json are the same for every case: same seed, no effect);
  * test.csv WITH the effect (generate.py --effect NAME --seed S: same instrument, and the test
    log's random stream is that of --effect none, so the two differ by the effect alone);
  * pliant diagnose --params P.json test.csv --json         (run in the case's directory)
  * if "missing_effect" names an effect:
        pliant diagnose --params P.json test.csv --json --add NAME
    and its held-out "rms_before" -> "rms_after" (mm).
One line per case, then the hit rate (true effect named, control quiet) and the number of cases
where adding the named effect cut the held-out error by >= 50 %.

Usage: hit_rate.py [--seed S] [--work DIR] [--pliant PATH] [--rate HZ] [--only NAME ...]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import physics as ph  # noqa: E402

EFFECTS = [e for e in ph.EFFECT_NAMES if e != "none"]


def run(cmd, cwd):
    t0 = time.time()
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    dt = time.time() - t0
    with open(os.path.join(cwd, "commands.log"), "a") as f:
        f.write(f"$ {' '.join(cmd)}\n# exit {p.returncode}, {dt:.1f} s\n{p.stderr}\n")
    return p, dt


def last_line(text):
    lines = [ln for ln in text.strip().splitlines() if ln.strip()]
    return lines[-1].strip() if lines else "(no stderr)"


def generate(effect, seed, out, rate):
    cmd = [sys.executable, os.path.join(HERE, "generate.py"), "--seed", str(seed), "--effect", effect,
           "--out", out, "--rate", str(rate)]
    os.makedirs(out, exist_ok=True)
    p, _ = run(cmd, out)
    if p.returncode != 0:
        raise SystemExit(f"generate.py --effect {effect} failed: {last_line(p.stderr)}")


def diagnose(pliant, cwd, add=None):
    cmd = [pliant, "diagnose", "--params", "P.json", "test.csv", "--json"] + (["--add", add] if add else [])
    p, dt = run(cmd, cwd)
    js = None
    if p.returncode == 0:
        try:
            js = json.loads(p.stdout)
        except json.JSONDecodeError as e:
            return p, dt, None, f"bad JSON on stdout: {e}"
    return p, dt, js, None if p.returncode == 0 else last_line(p.stderr)


def fmt_effects(js, n=3):
    parts = []
    for e in (js.get("effects") or [])[:n]:
        parts.append(f"{e.get('name')}(u={e.get('unique_score', float('nan')):.3f} s={e.get('score', float('nan')):.3f}"
                     f" p={e.get('p_value', float('nan')):.2g} missing={str(e.get('missing')).lower()})")
    return "; ".join(parts) if parts else "(no effects)"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--work", default="/tmp/third/hit_rate")
    ap.add_argument("--pliant", default=os.path.normpath(os.path.join(HERE, "..", "..", "build", "cli", "pliant")))
    ap.add_argument("--rate", type=float, default=400.0, help="test log rate, Hz (generate.py --rate)")
    ap.add_argument("--only", nargs="+", choices=ph.EFFECT_NAMES, help="run only these cases")
    args = ap.parse_args()
    pliant = os.path.abspath(args.pliant)
    T0 = time.time()
    work = os.path.abspath(args.work)
    os.makedirs(work, exist_ok=True)

    # calibration without the effect, identified once (shared by every case)
    base = os.path.join(work, "none")
    generate("none", args.seed, base, args.rate)
    p, dt = run([pliant, "identify", "calibration.csv", "-o", "P.json"], base)
    if p.returncode != 0:
        raise SystemExit(f"pliant identify failed (exit {p.returncode}): {last_line(p.stderr)}")
    print(f"seed {args.seed}, test log at {args.rate:g} Hz; pliant identify calibration.csv (no effect): "
          f"exit 0, {dt:.1f} s")

    cases = ["none"] + EFFECTS
    if args.only:
        cases = [c for c in cases if c in args.only]
    results = []
    for truth in cases:
        cdir = os.path.join(work, truth)
        if truth != "none":
            generate(truth, args.seed, cdir, args.rate)
            shutil.copyfile(os.path.join(base, "P.json"), os.path.join(cdir, "P.json"))
        p, dt, js, err = diagnose(pliant, cdir)
        r = dict(truth=truth, named=None, exit=p.returncode, cut=None)
        if js is None:
            print(f"{truth:26s} diagnose exit {p.returncode} ({dt:.0f} s): {err}")
            results.append(r)
            continue
        named = js.get("missing_effect")
        r["named"] = named
        line = (f"{truth:26s} named={named or 'none':26s} exit={p.returncode} ({dt:.0f} s) "
                f"rms {js.get('rms_before', float('nan')):.4f} mm | top-3: {fmt_effects(js)}")
        if named:
            top = next((e for e in js.get("effects") or [] if e.get("name") == named), {})
            if "heldout_rms_after_mm" in top:
                line += (f" [ranking's held-out {top.get('heldout_rms_before_mm', float('nan')):.4f} -> "
                         f"{top['heldout_rms_after_mm']:.4f} mm]")
            pa, dta, jsa, erra = diagnose(pliant, cdir, add=named)
            if jsa is None:
                line += f" || --add {named}: exit {pa.returncode}: {erra}"
            else:
                b, a = jsa.get("rms_before"), jsa.get("rms_after")
                cut = 100.0 * (b - a) / b if b else float("nan")
                r["cut"] = cut
                line += (f" || --add {named}: exit={pa.returncode} ({dta:.0f} s) {b:.4f} -> {a:.4f} mm "
                         f"({cut:+.1f} % cut)")
        print(line, flush=True)
        results.append(r)

    eff = [r for r in results if r["truth"] != "none"]
    hits = sum(1 for r in eff if r["named"] == r["truth"])
    ctrl = [r for r in results if r["truth"] == "none"]
    quiet = all(r["named"] is None and r["exit"] == 0 for r in ctrl)
    wrong = [f"{r['truth']}->{r['named']}" for r in eff if r["named"] and r["named"] != r["truth"]]
    missed = [r["truth"] for r in eff if not r["named"]]
    big = [r for r in results if r["cut"] is not None and r["cut"] >= 50.0]
    print()
    if not ctrl:
        cstate = "not run"
    elif quiet:
        cstate = "quiet"
    else:
        cstate = f"NOT quiet (named {ctrl[0]['named']}, exit {ctrl[0]['exit']})"
    print(f"hit rate: {hits}/{len(eff)} effects named first; control {cstate} -> "
          f"{hits + (1 if ctrl and quiet else 0)}/{len(eff) + len(ctrl)} cases right")
    print(f"wrongly named: {', '.join(wrong) or 'none'}; not named: {', '.join(missed) or 'none'}")
    print(f"adding the named effect cut the held-out error by >= 50 %: {len(big)} case(s)"
          + (f" ({', '.join(r['truth'] for r in big)})" if big else ""))
    print(f"total run time {time.time() - T0:.0f} s; work dir {work}")


if __name__ == "__main__":
    main()
