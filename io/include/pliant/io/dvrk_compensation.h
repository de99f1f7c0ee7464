#pragma once
// The dVRK's own compensation parameter file: the JSON that the component
// mtsPSMCompensation (jhu-dvrk/sawIntuitiveResearchKit,
// components/code/mtsPSMCompensation.cpp) reads in Configure(). Its layout:
//
//   /* a C-style comment line */
//   { "parameters": [
//       { "parameter": "compliance_first", "value-a": a, "value-b": b, "value-c": c, "value-d": d },
//       { "parameter": "torque_offset_first", "value-a": ..., ... },
//       { "parameter": "backlash_first", "value-a": delta, ... },
//       ... the same three for "_second" ... ] }
//
// What the component computes from them (ComputeCompensation), q3 the
// insertion depth L in m:
//   compliance      K(L) = a·L³ + b·L² + c·L + d, rad/(N·m), both joints;
//   torque offset   joint 1: tau0 = value-a (a constant, N·m);
//                   joint 2: tau0 = value-a·L + value-b (linear in L, N·m);
//   backlash        value-a, rad (the group's file stores joint 2's under
//                   "value"; both keys are read here, and written as value-a,
//                   the key the component reads).
// value-c and value-d of the torque offsets and value-b … value-d of the
// backlash are not used by the component.

#include <array>
#include <string>
#include <vector>

#include "pliant/models/parameters.h"

namespace pliant::io {

/// The file's numbers, per joint ([0] joint 1 "first", [1] joint 2 "second").
struct DvrkCompensation {
  std::array<std::array<double, 4>, 2> compliance{};     ///< a, b, c, d of K(L), rad/(N·m)
  std::array<std::array<double, 4>, 2> torque_offset{};  ///< value-a … value-d as stored
  std::array<double, 2> backlash_rad{};                  ///< delta, rad
};

/// True when `text` is a JSON object (comments allowed) with a "parameters"
/// array and no "format" key: the dVRK's layout, not pliant's.
bool LooksLikeDvrkCompensation(const std::string& text);

/// Parses the dVRK file; `file` names it in messages. Every one of the six
/// entries must be present once with finite numbers. Throws InputError at the
/// line of the fault.
DvrkCompensation ParseDvrkCompensation(const std::string& text, const std::string& file);

/// The file's text: a comment line, then the six entries in the order above,
/// each number in its shortest round-trip form.
std::string DvrkCompensationText(const DvrkCompensation& compensation);

/// tau0 (N·m) of joint `joint` (0 or 1) at depth L (m), as the component computes it.
double DvrkTorqueOffset(const DvrkCompensation& compensation, int joint, double depth_m);

/// Reads a parameters file in either format: pliant's, or the dVRK's (found by
/// LooksLikeDvrkCompensation, then converted by DvrkToParameters). `*dvrk`
/// says which. Throws InputError.
models::ModelParameters ReadAnyParameters(const std::string& path, bool* dvrk);

/// pliant's parameters holding exactly what the component computes: K(L) as a
/// direct cubic, tau0 as a depth-linear bias (Fourier a0 with a depth slope,
/// reference depth 0), delta as the backlash. The file holds no tau_min, no
/// dead-zone width and no depth range: those are the paper's (data/paper.json:
/// 0.1 / 0.2 N·m, 0.09–0.22 m). Throws InputError (file `file`) when the result
/// fails models::ValidateParameters.
models::ModelParameters DvrkToParameters(const DvrkCompensation& compensation,
                                         const std::string& file);

/// The file that makes the component apply `parameters` as closely as its
/// model can: a direct cubic is copied; any other law is fitted by a cubic in
/// least squares at 61 depths over the valid range; the bias torque becomes
/// its value at q = 0 (the component has no angle term), constant for joint 1
/// (taken at the middle of the range) and linear in L for joint 2. `notes`
/// receives one line for each approximation made, with its size.
DvrkCompensation ParametersToDvrk(const models::ModelParameters& parameters,
                                  std::vector<std::string>* notes);

}  // namespace pliant::io
