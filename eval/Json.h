// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

/// @file
/// The JSON reader of the evaluation suite's scene files, on RapidJSON. A scene file is written by
/// hand, so a mistake in it must come back as one clear line: the file, the line and column, the
/// field and what was expected there. parseJson follows RFC 8259 strictly (no comments, no
/// trailing commas) and reports the first problem; JsonField does the typed reads on top of it,
/// so the code that reads a scene never formats an error message itself.

#include <array>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace thintool::eval {

struct JsonValue {
  enum class Kind { Null, Boolean, Number, String, Array, Object };
  Kind kind = Kind::Null;
  int line = 0, column = 0;  ///< 1-based, where the value starts; columns count characters
  bool boolean = false;
  double number = 0;       ///< always finite when parsed
  std::string text;        ///< String, as UTF-8
  std::vector<JsonValue> items;                            ///< Array
  std::vector<std::pair<std::string, JsonValue>> members;  ///< Object, in file order, keys unique
};

/// "null", "a boolean", "a number", "a string", "an array", "an object": for messages.
const char* kindName(JsonValue::Kind kind);

/// Parses text as one JSON value (RFC 8259). Throws thintool::Error with
/// "source:line:column: <what was expected>, found <what>" for the first problem. Beyond the RFC's
/// grammar these are errors too: a key used twice in one object, nesting deeper than 64 arrays
/// and objects, a number too large for a double (one too small becomes 0), text that is not UTF-8,
/// and anything but white space after the value. \uXXXX escapes, surrogate pairs included, become
/// UTF-8. A leading UTF-8 byte order mark is skipped.
JsonValue parseJson(std::string_view text, const std::string& sourceName);

/// text as a JSON string literal: in double quotes, with quotes, backslashes and control
/// characters escaped, so that it also stays on one line in a message.
std::string jsonQuoted(std::string_view text);

/// The whole file at path, bytes as they are. Throws thintool::Error "path: cannot read the file"
/// when it cannot be opened or read (a missing file, a directory).
std::string readTextFile(const std::string& path);

/// Reads and parses the file at path; errors name the path as the source. An unreadable file
/// throws thintool::Error "path: cannot read the file".
JsonValue loadJsonFile(const std::string& path);

/// A value reached from the root by a path such as `tools[1].trajectory.speed`, for typed reads
/// whose errors name the file, line, field and what was expected, e.g.
/// "scene.json:12:14: tools[1].trajectory.speed: expected a number, found a string".
/// It refers to the value, which must outlive it.
class JsonField {
 public:
  JsonField(const JsonValue& value, std::string path, std::string source);  ///< root: path ""

  const JsonValue& value() const;
  const std::string& path() const;  ///< "" for the root; errors print "(root)" for it

  bool has(std::string_view key) const;               ///< member present (error if not an object)
  JsonField at(std::string_view key) const;           ///< required member
  std::optional<JsonField> find(std::string_view key) const;
  std::size_t size() const;                           ///< array length (error if not an array)
  JsonField at(std::size_t index) const;              ///< array item, path "name[3]"

  double number() const;                                        ///< a finite number
  double number(std::string_view key, double fallback) const;   ///< optional member
  double positive(std::string_view key, double fallback) const; ///< optional member, > 0 if present
  int integer() const;                                          ///< a whole number within int range
  int integer(std::string_view key, int fallback) const;
  bool boolean() const;
  bool boolean(std::string_view key, bool fallback) const;
  std::string string() const;
  std::string string(std::string_view key, const std::string& fallback) const;
  /// A string that must be one of choices; the error lists them.
  std::string oneOf(std::initializer_list<std::string_view> choices) const;
  std::array<double, 3> vec3() const;  ///< an array of exactly 3 finite numbers

  void expect(JsonValue::Kind kind) const;  ///< error "expected an object, found an array"
  /// Members other than keys are errors, so a misspelt optional field is not silently ignored.
  void allowOnly(std::initializer_list<std::string_view> keys) const;
  /// Throws thintool::Error "source:line:column: path: what" at this value.
  [[noreturn]] void fail(const std::string& what) const;

 private:
  const JsonValue* value_;
  std::string path_;
  std::string source_;
};

}  // namespace thintool::eval
