#include "pliant/io/log.h"

#include <stdexcept>

namespace pliant::io {
namespace {

int Required(const LogHeader& header, std::string_view name) {
  const int index = header.Index(name);
  if (index < 0) {
    // LogReader never produces such a header; a hand-built one is a programming error.
    throw std::out_of_range("log header has no required column '" + std::string(name) + "'");
  }
  return index;
}

}  // namespace

int LogHeader::Index(std::string_view name) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return static_cast<int>(i);
  }
  return -1;
}

int LogHeader::AddColumn(std::string_view name) {
  const int existing = Index(name);
  if (existing >= 0) return existing;
  columns.emplace_back(name);
  return static_cast<int>(columns.size() - 1);
}

std::string LogHeader::Metadata(std::string_view key) const {
  for (const auto& [k, v] : metadata) {
    if (k == key) return v;
  }
  return {};
}

StandardColumns::StandardColumns(const LogHeader& header)
    : t(Required(header, "t")),
      q1(Required(header, "q1")),
      q2(Required(header, "q2")),
      q3(Required(header, "q3")),
      tau1(Required(header, "tau1")),
      tau2(Required(header, "tau2")),
      v1(header.Index("v1")),
      v2(header.Index("v2")),
      q1_ref(header.Index("q1_ref")),
      q2_ref(header.Index("q2_ref")),
      q1_true(header.Index("q1_true")),
      q2_true(header.Index("q2_true")),
      tip_fixed(header.Index("tip_fixed")),
      segment(header.Index("segment")) {}

TipReference FindTipReference(const StandardColumns& c) {
  if (c.q1_true >= 0 && c.q2_true >= 0) return {c.q1_true, c.q2_true, "q*_true"};
  if (c.q1_ref >= 0 && c.q2_ref >= 0) return {c.q1_ref, c.q2_ref, "q*_ref"};
  return {};
}

std::size_t Log::Rows() const { return Columns() == 0 ? 0 : values.size() / Columns(); }

double Log::Value(std::size_t row, std::size_t column) const {
  return values[row * Columns() + column];
}

std::vector<double> Log::Column(std::string_view name) const {
  const int column = header.Index(name);
  if (column < 0) throw std::out_of_range("log has no column '" + std::string(name) + "'");
  std::vector<double> out(Rows());
  for (std::size_t row = 0; row < out.size(); ++row) out[row] = Value(row, column);
  return out;
}

}  // namespace pliant::io
