// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The JSON reader of Json.h: a recursive-descent parser (the depth is capped, so the recursion is
// bounded) that keeps the line and column as it goes, so that every value carries where it
// started and every error says where it happened, and JsonField's typed reads.

#include "Json.h"

#include <thintool/core/Error.h>

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <system_error>
#include <unordered_map>

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

void appendUtf8(std::string& out, std::uint32_t code) {
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
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

class Parser {
 public:
  Parser(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  JsonValue document() {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") {
      pos_ = 3;  // a byte order mark, as some editors write: not a column
    }
    JsonValue root = value("expected a value", 0);
    skipSpace();
    if (!atEnd()) {
      fail("expected the end of the input after the value");
    }
    return root;
  }

 private:
  Mark here() const { return {pos_, line_, column_}; }
  bool atEnd() const { return pos_ >= text_.size(); }
  char peek() const { return atEnd() ? '\0' : text_[pos_]; }

  // Columns count characters, not bytes, so they match an editor's for UTF-8 text.
  void advance() {
    const char c = text_[pos_++];
    if (c == '\n') {
      ++line_;
      column_ = 1;
    } else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) {
      ++column_;
    }
  }

  bool consume(char c) {
    if (atEnd() || text_[pos_] != c) {
      return false;
    }
    advance();
    return true;
  }

  void skipSpace() {
    while (!atEnd() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\n' || text_[pos_] == '\r')) {
      advance();
    }
  }

  // What is at text[at], for "found ...". A word is shown whole (`tru`, `1e999`), unless a single
  // character is what is wrong, as in a bad escape.
  std::string describe(std::size_t at, bool wholeWord) const {
    if (at >= text_.size()) {
      return "the end of the input";
    }
    const auto c = static_cast<unsigned char>(text_[at]);
    if (c == '\n' || c == '\r') {
      return "the end of the line";
    }
    if (c < 0x20 || c == 0x7F) {
      return "control character U+" + hex(c, 4);
    }
    if (c >= 0x80) {
      const std::size_t length = utf8Length(text_, at);
      return length == 0 ? "byte 0x" + hex(c, 2) + ", not valid UTF-8 here"
                         : "'" + std::string(text_.substr(at, length)) + "'";
    }
    if (!wholeWord || !isWordChar(text_[at])) {
      return std::string("'") + text_[at] + "'";
    }
    std::size_t end = at;
    while (end < text_.size() && end - at < 24 && isWordChar(text_[end])) {
      ++end;
    }
    const bool cut = end < text_.size() && isWordChar(text_[end]);
    return "'" + std::string(text_.substr(at, end - at)) + (cut ? "...'" : "'");
  }

  [[noreturn]] void failAt(const Mark& mark, const std::string& expected, const std::string& found) const {
    throw Error(source_ + ":" + lineColumn(mark) + ": " + expected + ", found " + found);
  }
  [[noreturn]] void fail(const std::string& expected) const { failAt(here(), expected, describe(pos_, true)); }
  [[noreturn]] void failChar(const std::string& expected) const {
    failAt(here(), expected, describe(pos_, false));
  }

  // depth: how many arrays and objects enclose the value.
  JsonValue value(const char* expected, int depth) {
    skipSpace();
    JsonValue result;
    result.line = line_;
    result.column = column_;
    const char c = peek();
    if (atEnd()) {
      fail(expected);
    } else if (c == '{') {
      object(result, depth + 1);
    } else if (c == '[') {
      array(result, depth + 1);
    } else if (c == '"') {
      result.kind = JsonValue::Kind::String;
      result.text = string();
    } else if (c == '-' || isDigit(c)) {
      number(result);
    } else if (literal("true") || literal("false")) {
      result.kind = JsonValue::Kind::Boolean;
      result.boolean = c == 't';
    } else if (!literal("null")) {
      fail(expected);
    }
    return result;
  }

  bool literal(std::string_view word) {
    const std::size_t after = pos_ + word.size();
    if (text_.compare(pos_, word.size(), word) != 0 || (after < text_.size() && isWordChar(text_[after]))) {
      return false;
    }
    while (pos_ < after) {
      advance();
    }
    return true;
  }

  void enter(int depth) const {
    if (depth > kMaxDepth) {
      failAt(here(), "expected arrays and objects nested at most " + std::to_string(kMaxDepth) + " deep",
             "one nested deeper");
    }
  }

  void array(JsonValue& result, int depth) {
    enter(depth);
    advance();
    result.kind = JsonValue::Kind::Array;
    skipSpace();
    if (consume(']')) {
      return;
    }
    const char* expected = "expected a value or ']'";
    for (;;) {
      result.items.push_back(value(expected, depth));
      skipSpace();
      if (consume(']')) {
        return;
      }
      if (!consume(',')) {
        fail("expected ',' or ']'");
      }
      expected = "expected a value after ','";
    }
  }

  void object(JsonValue& result, int depth) {
    enter(depth);
    advance();
    result.kind = JsonValue::Kind::Object;
    std::unordered_map<std::string, Mark> seen;  // where each key was first written
    skipSpace();
    if (consume('}')) {
      return;
    }
    const char* expected = "expected a key in double quotes or '}'";
    for (;;) {
      skipSpace();
      if (peek() != '"') {
        fail(expected);
      }
      const Mark keyMark = here();
      std::string key = string();
      const auto [first, isNew] = seen.emplace(key, keyMark);
      if (!isNew) {
        failAt(keyMark, "expected a key not already in this object",
               jsonQuoted(key) + " again (first at " + lineColumn(first->second) + ")");
      }
      skipSpace();
      if (!consume(':')) {
        fail("expected ':' after the key " + jsonQuoted(key));
      }
      JsonValue member = value("expected a value", depth);
      result.members.emplace_back(std::move(key), std::move(member));
      skipSpace();
      if (consume('}')) {
        return;
      }
      if (!consume(',')) {
        fail("expected ',' or '}'");
      }
      expected = "expected a key in double quotes after ','";
    }
  }

  std::string string() {
    const Mark open = here();
    advance();
    std::string out;
    for (;;) {
      if (atEnd() || text_[pos_] == '\n' || text_[pos_] == '\r') {
        fail("expected '\"' to close the string begun at " + lineColumn(open));
      }
      const auto c = static_cast<unsigned char>(text_[pos_]);
      if (c == '"') {
        advance();
        return out;
      }
      if (c == '\\') {
        escape(out);
        continue;
      }
      const std::size_t length = utf8Length(text_, pos_);
      if (c < 0x20 || length == 0) {
        fail("expected a character or an escape in the string");
      }
      out.append(text_.substr(pos_, length));
      for (std::size_t i = 0; i < length; ++i) {
        advance();
      }
    }
  }

  void escape(std::string& out) {
    const Mark backslash = here();
    advance();
    const char c = peek();
    const char* const from = "\"\\/bfnrt";
    const char* const to = "\"\\/\b\f\n\r\t";
    if (const char* known = atEnd() ? nullptr : std::char_traits<char>::find(from, 8, c)) {
      out += to[known - from];
      advance();
      return;
    }
    if (c != 'u') {
      failChar("expected an escape (\\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX) after '\\'");
    }
    advance();
    std::uint32_t code = hex4();
    if (code >= 0xDC00 && code <= 0xDFFF) {
      failAt(backslash, "expected a high surrogate (\\uD800-\\uDBFF) before a low one", "\\u" + hex(code, 4) + " alone");
    }
    if (code >= 0xD800 && code <= 0xDBFF) {
      const std::string expected = "expected a low surrogate (\\uDC00-\\uDFFF) after \\u" + hex(code, 4);
      const Mark second = here();
      if (text_.compare(pos_, 2, "\\u") != 0) {
        fail(expected);
      }
      advance();
      advance();
      const std::uint32_t low = hex4();
      if (low < 0xDC00 || low > 0xDFFF) {
        failAt(second, expected, "\\u" + hex(low, 4));
      }
      code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
    }
    appendUtf8(out, code);
  }

  std::uint32_t hex4() {
    std::uint32_t code = 0;
    for (int i = 0; i < 4; ++i) {
      const char c = peek();
      const int digit = isDigit(c) ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
      if (digit < 0) {
        failChar("expected 4 hex digits after \\u");
      }
      code = code * 16 + static_cast<std::uint32_t>(digit);
      advance();
    }
    return code;
  }

  void number(JsonValue& result) {
    const Mark start = here();
    consume('-');
    if (consume('0')) {
      if (isDigit(peek())) {
        failAt(start, "expected a number without leading zeros", describe(start.pos, true));
      }
    } else if (isDigit(peek())) {
      while (isDigit(peek())) {
        advance();
      }
    } else {
      failChar("expected a digit after '-'");
    }
    if (consume('.')) {
      if (!isDigit(peek())) {
        failChar("expected a digit after '.'");
      }
      while (isDigit(peek())) {
        advance();
      }
    }
    if (consume('e') || consume('E')) {
      if (!consume('+')) {
        consume('-');
      }
      if (!isDigit(peek())) {
        failChar("expected a digit in the exponent");
      }
      while (isDigit(peek())) {
        advance();
      }
    }
    const std::string_view spelled = text_.substr(start.pos, pos_ - start.pos);
    double number = 0;
    const std::from_chars_result read = std::from_chars(spelled.data(), spelled.data() + spelled.size(), number);
    if (read.ec == std::errc::result_out_of_range && belowDoubleRange(spelled)) {
      number = spelled[0] == '-' ? -0.0 : 0.0;
    } else if (read.ec != std::errc() || read.ptr != spelled.data() + spelled.size() || !std::isfinite(number)) {
      failAt(start, "expected a number within a double's range (magnitude up to 1.8e308)", describe(start.pos, true));
    }
    result.kind = JsonValue::Kind::Number;
    result.number = number;
  }

  std::string_view text_;
  const std::string& source_;
  std::size_t pos_ = 0;
  int line_ = 1, column_ = 1;
};

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
  return Parser(text, sourceName).document();
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
