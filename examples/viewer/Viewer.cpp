// SPDX-License-Identifier: Zlib
// Copyright (c) 2026 The ThinTool developers
#include "Viewer.h"

#include "tool/ToolModel.h"

#include <thintool/bullet/Convert.h>
#include <thintool/bullet/Tool.h>

#include <BulletSoftBody/btDeformableMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#define GL_SILENCE_DEPRECATION
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace thintool::viewer {

namespace {

// The light comes from over the viewer's shoulder; faces are lit by hand (flat shading), so the
// fixed-function lighting stays off.
const btVector3 kLight = btVector3(0.4f, 1.0f, 0.6f).normalized();

void setColour(const std::array<unsigned char, 3>& rgb, float shade = 1) {
  glColor3f(rgb[0] / 255.f * shade, rgb[1] / 255.f * shade, rgb[2] / 255.f * shade);
}

float shadeOf(const btVector3& normal) {
  // Two-sided: a face seen from behind is lit like its front.
  return 0.55f + 0.45f * std::abs(float(normal.dot(kLight)));
}

void vertex(const btVector3& p) { glVertex3f(float(p.x()), float(p.y()), float(p.z())); }

// The column-major matrices OpenGL wants.
void perspective(float fovY, float aspect, float zNear, float zFar, float* m) {
  const float f = 1 / std::tan(fovY / 2);
  std::fill(m, m + 16, 0.f);
  m[0] = f / aspect;
  m[5] = f;
  m[10] = (zFar + zNear) / (zNear - zFar);
  m[11] = -1;
  m[14] = 2 * zFar * zNear / (zNear - zFar);
}

void lookAt(const btVector3& eye, const btVector3& target, float* m) {
  const btVector3 forward = (target - eye).normalized();
  const btVector3 side = forward.cross(btVector3(0, 1, 0)).normalized();
  const btVector3 up = side.cross(forward);
  const float rows[3][3] = {{float(side.x()), float(side.y()), float(side.z())},
                            {float(up.x()), float(up.y()), float(up.z())},
                            {float(-forward.x()), float(-forward.y()), float(-forward.z())}};
  std::fill(m, m + 16, 0.f);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m[c * 4 + r] = rows[r][c];
  }
  m[12] = -(rows[0][0] * float(eye.x()) + rows[0][1] * float(eye.y()) + rows[0][2] * float(eye.z()));
  m[13] = -(rows[1][0] * float(eye.x()) + rows[1][1] * float(eye.y()) + rows[1][2] * float(eye.z()));
  m[14] = -(rows[2][0] * float(eye.x()) + rows[2][1] * float(eye.y()) + rows[2][2] * float(eye.z()));
  m[15] = 1;
}

void drawBox(const btTransform& pose, const btVector3& half) {
  static const int kFaces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  btVector3 corners[8];
  for (int i = 0; i < 8; ++i) {
    corners[i] = pose * btVector3((i & 4) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                                  (i & 1) ? half.z() : -half.z());
  }
  glBegin(GL_QUADS);
  for (const auto& face : kFaces) {
    const btVector3 normal = (corners[face[1]] - corners[face[0]]).cross(corners[face[2]] - corners[face[0]]);
    setColour(Palette::tool, normal.length2() > 0 ? shadeOf(normal.normalized()) : 1);
    for (int k : face) vertex(corners[k]);
  }
  glEnd();
}

void drawShape(const btCollisionShape* shape, const btTransform& pose) {
  if (const auto* box = dynamic_cast<const btBoxShape*>(shape)) {
    drawBox(pose, box->getHalfExtentsWithMargin());
  } else if (const auto* compound = dynamic_cast<const btCompoundShape*>(shape)) {
    for (int i = 0; i < compound->getNumChildShapes(); ++i) {
      drawShape(compound->getChildShape(i), pose * compound->getChildTransform(i));
    }
  }
}

// Dear ImGui's draw lists, with fixed-function OpenGL: our own few lines in place of a backend.
void renderImGui(ImDrawData* data) {
  glPushAttrib(GL_ENABLE_BIT | GL_TRANSFORM_BIT | GL_TEXTURE_BIT);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glEnable(GL_SCISSOR_TEST);
  glEnable(GL_TEXTURE_2D);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glMatrixMode(GL_PROJECTION);
  glPushMatrix();
  glLoadIdentity();
  glOrtho(data->DisplayPos.x, data->DisplayPos.x + data->DisplaySize.x, data->DisplayPos.y + data->DisplaySize.y,
          data->DisplayPos.y, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glPushMatrix();
  glLoadIdentity();
  const float height = data->DisplaySize.y;
  for (int n = 0; n < data->CmdListsCount; ++n) {
    const ImDrawList* list = data->CmdLists[n];
    const ImDrawVert* vertices = list->VtxBuffer.Data;
    const char* base = reinterpret_cast<const char*>(vertices);
    glVertexPointer(2, GL_FLOAT, sizeof(ImDrawVert), base + offsetof(ImDrawVert, pos));
    glTexCoordPointer(2, GL_FLOAT, sizeof(ImDrawVert), base + offsetof(ImDrawVert, uv));
    glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(ImDrawVert), base + offsetof(ImDrawVert, col));
    for (const ImDrawCmd& cmd : list->CmdBuffer) {
      const ImVec4& clip = cmd.ClipRect;
      glScissor(int(clip.x), int(height - clip.w), int(clip.z - clip.x), int(clip.w - clip.y));
      glBindTexture(GL_TEXTURE_2D, GLuint(reinterpret_cast<std::intptr_t>(cmd.GetTexID())));
      glDrawElements(GL_TRIANGLES, GLsizei(cmd.ElemCount), sizeof(ImDrawIdx) == 2 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT,
                     list->IdxBuffer.Data + cmd.IdxOffset);
    }
  }
  glPopMatrix();
  glMatrixMode(GL_PROJECTION);
  glPopMatrix();
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_TEXTURE_COORD_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glPopAttrib();
}

}  // namespace

btVector3 Camera::eye() const {
  const float c = std::cos(pitch);
  return target + btVector3(c * std::sin(yaw), std::sin(pitch), c * std::cos(yaw)) * distance;
}

bool Camera::project(const btVector3& world, int width, int height, float& x, float& y) const {
  float projection[16], view[16];
  perspective(fieldOfView, float(width) / float(height), 0.05f, 200.f, projection);
  lookAt(eye(), target, view);
  const float p[4] = {float(world.x()), float(world.y()), float(world.z()), 1};
  float v[4] = {0, 0, 0, 0}, c[4] = {0, 0, 0, 0};
  for (int r = 0; r < 4; ++r) {
    for (int k = 0; k < 4; ++k) v[r] += view[k * 4 + r] * p[k];
  }
  for (int r = 0; r < 4; ++r) {
    for (int k = 0; k < 4; ++k) c[r] += projection[k * 4 + r] * v[k];
  }
  if (!(c[3] > 0)) return false;
  x = (c[0] / c[3] * 0.5f + 0.5f) * float(width);
  y = (0.5f - c[1] / c[3] * 0.5f) * float(height);
  return true;
}

Viewer::Viewer(const ViewerSettings& settings) {
  if (glfwInit() != GLFW_TRUE) {
    const char* reason = nullptr;
    glfwGetError(&reason);
    throw std::runtime_error(std::string("viewer: GLFW cannot start (") + (reason ? reason : "no reason given") +
                             "; no display? run under xvfb-run)");
  }
  glfwWindowHint(GLFW_VISIBLE, settings.visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
  m_window = glfwCreateWindow(settings.width, settings.height, settings.title.c_str(), nullptr, nullptr);
  if (m_window == nullptr) {
    glfwTerminate();
    throw std::runtime_error("viewer: no OpenGL 2.1 window could be opened");
  }
  glfwMakeContextCurrent(m_window);
  glfwSwapInterval(settings.visible ? 1 : 0);
  glfwSetWindowUserPointer(m_window, this);
  glfwSetKeyCallback(m_window, &Viewer::onKey);
  glfwSetScrollCallback(m_window, &Viewer::onScroll);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // nothing written next to the user's files
  unsigned char* pixels = nullptr;
  int width = 0, height = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(texture)));
  m_imgui = true;
  m_lastTime = glfwGetTime();
}

Viewer::~Viewer() {
  if (m_imgui) ImGui::DestroyContext();
  glfwDestroyWindow(m_window);
  glfwTerminate();
}

int Viewer::width() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(m_window, &w, &h);
  return w;
}

int Viewer::height() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(m_window, &w, &h);
  return h;
}

bool Viewer::keyDown(int key) const { return glfwGetKey(m_window, key) == GLFW_PRESS; }

void Viewer::onKey(GLFWwindow* window, int key, int, int action, int) {
  auto* self = static_cast<Viewer*>(glfwGetWindowUserPointer(window));
  if (action == GLFW_PRESS) self->m_keysThisFrame.push_back(key);
}

void Viewer::onScroll(GLFWwindow* window, double, double dy) {
  auto* self = static_cast<Viewer*>(glfwGetWindowUserPointer(window));
  self->m_camera.distance = std::clamp(self->m_camera.distance * float(std::pow(0.9, dy)), 0.5f, 100.f);
}

void Viewer::handleMouse() {
  double x = 0, y = 0;
  glfwGetCursorPos(m_window, &x, &y);
  const bool down = glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS &&
                    !ImGui::GetIO().WantCaptureMouse;
  if (down && m_dragging) {
    m_camera.yaw -= float(x - m_lastMouseX) * 0.01f;
    m_camera.pitch = std::clamp(m_camera.pitch + float(y - m_lastMouseY) * 0.01f, -1.5f, 1.5f);
  }
  m_dragging = down;
  const bool right = glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  if (right && m_rightDragging) {
    m_rightDragX += x - m_lastMouseX;
    m_rightDragY += y - m_lastMouseY;
  }
  m_rightDragging = right;
  m_lastMouseX = x;
  m_lastMouseY = y;
}

btVector3 Viewer::takeRightDrag(float metresPerPixel) {
  // Screen right is the camera's right; screen down comes towards the camera, both horizontal.
  const btVector3 towardsCamera(std::sin(m_camera.yaw), 0, std::cos(m_camera.yaw));
  const btVector3 right = btVector3(0, 1, 0).cross(towardsCamera);
  const btVector3 move = (right * btScalar(m_rightDragX) + towardsCamera * btScalar(m_rightDragY)) * metresPerPixel;
  m_rightDragX = m_rightDragY = 0;
  return move;
}

WorldView::WorldView(const btSoftRigidDynamicsWorld& world) : objects(world), softBodies(world.getSoftBodyArray()) {}

WorldView::WorldView(const btSoftMultiBodyDynamicsWorld& world)
    : objects(world), softBodies(world.getSoftBodyArray()) {}

WorldView::WorldView(const btDeformableMultiBodyDynamicsWorld& world)
    : objects(world), softBodies(world.getSoftBodyArray()) {}

WorldView::WorldView(const btCollisionWorld& world, const btAlignedObjectArray<btSoftBody*>& worldSoftBodies)
    : objects(world), softBodies(worldSoftBodies) {}

void Viewer::drawWorld(const WorldView& world, const Overlay& overlay) const {
  const int w = width(), h = height();
  glViewport(0, 0, w, h);
  setColour(Palette::background);
  glClearColor(Palette::background[0] / 255.f, Palette::background[1] / 255.f, Palette::background[2] / 255.f, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  float projection[16], view[16];
  perspective(m_camera.fieldOfView, float(w) / float(std::max(h, 1)), 0.05f, 200.f, projection);
  lookAt(m_camera.eye(), m_camera.target, view);
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixf(projection);
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixf(view);

  // The ground: a large quad at y = 0 under the scene.
  setColour(Palette::ground);
  glBegin(GL_QUADS);
  const btVector3& t = m_camera.target;
  for (const auto& c : {btVector3(-8, 0, -8), btVector3(-8, 0, 8), btVector3(8, 0, 8), btVector3(8, 0, -8)}) {
    vertex(btVector3(t.x() + c.x(), 0, t.z() + c.z()));
  }
  glEnd();

  // Soft bodies: faces, then their wireframe slightly in front.
  const btSoftBodyArray& softBodies = world.softBodies;
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1, 1);
  for (int b = 0; b < softBodies.size(); ++b) {
    const btSoftBody& body = *softBodies[b];
    glBegin(GL_TRIANGLES);
    for (int f = 0; f < body.m_faces.size(); ++f) {
      const btSoftBody::Face& face = body.m_faces[f];
      const btVector3 n = (face.m_n[1]->m_x - face.m_n[0]->m_x).cross(face.m_n[2]->m_x - face.m_n[0]->m_x);
      setColour(Palette::softBody, n.length2() > 0 ? shadeOf(n.normalized()) : 1);
      for (int k = 0; k < 3; ++k) vertex(face.m_n[k]->m_x);
    }
    glEnd();
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  glColor3f(0.35f, 0.18f, 0.16f);
  glBegin(GL_LINES);
  for (int b = 0; b < softBodies.size(); ++b) {
    const btSoftBody& body = *softBodies[b];
    for (int l = 0; l < body.m_links.size(); ++l) {
      vertex(body.m_links[l].m_n[0]->m_x);
      vertex(body.m_links[l].m_n[1]->m_x);
    }
  }
  glEnd();

  // Rigid bodies with box shapes: the tools (the ground is drawn above).
  const btCollisionObjectArray& objects = world.objects.getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) {
    const btCollisionObject* object = objects[i];
    // Bullet flags a kinematic body static too (mass 0): only the ground is left out.
    if (btSoftBody::upcast(object) != nullptr || (object->isStaticObject() && !object->isKinematicObject())) continue;
    if ((object->getCollisionFlags() & btCollisionObject::CF_NO_CONTACT_RESPONSE) != 0) continue;
    drawShape(object->getCollisionShape(), object->getWorldTransform());
  }

  // Each tool's sample nodes, red where they collide, and the force on it (0.1 m per newton, at
  // most a metre).
  glDisable(GL_DEPTH_TEST);
  glPointSize(4);
  for (Tool* tool : overlay.tools) {
    const ToolStepReport& report = tool->report();
    const btTransform body = tool->body().getWorldTransform();
    std::vector<std::uint8_t> hit;
    glBegin(GL_POINTS);
    for (Index piece = 0; piece < tool->pieceCount(); ++piece) {
      const ToolModel& model = tool->piece(piece);
      hit.assign(model.nodeCount(), 0);
      for (const ToolContact& c : report.contacts) {
        if (c.piece == piece && c.contact.toolNode < model.nodeCount()) hit[c.contact.toolNode] = 1;
      }
      for (const ToolExcludedNode& e : report.excludedNodes) {
        if (e.piece == piece && e.toolNode < model.nodeCount()) hit[e.toolNode] = std::uint8_t(1 + e.check);
      }
      const btTransform pieceFrame = body * toTransform(tool->pieceTransform(piece));
      for (Index n = 0; n < model.nodeCount(); ++n) {
        // Colliding red, excluded by check 1 orange, by check 2 violet, the others dark grey.
        static const float kNodeColours[4][3] = {{0.2f, 0.2f, 0.25f}, {0.9f, 0.1f, 0.1f}, {1.0f, 0.6f, 0.0f},
                                                 {0.6f, 0.2f, 0.9f}};
        glColor3fv(kNodeColours[hit[n]]);
        vertex(pieceFrame * toBt(model.positions[n]));
      }
    }
    glEnd();
    const Vec3 force = report.contactForce.faces.empty() ? report.wrench.force : report.contactForce.force;
    glLineWidth(3);
    glColor3f(0.1f, 0.6f, 0.2f);
    glBegin(GL_LINES);
    vertex(body.getOrigin());
    const btVector3 arrow = toBt(force) * btScalar(0.1);
    vertex(body.getOrigin() + (arrow.length() > 1 ? arrow.normalized() : arrow));
    glEnd();
    glLineWidth(1);
  }
  glLineWidth(4);
  glColor3ub(Palette::arrow[0], Palette::arrow[1], Palette::arrow[2]);
  glBegin(GL_LINES);
  for (const auto& arrow : overlay.arrows) {
    vertex(arrow[0]);
    vertex(arrow[1]);
  }
  glEnd();
  glLineWidth(1);
  glEnable(GL_DEPTH_TEST);
}

void Viewer::drawPanel(const Overlay& overlay) {
  ImGuiIO& io = ImGui::GetIO();
  int w = 0, h = 0;
  glfwGetWindowSize(m_window, &w, &h);
  io.DisplaySize = ImVec2(float(w), float(h));
  const double now = glfwGetTime();
  io.DeltaTime = float(std::max(now - m_lastTime, 1e-4));
  m_lastTime = now;
  double x = 0, y = 0;
  glfwGetCursorPos(m_window, &x, &y);
  io.MousePos = ImVec2(float(x), float(y));
  io.MouseDown[0] = glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  ImGui::NewFrame();
  ImGui::SetNextWindowPos(ImVec2(8, 8));
  ImGui::Begin("ThinTool", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove);
  for (const std::string& line : overlay.panelLines) ImGui::TextUnformatted(line.c_str());
  ImGui::End();
  ImGui::Render();
  renderImGui(ImGui::GetDrawData());
}

void Viewer::render(const WorldView& world, const Overlay& overlay) {
  drawWorld(world, overlay);
  drawPanel(overlay);
  glFinish();
}

bool Viewer::renderToFile(const WorldView& world, const Overlay& overlay, const std::string& path) {
  for (int settle = 0; settle < 2; ++settle) {
    render(world, overlay);
    present();
  }
  render(world, overlay);
  return screenshot(path);
}

bool Viewer::present() {
  glfwSwapBuffers(m_window);
  glfwPollEvents();
  m_keysPressed.swap(m_keysThisFrame);
  m_keysThisFrame.clear();
  handleMouse();
  return glfwWindowShouldClose(m_window) == GLFW_FALSE;
}

bool Viewer::screenshot(const std::string& path) const {
  const int w = width(), h = height();
  std::vector<unsigned char> pixels(std::size_t(w) * std::size_t(h) * 3);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  stbi_flip_vertically_on_write(1);  // OpenGL's rows run bottom-up
  return stbi_write_png(path.c_str(), w, h, 3, pixels.data(), w * 3) != 0;
}

std::unique_ptr<RunWindow> RunWindow::open(const std::string& title, const std::string& screenshotPath,
                                           double screenshotTime) {
  ViewerSettings settings;
  settings.visible = screenshotPath.empty();
  settings.title = title;
  try {
    return std::unique_ptr<RunWindow>(new RunWindow(settings, screenshotPath, screenshotTime));
  } catch (const std::runtime_error& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return nullptr;
  }
}

RunWindow::RunWindow(const ViewerSettings& settings, const std::string& screenshotPath, double screenshotTime)
    : m_viewer(settings), m_screenshotPath(screenshotPath), m_screenshotTime(screenshotTime) {}

bool RunWindow::show(const WorldView& world, const Overlay& overlay, double time) {
  if (m_screenshotPath.empty()) return m_viewer.frame(world, overlay);
  if (time < m_screenshotTime) return true;
  m_written = m_viewer.renderToFile(world, overlay, m_screenshotPath);
  return false;
}

int RunWindow::finish(const char* program) const {
  if (m_screenshotPath.empty()) return 0;
  if (!m_written) {
    std::fprintf(stderr, "%s: cannot write %s\n", program, m_screenshotPath.c_str());
    return 1;
  }
  std::printf("wrote %s\n", m_screenshotPath.c_str());
  return 0;
}

}  // namespace thintool::viewer
