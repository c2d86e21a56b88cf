// The viewer's panel column and overlay: what the panels are shown (the hands, the grab marks), the
// requests they return, and how an edited setting takes effect (at once, or on Reload).
#include "app/viewer/viewer.h"

#include "app/viewer/panel_fields.h"
#include "core/settings/settings_io.h"

#include <imgui.h>

namespace slime {

// --- panels ----------------------------------------------------------------------------------------

Viewer::GrabMarks Viewer::grabMarks() const {
  GrabMarks marks;
  const glm::ivec2 size = viewSize();
  for (int hand = 0; hand < kHands; ++hand) {
    GrabMark& mark = marks.hands[hand];
    if (grab_.active() && cursorHand_ == hand && size.x > 0 && size.y > 0)
      mark.target = grab_.target(makeCamera(settings_.camera, size.x, size.y), size);
    else if (simulation_.grabbing(hand))  // the kept second hand, or a scenario's grab
      mark.target = simulation_.grabTarget(hand);
    if (mark.target) mark.held = simulation_.grabbedPoint(hand);
  }
  marks.views = handViews();
  marks.pieces = simulation_.pieceCount();
  marks.tears = simulation_.tears();
  marks.merges = simulation_.merges();
  return marks;
}

std::vector<HandView> Viewer::handViews() const {
  std::vector<HandView> views(kHands);
  for (int hand = 0; hand < kHands; ++hand) {
    views[hand].holding = simulation_.grabbing(hand);
    if (!views[hand].holding) continue;
    views[hand].position = simulation_.grabbedPoint(hand);
    views[hand].target = simulation_.grabTarget(hand);
    views[hand].force = simulation_.handForce(hand);
    views[hand].piece = simulation_.handPieceIndex(hand);
  }
  return views;
}

PanelRequests Viewer::drawPanelsAndOverlay(const GrabMarks& marks) {
  const Stopwatch uiTime;
  // The panels edit a draft of what is in force. A refused edit is not kept in it: its field shows
  // the value in force, red, with the message naming what was refused; every other field can still
  // be edited (a kept invalid value made every later edit fail on it).
  draft_ = settings_;
  copyReloadFields(wanted_, draft_);
  PanelView view{stats_,       metrics_,    editError_, errorGroup_, differingReloadFields(draft_, built_),
                 fileMessage_, fileFailed_, &settings_, marks.views, integratorName(simulation_.integrator())};
  view.pieces = marks.pieces;
  view.tears = marks.tears;
  view.merges = marks.merges;
  const PanelRequests requests = drawPanels(draft_, scenePath_, view);
  if (showHelp_) drawHelpOverlay(requests.columnWidth);

  // Each hand's grab spot: a ring at its target (hand 0 yellow, hand 1 cyan with a square inside),
  // a line from where its grabbed points are.
  const glm::ivec2 size = viewSize();
  for (int hand = 0; hand < kHands; ++hand) {
    const GrabMark& mark = marks.hands[hand];
    if (!mark.target || size.x <= 0 || size.y <= 0) continue;
    const Camera camera = makeCamera(settings_.camera, size.x, size.y);
    ImDrawList* overlay = ImGui::GetForegroundDrawList();
    const auto target = projectToWindow(camera, *mark.target, size);
    const auto held = projectToWindow(camera, mark.held, size);
    const float left = columnWidth_;
    const ImU32 colour = hand == 0 ? IM_COL32(255, 230, 80, 255) : IM_COL32(80, 220, 255, 255);
    if (target && held)
      overlay->AddLine(ImVec2(left + float(held->x), float(held->y)), ImVec2(left + float(target->x), float(target->y)),
                       IM_COL32(255, 255, 255, 160), 1.5f);
    if (target) {
      const ImVec2 centre(left + float(target->x), float(target->y));
      overlay->AddCircle(centre, 9.0f, colour, 24, 2.0f);
      if (hand == 0) {
        overlay->AddCircleFilled(centre, 2.5f, colour);
      } else {
        overlay->AddRectFilled(ImVec2(centre.x - 3.0f, centre.y - 3.0f), ImVec2(centre.x + 3.0f, centre.y + 3.0f), colour);
      }
    }
  }
  ImGui::Render();
  stats_.stages.ui = uiTime.milliseconds();
  return requests;
}

void Viewer::applyPanelRequests(const PanelRequests& requests) {
  if (!requests.editedGroup.empty()) applyEdit(requests.editedGroup);
  if (requests.reloadSlime) reloadSlime();
  if (requests.singleStep) singleStepPending_ = true;
  if (requests.releaseHand >= 0 && requests.releaseHand < kHands) {
    if (grab_.active() && cursorHand_ == requests.releaseHand) grab_.end();
    simulation_.release(requests.releaseHand);
  }
  if (requests.save) saveScene();
  if (requests.load) loadScene();
  if (requests.columnWidth != columnWidth_) {  // the column opened or closed: the image takes the rest
    columnWidth_ = requests.columnWidth;
    sceneChanged_ = true;
  }
  if (requests.targetFps >= 0) settings_.render.targetFps = requests.targetFps;
  followTargetFps();  // the Stats window's field, the Render panel's, or a loaded scene's
}

// A valid edit applies at once, except the rebuild-type settings (level, radius, ...): they wait in
// wanted_ for Reload, so dragging the level slider does not rebuild the slime every frame.
void Viewer::applyEdit(const std::string& group) {
  try {
    checkSettings(draft_, settings_);
  } catch (const SettingsError& error) {
    editError_ = error.what();  // shown in the panel; the settings keep their last valid value
    editErrors_.push_back(editError_);
    errorGroup_ = group;
    return;
  }
  editError_.clear();
  errorGroup_.clear();
  wanted_ = draft_;
  settings_ = draft_;
  copyReloadFields(built_, settings_);
  simulation_.applySettings(settings_);
  sceneChanged_ = true;
  editedFrame_ = stats_.frames;
  editDrawnFrame_ = stats_.frames + 1;
}

void Viewer::reloadSlime() {
  if (grab_.active()) grab_.end();
  copyReloadFields(wanted_, settings_);
  built_ = settings_;
  simulation_.reload(settings_);
  sceneChanged_ = true;
  clock_.reset();
  slimeMoved_ = true;
  drawnPositions_.clear();  // a new mesh: draw it whatever it moved
  landed_ = false;
  metrics_ = simulation_.metrics();
}

}  // namespace slime
