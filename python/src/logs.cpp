// Canonical logs (docs/log-format.md) to and from numpy: read with
// io::ReadLog, written with io::WriteLog (atomic, shortest round-trip numbers),
// so a log read here is the log every pliant command reads; real recordings
// imported as `pliant import` does.
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "pliant/io/import.h"
#include "pliant/io/input_error.h"
#include "pliant/io/log_reader.h"
#include "pliant/io/log_writer.h"
#ifdef PLIANT_HAVE_ROS1
#include "pliant/ros/crtk_bag.h"
#endif

namespace pliant::python {
namespace {

using Metadata = std::vector<std::pair<std::string, std::string>>;
using Column = py::array_t<double, py::array::c_style | py::array::forcecast>;

// (columns, values of shape (columns, rows), metadata): each column one
// contiguous row of `values`, which __init__.py hands out as a dict.
py::tuple Columns(const io::Log& log) {
  const std::size_t rows = log.Rows(), columns = log.Columns();
  py::array_t<double> values({columns, rows});
  auto out = values.mutable_unchecked<2>();
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns; ++c) out(c, r) = log.values[r * columns + c];
  }
  return py::make_tuple(log.header.columns, values, log.header.metadata);
}

py::tuple ReadLogColumns(const std::string& path, bool skip_bad_rows) {
  io::Log log;
  {
    py::gil_scoped_release unlocked;
    log = io::ReadLog(path, {skip_bad_rows});
  }
  return Columns(log);
}

// A real recording (docs/import.md) as ReadLogColumns gives a log, and the
// lines saying how its format was recognised: `pliant import`'s rules
// (io::ChooseImportFormat, ImportRecording).
py::tuple ImportRecordingColumns(const std::vector<std::string>& paths,
                                 const std::string& format_name, int joint,
                                 const std::string& topic, const std::string& arm) {
  io::Log log;
  io::RecordingFormat chosen;
  {
    py::gil_scoped_release unlocked;
    chosen = io::ChooseImportFormat(paths, format_name);
    io::BagReader read_bag;  // none: ImportRecording says how to build ROS 1 support
#ifdef PLIANT_HAVE_ROS1
    read_bag = ros::CrtkBagReader();
#endif
    log = io::ImportRecording(chosen.format, paths, {joint, topic, arm}, read_bag);
  }
  return py::make_tuple(Columns(log), std::string(io::ImportFormatName(chosen.format)),
                        chosen.evidence);
}

void WriteLogColumns(const std::string& path, const std::vector<std::string>& names,
                     const std::vector<Column>& columns, const Metadata& metadata) {
  if (names.empty()) {
    throw io::InputError(path, 0, 0, "the log to write has no columns",
                         "give at least t, q1, q2, q3, tau1, tau2 (docs/log-format.md)");
  }
  io::Log log;
  log.header.columns = names;
  log.header.metadata = metadata;
  const auto rows = static_cast<std::size_t>(columns[0].size());
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (columns[c].ndim() != 1 || static_cast<std::size_t>(columns[c].size()) != rows) {
      throw io::InputError(path, 0, 0,
                           "column '" + names[c] + "' holds " + std::to_string(columns[c].size()) +
                               " values in " + std::to_string(columns[c].ndim()) +
                               " dimension(s) and '" + names[0] + "' " + std::to_string(rows),
                           "give every column as a 1-D sequence of the same length");
    }
  }
  log.values.resize(rows * names.size());
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const double* data = columns[c].data();
    for (std::size_t r = 0; r < rows; ++r) log.values[r * names.size() + c] = data[r];
  }
  py::gil_scoped_release unlocked;
  io::WriteLog(path, log);
}

}  // namespace

void BindLogs(py::module_& m) {
  m.def("_read_log", &ReadLogColumns, py::arg("path"), py::arg("skip_bad_rows") = false,
        "(columns, values[column, row], metadata) of a canonical log; see pliant.read_log.");
  m.def("_write_log", &WriteLogColumns, py::arg("path"), py::arg("names"), py::arg("columns"),
        py::arg("metadata"),
        "Writes a canonical log atomically from named columns; see pliant.write_log.");
  m.def("_import_recording", &ImportRecordingColumns, py::arg("paths"), py::arg("format"),
        py::arg("joint"), py::arg("topic"), py::arg("arm"),
        "((columns, values, metadata), format, evidence) of a real recording; see "
        "pliant.import_recording.");
}

}  // namespace pliant::python
