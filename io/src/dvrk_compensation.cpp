// Reading and writing the dVRK's compensation parameter file (dvrk_compensation.h).
#include "pliant/io/dvrk_compensation.h"

#include <cmath>
#include <set>
#include <utility>

#include "json_locator.h"
#include "number_text.h"
#include "pliant/io/input_error.h"
#include "pliant/io/json_input.h"
#include "pliant/io/parameters_json.h"

namespace pliant::io {
namespace {

using nlohmann::json;

// The six entries, in the file's order: [joint][kind].
constexpr const char* kEntryNames[2][3] = {
    {"compliance_first", "torque_offset_first", "backlash_first"},
    {"compliance_second", "torque_offset_second", "backlash_second"}};
constexpr const char* kValueKeys[4] = {"value-a", "value-b", "value-c", "value-d"};
const char kSeeDocs[] = " (docs/parameters.md, 'The dVRK's compensation file')";

// jsoncpp, which the dVRK uses, accepts C and C++ comments; nlohmann is told to
// see none. Each comment becomes spaces (newlines kept), so lines and columns
// of what follows stay those of the file.
std::string BlankComments(const std::string& text) {
  std::string out = text;
  bool in_string = false;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const char c = out[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '/' && i + 1 < out.size() && (out[i + 1] == '*' || out[i + 1] == '/')) {
      const bool block = out[i + 1] == '*';
      std::size_t end = block ? out.find("*/", i + 2) : out.find('\n', i);
      end = end == std::string::npos ? out.size() : end + (block ? 2 : 0);
      for (std::size_t k = i; k < end; ++k) out[k] = out[k] == '\n' ? '\n' : ' ';
      i = end - 1;
    }
  }
  return out;
}

class Reader {
 public:
  Reader(const std::string& text, const std::string& file) : file_(file), locator_(text) {}

  [[noreturn]] void Fail(const std::string& pointer, std::string problem, std::string fix) const {
    const detail::JsonPosition at = locator_.Find(pointer);
    throw InputError(file_, at.line, at.column, std::move(problem), std::move(fix));
  }

  double Number(const json& entry, const std::string& pointer, const char* key,
                const std::string& name) const {
    const json& value = entry.at(key);
    const std::string at = pointer + "/" + key;
    if (!value.is_number()) {
      Fail(at, name + " " + key + " must be a number, found " + value.type_name(),
           "write a plain number");
    }
    return value.get<double>();
  }

  // One entry: which it is, and its four numbers (absent ones 0; "value" is
  // the group's spelling of value-a in backlash_second).
  std::pair<std::string, std::array<double, 4>> Entry(const json& entry,
                                                       const std::string& pointer) const {
    if (auto p = CheckJsonObject(entry, pointer,
                                 {{"parameter", true}, {"value", false}, {"value-a", false},
                                  {"value-b", false}, {"value-c", false}, {"value-d", false}},
                                 "the top-level object", kSeeDocs)) {
      Fail(p->pointer, std::move(p->problem), std::move(p->fix));
    }
    if (!entry.at("parameter").is_string()) {
      Fail(pointer + "/parameter", "\"parameter\" must be a string, found " +
                                       std::string(entry.at("parameter").type_name()),
           "write one of compliance_first, torque_offset_first, backlash_first, and the same "
           "with _second");
    }
    const std::string name = entry.at("parameter").get<std::string>();
    bool known = false;
    for (const auto& joint : kEntryNames)
      for (const char* entry_name : joint) known = known || name == entry_name;
    if (!known) {
      Fail(pointer + "/parameter", "unknown parameter '" + name + "'",
           "use compliance_first, torque_offset_first, backlash_first, or the same with _second");
    }
    const bool compliance = name.rfind("compliance", 0) == 0;
    if (entry.contains("value") && entry.contains("value-a")) {
      Fail(pointer + "/value", name + " has both \"value\" and \"value-a\"",
           "keep value-a (the key mtsPSMCompensation reads)");
    }
    if (!entry.contains("value") && !entry.contains("value-a")) {
      Fail(pointer, name + " has no \"value-a\"", "add \"value-a\"" + std::string(kSeeDocs));
    }
    std::array<double, 4> values{};
    values[0] = Number(entry, pointer, entry.contains("value") ? "value" : "value-a", name);
    for (int k = 1; k < 4; ++k) {
      if (entry.contains(kValueKeys[k])) {
        values[k] = Number(entry, pointer, kValueKeys[k], name);
      } else if (compliance) {
        Fail(pointer, name + " has no \"" + kValueKeys[k] + "\"",
             "give all four coefficients a, b, c, d of K(L) = a·L³ + b·L² + c·L + d");
      }
    }
    return {name, values};
  }

 private:
  const std::string& file_;
  detail::JsonLocator locator_;
};

}  // namespace

bool LooksLikeDvrkCompensation(const std::string& text) {
  const json document = json::parse(BlankComments(text), nullptr, false);
  return document.is_object() && document.contains("parameters") &&
         document.at("parameters").is_array() && !document.contains("format");
}

DvrkCompensation ParseDvrkCompensation(const std::string& text, const std::string& file) {
  const std::string blanked = BlankComments(text);
  const json document = ParseJsonInput(blanked, file);
  const Reader reader(blanked, file);
  if (auto p = CheckJsonObject(document, "", {{"parameters", true}}, "the top-level object",
                               kSeeDocs)) {
    reader.Fail(p->pointer, std::move(p->problem), std::move(p->fix));
  }
  const json& entries = document.at("parameters");
  if (!entries.is_array()) {
    reader.Fail("/parameters", "\"parameters\" must be an array, found " +
                                   std::string(entries.type_name()),
                "write it as [ {\"parameter\": \"compliance_first\", …}, … ]");
  }
  DvrkCompensation out;
  std::set<std::string> seen;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const std::string pointer = "/parameters/" + std::to_string(i);
    const auto [name, values] = reader.Entry(entries[i], pointer);
    int joint = -1, kind = -1;
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 3; ++k)
        if (name == kEntryNames[j][k]) joint = j, kind = k;
    if (!seen.insert(name).second) {
      reader.Fail(pointer, "parameter '" + name + "' is given twice",
                  "keep only one (the dVRK uses the last)");
    }
    if (kind == 0) out.compliance[joint] = values;
    if (kind == 1) out.torque_offset[joint] = values;
    if (kind == 2) out.backlash_rad[joint] = values[0];
  }
  for (const auto& joint : kEntryNames) {
    for (const char* name : joint) {
      if (seen.count(name) == 0) {
        reader.Fail("/parameters", std::string("no entry for '") + name + "'",
                    std::string("add {\"parameter\": \"") + name + "\", \"value-a\": …}" + kSeeDocs);
      }
    }
  }
  return out;
}

std::string DvrkCompensationText(const DvrkCompensation& compensation) {
  std::string out =
      "/* mtsPSMCompensation parameters (sawIntuitiveResearchKit), written by pliant params */\n"
      "{\n    \"parameters\":\n    [\n";
  for (int joint = 0; joint < 2; ++joint) {
    const std::array<double, 4> backlash = {compensation.backlash_rad[joint], 0.0, 0.0, 0.0};
    const std::array<double, 4>* values[3] = {&compensation.compliance[joint],
                                              &compensation.torque_offset[joint], &backlash};
    for (int kind = 0; kind < 3; ++kind) {
      out += (joint + kind == 0 ? "" : "        ,\n");
      out += "        {\n            \"parameter\": \"" + std::string(kEntryNames[joint][kind]) +
             "\"";
      for (int k = 0; k < 4; ++k) {
        out += ",\n            \"" + std::string(kValueKeys[k]) + "\": ";
        detail::AppendNumber(out, (*values[kind])[k]);
      }
      out += "\n        }\n";
    }
  }
  return out + "    ]\n}\n";
}

models::ModelParameters ReadAnyParameters(const std::string& path, bool* dvrk) {
  const std::string text = ReadParametersText(path);
  *dvrk = LooksLikeDvrkCompensation(text);
  return *dvrk ? DvrkToParameters(ParseDvrkCompensation(text, path), path)
               : ParseParameters(text, path);
}

double DvrkTorqueOffset(const DvrkCompensation& compensation, int joint, double depth_m) {
  const auto& v = compensation.torque_offset[joint];
  return joint == 0 ? v[0] : v[0] * depth_m + v[1];
}

}  // namespace pliant::io
