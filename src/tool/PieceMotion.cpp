// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "tool/PieceMotion.h"

#include <algorithm>
#include <cmath>

namespace thintool {

namespace {

// The rotation R with R = rotationAboutAxis(axis, angle), angle in [0, π].
void axisAngleOf(const Mat3& r, Vec3& outAxis, Real& outAngle) {
  const Real trace = r.row[0].x + r.row[1].y + r.row[2].z;
  const Vec3 skew{r.row[2].y - r.row[1].z, r.row[0].z - r.row[2].x, r.row[1].x - r.row[0].y};
  const Real skewLength = length(skew);
  // |skew| = 2 sin θ and trace − 1 = 2 cos θ: atan2 keeps full precision near 0 and π, where
  // acos of the cosine alone loses half the digits.
  outAngle = std::atan2(skewLength, trace - 1);
  if (outAngle < Real(1e-12)) {
    outAxis = {1, 0, 0};
    outAngle = 0;
  } else if (skewLength > Real(1e-6)) {
    outAxis = skew / skewLength;
  } else {
    // A half turn: R = 2aaᵀ − I, so the axis comes from the column of the largest diagonal.
    int i = 0;
    for (int k = 1; k < 3; ++k) {
      if (r.row[k][k] > r.row[i][i]) i = k;
    }
    Vec3 axis;
    axis[i] = std::sqrt(std::max(Real(0), (r.row[i][i] + 1) / 2));
    for (int k = 0; k < 3; ++k) {
      if (k != i) axis[k] = (r.row[i][k] + r.row[k][i]) / (4 * axis[i]);
    }
    outAxis = normalizedOrZero(axis);
  }
}

}  // namespace

PieceMotion::PieceMotion(const Pose& bodyStart, const Pose& bodyEnd, Real maxTurnPerSample, const Pose& inBody)
    : m_bodyStart(bodyStart), m_bodyEnd(bodyEnd), m_inBody(inBody), m_start(bodyStart * inBody), m_end(bodyEnd * inBody) {
  axisAngleOf(bodyStart.rotation.transposed() * bodyEnd.rotation, m_axis, m_angle);
  const Real samples = std::ceil(m_angle / std::max(maxTurnPerSample, Real(1e-6)));
  m_samples = std::clamp(static_cast<int>(samples), 1, kMostSamples);
}

PieceMotion PieceMotion::alongChord() const {
  PieceMotion chord = *this;
  chord.m_samples = 1;
  return chord;
}

Pose PieceMotion::at(Real t) const {
  if (t <= 0) return m_start;
  if (t >= 1) return m_end;
  Pose body;
  body.rotation = m_bodyStart.rotation * rotationAboutAxis(m_axis, m_angle * t);
  body.translation = m_bodyStart.translation + (m_bodyEnd.translation - m_bodyStart.translation) * t;
  return body * m_inBody;
}

void PieceMotion::samplePoses(Pose* out) const {
  for (int k = 0; k <= m_samples; ++k) out[k] = at(Real(k) / Real(m_samples));
}

}  // namespace thintool
