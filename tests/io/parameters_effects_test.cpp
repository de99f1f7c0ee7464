// The parameters file's "effects": read, written back, and refused with the
// line of the bad value.
#include <gtest/gtest.h>

#include "pliant/io/input_error.h"
#include "pliant/io/parameters_json.h"
#include "pliant/models/paper_parameters.h"
#include "temp_directory.h"

namespace pliant::io {
namespace {

TEST(ParametersEffects, RoundTripKeepsNamesValuesAndSd) {
  auto parameters = models::PaperParameters();
  parameters.effects = {{"held_friction",
                         {"held_friction1", "held_friction2", "presliding_travel"},
                         {0.0919, 0.1237, 0.002},
                         {0.0025, 0.0022, 0.0}}};
  const auto text = ParametersToJson(parameters).dump(2);
  const auto back = ParseParameters(text, "p.json");
  ASSERT_EQ(back.effects.size(), 1u);
  EXPECT_EQ(back.effects[0].name, "held_friction");
  EXPECT_EQ(back.effects[0].parameter_names, parameters.effects[0].parameter_names);
  EXPECT_EQ(back.effects[0].values, parameters.effects[0].values);
  EXPECT_EQ(back.effects[0].sd, parameters.effects[0].sd);
}

TEST(ParametersEffects, AValueThatIsNotANumberNamesItsLine) {
  auto json = ParametersToJson(models::PaperParameters());
  json["effects"] = {{"held_friction", {{"held_friction1", {{"value", "high"}}}}}};
  try {
    ParseParameters(json.dump(2), "p.json");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("effects.held_friction.held_friction1.value must be a number"),
              std::string::npos)
        << e.what();
    EXPECT_GT(e.line(), 1u);
  }
}

}  // namespace
}  // namespace pliant::io
