#pragma once
// Checked access to a scenario's JSON: every problem becomes an io::InputError
// at the line of the offending key, or at the --set override that put it there.

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "pliant/io/input_error.h"
#include "pliant/io/json_input.h"
#include "pliant/io/json_location.h"

namespace pliant::experiments::detail {

using nlohmann::json;

using Key = io::JsonKey;

/// A --set override: where it points and how the user wrote it.
struct Override {
  std::string pointer;
  std::string text;
};

class ScenarioReader {
 public:
  /// `top` names the document in messages ("the scenario", "the study") and
  /// `see_docs` ends the fixes of object-key problems.
  ScenarioReader(const std::string& text, std::string file, std::vector<Override> overrides,
                 std::string top = "the scenario",
                 std::string see_docs = " (docs/simulator.md shows every section)")
      : file_(std::move(file)), map_(text), overrides_(std::move(overrides)),
        top_(std::move(top)), see_docs_(std::move(see_docs)) {}

  [[noreturn]] void Fail(const std::string& pointer, std::string problem, std::string fix) const {
    for (const Override& o : overrides_) {
      // The problem lies in what the override set, or in an object it changed.
      if (pointer.rfind(o.pointer, 0) == 0 || o.pointer.rfind(pointer + "/", 0) == 0) {
        throw io::InputError("--set " + o.text, 0, 0, std::move(problem), std::move(fix));
      }
    }
    const io::JsonLocation at = map_.Find(pointer);
    throw io::InputError(file_, at.line, at.column, std::move(problem), std::move(fix));
  }

  /// "/truth/backlash_rad" -> "truth.backlash_rad", as users think of it.
  std::string Dotted(const std::string& pointer) const {
    return io::DottedJsonPointer(pointer, top_);
  }

  static std::string Child(const std::string& pointer, const std::string& key) {
    return pointer + "/" + io::JsonPointerToken(key);
  }

  void Object(const json& value, const std::string& pointer, const std::vector<Key>& keys) const {
    if (auto p = io::CheckJsonObject(value, pointer, keys, top_, see_docs_)) {
      Fail(p->pointer, std::move(p->problem), std::move(p->fix));
    }
  }

  /// A number in [lower, upper].
  double Number(const json& value, const std::string& pointer, const char* unit, double lower,
                double upper) const {
    if (!value.is_number()) {
      Fail(pointer, Dotted(pointer) + " must be a number, found " + std::string(value.type_name()),
           std::string("write a number in ") + unit);
    }
    const double x = value.get<double>();
    if (!(x >= lower && x <= upper)) {
      Fail(pointer,
           Dotted(pointer) + " = " + value.dump() + " is outside [" + Text(lower) + ", " +
               Text(upper) + "] " + unit,
           "use a value in that range");
    }
    return x;
  }

  int Integer(const json& value, const std::string& pointer, int lower, int upper) const {
    if (!value.is_number_integer()) {
      Fail(pointer, Dotted(pointer) + " must be a whole number, found " + value.dump(),
           "write an integer");
    }
    return static_cast<int>(Number(value, pointer, "", lower, upper));
  }

  std::vector<double> Numbers(const json& value, const std::string& pointer, std::size_t size,
                              const char* unit, double lower, double upper) const {
    if (!value.is_array() || value.empty() || (size != 0 && value.size() != size)) {
      const std::string need = size == 0 ? "a non-empty array" : std::to_string(size) + " values";
      Fail(pointer, Dotted(pointer) + " must be " + need + ", found " + value.dump(),
           std::string("write it as [numbers in ") + unit + "]");
    }
    std::vector<double> out;
    for (std::size_t i = 0; i < value.size(); ++i) {
      out.push_back(Number(value[i], pointer + "/" + std::to_string(i), unit, lower, upper));
    }
    return out;
  }

  Eigen::Vector2d Pair(const json& value, const std::string& pointer, const char* unit,
                       double lower, double upper) const {
    const auto v = Numbers(value, pointer, 2, unit, lower, upper);
    return {v[0], v[1]};
  }

  std::string String(const json& value, const std::string& pointer) const {
    if (!value.is_string()) {
      Fail(pointer, Dotted(pointer) + " must be a string, found " + value.dump(),
           "write it in double quotes");
    }
    return value.get<std::string>();
  }

  static std::string Text(double x) { return json(x).dump(); }

 private:
  std::string file_;
  io::JsonSourceMap map_;
  std::vector<Override> overrides_;
  std::string top_;
  std::string see_docs_;
};

}  // namespace pliant::experiments::detail
