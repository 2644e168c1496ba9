// nut-viewer's window: GLFW, a fly camera and a Dear ImGui overlay (viewer_window.hpp).
#include "viewer_window.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <nut/png_io.hpp>
#include <viewer/context.hpp>
#include <viewer/mesh_renderer.hpp>
#include <viewer/post_process.hpp>
#include <viewer/render_target.hpp>
#include <viewer/shader_library.hpp>

namespace nut::viewer {

namespace {

// Eye, heading and pitch; W/S along the view, A/D sideways, Q/E down and up, the right mouse
// button held turns, the wheel scales the speed.
struct FlyCamera {
  glm::dvec3 eye{0.0};
  double yaw = 0, pitch = 0;  // radians; yaw 0 looks along +x
  double speedMps = 20;

  explicit FlyCamera(const Camera& c) : eye(c.eye) {
    const glm::dvec3 d = glm::normalize(c.target - c.eye);
    yaw = std::atan2(d.z, d.x);
    pitch = std::asin(std::clamp(d.y, -1.0, 1.0));
    speedMps = std::max(5.0, 0.2 * glm::length(c.target - c.eye));
  }
  glm::dvec3 forward() const {
    return {std::cos(pitch) * std::cos(yaw), std::sin(pitch), std::cos(pitch) * std::sin(yaw)};
  }
  void update(GLFWwindow* window, double seconds, glm::dvec2 mouseDelta, bool overlayWantsInput) {
    const glm::dvec3 f = forward();
    const glm::dvec3 right = glm::normalize(glm::cross(f, glm::dvec3(0, 1, 0)));
    const auto down = [&](int key) { return !overlayWantsInput && glfwGetKey(window, key) == GLFW_PRESS; };
    glm::dvec3 move(0.0);
    if (down(GLFW_KEY_W)) move += f;
    if (down(GLFW_KEY_S)) move -= f;
    if (down(GLFW_KEY_D)) move += right;
    if (down(GLFW_KEY_A)) move -= right;
    if (down(GLFW_KEY_E)) move.y += 1;
    if (down(GLFW_KEY_Q)) move.y -= 1;
    eye += move * speedMps * seconds;
    if (!overlayWantsInput && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) {
      yaw += 0.004 * mouseDelta.x;
      pitch = std::clamp(pitch - 0.004 * mouseDelta.y, -1.5, 1.5);
    }
  }
  Camera camera(const Camera& base) const {
    Camera c = base;
    c.eye = eye;
    c.target = eye + forward();
    return c;
  }
};

double gScroll = 0;  // wheel steps since the last frame (GLFW calls back with no user pointer here)

}  // namespace

int runWindow(const WindowRun& run) {
  const auto fail = [](const std::string& message) {
    std::fprintf(stderr, "error: %s\n", message.c_str());
    return 1;
  };
  ContextOptions window;
  window.windowWidth = run.start.width;
  window.windowHeight = run.start.height;
  window.windowTitle = "nut-viewer: " + run.city.name;
  window.visible = true;
  auto context = createContext(Backend::Glfw, window);
  if (!context) return fail("GL: " + context.error().message);
  GLFWwindow* glfw = (*context)->window();
  const Gl& gl = (*context)->gl();
  const ShaderLibrary library = ShaderLibrary::fromEnvironment();
  auto hni = HniRenderer::create(**context, library);
  if (!hni) return fail(hni.error().message);
  auto fxaa = Fxaa::create(**context, library);
  if (!fxaa) return fail(fxaa.error().message);
  auto meshes = MeshRenderer::create(**context, library);
  if (!meshes) return fail(meshes.error().message);
  CityRenderer renderer(gl, *hni, &*meshes, run.city, run.base, run.fetch, run.options);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini beside the user's files
  ImGui_ImplGlfw_InitForOpenGL(glfw, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  glfwSetScrollCallback(glfw, [](GLFWwindow*, double, double y) { gScroll += y; });
  glfwSwapInterval(0);

  FlyCamera fly(run.start);
  RayCastOptions cast = run.cast;
  bool frustumCulling = run.options.frustumCulling, occlusionCulling = run.options.occlusionCulling,
       frontToBack = run.options.frontToBack, antiAlias = run.fxaa, heatMap = cast.heatMap;
  float lodPx = static_cast<float>(cast.lodPx), summaryPx = static_cast<float>(run.options.summaryBelowPx);
  std::optional<RenderTarget> frame, smoothed;
  CityFrameStats stats;
  nlohmann::json frames = nlohmann::json::array();
  double overlay[4] = {0, 0, 0, 0};
  glm::dvec2 lastMouse(0.0);
  glfwGetCursorPos(glfw, &lastMouse.x, &lastMouse.y);
  auto previous = std::chrono::steady_clock::now();
  double frameMs = 0;
  for (int f = 0; !glfwWindowShouldClose(glfw); ++f) {
    glfwPollEvents();
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - previous).count();
    previous = now;
    glm::dvec2 mouse;
    glfwGetCursorPos(glfw, &mouse.x, &mouse.y);
    fly.speedMps *= std::pow(1.2, gScroll);
    gScroll = 0;
    fly.update(glfw, seconds, mouse - lastMouse, ImGui::GetIO().WantCaptureKeyboard || ImGui::GetIO().WantCaptureMouse);
    lastMouse = mouse;

    int width = 0, height = 0;
    glfwGetFramebufferSize(glfw, &width, &height);
    if (width < 1 || height < 1) continue;  // minimised
    for (auto* target : {&frame, &smoothed})
      if (!*target || (*target)->width() != width || (*target)->height() != height) {
        auto created = RenderTarget::create(gl, width, height);
        if (!created) return fail(created.error().message);
        target->emplace(std::move(*created));
      }
    Camera camera = fly.camera(run.start);
    camera.width = width, camera.height = height;

    const auto start = std::chrono::steady_clock::now();
    frame->bindCleared();
    renderer.setFrustumCulling(frustumCulling);
    renderer.setOcclusionCulling(occlusionCulling);
    renderer.setFrontToBack(frontToBack);
    cast.lodPx = lodPx;
    cast.heatMap = heatMap;
    renderer.setSummaryBelowPx(summaryPx);
    if (Status s = renderer.drawFrame(camera, cast, stats); !s) return fail(s.error().message);
    for (const std::string& failure : stats.newFailures) std::fprintf(stderr, "warning: %s\n", failure.c_str());
    if (antiAlias) fxaa->apply(*frame, *smoothed);
    const RenderTarget& shown = antiAlias ? *smoothed : *frame;
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, shown.framebuffer());
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    gl.BlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Finish();
    frameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
    ImGui::Begin("nut-viewer", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove);
    ImGui::Text("%.1f fps, frame %.2f ms", seconds > 0 ? 1.0 / seconds : 0.0, frameMs);
    ImGui::Text("buildings: %zu known, %zu loaded, %zu failed", stats.known, stats.loaded, stats.failed);
    ImGui::Text("this frame: %zu drawn, culled %zu by frustum and %zu by occlusion, %zu waiting", stats.drawn,
                stats.culledByFrustum, stats.culledByOcclusion, stats.waiting);
    ImGui::Text("streamed %.2f MB, atlas %.0f MB, %zu evicted", stats.bytesStreamed / 1e6, stats.atlasBytes / 1048576.0,
                stats.evicted);
    ImGui::ProgressBar(stats.known ? static_cast<float>(stats.loaded) / static_cast<float>(stats.known) : 1.0f);
    ImGui::Text("as summaries %zu, proxies %zu, complement triangles %zu", stats.asSummary, stats.proxies,
                stats.complementTriangles);
    ImGui::SliderFloat("LOD px (cells)", &lodPx, 0.0f, 16.0f, "%.1f");
    ImGui::SliderFloat("summary px (buildings)", &summaryPx, 0.0f, 64.0f, "%.0f");
    ImGui::Checkbox("frustum culling", &frustumCulling);
    ImGui::SameLine();
    ImGui::Checkbox("occlusion culling", &occlusionCulling);
    ImGui::SameLine();
    ImGui::Checkbox("front to back", &frontToBack);
    ImGui::SameLine();
    ImGui::Checkbox("FXAA", &antiAlias);
    ImGui::SameLine();
    ImGui::Checkbox("heat-map", &heatMap);
    ImGui::Text("W/A/S/D/Q/E move, right mouse turns, wheel: speed %.0f m/s", fly.speedMps);
    const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    overlay[0] = at.x, overlay[1] = at.y, overlay[2] = size.x, overlay[3] = size.y;
    ImGui::End();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    frames.push_back({{"ms", frameMs},
                      {"drawn", stats.drawn},
                      {"culled_frustum", stats.culledByFrustum},
                      {"culled_occlusion", stats.culledByOcclusion},
                      {"waiting", stats.waiting},
                      {"loaded", stats.loaded}});
    const bool last = run.frames > 0 && f + 1 >= run.frames && renderer.settled();
    if (last && !run.screenshot.empty()) {
      gl.Finish();
      Image shot(width, height);
      gl.ReadBuffer(GL_BACK);
      gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
      gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, shot.pixels.data());
      Image flipped(width, height);  // GL reads bottom row first
      for (int y = 0; y < height; ++y) std::copy_n(shot.at(0, height - 1 - y), 4 * width, flipped.at(0, y));
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) flipped.at(x, y)[3] = 255;
      if (Status s = writePng(run.screenshot, flipped); !s) return fail(s.error().message);
    }
    glfwSwapBuffers(glfw);
    if (last) break;
  }
  if (!run.stats.empty()) {
    const nlohmann::json j = {{"frames", frames},
                              {"overlay", {overlay[0], overlay[1], overlay[2], overlay[3]}},
                              {"loaded", stats.loaded},
                              {"failed", stats.failed}};
    if (Status s = writeTextFile(run.stats, j.dump(2) + "\n"); !s) return fail(s.error().message);
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  return 0;
}

}  // namespace nut::viewer
