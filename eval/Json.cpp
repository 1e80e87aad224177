// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The JSON reader of Json.h on RapidJSON's SAX reader (Debian's rapidjson-dev): its iterative
// parser checks the grammar and the UTF-8 without recursion, and the handler here builds the tree,
// keeps where each value starts and checks what RFC 8259 leaves to the reader. RapidJSON reports
// an error as a code and a byte offset; the message is written here as "expected ..., found ..."
// at a line and column, in the same words as JsonField's. Then JsonField's typed reads.

#include "Json.h"

#include <thintool/core/Error.h>

#include <rapidjson/error/en.h>
#include <rapidjson/memorystream.h>
#include <rapidjson/reader.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <system_error>
#include <optional>
#include <unordered_map>
#include <vector>

namespace thintool::eval {

namespace {

constexpr int kMaxDepth = 64;

struct Mark {
  std::size_t pos;
  int line, column;
};

std::string hex(unsigned value, int digits) {
  char text[16];
  std::snprintf(text, sizeof text, "%0*X", digits, value);
  return text;
}

std::string lineColumn(const Mark& mark) { return std::to_string(mark.line) + ":" + std::to_string(mark.column); }

bool isDigit(char c) { return c >= '0' && c <= '9'; }

// The characters of a stray word such as `tru` or `1e999`, shown whole in messages.
bool isWordChar(char c) {
  return isDigit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == '.' || c == '+' ||
         c == '-';
}

std::string formatNumber(double value) {
  char text[32];
  const std::to_chars_result result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

// The length of the UTF-8 sequence at text[pos], or 0 when it is not valid UTF-8: overlong forms,
// surrogates and code points beyond U+10FFFF are refused, as RFC 3629 asks.
std::size_t utf8Length(std::string_view text, std::size_t pos) {
  const auto lead = static_cast<unsigned char>(text[pos]);
  if (lead < 0x80) {
    return 1;
  }
  std::size_t length = 0;
  unsigned low = 0x80, high = 0xBF;  // the second byte's range
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    low = lead == 0xE0 ? 0xA0 : low;
    high = lead == 0xED ? 0x9F : high;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    low = lead == 0xF0 ? 0x90 : low;
    high = lead == 0xF4 ? 0x8F : high;
  } else {
    return 0;
  }
  if (text.size() - pos < length) {
    return 0;
  }
  for (std::size_t i = 1; i < length; ++i) {
    const auto byte = static_cast<unsigned char>(text[pos + i]);
    if (byte < (i == 1 ? low : 0x80) || byte > (i == 1 ? high : 0xBF)) {
      return 0;
    }
  }
  return length;
}
// from_chars reports a number outside a double's range the same way whether it is too large or
// too small; a too small one (1e-400) is valid JSON and reads as 0, so tell them apart by the
// decimal exponent of the first significant digit. number is well formed and not zero.
bool belowDoubleRange(std::string_view number) {
  std::size_t i = number[0] == '-' ? 1 : 0;
  const std::size_t integerStart = i;
  while (i < number.size() && isDigit(number[i])) {
    ++i;
  }
  long long lead = static_cast<long long>(i - integerStart) - 1;
  if (number[integerStart] == '0') {  // 0.000ddd: the first significant digit follows the zeros
    lead = -1;
    if (i < number.size() && number[i] == '.') {
      for (++i; i < number.size() && number[i] == '0'; ++i) {
        --lead;
      }
    }
  }
  while (i < number.size() && number[i] != 'e' && number[i] != 'E') {
    ++i;
  }
  long long exponent = 0;
  if (i < number.size()) {
    ++i;
    const bool negative = number[i] == '-';
    i += number[i] == '-' || number[i] == '+' ? 1 : 0;
    for (; i < number.size(); ++i) {
      exponent = std::min(exponent * 10 + (number[i] - '0'), 1'000'000'000'000LL);  // saturates
    }
    exponent = negative ? -exponent : exponent;
  }
  return lead + exponent < 0;
}

// What is at text[at], for "found ...". A word is shown whole (`tru`, `1e999`), unless a single
// character is what is wrong, as in a bad escape.
std::string describe(std::string_view text, std::size_t at, bool wholeWord) {
  if (at >= text.size()) {
    return "the end of the input";
  }
  const auto c = static_cast<unsigned char>(text[at]);
  if (c == '\n' || c == '\r') {
    return "the end of the line";
  }
  if (c < 0x20 || c == 0x7F) {
    return "control character U+" + hex(c, 4);
  }
  if (c >= 0x80) {
    const std::size_t length = utf8Length(text, at);
    return length == 0 ? "byte 0x" + hex(c, 2) + ", not valid UTF-8 here"
                       : "'" + std::string(text.substr(at, length)) + "'";
  }
  if (!wholeWord || !isWordChar(text[at])) {
    return std::string("'") + text[at] + "'";
  }
  std::size_t end = at;
  while (end < text.size() && end - at < 24 && isWordChar(text[end])) {
    ++end;
  }
  const bool cut = end < text.size() && isWordChar(text[end]);
  return "'" + std::string(text.substr(at, end - at)) + (cut ? "...'" : "'");
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Line and column of byte offsets that only grow while a document is read, so that one cursor
// walks the text once. Columns count characters, not bytes, to match an editor's for UTF-8 text.
class Locator {
 public:
  explicit Locator(std::string_view text) : text_(text) {}

  Mark at(std::size_t offset) {
    if (offset < cursor_.pos) {
      cursor_ = {0, 1, 1};
    }
    while (cursor_.pos < offset && cursor_.pos < text_.size()) {
      const char c = text_[cursor_.pos++];
      if (c == '\n') {
        ++cursor_.line;
        cursor_.column = 1;
      } else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
        ++cursor_.column;
      }
    }
    return cursor_;
  }

 private:
  std::string_view text_;
  Mark cursor_{0, 1, 1};
};

// Builds the JsonValue tree from RapidJSON's events, with where each value starts, and checks what
// RFC 8259 leaves to the reader: unique keys, a bounded depth, numbers within a double's range.
// Between two tokens JSON has only white space, ',' and ':', so a token starts at the first other
// byte after the previous one ends. The reader calls a scalar's or a key's handler with its token
// read, and a bracket's before it takes the bracket. A handler that returns false stops the
// reader, and `problem` says why.
class TreeBuilder : public rapidjson::BaseReaderHandler<rapidjson::UTF8<>, TreeBuilder> {
 public:
  TreeBuilder(std::string_view text, const rapidjson::MemoryStream& stream, Locator& locator)
      : text_(text), stream_(stream), locator_(locator) {}

  bool Null() {
    add(JsonValue::Kind::Null, tokenStart());
    return true;
  }
  bool Bool(bool value) {
    add(JsonValue::Kind::Boolean, tokenStart()).boolean = value;
    return true;
  }
  // Numbers come as written (kParseNumbersAsStringsFlag), so that -0 keeps its sign and one too
  // small for a double reads as 0.
  bool RawNumber(const char* spelled, rapidjson::SizeType length, bool) {
    const std::size_t start = tokenStart();
    double number = 0;
    const std::from_chars_result read = std::from_chars(spelled, spelled + length, number);
    const std::string_view text(spelled, length);
    if (read.ec == std::errc::result_out_of_range && belowDoubleRange(text)) {
      number = text[0] == '-' ? -0.0 : 0.0;
    } else if (read.ec != std::errc() || read.ptr != spelled + length || !std::isfinite(number)) {
      return stop(start, kNumberRange, describe(text_, start, true));
    }
    add(JsonValue::Kind::Number, start).number = number;
    return true;
  }
  bool String(const char* text, rapidjson::SizeType length, bool) {
    const std::size_t start = tokenStart();
    if (!validUtf8(std::string_view(text, length), start)) return false;
    add(JsonValue::Kind::String, start).text.assign(text, length);
    return true;
  }
  bool StartObject() { return open(JsonValue::Kind::Object); }
  bool Key(const char* text, rapidjson::SizeType length, bool) {
    const std::size_t start = tokenStart();
    std::string key(text, length);
    if (!validUtf8(key, start)) return false;
    const Mark mark = locator_.at(start);
    const auto [first, isNew] = keys_.back().emplace(key, mark);
    if (!isNew) {
      return stop(start, "expected a key not already in this object",
                  jsonQuoted(key) + " again (first at " + lineColumn(first->second) + ")");
    }
    key_ = std::move(key);
    ended();
    return true;
  }
  bool EndObject(rapidjson::SizeType) { return close(); }
  bool StartArray() { return open(JsonValue::Kind::Array); }
  bool EndArray(rapidjson::SizeType) { return close(); }

  JsonValue& root() { return root_; }
  std::size_t nextTokenStart() const { return tokenStart(); }
  const std::string& key() const { return key_; }
  // Set when a handler stopped the reader: where, what was expected and what was found.
  struct Problem {
    std::size_t offset = 0;
    std::string expected, found;
  };
  const std::optional<Problem>& problem() const { return problem_; }

  static constexpr const char* kNumberRange = "expected a number within a double's range (magnitude up to 1.8e308)";
  static constexpr const char* kLoneLow = "expected a high surrogate (\\uD800-\\uDBFF) before a low one";

 private:
  std::size_t tokenStart() const {
    std::size_t at = scanFrom_;
    while (at < text_.size() && (isSpace(text_[at]) || text_[at] == ',' || text_[at] == ':')) ++at;
    return at;
  }
  void ended() { scanFrom_ = stream_.Tell(); }

  bool stop(std::size_t offset, std::string expected, std::string found) {
    problem_ = Problem{offset, std::move(expected), std::move(found)};
    return false;
  }

  // RapidJSON pairs a high surrogate's \u escape with the low one that must follow, but lets a
  // lone low one through as bytes that are not UTF-8, which the file's own bytes cannot be
  // (kParseValidateEncodingFlag). The escape is found in the string as written, from its quote.
  bool validUtf8(std::string_view decoded, std::size_t start) {
    for (std::size_t i = 0; i < decoded.size();) {
      const std::size_t length = utf8Length(decoded, i);
      if (length == 0) {
        const auto [at, escape] = loneSurrogate(start);
        return stop(at, kLoneLow, escape + " alone");
      }
      i += length;
    }
    return true;
  }
  // Where the string opened at quote has its lone low surrogate, and the escape as \uXXXX.
  std::pair<std::size_t, std::string> loneSurrogate(std::size_t quote) const {
    for (std::size_t i = quote + 1; i + 6 <= text_.size() && text_[i] != '"';) {
      if (text_[i] != '\\') {
        ++i;
        continue;
      }
      if (text_[i + 1] != 'u') {
        i += 2;
        continue;
      }
      const unsigned long code = std::strtoul(std::string(text_.substr(i + 2, 4)).c_str(), nullptr, 16);
      if (code >= 0xDC00 && code <= 0xDFFF) return {i, "\\u" + hex(static_cast<unsigned>(code), 4)};
      i += code >= 0xD800 && code <= 0xDBFF ? 12 : 6;
    }
    return {quote, "a \\u escape"};
  }

  JsonValue& add(JsonValue::Kind kind, std::size_t start) {
    JsonValue* value = &root_;
    if (!open_.empty()) {
      JsonValue& parent = *open_.back();
      if (parent.kind == JsonValue::Kind::Array) {
        value = &parent.items.emplace_back();
      } else {
        value = &parent.members.emplace_back(std::move(key_), JsonValue{}).second;
      }
    }
    const Mark mark = locator_.at(start);
    value->kind = kind;
    value->line = mark.line;
    value->column = mark.column;
    ended();
    return *value;
  }

  bool open(JsonValue::Kind kind) {
    const std::size_t start = tokenStart();
    if (open_.size() >= static_cast<std::size_t>(kMaxDepth)) {
      return stop(start, "expected arrays and objects nested at most " + std::to_string(kMaxDepth) + " deep",
                  "one nested deeper");
    }
    // A value's parent never gains another item while the value is open, so the pointers stay valid.
    open_.push_back(&add(kind, start));
    if (kind == JsonValue::Kind::Object) keys_.emplace_back();
    scanFrom_ = start + 1;
    return true;
  }
  bool close() {
    if (open_.back()->kind == JsonValue::Kind::Object) keys_.pop_back();
    open_.pop_back();
    scanFrom_ = stream_.Tell() + 1;
    return true;
  }

  std::string_view text_;
  const rapidjson::MemoryStream& stream_;
  Locator& locator_;
  JsonValue root_;
  std::vector<JsonValue*> open_;
  std::vector<std::unordered_map<std::string, Mark>> keys_;  // per open object: where each key was first written
  std::string key_;  // the key of the member whose value comes next
  std::size_t scanFrom_ = 0;
  std::optional<Problem> problem_;
};

// The last byte before offset that is not white space, or '\0' at the start.
char previousToken(std::string_view text, std::size_t offset) {
  while (offset > 0 && isSpace(text[offset - 1])) --offset;
  return offset > 0 ? text[offset - 1] : '\0';
}

// What was expected where RapidJSON stopped, in the words of the rest of this reader; RapidJSON's
// offsets point at the byte that broke the grammar, or at the backslash of a bad escape.
[[noreturn]] void failParse(std::string_view text, const std::string& source, Locator& locator,
                            rapidjson::ParseErrorCode code, std::size_t offset, const TreeBuilder& builder) {
  std::string expected;
  bool wholeWord = true;
  // A misspelt literal stops RapidJSON where it goes wrong (`tru]` at the bracket) or, when it
  // begins with one (`truex`), at what follows: shown whole, from its start, as a value.
  const std::size_t tokenStart = builder.nextTokenStart();
  const bool leadingZero = offset >= 1 && offset < text.size() && isDigit(text[offset]) && text[offset - 1] == '0' &&
                           (offset == 1 || !(isDigit(text[offset - 2]) || text[offset - 2] == '.'));
  if (code == rapidjson::kParseErrorValueInvalid && tokenStart < offset && tokenStart < text.size() &&
      std::isalpha(static_cast<unsigned char>(text[tokenStart]))) {
    offset = tokenStart;
  } else if (code != rapidjson::kParseErrorValueInvalid && !leadingZero && offset > 0 && offset < text.size() &&
             isWordChar(text[offset]) && isWordChar(text[offset - 1])) {
    while (offset > 0 && isWordChar(text[offset - 1])) --offset;
    code = rapidjson::kParseErrorValueInvalid;
  }
  const char before = previousToken(text, offset);
  switch (code) {
    case rapidjson::kParseErrorTermination:
      if (builder.problem().has_value()) {
        const TreeBuilder::Problem& problem = *builder.problem();
        throw Error(source + ":" + lineColumn(locator.at(problem.offset)) + ": " + problem.expected + ", found " +
                    problem.found);
      }
      expected = "expected valid JSON";
      break;
    case rapidjson::kParseErrorDocumentEmpty:
      expected = "expected a value";
      break;
    case rapidjson::kParseErrorValueInvalid:
      if (offset > 0 && text[offset - 1] == '-') {
        expected = "expected a digit after '-'";
        wholeWord = false;
      } else {
        expected = before == '['   ? "expected a value or ']'"
                   : before == ',' ? "expected a value after ','"
                                   : "expected a value";
      }
      break;
    case rapidjson::kParseErrorObjectMissName:
      expected = before == ',' ? "expected a key in double quotes after ','" : "expected a key in double quotes or '}'";
      break;
    case rapidjson::kParseErrorObjectMissColon:
      expected = "expected ':' after the key " + jsonQuoted(builder.key());
      break;
    case rapidjson::kParseErrorObjectMissCommaOrCurlyBracket:
    case rapidjson::kParseErrorArrayMissCommaOrSquareBracket:
    case rapidjson::kParseErrorDocumentRootNotSingular:
      if (leadingZero) {
        // RapidJSON reads a leading zero as the whole number: "01" stops at the 1.
        const std::size_t start = offset >= 2 && text[offset - 2] == '-' ? offset - 2 : offset - 1;
        throw Error(source + ":" + lineColumn(locator.at(start)) + ": expected a number without leading zeros, found " +
                    describe(text, start, true));
      }
      if (code == rapidjson::kParseErrorObjectMissCommaOrCurlyBracket) {
        expected = "expected ',' or '}'";
      } else if (code == rapidjson::kParseErrorArrayMissCommaOrSquareBracket) {
        expected = "expected ',' or ']'";
      } else {
        expected = "expected the end of the input after the value";
      }
      break;
    case rapidjson::kParseErrorStringMissQuotationMark:
    case rapidjson::kParseErrorStringInvalidEncoding: {
      const char c = offset < text.size() ? text[offset] : '\n';
      expected = c == '\n' || c == '\r'
                     ? "expected '\"' to close the string begun at " + lineColumn(locator.at(builder.nextTokenStart()))
                     : "expected a character or an escape in the string";
      wholeWord = false;
      break;
    }
    case rapidjson::kParseErrorStringEscapeInvalid:
      // At the backslash of a bad escape, or at a control character written as it is.
      wholeWord = false;
      if (offset < text.size() && text[offset] == '\\') {
        expected = "expected an escape (\\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX) after '\\'";
        offset += 1;
      } else if (offset < text.size() && (text[offset] == '\n' || text[offset] == '\r')) {
        expected = "expected '\"' to close the string begun at " + lineColumn(locator.at(builder.nextTokenStart()));
      } else {
        expected = "expected a character or an escape in the string";
      }
      break;
    case rapidjson::kParseErrorStringUnicodeEscapeInvalidHex: {
      // At the backslash: the culprit is the first of the four that is not a hex digit.
      std::size_t at = offset;
      for (std::size_t i = offset; i + 1 < text.size() && i < offset + 12; ++i) {
        if (text[i] == '\\' && text[i + 1] == 'u') {
          at = i + 2;
          while (at < text.size() && at < i + 6 && std::isxdigit(static_cast<unsigned char>(text[at]))) ++at;
          if (at < i + 6) break;
        }
      }
      offset = at;
      expected = "expected 4 hex digits after \\u";
      wholeWord = false;
      break;
    }
    case rapidjson::kParseErrorStringUnicodeSurrogateInvalid: {
      // At the high surrogate's backslash; what follows it is wrong.
      expected = "expected a low surrogate (\\uDC00-\\uDFFF) after " + std::string(text.substr(offset, 6));
      offset = std::min(offset + 6, text.size());
      if (text.compare(offset, 2, "\\u") == 0) {
        throw Error(source + ":" + lineColumn(locator.at(offset)) + ": " + expected + ", found " +
                    std::string(text.substr(offset, 6)));
      }
      wholeWord = false;
      break;
    }
    case rapidjson::kParseErrorNumberTooBig:
      expected = TreeBuilder::kNumberRange;
      break;
    case rapidjson::kParseErrorNumberMissFraction:
      expected = "expected a digit after '.'";
      wholeWord = false;
      break;
    case rapidjson::kParseErrorNumberMissExponent:
      expected = "expected a digit in the exponent";
      wholeWord = false;
      break;
    default:
      expected = std::string("expected valid JSON (") + rapidjson::GetParseError_En(code) + ")";
      break;
  }
  throw Error(source + ":" + lineColumn(locator.at(offset)) + ": " + expected + ", found " +
              describe(text, offset, wholeWord));
}

std::string memberPath(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

}  // namespace

const char* kindName(JsonValue::Kind kind) {
  switch (kind) {
    case JsonValue::Kind::Null:
      return "null";
    case JsonValue::Kind::Boolean:
      return "a boolean";
    case JsonValue::Kind::Number:
      return "a number";
    case JsonValue::Kind::String:
      return "a string";
    case JsonValue::Kind::Array:
      return "an array";
    case JsonValue::Kind::Object:
      return "an object";
  }
  return "an unknown kind";
}

std::string jsonQuoted(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += "\\u" + hex(static_cast<unsigned char>(c), 4);
    } else {
      out += c;
    }
  }
  return out + '"';
}

JsonValue parseJson(std::string_view text, const std::string& sourceName) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") {
    text.remove_prefix(3);  // a byte order mark, as some editors write: not a column
  }
  constexpr unsigned kFlags = rapidjson::kParseValidateEncodingFlag | rapidjson::kParseIterativeFlag |
                              rapidjson::kParseNumbersAsStringsFlag;
  rapidjson::MemoryStream stream(text.data(), text.size());
  Locator locator(text);
  TreeBuilder builder(text, stream, locator);
  rapidjson::Reader reader;
  const rapidjson::ParseResult result = reader.Parse<kFlags>(stream, builder);
  if (result.IsError()) {
    failParse(text, sourceName, locator, result.Code(), result.Offset(), builder);
  }
  // RapidJSON's streams end at a NUL byte: what follows one was never read.
  std::size_t end = stream.Tell();
  while (end < text.size() && isSpace(text[end])) ++end;
  if (end < text.size()) {
    throw Error(sourceName + ":" + lineColumn(locator.at(end)) +
                ": expected the end of the input after the value, found " + describe(text, end, true));
  }
  return std::move(builder.root());
}

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string text;
  char buffer[4096];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
  }
  if (!in.eof()) {  // not opened, or a read failed (a directory, an I/O error)
    throw Error(path + ": cannot read the file");
  }
  return text;
}

JsonValue loadJsonFile(const std::string& path) { return parseJson(readTextFile(path), path); }

JsonField::JsonField(const JsonValue& value, std::string path, std::string source)
    : value_(&value), path_(std::move(path)), source_(std::move(source)) {}

const JsonValue& JsonField::value() const { return *value_; }

const std::string& JsonField::path() const { return path_; }

void JsonField::fail(const std::string& what) const {
  throw Error(source_ + ":" + std::to_string(value_->line) + ":" + std::to_string(value_->column) + ": " +
              (path_.empty() ? "(root)" : path_) + ": " + what);
}

void JsonField::expect(JsonValue::Kind kind) const {
  if (value_->kind != kind) {
    fail(std::string("expected ") + kindName(kind) + ", found " + kindName(value_->kind));
  }
}

bool JsonField::has(std::string_view key) const { return find(key).has_value(); }

std::optional<JsonField> JsonField::find(std::string_view key) const {
  expect(JsonValue::Kind::Object);
  for (const auto& [name, member] : value_->members) {
    if (name == key) {
      return JsonField(member, memberPath(path_, key), source_);
    }
  }
  return std::nullopt;
}

JsonField JsonField::at(std::string_view key) const {
  std::optional<JsonField> member = find(key);
  if (!member) {
    fail("missing field '" + std::string(key) + "'");
  }
  return *member;
}

std::size_t JsonField::size() const {
  expect(JsonValue::Kind::Array);
  return value_->items.size();
}

JsonField JsonField::at(std::size_t index) const {
  if (index >= size()) {
    fail("expected at least " + std::to_string(index + 1) + " items, found " + std::to_string(size()));
  }
  return JsonField(value_->items[index], path_ + "[" + std::to_string(index) + "]", source_);
}

double JsonField::number() const {
  expect(JsonValue::Kind::Number);
  if (!std::isfinite(value_->number)) {  // only a hand-built value can hold one
    fail("expected a finite number, found " + formatNumber(value_->number));
  }
  return value_->number;
}

double JsonField::number(std::string_view key, double fallback) const {
  const std::optional<JsonField> member = find(key);
  return member ? member->number() : fallback;
}

double JsonField::positive(std::string_view key, double fallback) const {
  const std::optional<JsonField> member = find(key);
  if (!member) {
    return fallback;
  }
  const double value = member->number();
  if (!(value > 0)) {
    member->fail("expected a number > 0, found " + formatNumber(value));
  }
  return value;
}

int JsonField::integer() const {
  const double value = number();
  if (value != std::floor(value) || value < INT_MIN || value > INT_MAX) {
    fail("expected a whole number within int range, found " + formatNumber(value));
  }
  return static_cast<int>(value);
}

int JsonField::integer(std::string_view key, int fallback) const {
  const std::optional<JsonField> member = find(key);
  return member ? member->integer() : fallback;
}

bool JsonField::boolean() const {
  expect(JsonValue::Kind::Boolean);
  return value_->boolean;
}

bool JsonField::boolean(std::string_view key, bool fallback) const {
  const std::optional<JsonField> member = find(key);
  return member ? member->boolean() : fallback;
}

std::string JsonField::string() const {
  expect(JsonValue::Kind::String);
  return value_->text;
}

std::string JsonField::string(std::string_view key, const std::string& fallback) const {
  const std::optional<JsonField> member = find(key);
  return member ? member->string() : fallback;
}

std::string JsonField::oneOf(std::initializer_list<std::string_view> choices) const {
  std::string text = string();
  std::string listed;
  for (const std::string_view choice : choices) {
    if (text == choice) {
      return text;
    }
    listed += (listed.empty() ? "" : ", ") + jsonQuoted(choice);
  }
  fail("expected one of " + listed + ", found " + jsonQuoted(text));
}

std::array<double, 3> JsonField::vec3() const {
  if (size() != 3) {
    fail("expected an array of 3 numbers, found " + std::to_string(size()) + " items");
  }
  return {at(std::size_t{0}).number(), at(std::size_t{1}).number(), at(std::size_t{2}).number()};
}

void JsonField::allowOnly(std::initializer_list<std::string_view> keys) const {
  expect(JsonValue::Kind::Object);
  for (const auto& [name, member] : value_->members) {
    if (std::find(keys.begin(), keys.end(), name) == keys.end()) {
      std::string listed;
      for (const std::string_view key : keys) {
        listed += (listed.empty() ? "" : ", ") + std::string(key);
      }
      // At the member's value, whose line is the typo's, but named by this object's path.
      JsonField(member, path_, source_).fail("unknown field '" + name + "'; expected one of " + listed);
    }
  }
}

}  // namespace thintool::eval
