"""pliant from Python: compliance and backlash of the dVRK PSM's joints 1-2.

A thin layer over pliant's C++ libraries (the same code the ``pliant`` command
runs, so the numbers are the same to the last digit). Units are SI throughout:
angles in rad, the insertion depth q3 in m, efforts in N·m, time in s, tip
errors in mm. See docs/python.md.

    import pliant
    params = pliant.load_parameters("data/paper.json")
    log = pliant.read_log("data/divot_push.csv")           # dict of numpy columns
    out = pliant.correct(params, log["q1"], log["q2"], log["q3"], log["tau1"], log["tau2"])
    f = pliant.Filter(params)
    est = f.step(0.0, 0.1, -0.2, 0.12, 0.3, -0.1)          # t, q1, q2, q3, tau1, tau2
    est.corrected, est.covariance                           # rad, rad²

Bad input raises pliant.InputError (a ValueError) whose text is the
command's: ``FILE:LINE[:COLUMN]: what is wrong — what to do``.
"""

import os
import tempfile

import numpy as np

from ._pliant import (  # the public API, with __all__ below
    FLAG_DEPTH_OUT_OF_RANGE,
    FLAG_EFFORT_SATURATED,
    FLAG_MISSING,
    FLAG_MODEL_MISMATCH,
    FLAG_OUTPUT_LIMITED,
    FLAG_REACQUIRED,
    FLAG_REJECTED,
    FLAG_REPAIRED,
    Filter,
    FilterEstimate,
    InputError,
    Parameters,
    correct,
    filter_option_defaults,
    load_parameters,
    parameters_from_json,
)
from . import _pliant

__all__ = [
    "InputError", "Log", "read_log", "import_recording", "write_log", "Parameters", "load_parameters",
    "parameters_from_json", "correct", "correct_log", "identify", "identify_arm_dynamics",
    "diagnose", "filter_log",
    "Filter", "FilterEstimate", "filter_option_defaults", "FLAG_REJECTED", "FLAG_MISSING",
    "FLAG_DEPTH_OUT_OF_RANGE", "FLAG_EFFORT_SATURATED", "FLAG_MODEL_MISMATCH", "FLAG_REACQUIRED",
    "FLAG_REPAIRED", "FLAG_OUTPUT_LIMITED",
]


class Log(dict):
    """A canonical log: column name -> 1-D float64 numpy array, in file order.

    ``metadata`` holds the ``# key: value`` lines above the header, in order,
    as a list of (key, value) string pairs; write_log writes them back.
    """

    def __init__(self, columns=(), metadata=()):
        super().__init__(columns)
        self.metadata = list(metadata)

    @property
    def rows(self):
        """Number of data rows."""
        return len(next(iter(self.values()))) if self else 0


def read_log(path, skip_bad_rows=False):
    """Reads a canonical log (docs/log-format.md) into a Log of numpy columns.

    Every check of ``pliant``'s reader applies (required columns, units,
    increasing t); bad input raises InputError naming its line and column.
    skip_bad_rows drops rows whose required values are NaN/Inf/empty instead.
    """
    names, values, metadata = _pliant._read_log(os.fspath(path), skip_bad_rows)
    return Log(zip(names, values), metadata)


def import_recording(paths, format=None, joint=0, topic=None, arm=None):
    """Imports a real recording into a Log, as ``pliant import`` does (docs/import.md).

    paths: one file, or the files of one recording (a ROS 2 extractor's
    measured_js and setpoint_js CSVs). format: "jhu2017-clamped-beam",
    "jhu2017-bias-sweep", "ros1-bag" or "ros2-csv"; by default recognised from
    the files' content, and ``log.import_format`` / ``log.import_evidence`` say
    which and why. joint: the JHU files' joint under test (1 or 2; default from
    the file name); topic: a single ros2-csv file's topic; arm: a bag's arm
    (e.g. "PSM2"; default its only one). An option the format does not read,
    mixed formats, or a bag where pliant was built without ROS 1 raise
    InputError; write the result with write_log.
    """
    if isinstance(paths, (str, bytes, os.PathLike)):
        paths = [paths]
    (names, values, metadata), chosen, evidence = _pliant._import_recording(
        [os.fspath(p) for p in paths], format or "", int(joint), topic or "", arm or "")
    log = Log(zip(names, values), metadata)
    log.import_format, log.import_evidence = chosen, list(evidence)
    return log


def write_log(path, log, metadata=None):
    """Writes a canonical log atomically from a mapping of column -> 1-D values.

    Columns are written in the mapping's order; numbers in the shortest form
    that reads back to the same double. metadata: (key, value) pairs, by
    default ``log.metadata`` when log is a Log.
    """
    if metadata is None:
        metadata = getattr(log, "metadata", [])
    names = [str(name) for name in log]
    columns = [np.asarray(log[name], dtype=np.float64) for name in log]
    _pliant._write_log(os.fspath(path), names, columns, [(str(k), str(v)) for k, v in metadata])


def _parameters(params):
    """(Parameters, the name the output's metadata gives them)."""
    if isinstance(params, Parameters):
        return params, "'" + params.description + "'"
    return load_parameters(os.fspath(params)), os.fspath(params)


def _through_files(run, log, output, skip_bad_rows):
    """Runs a file-to-file command on a path or an in-memory log; returns the
    output as a Log and the command's summary."""
    with tempfile.TemporaryDirectory(prefix="pliant-") as scratch:
        if isinstance(log, (str, os.PathLike)):
            source = os.fspath(log)
        else:
            source = os.path.join(scratch, "input.csv")
            write_log(source, log)
        target = os.fspath(output) if output is not None else os.path.join(scratch, "output.csv")
        summary = run(source, target)
        return read_log(target, skip_bad_rows), summary


def correct_log(params, log, output=None, model="paper", tare=None, skip_bad_rows=False):
    """``pliant correct`` on a log: adds q1_corr, q2_corr (rad).

    params: Parameters or a parameters file's path. log: a log file's path or
    a Log / mapping of columns. model: 'paper' (equation 2) or 'deadzone'.
    output: also keep the corrected log there (written atomically, the file
    ``pliant correct`` writes). tare: ``--tare``, 'auto' or 'T0:T1' — the
    parameters' bias torque tared on the log's unloaded rows first, as a real
    arm's bias drifts between days (docs/real-data.md). Returns (Log, summary);
    the summary has rows, depth_clamped_rows, the tip error (mm) uncorrected
    and corrected against the log's q*_true or q*_ref when it has one, and
    'tare' (the command's tare lines, '' untared).
    """
    parameters, name = _parameters(params)
    note = model + " model, parameters " + name

    def run(source, target):
        return _pliant._correct_file(parameters, source, target, model, note, tare or "",
                                     skip_bad_rows)

    return _through_files(run, log, output, skip_bad_rows)


def filter_log(params, log, output=None, smooth=False, tare=None, skip_bad_rows=False,
               **options):
    """``pliant filter`` on a log: the EKF (or with smooth=True the RTS smoother).

    Adds q1_corr, q2_corr (rad), q1_sd, q2_sd (rad), q12_cov (rad²),
    tip_corr_mm, tip_corr_sd_mm (mm), nis and flags (FLAG_* bits). params,
    log, output and tare as in correct_log; options as pliant.Filter's. Returns
    (Log, summary): rows, flagged rows, mean_nis_per_dof, the tip error (mm)
    uncorrected, filtered (and smoothed_error) against the reference, notes
    (what the log's header changed) and advice (what the summary prints beside
    them, e.g. an instrument state ended beyond 3 σ of the file's).
    """
    parameters, name = _parameters(params)
    note = "pliant filter, parameters " + name

    def run(source, target):
        return _pliant._filter_file(parameters, source, target, smooth, options, note,
                                    tare or "", skip_bad_rows)

    return _through_files(run, log, output, skip_bad_rows)


def identify(logs, output=None, method="auto", law="inverse_cubic", prior=None,
             harmonics=2, held_friction=True, effects=(), skip_bad_rows=False):
    """``pliant identify``: compliance K(L) (rad/(N·m)), backlash δ (rad) and bias
    torque (N·m) from log files, with the covariance (docs/identification.md).

    logs: a path or a list of paths. method: 'auto' (as the command: 'quasi_static'
    when a log records a single joint, as the real JHU files do; else 'smoother'), 'smoother', 'quasi_static' (clamp by clamp with the
    held friction; held_friction=False fits the paper's form) or 'paper'. law:
    'inverse_cubic', 'direct_cubic' or 'beam_series'. prior: Parameters (or a
    path) the priors are centred on; default the paper's. effects: catalogue
    effect names fitted beside the base model with their σ, as ``--effect``. output: also save
    the parameters file there. Returns (Parameters, report), the report being
    what ``pliant identify --json`` prints.
    """
    if isinstance(logs, (str, os.PathLike)):
        logs = [logs]
    if prior is not None:
        prior = _parameters(prior)[0]
    parameters, report = _pliant.identify([os.fspath(p) for p in logs], method, law, prior,
                                          harmonics, held_friction, list(effects),
                                          skip_bad_rows)
    if output is not None:
        parameters.save(os.fspath(output))
        report["output"] = os.fspath(output)
    return parameters, report


def identify_arm_dynamics(logs, params, output=None, skip_bad_rows=False):
    """``pliant identify --effect joint_inertia --effect joint_friction`` on free motion:
    the arm's inertia (kg·m²) and friction fitted where nothing holds the tip and a
    joint moves, with their σ (docs/identification.md, "The arm's dynamics from free
    motion"); the filter takes those σ as the prior of the arm torque it learns online.

    logs: a path or a list of paths. params: the arm's Parameters (or a path), whose
    bias table the fit reads. output: also save the parameters there. Returns
    (Parameters with the effects, report), the report being ``--json``'s
    'free_motion_fit'.
    """
    if isinstance(logs, (str, os.PathLike)):
        logs = [logs]
    parameters, report = _pliant.identify_arm_dynamics(
        [os.fspath(p) for p in logs], _parameters(params)[0], skip_bad_rows)
    if output is not None:
        parameters.save(os.fspath(output))
    return parameters, report


def diagnose(params, log, add=(), candidates=(), reference="auto", max_lag=30, folds=5,
             report_dir=None, write_params=None):
    """``pliant diagnose --json``: the effect the model lacks on a log file.

    params: Parameters or a path. Returns the summary dict: rms_before,
    rms_after (held-out tip RMS, mm), missing_effect (a name or None), effects
    and channels best first; with report_dir, also the HTML report there; with
    write_params (``--write-params``), also the parameters with the ``add``
    effects fitted on this log, which correct_log and filter_log apply.
    """
    parameters = _parameters(params)[0]
    path = lambda p: None if p is None else os.fspath(p)
    return _pliant.diagnose(parameters, os.fspath(log), list(add), list(candidates), reference,
                            max_lag, folds, path(report_dir), path(write_params))
