#include "pliant/io/json_location.h"

#include <gtest/gtest.h>

namespace pliant::io {
namespace {

const std::string kText =
    "{\n"
    "  \"a\": {\"b\": [10, {\"c\": true}],\n"
    "         \"x/y~z\": \"s\\\"}\"},\n"
    "  \"n\": 1,\n"
    "  \"n\": 2\n"
    "}\n";

void ExpectAt(const JsonSourceMap& map, const std::string& pointer, std::size_t line,
              std::size_t column) {
  const JsonLocation at = map.Find(pointer);
  EXPECT_EQ(at.line, line) << pointer;
  EXPECT_EQ(at.column, column) << pointer;
}

TEST(JsonSourceMap, FindsKeysAndArrayElements) {
  const JsonSourceMap map(kText);
  ExpectAt(map, "", 1, 1);
  ExpectAt(map, "/a", 2, 3);
  ExpectAt(map, "/a/b", 2, 9);
  ExpectAt(map, "/a/b/0", 2, 15);
  ExpectAt(map, "/a/b/1", 2, 19);
  ExpectAt(map, "/a/b/1/c", 2, 20);
  // Escaped pointer tokens; the string value holds an escaped quote and a brace.
  ExpectAt(map, "/a/" + JsonPointerToken("x/y~z"), 3, 10);
  EXPECT_EQ(JsonPointerToken("x/y~z"), "x~1y~0z");
}

TEST(JsonSourceMap, FallsBackToTheNearestAncestor) {
  const JsonSourceMap map(kText);
  ExpectAt(map, "/a/b/7", 2, 9);
  ExpectAt(map, "/a/missing/deeper", 2, 3);
  ExpectAt(map, "/nothing", 1, 1);
}

TEST(JsonSourceMap, ReportsTheSecondOccurrenceOfADuplicateKey) {
  const JsonSourceMap map(kText);
  EXPECT_EQ(map.DuplicateKey(), "/n");
  ExpectAt(map, "/n", 5, 3);
  EXPECT_EQ(JsonSourceMap("{\"a\": 1, \"b\": {\"a\": 2}}").DuplicateKey(), "");
}

TEST(JsonSourceMap, MapsMalformedTextAsFarAsItGoes) {
  const JsonSourceMap map("{\n  \"a\": 1,\n  \"b\" 2,\n  \"c\": 3\n}");
  ExpectAt(map, "/a", 2, 3);
  ExpectAt(map, "/b", 3, 3);
  ExpectAt(map, "/c", 1, 1);  // after the error: unknown, so the document
}

TEST(JsonSourceMap, LocationOfByteOffset) {
  const std::string text = "ab\ncd\n\nef";
  const JsonLocation first = JsonLocationOfOffset(text, 0);
  EXPECT_EQ(first.line, 1u);
  EXPECT_EQ(first.column, 1u);
  const JsonLocation d = JsonLocationOfOffset(text, 4);
  EXPECT_EQ(d.line, 2u);
  EXPECT_EQ(d.column, 2u);
  const JsonLocation end = JsonLocationOfOffset(text, 99);  // clamped to the end
  EXPECT_EQ(end.line, 4u);
  EXPECT_EQ(end.column, 3u);
}

}  // namespace
}  // namespace pliant::io
