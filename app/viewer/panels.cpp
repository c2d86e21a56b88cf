#include "app/viewer/panels.h"

#include <imgui.h>
#include <imgui_internal.h>  // TempInputIsActive: a slider in its Ctrl+click text mode
#include <imgui_stdlib.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "app/viewer/adaptive_resolution.h"
#include "app/viewer/panel_fields.h"
#include "core/settings/settings_fields.h"

namespace slime {
namespace {

constexpr float kStatsWidth = 214.0f;
constexpr float kMargin = 6.0f;
const ImVec4 kErrorColor{1.0f, 0.45f, 0.35f, 1.0f};
const ImVec4 kDoneColor{0.55f, 0.9f, 0.55f, 1.0f};

// The unit goes into the slider's number when it is short ("m", "N/m"); longer ones only into the
// tooltip, with the meaning and the range.
std::string numberFormat(const SettingInfo& info, const char* number) {
  std::string format = number;
  if (!info.unit.empty() && info.unit.size() <= 8 && info.unit.find(' ') == std::string::npos)
    format += " " + info.unit;
  return format;
}

void tooltip(const PanelField& field) {
  if (!ImGui::IsItemHovered()) return;
  const SettingInfo& info = field.setting;
  ImGui::BeginTooltip();
  ImGui::TextUnformatted(info.help.c_str());
  ImGui::TextDisabled("key: %s", info.key.c_str());
  std::string allowed = "allowed: " + allowedText(info);
  if (!info.unit.empty()) allowed += " " + info.unit;
  ImGui::TextDisabled("%s", allowed.c_str());
  if (field.appliesOnReload) ImGui::TextDisabled("applies on Reload slime");
  ImGui::EndTooltip();
}

std::string labelOf(const PanelField& field) {
  return field.label + (field.appliesOnReload ? " *" : "") + "##" + field.setting.key;
}

// A number typed into a slider or a component of a three-component field (Ctrl+click) counts when
// the user leaves the field (Enter, Tab, a click elsewhere), not letter by letter: Dear ImGui writes
// the value at every letter, so typing 2000 would apply 2, 20 and 200 on the way. Escape drops it.
// Sliding and dragging still apply at once. Call right after the widget, with what it returned.
template <typename T>
bool typedOnLeaving(bool changed, T& value) {
  static std::unordered_map<ImGuiID, T> typed;  // the panels run on one thread
  const ImGuiID id = ImGui::GetItemID();
  // (An idle group of components ends on its label, an item with no ID: id 0, never typed into.)
  if (id != 0 && ImGui::TempInputIsActive(id)) {
    if (changed) typed[id] = value;
    return false;
  }
  const auto pending = typed.find(id);
  if (pending == typed.end()) return changed;
  const T entered = pending->second;
  typed.erase(pending);
  if (!ImGui::IsItemDeactivated() || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) return false;
  value = entered;
  return true;
}

// One widget per field type; each returns whether the user changed the value this frame.
bool edit(const PanelField& field, double& value) {
  const SettingInfo& info = field.setting;
  const std::string label = labelOf(field), format = numberFormat(info, "%.4g");
  const ImGuiSliderFlags flags =
      field.widget == Widget::LogSlider ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None;
  return typedOnLeaving(
      ImGui::SliderScalar(label.c_str(), ImGuiDataType_Double, &value, &info.min, &info.max, format.c_str(), flags), value);
}

bool edit(const PanelField& field, int& value) {
  const SettingInfo& info = field.setting;
  const std::string label = labelOf(field);
  if (field.widget == Widget::WindowSize) {
    ImGui::BeginDisabled();
    ImGui::InputInt(label.c_str(), &value, 0, 0, ImGuiInputTextFlags_ReadOnly);
    ImGui::EndDisabled();
    return false;
  }
  if (field.widget == Widget::ValueCombo) {
    bool changed = false;
    if (ImGui::BeginCombo(label.c_str(), std::to_string(value).c_str())) {
      for (int choice : info.onlyValues)
        if (ImGui::Selectable(std::to_string(choice).c_str(), value == choice)) {
          changed = value != choice;
          value = choice;
        }
      ImGui::EndCombo();
    }
    return changed;
  }
  const int low = static_cast<int>(info.min), high = static_cast<int>(info.max);
  return typedOnLeaving(ImGui::SliderInt(label.c_str(), &value, low, high, numberFormat(info, "%d").c_str()), value);
}

bool edit(const PanelField& field, glm::dvec3& value) {
  const SettingInfo& info = field.setting;
  const std::string label = labelOf(field);
  // Three components: a component typed after a Ctrl+click counts when the field is left, as a
  // slider's (typedOnLeaving; the group's item is the component being typed).
  if (field.widget == Widget::Color) {
    glm::vec3 rgb{static_cast<float>(value.r), static_cast<float>(value.g), static_cast<float>(value.b)};
    if (!typedOnLeaving(ImGui::ColorEdit3(label.c_str(), &rgb.x, ImGuiColorEditFlags_Float), rgb)) return false;
    value = glm::dvec3(rgb);
    return true;
  }
  // Positions: a millimetre per pixel dragged; intensities a hundredth. Dragging stops at the range;
  // a typed value outside it is not clamped but refused, with the range, as a slider's.
  const float speed = info.unit == "m" ? 0.001f : 0.01f;
  return typedOnLeaving(
      ImGui::DragScalarN(label.c_str(), ImGuiDataType_Double, &value.x, 3, speed, &info.min, &info.max, "%.3f"), value);
}

bool edit(const PanelField& field, std::string& value) {
  const std::string label = labelOf(field);
  if (field.widget == Widget::Text) {
    ImGui::InputText(label.c_str(), &value);
    return ImGui::IsItemDeactivatedAfterEdit();  // applied when the user leaves the field, not per letter
  }
  bool changed = false;
  if (ImGui::BeginCombo(label.c_str(), value.c_str())) {
    for (const std::string& choice : field.setting.choices) {
      const bool selected = value == choice;
      if (ImGui::Selectable(choice.c_str(), selected)) {
        changed = value != choice;
        value = choice;
      }
      if (selected) ImGui::SetItemDefaultFocus();
    }
    ImGui::EndCombo();
  }
  return changed;
}

bool edit(const PanelField& field, bool& value) { return ImGui::Checkbox(labelOf(field).c_str(), &value); }

void showError(const std::string& error) {
  ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
  ImGui::TextWrapped("Not applied: %s", error.c_str());
  ImGui::PopStyleColor();
}

// Every setting of one group, in the table's order; true when one changed. The field an error names
// ("slime.mass: 0 is not allowed ...") is drawn red with the message under it.
// Settings that do nothing to what is on screen are left out and listed in one grey line whose
// tooltip gives each one's key and reason.
bool groupFields(Settings& draft, const std::string& group, const PanelView& view) {
  const std::vector<PanelField>& fields = panelFields();
  const Settings& shown = view.shown != nullptr ? *view.shown : draft;
  std::size_t index = 0;
  bool edited = false, errorShown = false;
  std::vector<std::pair<const PanelField*, std::string>> hidden;
  forEachField(draft, [&](std::string_view key, auto& value, const auto&) {
    const PanelField& field = fields[index++];
    if (field.setting.group() != group || field.setting.key != key) return;
    if (std::string reason = inactiveReason(field, shown); !reason.empty()) {
      hidden.emplace_back(&field, std::move(reason));
      return;
    }
    const bool invalid = !view.editError.empty() && view.editError.rfind(field.setting.key + ":", 0) == 0;
    if (invalid) ImGui::PushStyleColor(ImGuiCol_FrameBg, ImVec4(0.55f, 0.12f, 0.1f, 1.0f));
    edited |= edit(field, value);
    if (invalid) ImGui::PopStyleColor();
    tooltip(field);
    if (invalid) showError(view.editError), errorShown = true;
  });
  if (!errorShown && view.errorGroup == group && !view.editError.empty()) showError(view.editError);
  if (!hidden.empty()) {
    ImGui::TextDisabled("%zu not acting here (hover)", hidden.size());
    if (ImGui::IsItemHovered()) {
      ImGui::BeginTooltip();
      for (const auto& [field, reason] : hidden)
        ImGui::Text("%s (%s): %s", field->label.c_str(), field->setting.key.c_str(), reason.c_str());
      ImGui::EndTooltip();
    }
  }
  return edited;
}

void sceneSection(std::string& scenePath, const PanelView& view, PanelRequests& requests) {
  ImGui::InputText("path##scene", &scenePath);
  if (ImGui::Button("Save (Ctrl+S)")) requests.save = true;
  ImGui::SameLine();
  if (ImGui::Button("Load (Ctrl+O)")) requests.load = true;
  if (view.fileMessage.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, view.fileFailed ? kErrorColor : kDoneColor);
  ImGui::TextWrapped("%s", view.fileMessage.c_str());
  ImGui::PopStyleColor();
}

void slimeExtras(const PanelView& view, PanelRequests& requests) {
  if (ImGui::Button("Reload slime")) requests.reloadSlime = true;
  ImGui::SameLine();
  if (view.reloadPending.empty()) {
    ImGui::TextDisabled("* apply on Reload");
    return;
  }
  std::string pending;
  for (const std::string& key : view.reloadPending)
    pending += (pending.empty() ? "" : ", ") + key.substr(key.find('.') + 1);
  ImGui::PushStyleColor(ImGuiCol_Text, kDoneColor);
  ImGui::TextWrapped("Reload to apply %s", pending.c_str());
  ImGui::PopStyleColor();
}

void simulationExtras(const Settings& draft, const PanelView& view, PanelRequests& requests) {
  ImGui::BeginDisabled(!draft.sim.paused);
  if (ImGui::Button("step")) requests.singleStep = true;
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::Text("volume %.3f  height %.1f mm", view.metrics.volumeRatio, view.metrics.height * 1000.0);
  if (draft.sim.integrator == "auto") ImGui::Text("auto steps with %s", view.integrator.c_str());
  if (draft.slime.tearing || view.pieces > 1)
    ImGui::Text("pieces %zu  (%d %s, %d %s)", view.pieces, view.tears, view.tears == 1 ? "tear" : "tears", view.merges,
                view.merges == 1 ? "merge" : "merges");
}

// The traced image's scale and the adaptive resolution's target frame rate (0: off), which the user
// may change here.
void resolutionRows(const FrameStats& stats, PanelRequests& requests) {
  ImGui::Text("scale   %.2f  %s", stats.renderScale, stats.renderScale < 1.0 ? "(reduced)" : "(full)");
  int target = static_cast<int>(std::lround(stats.targetFps));
  ImGui::SetNextItemWidth(kStatsWidth * 0.5f);
  const int highest = static_cast<int>(AdaptiveResolution::kMaximumTargetFps);
  const char* format = target == 0 ? "off" : "%d fps";
  if (ImGui::SliderInt("target", &target, 0, highest, format, ImGuiSliderFlags_AlwaysClamp))
    requests.targetFps = target;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Adaptive resolution: when frames take longer than 1/target while the view moves,\n"
                      "the image is traced smaller until they fit; full resolution as soon as they do.\n"
                      "0 = off (always full resolution; render.scale still applies).");
}

// Each hand: holding or free, where its part of the surface is, its pull on the body, and a release
// button. Hand 0 is the left-drag's (it lets go with the button); hand 1 the Ctrl+left-drag's, which
// keeps holding where the drag left it.
void handsSection(const PanelView& view, PanelRequests& requests) {
  static constexpr const char* kNames[] = {"hand 0 (left)", "hand 1 (Ctrl+left)"};
  for (std::size_t hand = 0; hand < view.hands.size() && hand < 2; ++hand) {
    const HandView& h = view.hands[hand];
    ImGui::PushID(static_cast<int>(hand));
    if (!h.holding) {
      ImGui::TextDisabled("%s: free", kNames[hand]);
      ImGui::PopID();
      continue;
    }
    ImGui::Text("%s", kNames[hand]);
    ImGui::SameLine();
    if (ImGui::SmallButton("release")) requests.releaseHand = static_cast<int>(hand);
    if (view.pieces > 1) ImGui::Text("  holds piece %zu of %zu", h.piece + 1, view.pieces);
    ImGui::Text("  at %+.1f %+.1f %+.1f cm", 100.0 * h.position.x, 100.0 * h.position.y, 100.0 * h.position.z);
    ImGui::Text("  force %.2f N (%+.1f %+.1f %+.1f)", glm::length(h.force), h.force.x, h.force.y, h.force.z);
    ImGui::PopID();
  }
  ImGui::Text("width %.1f mm", view.metrics.width * 1000.0);
}

void statsWindow(const PanelView& view, PanelRequests& requests) {
  const FrameStats& stats = view.stats;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x - kStatsWidth - kMargin, kMargin), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(kStatsWidth, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.75f);
  ImGui::SetNextWindowCollapsed(true, ImGuiCond_Once);  // the slime first; one click opens it
  if (ImGui::Begin("Stats")) {
    ImGui::Text("%.1f fps   %.1f ms/frame", stats.fps, stats.frameMs);
    ImGui::Text("physics %6.1f ms  %d steps", stats.stages.physics, stats.physicsSteps);
    ImGui::Text("refit   %6.1f ms", stats.stages.refit);
    ImGui::Text("trace   %6.1f ms  %dx%d", stats.stages.trace, stats.imageWidth, stats.imageHeight);
    if (stats.causticPhotons > 0)
      ImGui::Text(" caust. %6.1f ms  %llu photons", stats.stages.caustics, static_cast<unsigned long long>(stats.causticPhotons));
    ImGui::Text("upload  %6.1f ms", stats.stages.upload);
    ImGui::Text("UI      %6.1f ms", stats.stages.ui);
    ImGui::Text("rays    %.2f M/frame", static_cast<double>(stats.rays) / 1e6);
    ImGui::Text("        %.1f M/s all rays,", stats.megaraysPerSecond);
    ImGui::Text("        incl. floor and sky");
    ImGui::Text("reused  %.0f%% of pixels", 100.0 * stats.reusedFraction);
    ImGui::Text("threads %d, %.0f%% busy", stats.traceThreads, 100.0 * stats.threadUse);
    ImGui::Text("sim     x%.2f real time", stats.simulationSpeed);
    // A setting that cannot run in real time here (a fine body, many substeps, a tiny step) slows the
    // slime instead of the window: say so where the figure is.
    if (stats.simulationSpeed > 0.0 && stats.simulationSpeed < 0.9)
      ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.2f, 1.0f), "physics behind real time:\nlower slime.resolution,\nsim.substeps or raise sim.dt");
    resolutionRows(stats, requests);
    ImGui::PlotLines("##frame", stats.frameHistoryMs.data(), FrameStats::kHistory, stats.historyNext,
                     "frame ms", 0.0f, FLT_MAX, ImVec2(kStatsWidth - 16.0f, 40.0f));
  }
  ImGui::End();
}

}  // namespace

float panelColumnWidth(float displayWidth) { return std::clamp(displayWidth * 0.26f, 250.0f, 340.0f); }

PanelRequests drawPanels(Settings& draft, std::string& scenePath, const PanelView& view) {
  PanelRequests requests;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float width = panelColumnWidth(display.x);
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(width, display.y), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.9f);
  const ImGuiWindowFlags flags =
      ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings;
  // No border: the column meets the image edge to edge, and ImGui draws a window's border line up to
  // a pixel past its right edge, onto the image's first column (and out of the kept column that
  // app/viewer/panel_layer.h copies instead of drawing it every frame).
  ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.0f);
  const bool open = ImGui::Begin("Controls (F1: help)", nullptr, flags);
  ImGui::PopStyleVar();
  if (open) {
    requests.columnWidth = width;
    ImGui::PushItemWidth(width * 0.45f);  // the rest for labels in words ("long-term fraction")
    ImGui::SetNextItemOpen(true, ImGuiCond_Once);
    if (ImGui::CollapsingHeader("Scene file")) sceneSection(scenePath, view, requests);
    for (const PanelGroup& group : panelGroups()) {
      ImGui::SetNextItemOpen(group.name == "slime" || group.name == "sim", ImGuiCond_Once);
      if (!ImGui::CollapsingHeader(group.title.c_str())) continue;
      ImGui::PushID(group.name.c_str());
      if (groupFields(draft, group.name, view)) requests.editedGroup = group.name;
      if (group.name == "slime") slimeExtras(view, requests);
      if (group.name == "sim") simulationExtras(draft, view, requests);
      ImGui::PopID();
    }
    // Last, so that it moves none of the sections above when it grows.
    ImGui::SetNextItemOpen(true, ImGuiCond_Once);
    if (ImGui::CollapsingHeader("Hands")) handsSection(view, requests);
    ImGui::PopItemWidth();
  }
  ImGui::End();
  statsWindow(view, requests);
  return requests;
}

void drawHelpOverlay(float columnWidth) {
  static constexpr const char* kControls[][2] = {
      {"left drag", "grab and stretch the slime (hand 0; lets go on release)"},
      {"Ctrl + left drag", "second hand (1): grab, drag, and it keeps holding"},
      {"Ctrl + click off the slime", "let the second hand go (or Hands > release)"},
      {"Shift + drag, or wheel, while grabbing", "press the grab point into the body"},
      {"right drag", "orbit around the slime"},
      {"middle drag", "pan"},
      {"wheel", "zoom towards the slime"},
      {"W / S", "camera forward / back"},
      {"A / D", "camera left / right"},
      {"Q / E", "turn left / right"},
      {"R / F", "tilt up / down"},
      {"Ctrl+S", "save the scene to the path in Scene file"},
      {"Ctrl+O", "load the scene at that path"},
      {"F12", "screenshot"},
      {"F1 or H", "show / hide this help"},
      {"Esc", "quit"},
  };
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(columnWidth + (display.x - columnWidth) * 0.5f, display.y * 0.5f),
                          ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoCollapse;
  if (ImGui::Begin("Help (F1 or H closes)", nullptr, flags)) {
    if (ImGui::BeginTable("controls", 2)) {
      for (const auto& [keys, action] : kControls) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(keys);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(action);
      }
      ImGui::EndTable();
    }
    ImGui::TextDisabled("Settings marked * apply when you press Reload slime.");
  }
  ImGui::End();
}

}  // namespace slime
