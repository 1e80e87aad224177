// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// libFuzzer target: the evaluation suite's JSON parser and scene-file reader. Any bytes either
// parse, giving a value whose every number is finite and whose every position is a real line and
// column, or throw thintool::Error; nothing else may happen, whatever the nesting, escapes or
// numbers. Text that parses is then read as a scene file, which must give a scene with a positive
// step and duration or throw thintool::Error (files it names are looked for where none exist).

#include "Json.h"
#include "SceneFile.h"

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
  const std::string text(reinterpret_cast<const char*>(bytes), size);
  try {
    check(thintool::eval::parseJson(text, "fuzz.json"));
  } catch (const thintool::Error&) {
    return 0;
  }
  try {
    const thintool::eval::SceneSpec scene = thintool::eval::parseScene(text, "fuzz.json", "/nonexistent");
    if (!(scene.timeStep > 0) || !(scene.duration > 0) || scene.tools.empty()) __builtin_trap();
  } catch (const thintool::Error&) {
  }
  return 0;
}
