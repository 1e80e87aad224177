// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The evaluation suite's JSON reader: values and where they start, escapes, each kind of error
// with its line, column and message, and JsonField's typed reads and their messages.

#include "Json.h"

#include <thintool/core/Error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

namespace thintool::eval {
namespace {

using Kind = JsonValue::Kind;

// The message a read throws, or "(no error)".
template <typename Read>
std::string readError(Read read) {
  try {
    read();
  } catch (const Error& error) {
    return error.what();
  }
  return "(no error)";
}

// The message parseJson throws for text, or "(no error)".
std::string parseError(std::string_view text) {
  return readError([&] { parseJson(text, "t.json"); });
}

TEST(Json, EachKindWithItsLineAndColumn) {
  const JsonValue root = parseJson(
      "{\n"
      "  \"n\": null,\n"
      "  \"b\": [true, false],\n"
      "  \"x\": -12.5e1,\n"
      "  \"s\": \"text\",\n"
      "  \"o\": {\"\xC3\xA9\": 1}\n"
      "}\n",
      "t.json");
  ASSERT_EQ(root.kind, Kind::Object);
  EXPECT_EQ(root.line, 1);
  EXPECT_EQ(root.column, 1);
  ASSERT_EQ(root.members.size(), 5u);
  const char* keys[] = {"n", "b", "x", "s", "o"};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(root.members[i].first, keys[i]);  // file order
    EXPECT_EQ(root.members[i].second.line, i + 2);
    EXPECT_EQ(root.members[i].second.column, 8);
  }
  EXPECT_EQ(root.members[0].second.kind, Kind::Null);
  const JsonValue& b = root.members[1].second;
  ASSERT_EQ(b.kind, Kind::Array);
  ASSERT_EQ(b.items.size(), 2u);
  EXPECT_TRUE(b.items[0].boolean);
  EXPECT_EQ(b.items[0].kind, Kind::Boolean);
  EXPECT_EQ(b.items[0].column, 9);
  EXPECT_FALSE(b.items[1].boolean);
  EXPECT_EQ(b.items[1].kind, Kind::Boolean);
  EXPECT_EQ(b.items[1].column, 15);
  EXPECT_EQ(root.members[2].second.kind, Kind::Number);
  EXPECT_EQ(root.members[2].second.number, -125.0);
  EXPECT_EQ(root.members[3].second.kind, Kind::String);
  EXPECT_EQ(root.members[3].second.text, "text");
  const JsonValue& o = root.members[4].second;
  ASSERT_EQ(o.kind, Kind::Object);
  ASSERT_EQ(o.members.size(), 1u);
  EXPECT_EQ(o.members[0].first, "\xC3\xA9");
  // Columns count characters: the two-byte e acute is one column, so the 1 is at column 14.
  EXPECT_EQ(o.members[0].second.column, 14);
  EXPECT_EQ(o.members[0].second.line, 6);
}

TEST(Json, ScalarsAtTheRootAndNumberForms) {
  EXPECT_EQ(parseJson("  42 ", "t").number, 42.0);
  EXPECT_EQ(parseJson("  42 ", "t").column, 3);
  EXPECT_EQ(parseJson("0", "t").number, 0.0);
  EXPECT_TRUE(std::signbit(parseJson("-0", "t").number));
  EXPECT_EQ(parseJson("1E+2", "t").number, 100.0);
  EXPECT_EQ(parseJson("0.5e-3", "t").number, 0.0005);
  EXPECT_EQ(parseJson("1.7976931348623157e308", "t").number, 1.7976931348623157e308);
  // Too small for a double is not an error: it reads as zero, keeping the sign.
  EXPECT_EQ(parseJson("1e-400", "t").number, 0.0);
  EXPECT_EQ(parseJson("0.00001e-320", "t").number, 0.0);
  EXPECT_EQ(parseJson("12345e-330", "t").number, 0.0);
  EXPECT_TRUE(std::signbit(parseJson("-1e-400", "t").number));
  EXPECT_EQ(parseJson("false", "t").kind, Kind::Boolean);
  EXPECT_EQ(parseJson("null", "t").kind, Kind::Null);
  EXPECT_EQ(parseJson("\"\"", "t").kind, Kind::String);
  EXPECT_EQ(parseJson("[]", "t").kind, Kind::Array);
  EXPECT_EQ(parseJson("{}", "t").kind, Kind::Object);
  // A byte order mark is skipped and takes no column.
  const JsonValue bom = parseJson("\xEF\xBB\xBF[1]", "t");
  ASSERT_EQ(bom.items.size(), 1u);
  EXPECT_EQ(bom.items[0].column, 2);
}

TEST(Json, KindNames) {
  EXPECT_STREQ(kindName(Kind::Null), "null");
  EXPECT_STREQ(kindName(Kind::Boolean), "a boolean");
  EXPECT_STREQ(kindName(Kind::Number), "a number");
  EXPECT_STREQ(kindName(Kind::String), "a string");
  EXPECT_STREQ(kindName(Kind::Array), "an array");
  EXPECT_STREQ(kindName(Kind::Object), "an object");
}

TEST(Json, EscapesAndSurrogatePairsBecomeUtf8) {
  EXPECT_EQ(parseJson(R"("\"\\\/\b\f\n\r\t")", "t").text, "\"\\/\b\f\n\r\t");
  EXPECT_EQ(parseJson(R"("\u0041\u00e9\u20AC")", "t").text, "A\xC3\xA9\xE2\x82\xAC");
  EXPECT_EQ(parseJson(R"("\uD83D\uDE00")", "t").text, "\xF0\x9F\x98\x80");  // U+1F600
  EXPECT_EQ(parseJson(R"("\uDBFF\uDFFF")", "t").text, "\xF4\x8F\xBF\xBF");  // U+10FFFF
  EXPECT_EQ(parseJson(R"("a\u0000b")", "t").text, std::string("a\0b", 3));
  EXPECT_EQ(parseJson("\"\xE2\x82\xAC \xF0\x9F\x98\x80\"", "t").text, "\xE2\x82\xAC \xF0\x9F\x98\x80");
}

TEST(Json, TruncatedFile) {
  EXPECT_EQ(parseError("{\"a\": [1, 2"), "t.json:1:12: expected ',' or ']', found the end of the input");
  EXPECT_EQ(parseError("{\"a\": 1"), "t.json:1:8: expected ',' or '}', found the end of the input");
  EXPECT_EQ(parseError("{\"a\":\n"), "t.json:2:1: expected a value, found the end of the input");
  EXPECT_EQ(parseError("[\"abc"),
            "t.json:1:6: expected '\"' to close the string begun at 1:2, found the end of the input");
  EXPECT_EQ(parseError("["), "t.json:1:2: expected a value or ']', found the end of the input");
  EXPECT_EQ(parseError("\"\\u12"), "t.json:1:6: expected 4 hex digits after \\u, found the end of the input");
}

TEST(Json, TrailingComma) {
  EXPECT_EQ(parseError("[1, 2,]"), "t.json:1:7: expected a value after ',', found ']'");
  EXPECT_EQ(parseError("{\"a\": 1,\n}"), "t.json:2:1: expected a key in double quotes after ',', found '}'");
}

TEST(Json, MissingColonOrComma) {
  EXPECT_EQ(parseError("{\"speed\" 3}"), "t.json:1:10: expected ':' after the key \"speed\", found '3'");
  // CRLF line ends count as one line.
  EXPECT_EQ(parseError("{\r\n  \"a\" 1}"), "t.json:2:7: expected ':' after the key \"a\", found '1'");
  EXPECT_EQ(parseError("[1 2]"), "t.json:1:4: expected ',' or ']', found '2'");
  EXPECT_EQ(parseError("{\"a\": 1 \"b\": 2}"), "t.json:1:9: expected ',' or '}', found '\"'");
  EXPECT_EQ(parseError("{speed: 1}"), "t.json:1:2: expected a key in double quotes or '}', found 'speed'");
}

TEST(Json, DuplicateKey) {
  EXPECT_EQ(parseError("{\"a\": 1,\n \"b\": 2,\n \"a\": 3}"),
            "t.json:3:2: expected a key not already in this object, found \"a\" again (first at 1:2)");
  // The same key in different objects is fine.
  EXPECT_EQ(parseError("[{\"a\": 1}, {\"a\": 2}]"), "(no error)");
}

TEST(Json, BadEscapes) {
  EXPECT_EQ(parseError(R"("a\qb")"),
            R"(t.json:1:4: expected an escape (\" \\ \/ \b \f \n \r \t \uXXXX) after '\', found 'q')");
  EXPECT_EQ(parseError(R"("\u12G4")"), R"(t.json:1:6: expected 4 hex digits after \u, found 'G')");
  EXPECT_EQ(parseError(R"("\uDE00")"),
            R"(t.json:1:2: expected a high surrogate (\uD800-\uDBFF) before a low one, found \uDE00 alone)");
  EXPECT_EQ(parseError(R"("\uD83Dx")"),
            R"(t.json:1:8: expected a low surrogate (\uDC00-\uDFFF) after \uD83D, found 'x')");
  EXPECT_EQ(parseError(R"("\uD83D\u0041")"),
            R"(t.json:1:8: expected a low surrogate (\uDC00-\uDFFF) after \uD83D, found \u0041)");
}

TEST(Json, ControlCharactersAndBadUtf8InStrings) {
  EXPECT_EQ(parseError("\"a\tb\""),
            "t.json:1:3: expected a character or an escape in the string, found control character U+0009");
  EXPECT_EQ(parseError("[\"ab\n\"]"),
            "t.json:1:5: expected '\"' to close the string begun at 1:2, found the end of the line");
  EXPECT_EQ(parseError(std::string("\"a\0\"", 4)),
            "t.json:1:3: expected a character or an escape in the string, found control character U+0000");
  EXPECT_EQ(parseError("\"\xC3\x28\""),
            "t.json:1:2: expected a character or an escape in the string, found byte 0xC3, not valid UTF-8 here");
  EXPECT_EQ(parseError("\"\xED\xA0\x80\""),  // a UTF-16 surrogate written as UTF-8
            "t.json:1:2: expected a character or an escape in the string, found byte 0xED, not valid UTF-8 here");
  EXPECT_EQ(parseError("\xFF"), "t.json:1:1: expected a value, found byte 0xFF, not valid UTF-8 here");
}

TEST(Json, NestingDeeperThan64) {
  const std::string deepest = std::string(64, '[') + std::string(64, ']');
  EXPECT_EQ(parseError(deepest), "(no error)");
  const std::string tooDeep = std::string(65, '[') + std::string(65, ']');
  EXPECT_EQ(parseError(tooDeep),
            "t.json:1:65: expected arrays and objects nested at most 64 deep, found one nested deeper");
  std::string objects;
  for (int i = 0; i < 65; ++i) {
    objects += "{\"a\":";
  }
  EXPECT_EQ(parseError(objects),
            "t.json:1:321: expected arrays and objects nested at most 64 deep, found one nested deeper");
}

TEST(Json, NumbersOutsideADoublesRangeAndMalformedNumbers) {
  EXPECT_EQ(parseError("{\"x\": 1e999}"),
            "t.json:1:7: expected a number within a double's range (magnitude up to 1.8e308), found '1e999'");
  EXPECT_EQ(parseError("[-1.8e308]"),
            "t.json:1:2: expected a number within a double's range (magnitude up to 1.8e308), found '-1.8e308'");
  EXPECT_EQ(parseError("0.001e312"),
            "t.json:1:1: expected a number within a double's range (magnitude up to 1.8e308), found '0.001e312'");
  EXPECT_EQ(parseError("[01]"), "t.json:1:2: expected a number without leading zeros, found '01'");
  EXPECT_EQ(parseError("-"), "t.json:1:2: expected a digit after '-', found the end of the input");
  EXPECT_EQ(parseError("[-a]"), "t.json:1:3: expected a digit after '-', found 'a'");
  EXPECT_EQ(parseError("1."), "t.json:1:3: expected a digit after '.', found the end of the input");
  EXPECT_EQ(parseError("1e+]"), "t.json:1:4: expected a digit in the exponent, found ']'");
  EXPECT_EQ(parseError("[+1]"), "t.json:1:2: expected a value or ']', found '+1'");
  EXPECT_EQ(parseError("[.5]"), "t.json:1:2: expected a value or ']', found '.5'");
}

TEST(Json, TrailingContentAndMisspeltLiterals) {
  EXPECT_EQ(parseError("{} x"), "t.json:1:4: expected the end of the input after the value, found 'x'");
  EXPECT_EQ(parseError("1\n2"), "t.json:2:1: expected the end of the input after the value, found '2'");
  EXPECT_EQ(parseError("[1]]"), "t.json:1:4: expected the end of the input after the value, found ']'");
  EXPECT_EQ(parseError("[tru]"), "t.json:1:2: expected a value or ']', found 'tru'");
  EXPECT_EQ(parseError("truex"), "t.json:1:1: expected a value, found 'truex'");
  EXPECT_EQ(parseError("[True]"), "t.json:1:2: expected a value or ']', found 'True'");
  EXPECT_EQ(parseError("NaN"), "t.json:1:1: expected a value, found 'NaN'");
  EXPECT_EQ(parseError("[1, // note\n 2]"), "t.json:1:5: expected a value after ',', found '/'");
  // A NUL byte is not the end of the input.
  EXPECT_EQ(parseError(std::string("[1]\0", 4)),
            "t.json:1:4: expected the end of the input after the value, found control character U+0000");
  EXPECT_EQ(parseError(std::string("[1,\0 2]", 7)),
            "t.json:1:4: expected a value after ',', found control character U+0000");
}

TEST(Json, EmptyInput) {
  EXPECT_EQ(parseError(""), "t.json:1:1: expected a value, found the end of the input");
  EXPECT_EQ(parseError("  \n "), "t.json:2:2: expected a value, found the end of the input");
}

// Lines and columns of the values the JsonField tests read are noted on the right.
const char* const kScene =
    "{\n"                                                            // 1: root at 1:1
    "  \"name\": \"press\",\n"                                       // 2
    "  \"dt\": 0.001,\n"                                             // 3
    "  \"steps\": 300,\n"                                            // 4
    "  \"gravity\": [0, -9.81, 0],\n"                                // 5
    "  \"tools\": [\n"                                               // 6: tools at 6:12
    "    {\"kind\": \"box\", \"size\": [0.1, 0.002, 0.1]},\n"        // 7: tools[0] at 7:5
    "    {\"kind\": \"bx\",\n"                                       // 8: tools[1] at 8:5, kind at 8:14
    "     \"trajectory\": {\"speed\": \"fast\", \"dt\": 0.01},\n"    // 9: speed at 9:30
    "     \"count\": 1.5, \"big\": 1e10, \"small\": -1,\n"           // 10: 15, 27, 42
    "     \"flag\": 1, \"pair\": [1, 2], \"mixed\": [1, \"a\", 3]}\n"  // 11: 14, 25, 46
    "  ]\n"
    "}\n";

class JsonFieldTest : public ::testing::Test {
 protected:
  JsonValue document = parseJson(kScene, "scene.json");
  JsonField root{document, "", "scene.json"};
};

TEST_F(JsonFieldTest, TypedReads) {
  EXPECT_EQ(root.path(), "");
  EXPECT_EQ(&root.value(), &document);
  EXPECT_EQ(root.string("name", "none"), "press");
  EXPECT_EQ(root.string("title", "none"), "none");
  EXPECT_EQ(root.number("dt", 1.0), 0.001);
  EXPECT_EQ(root.number("missing", 2.5), 2.5);
  EXPECT_EQ(root.positive("dt", 1.0), 0.001);
  EXPECT_EQ(root.positive("missing", 3.0), 3.0);
  EXPECT_EQ(root.integer("steps", 0), 300);
  EXPECT_EQ(root.integer("missing", 7), 7);
  EXPECT_TRUE(root.boolean("missing", true));
  EXPECT_EQ(root.at("gravity").vec3(), (std::array<double, 3>{0, -9.81, 0}));
  EXPECT_TRUE(root.has("tools"));
  EXPECT_FALSE(root.has("tool"));
  EXPECT_FALSE(root.find("tool").has_value());
  const JsonField tools = root.at("tools");
  EXPECT_EQ(tools.path(), "tools");
  ASSERT_EQ(tools.size(), 2u);
  const JsonField kind = tools.at(std::size_t{0}).at("kind");
  EXPECT_EQ(kind.path(), "tools[0].kind");
  EXPECT_EQ(kind.oneOf({"box", "hull"}), "box");
  EXPECT_EQ(kind.string(), "box");
  const std::optional<JsonField> size = tools.at(std::size_t{0}).find("size");
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->path(), "tools[0].size");
  EXPECT_EQ(size->at(std::size_t{1}).path(), "tools[0].size[1]");
  EXPECT_EQ(size->at(std::size_t{1}).number(), 0.002);
  EXPECT_EQ(tools.at(std::size_t{1}).at("trajectory").number("dt", 0), 0.01);
  EXPECT_EQ(parseJson("[false]", "t").items[0].kind, Kind::Boolean);
  const JsonValue flags = parseJson("{\"on\": true, \"off\": false}", "t");
  EXPECT_TRUE(JsonField(flags, "", "t").boolean("on", false));
  EXPECT_FALSE(JsonField(flags, "", "t").at("off").boolean());
}

TEST_F(JsonFieldTest, ErrorsNameSourceLinePathAndWhatWasExpected) {
  const JsonField tools = root.at("tools");
  const JsonField second = tools.at(std::size_t{1});
  EXPECT_EQ(readError([&] { second.at("trajectory").at("speed").number(); }),
            "scene.json:9:30: tools[1].trajectory.speed: expected a number, found a string");
  EXPECT_EQ(readError([&] { tools.at(std::size_t{0}).at("speed"); }),
            "scene.json:7:5: tools[0]: missing field 'speed'");
  EXPECT_EQ(readError([&] { second.at("kind").oneOf({"box", "hull"}); }),
            "scene.json:8:14: tools[1].kind: expected one of \"box\", \"hull\", found \"bx\"");
  EXPECT_EQ(readError([&] { second.positive("small", 1.0); }),
            "scene.json:10:42: tools[1].small: expected a number > 0, found -1");
  EXPECT_EQ(readError([&] { second.boolean("flag", false); }),
            "scene.json:11:14: tools[1].flag: expected a boolean, found a number");
  EXPECT_EQ(readError([&] { second.string("flag", ""); }),
            "scene.json:11:14: tools[1].flag: expected a string, found a number");
  EXPECT_EQ(readError([&] { second.at("pair").vec3(); }),
            "scene.json:11:25: tools[1].pair: expected an array of 3 numbers, found 2 items");
  EXPECT_EQ(readError([&] { second.at("mixed").vec3(); }),
            "scene.json:11:46: tools[1].mixed[1]: expected a number, found a string");
  EXPECT_EQ(readError([&] { tools.at(std::size_t{2}); }), "scene.json:6:12: tools: expected at least 3 items, found 2");
  EXPECT_EQ(readError([&] { tools.has("kind"); }), "scene.json:6:12: tools: expected an object, found an array");
  EXPECT_EQ(readError([&] { root.expect(Kind::Array); }),
            "scene.json:1:1: (root): expected an array, found an object");
  EXPECT_EQ(readError([&] { root.size(); }), "scene.json:1:1: (root): expected an array, found an object");
  EXPECT_EQ(readError([&] { root.at("nothing"); }), "scene.json:1:1: (root): missing field 'nothing'");
  EXPECT_EQ(readError([&] { root.fail("steps and dt disagree"); }), "scene.json:1:1: (root): steps and dt disagree");
  const JsonValue list = parseJson("[[1]]", "list.json");
  EXPECT_EQ(readError([&] { JsonField(list, "", "list.json").at(std::size_t{0}).at(std::size_t{0}).string(); }),
            "list.json:1:3: [0][0]: expected a string, found a number");
}

TEST_F(JsonFieldTest, IntegerRejectsFractionsAndValuesBeyondInt) {
  const JsonField second = root.at("tools").at(std::size_t{1});
  EXPECT_EQ(readError([&] { second.integer("count", 0); }),
            "scene.json:10:15: tools[1].count: expected a whole number within int range, found 1.5");
  EXPECT_EQ(readError([&] { second.at("big").integer(); }),
            "scene.json:10:27: tools[1].big: expected a whole number within int range, found 1e+10");
  EXPECT_EQ(second.integer("small", 0), -1);
  const JsonValue limits = parseJson("[2147483647, -2147483648, 2147483648, 3.0]", "t");
  const JsonField field(limits, "limits", "t");
  EXPECT_EQ(field.at(std::size_t{0}).integer(), 2147483647);
  EXPECT_EQ(field.at(std::size_t{1}).integer(), -2147483647 - 1);
  EXPECT_EQ(readError([&] { field.at(std::size_t{2}).integer(); }),
            "t:1:27: limits[2]: expected a whole number within int range, found 2147483648");
  EXPECT_EQ(field.at(std::size_t{3}).integer(), 3);
}

TEST(JsonField, AllowOnlyCatchesATypo) {
  const JsonValue document = parseJson("{\"tool\": {\"speed\": 1,\n          \"sped\": 2}}", "t.json");
  const JsonField tool = JsonField(document, "", "t.json").at("tool");
  EXPECT_EQ(readError([&] { tool.allowOnly({"speed", "sped", "dt"}); }), "(no error)");
  EXPECT_EQ(readError([&] { tool.allowOnly({"speed", "dt", "mass"}); }),
            "t.json:2:19: tool: unknown field 'sped'; expected one of speed, dt, mass");
  EXPECT_EQ(readError([&] { JsonField(document, "", "t.json").allowOnly({"tools"}); }),
            "t.json:1:10: (root): unknown field 'tool'; expected one of tools");
}

TEST(JsonField, HandBuiltNonFiniteNumbersAreRefused) {
  JsonValue value;
  value.kind = Kind::Number;
  value.line = 4;
  value.column = 2;
  value.number = std::nan("");
  EXPECT_EQ(readError([&] { JsonField(value, "x", "t").number(); }), "t:4:2: x: expected a finite number, found nan");
}

TEST(JsonFile, LoadsAFileAndNamesItInErrors) {
  const std::string good = ::testing::TempDir() + "thintool_json_good.json";
  const std::string bad = ::testing::TempDir() + "thintool_json_bad.json";
  std::ofstream(good) << "{\"dt\": 0.002}\n";
  std::ofstream(bad) << "{\n  \"dt\": 0.002,\n}\n";
  const JsonValue value = loadJsonFile(good);
  EXPECT_EQ(JsonField(value, "", good).number("dt", 0), 0.002);
  EXPECT_EQ(readError([&] { loadJsonFile(bad); }),
            bad + ":3:1: expected a key in double quotes after ',', found '}'");
  std::remove(good.c_str());
  std::remove(bad.c_str());
  EXPECT_EQ(readError([&] { loadJsonFile(good); }), good + ": cannot read the file");
  EXPECT_EQ(readError([&] { loadJsonFile(::testing::TempDir()); }), ::testing::TempDir() + ": cannot read the file");
}

}  // namespace
}  // namespace thintool::eval
