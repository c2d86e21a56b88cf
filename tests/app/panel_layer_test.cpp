// The kept panel column (app/viewer/panel_layer.h) against Dear ImGui's frame drawn live: the same
// pixels, headless (EGL), with the column drawn afresh only when what it draws changed.
#include "app/viewer/gl.h"
#include "app/viewer/gl_blit.h"
#include "app/viewer/headless_gl.h"
#include "app/viewer/panel_layer.h"
#include "app/viewer/panels.h"
#include "app/viewer/screenshot.h"
#include "core/settings_io.h"

#include <backends/imgui_impl_opengl3.h>
#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace slime {
namespace {

// The viewer's panels (the column at its clamped minimum width, 250 pixels: an integer edge) and,
// over the image, the Stats window and a grab ring.
class PanelLayerTest : public testing::Test {
 protected:
  static constexpr glm::ivec2 kSize{320, 240};

  void SetUp() override {
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    gl_.initImGuiPlatform();
    ImGui_ImplOpenGL3_Init("#version 330 core");
  }
  void TearDown() override {
    layer_.reset();
    ImGui_ImplOpenGL3_Shutdown();
    gl_.shutdownImGuiPlatform();
    ImGui::DestroyContext();
  }

  // One frame of the panels for `settings` and a scene path; `frames` of them, so that ImGui's layout settles.
  void buildFrames(const Settings& settings, const std::string& scenePath, int frames = 1) {
    for (int i = 0; i < frames; ++i) {
      gl_.newImGuiPlatformFrame();
      ImGui_ImplOpenGL3_NewFrame();
      ImGui::NewFrame();
      Settings draft = settings;
      std::string path = scenePath;
      const PanelView view{stats_, metrics_, noText_, "", {}, noText_};
      column_ = static_cast<int>(std::lround(drawPanels(draft, path, view).columnWidth));
      ImGui::GetForegroundDrawList()->AddCircle(ImVec2(290.0f, 120.0f), 12.0f, IM_COL32(255, 230, 80, 255), 24, 2.0f);
      ImGui::Render();
    }
  }

  // The framebuffer as the viewer leaves it before the panels: the background, an image right of the column.
  void drawBackground() const {
    glDisable(GL_SCISSOR_TEST);
    glClearColor(kViewerBackground[0], kViewerBackground[1], kViewerBackground[2], kViewerBackground[3]);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(column_, 0, kSize.x - column_, kSize.y);
    glClearColor(0.6f, 0.45f, 0.3f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
  }

  // The frame's pixels drawn live (every list), and through the layer with a column this wide.
  std::vector<std::uint8_t> live() const {
    drawBackground();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    return readFramebufferRgb(kSize);
  }
  std::vector<std::uint8_t> layered(int columnPixels) {
    if (!layer_) layer_ = std::make_unique<PanelLayer>();
    drawBackground();
    layer_->draw(*ImGui::GetDrawData(), kSize, columnPixels);
    return readFramebufferRgb(kSize);
  }

  HeadlessGl gl_{kSize.x, kSize.y};
  std::unique_ptr<PanelLayer> layer_;
  FrameStats stats_;
  SlimeMetrics metrics_;
  const std::string noText_;
  int column_ = 0;
};

// Bytes in which two pictures differ.
int differing(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  if (a.size() != b.size()) return static_cast<int>(std::max(a.size(), b.size()));
  int count = 0;
  for (std::size_t i = 0; i < a.size(); ++i) count += a[i] != b[i];
  return count;
}

TEST_F(PanelLayerTest, KeptColumnGivesTheLivePixelsAndIsDrawnAgainOnlyWhenItChanges) {
  const Settings settings = defaultSettings();
  buildFrames(settings, "scene.json", 3);
  ASSERT_EQ(column_, 250);
  const std::vector<std::uint8_t> first = live();
  EXPECT_EQ(differing(layered(column_), first), 0);
  EXPECT_EQ(layer_->columnDraws(), 1);

  buildFrames(settings, "scene.json");  // the same panels again: the column is copied
  EXPECT_EQ(differing(layered(column_), first), 0);
  EXPECT_EQ(layer_->columnDraws(), 1);
  EXPECT_EQ(layer_->columnCopies(), 1);

  buildFrames(settings, "another_scene.json", 3);  // the Scene section's path field changes
  const std::vector<std::uint8_t> second = live();
  EXPECT_GT(differing(second, first), 0);
  EXPECT_EQ(differing(layered(column_), second), 0);
  EXPECT_EQ(layer_->columnDraws(), 2);
}

TEST_F(PanelLayerTest, ListsReachingPastTheColumnAreDrawnLive) {
  buildFrames(defaultSettings(), "scene.json", 3);
  const std::vector<std::uint8_t> expected = live();
  // A column narrower than the window in it: nothing lies wholly inside, everything is drawn live.
  EXPECT_EQ(differing(layered(column_ - 20), expected), 0);
  EXPECT_EQ(layer_->columnDraws() + layer_->columnCopies(), 0);
  EXPECT_EQ(differing(layered(0), expected), 0);  // no column (collapsed)
  EXPECT_EQ(layer_->columnDraws() + layer_->columnCopies(), 0);
}

}  // namespace
}  // namespace slime
