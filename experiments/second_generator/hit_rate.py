#!/usr/bin/python3
"""Hit rate of `pliant diagnose` on the second generator's logs (docs/validation-diagnosis.md).

For each case: generate the calibration and test logs, `pliant identify` the
instrument from the calibration log, `pliant diagnose --json` the test log,
then `--add` the true effect and read the held-out error before and after.
The control's held-out error (nothing hidden: the sensors' noise left after
the 0.05 s windows and the generator's own take-up and bias shapes) is a
floor no added effect can go below; "above the control" is the share of the
error beyond it, in quadrature, that the added effect removes, and "above the
noise" the same beyond the log's own noise floor as the diagnosis reads it
(`noise_floor`, from the residual alone: what a user without a control has).

Usage: hit_rate.py PLIANT_BINARY OUT_DIR [--seed N] [--case NAME ...] [--identify-with-test]
                   [instrument options]

The instrument options (--k-scale K1 K2, --clearance D1 D2, --take-up W,
--noise-scale X, --rate HZ) go to generate.py: the hit rate on instruments
and sensors unlike the generator's defaults.
"""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import generate  # noqa: E402


def run(command):
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        return None, done.stderr.strip().splitlines()[-1] if done.stderr.strip() else "exit %d" % done.returncode
    return done.stdout, None


def diagnose(pliant, params, log, report, extra=()):
    out, error = run([pliant, "diagnose", "--params", params, log, "--json", "-o", report, *extra])
    return (json.loads(out), None) if out else (None, error)


def above(control, before, after):
    """Share of the error above the control's (added in quadrature) removed."""
    if control is None or before <= control:
        return None
    return 1.0 - (max(after ** 2 - control ** 2, 0.0) / (before ** 2 - control ** 2)) ** 0.5


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("pliant")
    parser.add_argument("out_dir")
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--case", action="append", choices=generate.CASES)
    parser.add_argument("--identify-with-test", action="store_true",
                        help="identify on the calibration and the test log together (the effect "
                             "in both, the test log's pushes from many tips beside the clamps)")
    args, instrument = parser.parse_known_args()
    cases = args.case or generate.CASES
    subprocess.run([sys.executable, os.path.join(HERE, "generate.py"), args.out_dir,
                    "--seed", str(args.seed)] + sum((["--case", c] for c in cases), []) + instrument,
                   check=True)
    print("| hidden effect | named first | missing | also flagged | held-out RMS before -> with the truth added (mm) | cut | above the control | noise floor (mm) | above the noise |")
    print("|---|---|---|---|---|---|---|---|---|")
    hits, warnings, cuts, control, excess, beyond_noise = 0, 0, [], None, [], []
    for case in cases:
        d = os.path.join(args.out_dir, case)
        params = os.path.join(d, "identified.json")
        logs = [os.path.join(d, "calibration.csv")]
        if args.identify_with_test:
            logs.append(os.path.join(d, "test.csv"))
        _, error = run([args.pliant, "identify", *logs, "-o", params])
        if error:
            print("| %s | identify failed: %s | | | | | |" % (case, error))
            continue
        log = os.path.join(d, "test.csv")
        result, error = diagnose(args.pliant, params, log, os.path.join(d, "report"))
        if error:
            print("| %s | diagnose failed: %s | | | | | |" % (case, error))
            continue
        first = result["effects"][0]["name"] if result["effects"] else "-"
        missing = result["missing_effect"]
        flagged = [e["name"] for e in result["effects"] if e["missing"] and e["name"] != missing]
        truth = None if case == "none" else case
        hit = missing == truth
        hits += hit
        # A wrong "none" on a log the parameters were fitted on comes with the
        # diagnosis's note that the fit may have taken the effect up.
        warned = not hit and missing is None and any(
            "were fitted on this log" in n for n in result.get("notes", []))
        warnings += warned
        cell = ""
        if truth:
            added, error = diagnose(args.pliant, params, log, os.path.join(d, "report_added"),
                                    ["--add", truth])
            if added:
                cut = 1.0 - added["rms_after"] / added["rms_before"]
                cuts.append(cut)
                share = above(control, added["rms_before"], added["rms_after"])
                excess.append(share)
                floor = added["noise_floor"]
                own = above(floor, added["rms_before"], added["rms_after"])
                beyond_noise.append(own)
                cell = "%.3f -> %.3f | %.0f %% | %s | %.3f | %s" % (
                    added["rms_before"], added["rms_after"], 100 * cut,
                    "-" if share is None else "%.0f %%" % (100 * share), floor,
                    "-" if own is None else "%.0f %%" % (100 * own))
            else:
                cell = "failed: %s | | | |" % error
        else:
            control = result["rms_before"]
            cell = "%.3f | - | - | %.3f | -" % (control, result["noise_floor"])
        verdict = "" if hit else (" (wrong; noted: fitted on this log)" if warned else " (wrong)")
        print("| %s | %s | %s%s | %s | %s |" % (case, first, missing or "none", verdict,
                                              ", ".join(flagged) or "-", cell))
    print()
    effects = [c for c in cases if c != "none"]
    print("right answer (the true effect named missing, the control quiet): %d of %d" % (hits, len(cases)))
    if warnings:
        print("wrong, with the note that the parameters were fitted on the diagnosed log: %d" % warnings)
    if cuts:
        print("adding the true effect cuts the held-out error by >= 50 %%: %d of %d"
              % (sum(c >= 0.5 for c in cuts), len(effects)))
    if control is not None and cuts:
        print("adding the true effect removes >= 50 %% of the error above the control's %.3f mm: %d of %d"
              % (control, sum(e is not None and e >= 0.5 for e in excess), len(effects)))
    if beyond_noise:
        print("adding the true effect removes >= 50 %% of the error above the log's own noise floor: %d of %d"
              % (sum(e is not None and e >= 0.5 for e in beyond_noise), len(effects)))


if __name__ == "__main__":
    main()
