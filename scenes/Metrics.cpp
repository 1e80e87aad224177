// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "Metrics.h"

namespace thintool::scenes {

namespace {

void toVec3s(const std::vector<Point>& points, std::vector<Vec3>& out) {
  out.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = {points[i].x, points[i].y, points[i].z};
}

}  // namespace

Point ToolBox::toLocal(const Point& world) const {
  // rotationRows are the rows of the tool's rotation R; local = Rᵀ·(world - origin).
  const Point d{world.x - origin.x, world.y - origin.y, world.z - origin.z};
  const auto& r = rotationRows;
  return {r[0].x * d.x + r[1].x * d.y + r[2].x * d.z, r[0].y * d.x + r[1].y * d.y + r[2].y * d.z,
          r[0].z * d.x + r[1].z * d.y + r[2].z * d.z};
}

Pose ToolBox::pose() const {
  Pose pose;
  for (int i = 0; i < 3; ++i) pose.rotation.row[i] = {rotationRows[i].x, rotationRows[i].y, rotationRows[i].z};
  pose.translation = {origin.x, origin.y, origin.z};
  return pose;
}

void BoxGroundTruth::start(const ToolBox& tool, const std::vector<Point>& nodes,
                            const std::vector<std::array<int, 3>>& faces, bool closedSurface) {
  m_metrics = RunMetrics{};
  eval::GroundTruthPiece piece{
      eval::SolidDistance(eval::ConvexSolid::box({tool.halfExtents.x, tool.halfExtents.y, tool.halfExtents.z})),
      Pose{}, 0, false};
  m_truth.emplace(std::vector<eval::GroundTruthPiece>{std::move(piece)}, closedSurface);
  toVec3s(nodes, m_nodes);
  m_truth->start({tool.pose()}, m_nodes, faces);
}

void BoxGroundTruth::update(const ToolBox& tool, const std::vector<Point>& nodes,
                             const std::vector<std::array<int, 3>>& faces) {
  if (!m_truth.has_value()) return;
  toVec3s(nodes, m_nodes);
  m_truth->update({tool.pose()}, m_nodes, faces);
  const eval::GroundTruthRun run = m_truth->run();
  m_metrics.crossed = run.crossedNodes;
  m_metrics.stillCrossed = run.stillCrossed;
  m_metrics.maxPenetration = run.maxPenetration;
  m_metrics.endsInside = run.endsInside;
  m_metrics.everInside = run.toolInsideSteps > 0;
  m_metrics.insideSteps = run.toolInsideSteps;
  m_metrics.piercedSteps = run.piercedSteps;
}

}  // namespace thintool::scenes
