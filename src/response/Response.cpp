// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include <thintool/response/Response.h>

namespace thintool {

void computeResponse(const ToolModel& model, const Pose& toolPose, const SoftPatch& patch,
                     const std::vector<Contact>& contacts, Real skin, Real dt, const ResponseSettings& settings,
                     ResponseWorkspace& work, std::vector<NodeCorrection>& outCorrections, Wrench& outWrench) {
  outCorrections.clear();
  outWrench = Wrench{};
  if (settings.kind == ResponseKind::None || contacts.empty() || !(dt > 0)) {
    return;
  }
  const Index vertexCount = patch.vertexCount();
  if (work.m_slot.size() < vertexCount) {
    work.m_slot.resize(vertexCount, kInvalidIndex);
  }
  work.m_positions.resize(vertexCount);

  auto slotOf = [&](Index vertex) -> NodeCorrection& {
    if (work.m_slot[vertex] == kInvalidIndex) {
      work.m_slot[vertex] = static_cast<Index>(outCorrections.size());
      work.m_positions[vertex] = patch.positions[vertex];
      NodeCorrection correction;
      correction.vertex = vertex;
      outCorrections.push_back(correction);
    }
    return outCorrections[work.m_slot[vertex]];
  };

  for (const Contact& contact : contacts) {
    const auto& corners = patch.faces[contact.patchFace];
    const Vec3 normal = contact.normal;
    // The entry-side plane: the tool face the node sits on, moved out by the skin.
    const Vec3 planePoint = toolPose.apply(model.positions[contact.toolNode]) + normal * skin;
    const Real planeOffset = -dot(normal, planePoint);
    const Real pushForce = settings.stiffness * (contact.depth + skin);
    for (int k = 0; k < 3; ++k) {
      const Index vertex = corners[k];
      const Real inverseMass = patch.inverseMasses[vertex];
      if (!(inverseMass > 0)) {
        continue;
      }
      if (settings.kind == ResponseKind::Constraint) {
        // Read the position through the slot so that earlier contacts' moves count.
        const Real distance =
            dot(work.m_slot[vertex] == kInvalidIndex ? patch.positions[vertex] : work.m_positions[vertex], normal) +
            planeOffset;
        if (distance >= 0) {
          continue;
        }
        NodeCorrection& correction = slotOf(vertex);
        work.m_positions[vertex] += normal * -distance;
        correction.planeNormal = normal;
        correction.planeOffset = planeOffset;
      } else {
        NodeCorrection& correction = slotOf(vertex);
        const Vec3 force = normal * (pushForce * contact.barycentric[k]);
        work.m_positions[vertex] += force * (inverseMass * dt * dt);
        correction.planeNormal = normal;
        correction.planeOffset = planeOffset;
      }
    }
  }

  // Displacements, the reaction on the tool, and the slots cleared for the next call.
  const Real inverseDtSquared = 1 / (dt * dt);
  for (NodeCorrection& correction : outCorrections) {
    const Index vertex = correction.vertex;
    correction.displacement = work.m_positions[vertex] - patch.positions[vertex];
    const Vec3 forceOnTool = correction.displacement * (-inverseDtSquared / patch.inverseMasses[vertex]);
    outWrench.force += forceOnTool;
    outWrench.torque += cross(patch.positions[vertex] - toolPose.translation, forceOnTool);
    work.m_slot[vertex] = kInvalidIndex;
  }
}

}  // namespace thintool
