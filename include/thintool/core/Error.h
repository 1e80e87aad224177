// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

#include <thintool/core/Api.h>

#include <stdexcept>
#include <string>

namespace thintool {

/// Thrown when a tool is registered with input ThinTool cannot use: an invalid shape, invalid
/// options, a world without ThinTool's collision configuration. The message names the tool and
/// the problem. Nothing on the per-step path throws: bad data met while stepping is skipped and
/// counted in the step's diagnostics instead.
class THINTOOL_API Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace thintool
