#include "app/viewer/panels.h"

#include "core/settings_fields.h"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <string>
#include <string_view>
#include <thread>
#include <type_traits>

namespace slime {
namespace {

constexpr float kControlsWidth = 250.0f;
constexpr float kStatsWidth = 214.0f;
// Below this display height the sections start closed so that the slime stays in view.
constexpr float kRoomForOpenSections = 500.0f;
constexpr float kMargin = 6.0f;
const ImVec4 kErrorColor{1.0f, 0.45f, 0.35f, 1.0f};

// The allowed interval and words of a setting, from the one table of settings (settings_fields.h).
Limits fieldLimits(std::string_view wanted) {
  Settings scratch;
  Limits found{0.0, 0.0, ""};
  forEachField(scratch, [&](std::string_view key, auto&, const auto& allowed) {
    if constexpr (std::is_same_v<std::decay_t<decltype(allowed)>, Limits>)
      if (key == wanted) found = allowed;
  });
  return found;
}

Choices fieldChoices(std::string_view wanted) {
  Settings scratch;
  Choices found;
  forEachField(scratch, [&](std::string_view key, auto&, const auto& allowed) {
    if constexpr (std::is_same_v<std::decay_t<decltype(allowed)>, Choices>)
      if (key == wanted) found = allowed;
  });
  return found;
}

// A slider over a useful part of the setting's allowed range; Ctrl+click types any value, which the
// viewer then validates against the full range.
bool slider(const char* label, double& value, std::string_view key, double low, double high,
            const char* format = "%.3f", bool logarithmic = false) {
  const Limits limits = fieldLimits(key);
  low = std::max(low, limits.min);
  high = std::min(high, limits.max);
  return ImGui::SliderScalar(label, ImGuiDataType_Double, &value, &low, &high, format,
                             logarithmic ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None);
}

bool slider(const char* label, int& value, std::string_view key, int low, int high) {
  const Limits limits = fieldLimits(key);
  low = std::max(low, static_cast<int>(limits.min));
  high = std::min(high, static_cast<int>(limits.max));
  return ImGui::SliderInt(label, &value, low, high);
}

bool combo(const char* label, std::string& value, std::string_view key) {
  bool changed = false;
  if (ImGui::BeginCombo(label, value.c_str())) {
    for (std::string_view choice : fieldChoices(key)) {
      const bool selected = value == choice;
      if (ImGui::Selectable(std::string(choice).c_str(), selected)) {
        changed = value != choice;
        value = std::string(choice);
      }
      if (selected) ImGui::SetItemDefaultFocus();
    }
    ImGui::EndCombo();
  }
  return changed;
}

bool colorPicker(const char* label, glm::dvec3& color) {
  float rgb[3] = {static_cast<float>(color.r), static_cast<float>(color.g), static_cast<float>(color.b)};
  if (!ImGui::ColorEdit3(label, rgb, ImGuiColorEditFlags_Float)) return false;
  color = {rgb[0], rgb[1], rgb[2]};
  return true;
}

void showError(const PanelView& view, Panel panel) {
  if (view.errorPanel != panel || view.editError.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
  ImGui::TextWrapped("Not applied: %s", view.editError.c_str());
  ImGui::PopStyleColor();
}

bool slimeSection(SlimeSettings& slime, const PanelView& view, PanelRequests& requests) {
  bool edited = colorPicker("colour", slime.color);
  edited |= slider("transmission", slime.transmission, "slime.transmission", 0.0, 1.0, "%.2f");
  edited |= slider("absorption", slime.absorption, "slime.absorption", 0.0, 500.0, "%.1f /m", true);
  edited |= slider("IOR", slime.ior, "slime.ior", 1.0, 3.0, "%.3f");
  edited |= slider("mass", slime.mass, "slime.mass", 0.01, 5.0, "%.3f kg", true);
  edited |= slider("stiffness", slime.stiffness, "slime.stiffness", 1.0, 2000.0, "%.1f N/m", true);
  edited |= slider("damping", slime.damping, "slime.damping", 0.0, 2.0, "%.3f N.s/m", true);
  edited |= slider("pressure", slime.pressure, "slime.pressure", 0.0, 20.0, "%.2f", true);
  edited |= slider("friction", slime.friction, "slime.friction", 0.0, 2.0, "%.2f");
  edited |= slider("rolling", slime.rolling, "slime.rolling", 0.0, 100.0, "%.1f /s", true);
  edited |= slider("level", slime.level, "slime.level", 0, 7);
  edited |= slider("radius", slime.radius, "slime.radius", 0.01, 0.1, "%.3f m");
  if (ImGui::Button("Reload slime")) requests.reloadSlime = true;
  if (view.reloadPending) {
    ImGui::SameLine();
    ImGui::TextDisabled("level/radius: reload");
  }
  showError(view, Panel::Slime);
  return edited;
}

bool renderSection(RenderSettings& render, const PanelView& view) {
  bool edited = slider("depth", render.depth, "render.depth", 1, 16);
  edited |= combo("normals", render.normals, "render.normals");
  edited |= combo("optics", render.optics, "render.optics");
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  edited |= slider("threads", render.threads, "render.threads", 0, cores);
  edited |= slider("scale", render.scale, "render.scale", 0.1, 1.0, "%.2f");
  static constexpr int kSampleCounts[] = {1, 4, 9, 16};
  if (ImGui::BeginCombo("samples", std::to_string(render.spp).c_str())) {
    for (int samples : kSampleCounts)
      if (ImGui::Selectable(std::to_string(samples).c_str(), render.spp == samples)) {
        edited |= render.spp != samples;
        render.spp = samples;
      }
    ImGui::EndCombo();
  }
  edited |= ImGui::Checkbox("shadows", &render.shadows);
  showError(view, Panel::Render);
  return edited;
}

bool simulationSection(SimSettings& sim, const PanelView& view, PanelRequests& requests) {
  bool edited = combo("integrator", sim.integrator, "sim.integrator");
  edited |= slider("dt", sim.dt, "sim.dt", 1e-5, 0.01, "%.5f s", true);
  edited |= slider("time scale", sim.timeScale, "sim.timeScale", 0.01, 10.0, "%.2f", true);
  edited |= ImGui::Checkbox("pause", &sim.paused);
  ImGui::SameLine();
  ImGui::BeginDisabled(!sim.paused);
  if (ImGui::Button("step")) requests.singleStep = true;
  ImGui::EndDisabled();
  ImGui::Text("volume %.3f  height %.1f mm", view.metrics.volumeRatio, view.metrics.height * 1000.0);
  showError(view, Panel::Simulation);
  return edited;
}

void statsWindow(const PanelView& view) {
  const FrameStats& stats = view.stats;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x - kStatsWidth - kMargin, kMargin), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(kStatsWidth, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.75f);
  ImGui::SetNextWindowCollapsed(display.y < kRoomForOpenSections, ImGuiCond_Once);
  if (ImGui::Begin("Stats")) {
    ImGui::Text("%.1f fps   %.1f ms/frame", stats.fps, stats.frameMs);
    ImGui::Text("physics %6.1f ms  %d steps", stats.stages.physics, stats.physicsSteps);
    ImGui::Text("refit   %6.1f ms", stats.stages.refit);
    ImGui::Text("trace   %6.1f ms  %dx%d", stats.stages.trace, stats.imageWidth, stats.imageHeight);
    ImGui::Text("upload  %6.1f ms", stats.stages.upload);
    ImGui::Text("UI      %6.1f ms", stats.stages.ui);
    ImGui::Text("rays    %.2f M/frame", static_cast<double>(stats.rays) / 1e6);
    ImGui::Text("        %.1f Mrays/s", stats.megaraysPerSecond);
    ImGui::Text("reused  %.0f%% of pixels", 100.0 * stats.reusedFraction);
    ImGui::Text("threads %d, %.0f%% busy", stats.traceThreads, 100.0 * stats.threadUse);
    ImGui::Text("sim     x%.2f real time", stats.simulationSpeed);
    ImGui::PlotLines("##frame", stats.frameHistoryMs.data(), FrameStats::kHistory, stats.historyNext,
                     "frame ms", 0.0f, FLT_MAX, ImVec2(kStatsWidth - 16.0f, 40.0f));
  }
  ImGui::End();
}

}  // namespace

PanelRequests drawPanels(Settings& draft, const PanelView& view) {
  PanelRequests requests;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(kMargin, kMargin), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSizeConstraints(ImVec2(kControlsWidth, 0.0f),
                                      ImVec2(kControlsWidth, std::max(display.y - 2.0f * kMargin, 60.0f)));
  ImGui::SetNextWindowBgAlpha(0.75f);
  if (ImGui::Begin("Controls", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::PushItemWidth(kControlsWidth * 0.52f);
    const bool roomy = display.y >= kRoomForOpenSections;
    ImGui::SetNextItemOpen(roomy, ImGuiCond_Once);
    if (ImGui::CollapsingHeader("Slime") && slimeSection(draft.slime, view, requests)) requests.edited = Panel::Slime;
    ImGui::SetNextItemOpen(false, ImGuiCond_Once);
    if (ImGui::CollapsingHeader("Render") && renderSection(draft.render, view)) requests.edited = Panel::Render;
    ImGui::SetNextItemOpen(roomy, ImGuiCond_Once);
    if (ImGui::CollapsingHeader("Simulation") && simulationSection(draft.sim, view, requests))
      requests.edited = Panel::Simulation;
    ImGui::PopItemWidth();
  }
  ImGui::End();
  statsWindow(view);
  return requests;
}

}  // namespace slime
