// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/bullet/ToolOptions.h>

#include <cmath>
#include <sstream>

namespace thintool {

namespace {

bool isLength(Real value) { return std::isfinite(value) && value >= 0; }

}  // namespace

std::string validateToolOptions(const ToolOptions& options) {
  std::ostringstream problem;
  if (!std::isfinite(options.skin)) {
    problem << "skin must be finite (negative picks the soft body's margin), got " << options.skin;
  } else if (!isLength(options.probeDepth)) {
    problem << "probeDepth must be a finite length >= 0 (0 = automatic), got " << options.probeDepth;
  } else if (options.filters.check1 && !options.association.enabled) {
    problem << "filters.check1 needs association.enabled; turn both off for the rays-only ablation "
               "(ToolOptions::rayOnly())";
  } else if (!isLength(options.filters.reverseRayLength)) {
    problem << "filters.reverseRayLength must be a finite length >= 0 (0 = automatic), got "
            << options.filters.reverseRayLength;
  } else if (!(std::isfinite(options.response.stiffness) && options.response.stiffness > 0)) {
    problem << "response.stiffness must be a finite stiffness > 0 N/m, got " << options.response.stiffness;
  }
  return problem.str();
}

}  // namespace thintool
