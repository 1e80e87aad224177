// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
//
// The viewer under a virtual display (ctest runs this under xvfb-run): each example scene is
// rendered to PNG, read back, and checked: not blank, the tool's colour where the camera projects
// the tool, the soft body's where it projects a soft face turned towards it.

#include "ClampScene.h"
#ifdef THINTOOL_HAVE_HAPTICS
#include "ClampSession.h"

#include <thintool/haptics/ReplayDevice.h>
#endif
#include "GripperScene.h"
#include "SoftBallScene.h"
#include "Viewer.h"

#include <thintool/thintool.h>

#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <gtest/gtest.h>
#include <stb_image.h>

#include <cstdio>
#include <memory>
#include <set>
#include <string>

namespace thintool::viewer {
namespace {

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;

  std::array<int, 3> at(int x, int y) const {
    const std::size_t i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

Image load(const std::string& path) {
  Image image;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &image.width, &image.height, &channels, 3);
  if (data != nullptr) {
    image.rgb.assign(data, data + std::size_t(image.width) * std::size_t(image.height) * 3);
    stbi_image_free(data);
  }
  return image;
}

// Whether a pixel within radius of (x, y) has the palette colour's hue: each channel within a
// shading factor of 0.5 to 1.05 of the palette's, in the same proportions (15 % slack).
bool colourNear(const Image& image, float x, float y, const std::array<unsigned char, 3>& palette, int radius = 3) {
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      const int px = int(x) + dx, py = int(y) + dy;
      if (px < 0 || py < 0 || px >= image.width || py >= image.height) continue;
      const std::array<int, 3> c = image.at(px, py);
      const float shade = float(c[0] + c[1] + c[2]) / float(palette[0] + palette[1] + palette[2]);
      if (shade < 0.5f || shade > 1.05f) continue;
      bool match = true;
      for (int k = 0; k < 3; ++k) match = match && std::abs(c[k] - shade * palette[k]) < 0.15f * 255;
      if (match) return true;
    }
  }
  return false;
}

ViewerSettings offScreen() {
  ViewerSettings settings;
  settings.visible = false;
  return settings;
}

// Draws world and overlay, writes the frame to path and reads it back.
Image renderToImage(Viewer& viewer, const WorldView& world, const Overlay& overlay, const std::string& path) {
  viewer.render(world, overlay);
  EXPECT_TRUE(viewer.screenshot(path)) << path;
  return load(path);
}

class ExampleScene : public ::testing::TestWithParam<scenes::ToolShape> {};

TEST_P(ExampleScene, RendersTheToolAndTheSoftBodyWhereTheyAre) {
  scenes::SceneSettings settings;
  settings.tool = GetParam();
  scenes::SoftBallScene scene(settings);
  scene.settle();
  btTransform pose(btQuaternion::getIdentity(), scene.aboveBall(scene.ballTop() + 0.1));
  // Down 0.25 m at 1 m/s, 0.15 m into the ball: deeper, the coarse ball's faces may close over the
  // needle, which then is rightly hidden.
  for (int i = 0; i < 15; ++i) {
    pose.setOrigin(pose.getOrigin() - btVector3(0, btScalar(1.0 / 60), 0));
    scene.step(pose);
  }
  Viewer viewer(offScreen());
  viewer.camera().target = scene.aboveBall(1);
  Overlay overlay;
  overlay.tools.push_back(scene.tool());
  viewer.render(scene.world(), overlay);
  const std::string path = std::string("viewer_") + scenes::toolShapeName(GetParam()) + ".png";
  ASSERT_TRUE(viewer.screenshot(path));
  const Image image = load(path);
  ASSERT_EQ(image.width, viewer.width());
  ASSERT_EQ(image.height, viewer.height());

  std::set<int> colours;
  for (int y = 0; y < image.height; y += 4) {
    for (int x = 0; x < image.width; x += 4) {
      const auto c = image.at(x, y);
      colours.insert((c[0] << 16) | (c[1] << 8) | c[2]);
    }
  }
  EXPECT_GT(colours.size(), 20u) << "the image is blank";

  // The tool: a point on its upper face, a third of the way from its centre to a corner (clear of
  // the force line drawn from its centre).
  const scenes::ToolBox box = scene.toolBox();
  const btVector3 onTop = scene.toolBody().getWorldTransform() *
                          btVector3(btScalar(box.halfExtents.x / 3), btScalar(box.halfExtents.y),
                                    btScalar(box.halfExtents.z / 3));
  float x = 0, y = 0;
  ASSERT_TRUE(viewer.camera().project(onTop, image.width, image.height, x, y));
  EXPECT_TRUE(colourNear(image, x, y, Palette::tool)) << "no tool colour at " << x << ", " << y;

  // The soft body: the centroid of the face nearest the camera among those facing it.
  const btVector3 eye = viewer.camera().eye();
  const btSoftBody& ball = scene.ball();
  double nearest = 1e30;
  btVector3 centroid;
  for (int f = 0; f < ball.m_faces.size(); ++f) {
    const btSoftBody::Face& face = ball.m_faces[f];
    const btVector3 c = (face.m_n[0]->m_x + face.m_n[1]->m_x + face.m_n[2]->m_x) / 3;
    const btVector3 n = (face.m_n[1]->m_x - face.m_n[0]->m_x).cross(face.m_n[2]->m_x - face.m_n[0]->m_x);
    if (n.dot(eye - c) <= 0 || c.y() > box.origin.y - 0.1) continue;
    if ((eye - c).length() < nearest) {
      nearest = (eye - c).length();
      centroid = c;
    }
  }
  ASSERT_LT(nearest, 1e30);
  ASSERT_TRUE(viewer.camera().project(centroid, image.width, image.height, x, y));
  EXPECT_TRUE(colourNear(image, x, y, Palette::softBody)) << "no soft-body colour at " << x << ", " << y;
  EXPECT_FALSE(colourNear(image, 2, image.height / 2.f, Palette::softBody, 1)) << "the ball fills the frame's edge";
}

INSTANTIATE_TEST_SUITE_P(PlateAndNeedle, ExampleScene,
                         ::testing::Values(scenes::ToolShape::Plate, scenes::ToolShape::Needle),
                         [](const ::testing::TestParamInfo<scenes::ToolShape>& shape) {
                           return std::string(scenes::toolShapeName(shape.param));
                         });

TEST(ClampScene, RendersTheJawsAndTheGraspedBodyWhereTheyAre) {
  Viewer viewer(offScreen());
  viewer.camera().target = btVector3(0, 1.2f, 0);
  viewer.camera().distance = 6;
  Image image;
  btVector3 jawPoint, bodyCentre;
  scenes::ClampRunSettings run;
  run.observer = [&](const btSoftRigidDynamicsWorld& world, Clamp& clamp, const scenes::ClampSample& sample) {
    if (sample.time < 3.5) return true;  // lifted and held
    Overlay overlay;
    overlay.tools = {&clamp.jaw(0), &clamp.jaw(1)};
    image = renderToImage(viewer, world, overlay, "viewer_clamp.png");
    // The jaw nearer the camera, at a point on its face turned to the camera, away from its
    // centre's force line.
    const btVector3 eye = viewer.camera().eye();
    const btTransform a = clamp.jawBody(0).getWorldTransform(), b = clamp.jawBody(1).getWorldTransform();
    const btTransform& near = (a.getOrigin() - eye).length() < (b.getOrigin() - eye).length() ? a : b;
    const btVector3 side = near.getBasis().getColumn(1);
    jawPoint = near * btVector3(-0.4f, 0, 0) + side * (side.dot(eye - near.getOrigin()) > 0 ? 0.011f : -0.011f);
    bodyCentre = btVector3(0, btScalar(sample.bodyCentreHeight), 0);
    return false;
  };
  scenes::runClamp(run);
  ASSERT_FALSE(image.rgb.empty());
  float x = 0, y = 0;
  ASSERT_TRUE(viewer.camera().project(jawPoint, image.width, image.height, x, y));
  EXPECT_TRUE(colourNear(image, x, y, Palette::tool)) << "no jaw colour at " << x << ", " << y;
  // The sphere's top, above the jaws (they are 0.6 m tall at its equator).
  ASSERT_TRUE(viewer.camera().project(bodyCentre + btVector3(0, 0.85f, 0), image.width, image.height, x, y));
  EXPECT_TRUE(colourNear(image, x, y, Palette::softBody)) << "no soft-body colour at " << x << ", " << y;
}

// A soft multibody world: the gripper's finger links, drawn as the tools they are, and the cube they
// hold up.
TEST(GripperScene, RendersTheFingersAndTheHeldCubeWhereTheyAre) {
  Viewer viewer(offScreen());
  viewer.camera().target = btVector3(0, 0.3f, 0);
  viewer.camera().distance = 1.4f;
  Image image;
  btVector3 fingerPoint, cubePoint;
  scenes::GripperSettings settings;
  settings.observer = [&](const btCollisionWorld& world, const btAlignedObjectArray<btSoftBody*>& softBodies,
                          const std::array<Tool*, 2>& fingers, double time) {
    if (time < 4) return true;  // lifted and held
    EXPECT_EQ(softBodies.size(), 1);
    const btSoftBody& cube = *softBodies[0];
    Overlay overlay;
    overlay.tools = {fingers[0], fingers[1]};
    image = renderToImage(viewer, WorldView(world, softBodies), overlay, "viewer_gripper.png");
    // The middle of a finger's outer face, on the finger whose outer face the camera sees.
    const btVector3 eye = viewer.camera().eye();
    for (Tool* finger : fingers) {
      const btTransform pose = finger->body().getWorldTransform();
      const btVector3 outward = pose.getBasis().getColumn(0) * (pose.getOrigin().x() < 0 ? -1 : 1);
      if (outward.dot(eye - pose.getOrigin()) > 0) fingerPoint = pose.getOrigin() + outward * 0.0105f;
    }
    // The middle of the cube's side turned to the camera along z.
    const btScalar towardsCamera = eye.z() > 0 ? 1 : -1;
    btScalar front = -BT_LARGE_FLOAT;
    for (int n = 0; n < cube.m_nodes.size(); ++n) front = btMax(front, cube.m_nodes[n].m_x.z() * towardsCamera);
    btVector3 sum(0, 0, 0);
    int count = 0;
    for (int n = 0; n < cube.m_nodes.size(); ++n) {
      if (cube.m_nodes[n].m_x.z() * towardsCamera > front - 0.01f) {
        sum += cube.m_nodes[n].m_x;
        ++count;
      }
    }
    cubePoint = sum / btScalar(std::max(count, 1));
    return false;
  };
  scenes::runGripper(settings);
  ASSERT_FALSE(image.rgb.empty());
  EXPECT_GT(cubePoint.y(), 0.3) << "the cube is not held up at 4 s";  // its centre rests 0.1 m up
  float x = 0, y = 0;
  ASSERT_TRUE(viewer.camera().project(fingerPoint, image.width, image.height, x, y));
  EXPECT_TRUE(colourNear(image, x, y, Palette::tool)) << "no finger colour at " << x << ", " << y;
  ASSERT_TRUE(viewer.camera().project(cubePoint, image.width, image.height, x, y));
  EXPECT_TRUE(colourNear(image, x, y, Palette::softBody)) << "no soft-body colour at " << x << ", " << y;
}

#ifdef THINTOOL_HAVE_HAPTICS
TEST(ClampSession, RendersTheLoadFedBackAsAnArrow) {
  Viewer viewer(offScreen());
  viewer.camera().target = btVector3(0, 1.2f, 0);
  viewer.camera().distance = 6;
  Image image;
  btVector3 arrowMiddle;
  scenes::ClampSessionSettings session;
  session.observer = [&](const btSoftRigidDynamicsWorld& world, Clamp& clamp, const scenes::ClampSessionSample& sample,
                         const haptics::HapticLoop&) {
    if (sample.time < 3.5) return true;  // lifted and held
    Overlay overlay;
    overlay.tools = {&clamp.jaw(0), &clamp.jaw(1)};
    const btVector3 start(-0.7f, btScalar(sample.bodyCentreHeight), 1.2f);  // in front of the grasp
    overlay.arrows.push_back({start, start + toBt(sample.onClamp) * btScalar(0.1)});
    arrowMiddle = start + toBt(sample.onClamp) * btScalar(0.05);
    image = renderToImage(viewer, world, overlay, "viewer_clamp_session.png");
    return false;
  };
  haptics::ReplayDevice device =
      haptics::ReplayDevice::fromFile(std::string(THINTOOL_CLAMP_TRAJECTORIES) + "/grasp-sphere.csv");
  const scenes::ClampSessionResult result = scenes::runClampSession(session, device);
  ASSERT_FALSE(image.rgb.empty());
  EXPECT_LT(result.trace.back().time, 3.6) << "the observer ended the session";
  float x = 0, y = 0;
  ASSERT_TRUE(viewer.camera().project(arrowMiddle, image.width, image.height, x, y));
  EXPECT_TRUE(colourNear(image, x, y, Palette::arrow)) << "no arrow colour at " << x << ", " << y;
}
#endif

}  // namespace
}  // namespace thintool::viewer
