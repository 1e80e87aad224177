// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "force/ContactForce.h"

#include <thintool/core/Assert.h>

#include <algorithm>
#include <cmath>

namespace thintool {

Real huntCrossleyForce(const HuntCrossley& model, Real deformation, Real rate) {
  if (!(deformation > 0) || !std::isfinite(deformation) || !std::isfinite(rate)) {
    return 0;
  }
  const Real power = std::pow(deformation, model.exponent);
  const Real force = power * (model.stiffness + model.damping * rate);
  return std::isfinite(force) ? std::max(force, Real(0)) : 0;
}

void RestShape::capture(const std::vector<Vec3>& positions, const std::vector<Real>& inverseMasses,
                        Index anchorCount) {
  m_positions = positions;
  m_anchors.clear();
  m_anchorWeights.clear();
  m_anchorCentroid = Vec3{};
  const Index count = nodeCount();
  if (count == 0 || anchorCount == 0) {
    return;
  }
  Real heaviest = 0;
  for (Index i = 0; i < count && i < inverseMasses.size(); ++i) {
    if (inverseMasses[i] > 0 && std::isfinite(inverseMasses[i])) {
      heaviest = std::max(heaviest, 1 / inverseMasses[i]);
    }
  }
  if (heaviest == 0) {
    heaviest = 1;
  }
  // An index stride spreads the anchors over the body: Bullet numbers a mesh's nodes roughly by
  // position (rings of a sphere, rows of a patch), never clustered at one spot.
  const Index stride = std::max<Index>(1, count / anchorCount);
  Real total = 0;
  for (Index node = 0; node < count; node += stride) {
    if (!isFinite(positions[node])) {
      continue;
    }
    const Real inverseMass = node < inverseMasses.size() ? inverseMasses[node] : 0;
    const Real weight = inverseMass > 0 && std::isfinite(inverseMass) ? 1 / inverseMass : heaviest;
    m_anchors.push_back(node);
    m_anchorWeights.push_back(weight);
    m_anchorCentroid += positions[node] * weight;
    total += weight;
  }
  if (total > 0) {
    m_anchorCentroid = m_anchorCentroid / total;
  }
}

RigidFit fitRigidMotion(const RestShape& rest, const std::vector<Vec3>& anchorPositions, const RigidFit& previous) {
  RigidFit fit;
  fit.restCentroid = rest.anchorCentroid();
  const auto& anchors = rest.anchors();
  const auto& weights = rest.anchorWeights();
  if (anchors.empty() || anchorPositions.size() != anchors.size()) {
    fit.centroid = fit.restCentroid;
    return fit;
  }
  Real total = 0;
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    fit.centroid += anchorPositions[i] * weights[i];
    total += weights[i];
  }
  fit.centroid = fit.centroid / total;
  if (!isFinite(fit.centroid)) {
    return previous;
  }
  // Columns of A = Σ w·(x − c)(x₀ − c₀)ᵀ.
  Vec3 column[3];
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    const Vec3 now = (anchorPositions[i] - fit.centroid) * weights[i];
    const Vec3 then = rest.position(anchors[i]) - fit.restCentroid;
    for (int c = 0; c < 3; ++c) {
      column[c] += now * then[c];
    }
  }
  // Müller et al. 2016: turn R about the axis that aligns its columns with A's, until it stops.
  fit.rotation = previous.rotation;
  for (int iteration = 0; iteration < 32; ++iteration) {
    const Mat3 transposed = fit.rotation.transposed();  // rows of Rᵀ are R's columns
    Vec3 turn;
    Real alignment = 0;
    for (int c = 0; c < 3; ++c) {
      turn += cross(transposed.row[c], column[c]);
      alignment += dot(transposed.row[c], column[c]);
    }
    turn = turn / (std::abs(alignment) + Real(1e-12));
    const Real angle = length(turn);
    if (!std::isfinite(angle) || angle < Real(1e-10)) {
      break;
    }
    fit.rotation = rotationAboutAxis(turn / angle, angle) * fit.rotation;
  }
  return fit;
}

void ForceHistory::resize(Index faceCount) {
  if (m_inContact.size() != faceCount) {
    m_lastDeformation.assign(faceCount, 0);
    m_rate.assign(faceCount, 0);
    m_inContact.reset(faceCount);
  }
}

void ForceHistory::reset() { m_inContact.forget(); }

void computeContactForces(const StepContext& step, const SoftPatch& patch, const std::vector<PatchContact>& contacts,
                          const ForceInput& input, ForceResult& out) {
  const ForceSettings& settings = input.settings;
  const RestShape& rest = input.rest;
  const RigidFit& rigidFit = input.rigidFit;
  const ToolModel& model = step.model;
  const Pose& toolPose = step.pose;
  const Real skin = step.skin;
  const Real dt = step.dt;
  ForceHistory& history = out.history;
  std::vector<FaceForce>& outForces = out.faces;
  THINTOOL_ASSERT(patch.consistent());
  outForces.clear();
  history.m_inContact.beginStep();
  if (!settings.enabled || !(dt > 0)) {
    return;
  }
  // A node collides when a contact holds it; it keeps the sum of those contacts' normals, which
  // are the directions the tool pushes it along.
  std::vector<Vec3>& vertexNormal = history.m_vertexNormal;
  vertexNormal.assign(patch.vertexCount(), Vec3{});
  for (const PatchContact& contact : contacts) {
    for (Index k = 0; k < contact.softNodeCount; ++k) {
      const Index v = contact.patchVertices[k];
      if (v < patch.vertexCount() && isFinite(contact.normal)) {
        vertexNormal[v] += contact.normal;
      }
    }
  }
  // Touching nodes: inside the tool grown by skin + touchTolerance; pushed along the normal of
  // the face they are farthest in front of.
  const Real reach = skin + settings.touchTolerance;
  for (Index v = 0; v < patch.vertexCount(); ++v) {
    if (lengthSquared(vertexNormal[v]) > 0 || !isFinite(patch.positions[v])) {
      continue;
    }
    Index nearest = kInvalidIndex;
    const Real outside = outsideDistance(model.planes, toolPose.applyInverse(patch.positions[v]), &nearest);
    if (nearest != kInvalidIndex && outside <= reach) {
      vertexNormal[v] = toolPose.rotation * model.planes[nearest].normal;
    }
  }
  const Real smoothing = settings.rateCutoff > 0 ? 1 - std::exp(-2 * kPi * settings.rateCutoff * dt) : 1;
  for (Index f = 0; f < patch.faceCount(); ++f) {
    const auto& face = patch.faces[f];
    Vec3 pushed;
    for (Index v : face) {
      pushed += vertexNormal[v];
    }
    const Index softFace = patch.faceIds[f];
    if (lengthSquared(pushed) == 0 || softFace >= history.m_inContact.size()) {
      continue;
    }
    Vec3 centroid;
    Vec3 previousCentroid;
    Vec3 restCentroid;
    bool known = true;
    for (Index v : face) {
      centroid += patch.positions[v] / 3;
      previousCentroid += patch.previousPositions[v] / 3;
      const Index node = patch.nodeIds[v];
      known = known && node < rest.nodeCount();
      if (known) {
        restCentroid += rest.position(node) / 3;
      }
    }
    if (!known || !isFinite(centroid)) {
      continue;
    }
    // The tool is pushed back against the direction it pushes the face, whichever measure gives x:
    // the direction of the centroid's displacement (the paper does not say which it uses) turns
    // sideways and even upwards as a squashed body bulges.
    const Vec3 normal = normalizedOrZero(pushed);
    const Vec3 direction = -normal;
    auto deformationAt = [&](const Vec3& point) {
      if (settings.measure == DeformationMeasure::CentroidDisplacement) {
        return length(point - restCentroid);
      }
      return dot(point - rigidFit.apply(restCentroid), normal);
    };
    const Real previousDeformation = deformationAt(previousCentroid);
    const Real deformation = deformationAt(centroid);
    if (!std::isfinite(deformation)) {
      continue;
    }
    // ẋ: from the face's own last value when it was in contact last step, else from where its
    // nodes started this step; a face entering contact starts its filter there.
    const bool continuing = history.m_inContact.stampedLastStep(softFace);
    const Real before = continuing ? history.m_lastDeformation[softFace] : previousDeformation;
    const Real rawRate = (deformation - before) / dt;
    Real rate = continuing ? history.m_rate[softFace] + smoothing * (rawRate - history.m_rate[softFace]) : rawRate;
    if (!std::isfinite(rate)) {
      rate = 0;
    }
    history.m_lastDeformation[softFace] = deformation;
    history.m_rate[softFace] = rate;
    history.m_inContact.stamp(softFace);

    Real magnitude = settings.law ? settings.law(deformation, rate)
                                  : huntCrossleyForce(settings.huntCrossley, deformation, rate);
    if (!std::isfinite(magnitude) || magnitude < 0 || deformation <= 0) {
      magnitude = 0;
    }
    outForces.push_back({softFace, centroid, direction * magnitude, deformation, rate});
  }
}

}  // namespace thintool
