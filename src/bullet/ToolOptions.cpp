// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/bullet/ToolOptions.h>

#include "response/Separation.h"

#include <cmath>
#include <sstream>

namespace thintool {

namespace {

bool isLength(Real value) { return std::isfinite(value) && value >= 0; }

// A length the user gave, when it must be positive: left empty, the library picks it.
bool badPositiveLength(const std::optional<Real>& length) {
  return length.has_value() && !(std::isfinite(*length) && *length > 0);
}

}  // namespace

std::string validateToolOptions(const ToolOptions& options) {
  std::ostringstream problem;
  if (options.skin.has_value() && !isLength(*options.skin)) {
    problem << "skin must be a finite length >= 0 (empty: the soft body's margin), got " << *options.skin;
  } else if (!(options.skinGrowthSpeed > 0)) {
    problem << "skinGrowthSpeed must be > 0 m/s (infinite: at once), got " << options.skinGrowthSpeed;
  } else if (badPositiveLength(options.probeDepth)) {
    problem << "probeDepth must be a finite length > 0 (empty: automatic), got " << *options.probeDepth;
  } else if (options.filters.check1 && !options.association.enabled) {
    problem << "filters.check1 needs association.enabled; turn both off for the rays-only ablation "
               "(ToolOptions::rayOnly())";
  } else if (badPositiveLength(options.filters.reverseRayLength)) {
    problem << "filters.reverseRayLength must be a finite length > 0 (empty: automatic), got "
            << *options.filters.reverseRayLength;
  } else if (!(std::isfinite(options.response.stiffness) && options.response.stiffness > 0)) {
    problem << "response.stiffness must be a finite stiffness > 0 N/m, got " << options.response.stiffness;
  } else if (options.response.friction.enabled &&
             !(std::isfinite(options.response.friction.staticCoefficient) &&
               options.response.friction.staticCoefficient >= 0)) {
    problem << "response.friction.staticCoefficient must be finite and >= 0, got "
            << options.response.friction.staticCoefficient;
  } else if (options.response.friction.enabled &&
             !(std::isfinite(options.response.friction.kineticCoefficient) &&
               options.response.friction.kineticCoefficient >= 0 &&
               options.response.friction.kineticCoefficient <= options.response.friction.staticCoefficient)) {
    problem << "response.friction.kineticCoefficient must be finite, >= 0 and <= staticCoefficient, got "
            << options.response.friction.kineticCoefficient;
  } else if (options.bullet.holdPlaneReach.has_value() && !isLength(*options.bullet.holdPlaneReach)) {
    problem << "bullet.holdPlaneReach must be finite and >= 0, got " << *options.bullet.holdPlaneReach;
  } else if (options.energyGuard.enabled &&
             !(std::isfinite(options.energyGuard.speedFactor) && options.energyGuard.speedFactor >= 1)) {
    problem << "energyGuard.speedFactor must be finite and >= 1, got " << options.energyGuard.speedFactor;
  } else if (options.energyGuard.enabled && !isLength(options.energyGuard.energySlack)) {
    problem << "energyGuard.energySlack must be finite and >= 0, got " << options.energyGuard.energySlack;
  } else if (options.energyGuard.enabled && !isLength(options.energyGuard.restingSpeed)) {
    problem << "energyGuard.restingSpeed must be a finite speed >= 0 m/s, got " << options.energyGuard.restingSpeed;
  } else if (options.separation.enabled && !validateSeparationSettings(options.separation).empty()) {
    problem << validateSeparationSettings(options.separation);
  } else if (options.force.enabled) {
    const HuntCrossley& hc = options.force.huntCrossley;
    if (!(std::isfinite(hc.stiffness) && hc.stiffness >= 0)) {
      problem << "force.huntCrossley.stiffness must be finite and >= 0 N/m^n, got " << hc.stiffness;
    } else if (!(std::isfinite(hc.damping) && hc.damping >= 0)) {
      problem << "force.huntCrossley.damping must be finite and >= 0 N*s/m^(n+1), got " << hc.damping;
    } else if (!(std::isfinite(hc.exponent) && hc.exponent > 0)) {
      problem << "force.huntCrossley.exponent must be finite and > 0, got " << hc.exponent;
    } else if (!(std::isfinite(options.force.rateCutoff) && options.force.rateCutoff >= 0)) {
      problem << "force.rateCutoff must be a finite frequency >= 0 Hz (0 = unfiltered), got "
              << options.force.rateCutoff;
    } else if (!isLength(options.force.touchTolerance)) {
      problem << "force.touchTolerance must be a finite length >= 0 m, got " << options.force.touchTolerance;
    } else if (!isFinite(options.force.torquePoint)) {
      problem << "force.torquePoint must be finite";
    }
  }
  return problem.str();
}

}  // namespace thintool
