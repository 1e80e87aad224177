// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// libFuzzer target: the evaluation suite's JSON parser. Any bytes either parse, giving a value
// whose every number is finite and whose every position is a real line and column, or throw
// thintool::Error; nothing else may happen, whatever the nesting, escapes or numbers.

#include "Json.h"

#include <thintool/core/Error.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace {

using thintool::eval::JsonValue;

// Depth is capped by the parser, so this recursion is bounded too.
void check(const JsonValue& value) {
  if (value.line < 1 || value.column < 1 || (value.kind == JsonValue::Kind::Number && !std::isfinite(value.number))) {
    __builtin_trap();
  }
  for (const JsonValue& item : value.items) {
    check(item);
  }
  for (const auto& member : value.members) {
    check(member.second);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
  try {
    check(thintool::eval::parseJson(std::string_view(reinterpret_cast<const char*>(bytes), size), "fuzz.json"));
  } catch (const thintool::Error&) {
  }
  return 0;
}
