// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#pragma once

// The examples' OpenGL viewer (optional: built when GLFW, OpenGL and Dear ImGui are found). It
// draws a Bullet world with soft bodies as it is (btSoftRigidDynamicsWorld, btSoftMultiBodyDynamicsWorld
// or btDeformableMultiBodyDynamicsWorld): soft bodies shaded with their wireframe, box-shaped
// rigid bodies, the registered tools' sample nodes (red where they collide this step), the force
// on each tool, and a panel of the caller's figures. An orbit camera (drag to turn, scroll to
// zoom), keys for the caller, and a screenshot to PNG that works under Xvfb with Mesa's software
// OpenGL. Legacy fixed-function OpenGL 2: the scenes are small and Mesa runs it everywhere.

#include <LinearMath/btAlignedObjectArray.h>
#include <LinearMath/btVector3.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

class btCollisionWorld;
class btDeformableMultiBodyDynamicsWorld;
class btSoftBody;
class btSoftMultiBodyDynamicsWorld;
class btSoftRigidDynamicsWorld;
struct GLFWwindow;

namespace thintool {
class Tool;
}

namespace thintool::viewer {

struct ViewerSettings {
  int width = 960;   ///< pixels
  int height = 640;  ///< pixels
  std::string title = "ThinTool";
  bool visible = true;  ///< false: a hidden window, for screenshots
};

/// An orbit camera about target; angles in radians, distance in metres.
struct Camera {
  btVector3 target{0, 1, 0};
  float yaw = 0.6f;     ///< about the world's y axis
  float pitch = 0.35f;  ///< above the horizon
  float distance = 4.5f;
  float fieldOfView = 0.8f;  ///< vertical, radians

  btVector3 eye() const;
  /// Where a world point lands in a width × height image, in pixels from the top-left corner;
  /// false when it is behind the camera.
  bool project(const btVector3& world, int width, int height, float& x, float& y) const;
};

/// The colours the viewer draws with (RGB, 0–255), public so that tests can look for them.
struct Palette {
  static constexpr std::array<unsigned char, 3> softBody{214, 120, 110};
  static constexpr std::array<unsigned char, 3> tool{70, 120, 200};
  static constexpr std::array<unsigned char, 3> ground{150, 150, 140};
  static constexpr std::array<unsigned char, 3> background{235, 238, 242};
  static constexpr std::array<unsigned char, 3> arrow{200, 40, 160};
};

/// One frame's content besides the world: the panel's lines and the tools to mark.
struct Overlay {
  std::vector<std::string> panelLines;
  std::vector<Tool*> tools;  ///< their nodes and forces are drawn
  /// Lines drawn over the scene in Palette::arrow, from the first point to the second (world, m):
  /// a force fed back to a device, say.
  std::vector<std::array<btVector3, 2>> arrows;
};

/// What the viewer draws of a world: its collision objects and its soft bodies. Each of Bullet's
/// worlds with soft bodies converts to it, so a world is passed as it is.
struct WorldView {
  WorldView(const btSoftRigidDynamicsWorld& world);
  WorldView(const btSoftMultiBodyDynamicsWorld& world);
  WorldView(const btDeformableMultiBodyDynamicsWorld& world);
  WorldView(const btCollisionWorld& world, const btAlignedObjectArray<btSoftBody*>& worldSoftBodies);

  const btCollisionWorld& objects;
  const btAlignedObjectArray<btSoftBody*>& softBodies;
};

class Viewer {
 public:
  /// Opens the window; throws std::runtime_error when there is no display or OpenGL.
  explicit Viewer(const ViewerSettings& settings);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  Camera& camera() { return m_camera; }
  /// Draws world and overlay into the back buffer.
  void render(const WorldView& world, const Overlay& overlay);
  /// Writes the frame render() drew to a PNG file; false if it could not be written. Call it
  /// before present().
  bool screenshot(const std::string& path) const;
  /// Draws world and overlay and writes the frame to a PNG file: the screenshot modes' one call.
  /// A panel that fits its text takes a frame to learn its size, so the frame is drawn three times.
  bool renderToFile(const WorldView& world, const Overlay& overlay, const std::string& path);
  /// Shows the frame and reads input; returns false once the window was asked to close.
  bool present();
  /// render() and present().
  bool frame(const WorldView& world, const Overlay& overlay) {
    render(world, overlay);
    return present();
  }
  /// The frame's size in pixels.
  int width() const;
  int height() const;

  /// Keys pressed since the last frame (GLFW key codes), for the caller's controls.
  const std::vector<int>& keysPressed() const { return m_keysPressed; }
  /// Whether a key is held down now.
  bool keyDown(int key) const;
  /// How far the mouse was dragged with the right button since the last call (pixels), turned into
  /// a horizontal move in the world seen from the camera (m), at metresPerPixel.
  btVector3 takeRightDrag(float metresPerPixel);

 private:
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void onScroll(GLFWwindow* window, double dx, double dy);
  void handleMouse();
  void drawWorld(const WorldView& world, const Overlay& overlay) const;
  void drawPanel(const Overlay& overlay);

  GLFWwindow* m_window = nullptr;
  Camera m_camera;
  std::vector<int> m_keysPressed;
  std::vector<int> m_keysThisFrame;
  double m_lastMouseX = 0, m_lastMouseY = 0;
  bool m_dragging = false;
  bool m_rightDragging = false;
  double m_rightDragX = 0, m_rightDragY = 0;
  double m_lastTime = 0;
  bool m_imgui = false;
};

/// An example's viewer over a run: every step drawn in a window, or, for a screenshot, the first
/// step at or after screenshotTime (s) written to a PNG without showing the window.
class RunWindow {
 public:
  /// Null, with the reason on stderr, where there is no display or OpenGL. An empty screenshotPath
  /// asks for the window.
  static std::unique_ptr<RunWindow> open(const std::string& title, const std::string& screenshotPath,
                                         double screenshotTime);
  Camera& camera() { return m_viewer.camera(); }
  /// Draws a step at time (s); false once the run should end (the window closed, the frame written).
  bool show(const WorldView& world, const Overlay& overlay, double time);
  /// The exit status once the run is over: 1 when a screenshot was asked for and not written, which
  /// program says on stderr.
  int finish(const char* program) const;

 private:
  RunWindow(const ViewerSettings& settings, const std::string& screenshotPath, double screenshotTime);

  Viewer m_viewer;
  std::string m_screenshotPath;
  double m_screenshotTime;
  bool m_written = false;
};

}  // namespace thintool::viewer
