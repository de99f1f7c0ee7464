#pragma once
// What the two JHU 2017 calibration formats share (docs/import.md): the joint
// under test from the file name, the metadata, the log's leading columns and
// the checks on the measured values.

#include <string>
#include <vector>

#include "import_csv.h"
#include "pliant/io/import.h"
#include "pliant/io/log.h"

namespace pliant::io::detail {

/// PSM joint 1 or 2: options.joint, else "joint_0" / "joint_1" in the file name.
/// @throws InputError when neither tells.
int JhuJointUnderTest(const std::string& path, const ImportOptions& options);

/// The four columns both formats read first, in this order, by their names in
/// the file: the depth block, q3 (m), qJ (rad) and the effort (N·m).
std::vector<std::string> JhuSharedColumns(ImportFormat format);

/// Metadata and the leading columns t, qJ, q3, tauJ, tip_fixed, segment of a
/// log of one JHU file; the other joint's q and tau are left out.
LogHeader JhuHeader(const std::string& path, ImportFormat format, int joint,
                    const std::string& experiment);

/// Checks one row's shared values (JhuSharedColumns' order, read from the file's
/// columns `read`): an integer depth block >= 0, and q3, qJ, tauJ within the log
/// format's ranges. @throws InputError at the cell.
void CheckJhuRow(const CsvText& csv, std::size_t row, const std::vector<int>& read,
                 const double* values);

}  // namespace pliant::io::detail
