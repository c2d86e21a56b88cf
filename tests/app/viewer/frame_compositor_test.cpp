// The viewer's picture composed by FrameCompositor (app/viewer/frame_compositor.h) against the frame
// drawn whole and live (the background, the image, every one of Dear ImGui's lists): the same pixels,
// headless (EGL), when the compositor draws into a framebuffer that keeps its pixels and draws again
// only what changed, and with the panel column drawn afresh only when what it draws changed.
#include "app/viewer/frame_compositor.h"
#include "app/viewer/gl.h"
#include "app/viewer/imgui_gl.h"
#include "app/viewer/gl_blit.h"
#include "app/viewer/headless_gl.h"
#include "app/viewer/panels.h"
#include "app/viewer/screenshot.h"
#include "core/settings/settings_io.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace slime {
namespace {

// An image with a different colour in every pixel (so a misplaced pixel shows), brighter where `tint`.
std::vector<std::uint8_t> testImage(glm::ivec2 size, PixelRect tint = {}, int shift = 0) {
  std::vector<std::uint8_t> rgba(4 * static_cast<std::size_t>(size.x) * size.y);
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) {
      const bool tinted = x >= tint.x0 && x < tint.x1 && y >= tint.y0 && y < tint.y1;
      std::uint8_t* pixel = &rgba[4 * (static_cast<std::size_t>(y) * size.x + x)];
      pixel[0] = static_cast<std::uint8_t>(x * 7 + (tinted ? shift : 0));
      pixel[1] = static_cast<std::uint8_t>(y * 5);
      pixel[2] = static_cast<std::uint8_t>(x * y + (tinted ? 2 * shift : 0));
      pixel[3] = 255;
    }
  return rgba;
}

// The viewer's panels (the column at its clamped minimum width, 250 pixels) and, over the image, the
// Stats window and a grab ring.
class FrameCompositorTest : public testing::Test {
 protected:
  static constexpr glm::ivec2 kSize{480, 270};
  static constexpr long long kWhole = static_cast<long long>(kSize.x) * kSize.y;

  void SetUp() override {
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    gl_.initImGuiPlatform();
    initImGuiGl();
    // The live frame's own framebuffer; the compositor's is the back-end's, which keeps its pixels.
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &keptFramebuffer_);
    glGenFramebuffers(1, &liveFramebuffer_);
    glGenRenderbuffers(1, &liveColor_);
    glBindFramebuffer(GL_FRAMEBUFFER, liveFramebuffer_);
    glBindRenderbuffer(GL_RENDERBUFFER, liveColor_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, kSize.x, kSize.y);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, liveColor_);
    ASSERT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), static_cast<GLenum>(GL_FRAMEBUFFER_COMPLETE));
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(keptFramebuffer_));
    compositor_ = std::make_unique<FrameCompositor>();
    liveBlit_ = std::make_unique<GlBlit>();
  }
  void TearDown() override {
    compositor_.reset();
    liveBlit_.reset();
    glDeleteRenderbuffers(1, &liveColor_);
    glDeleteFramebuffers(1, &liveFramebuffer_);
    shutdownImGuiGl();
    gl_.shutdownImGuiPlatform();
    ImGui::DestroyContext();
  }

  // One frame of the panels for `settings` and a scene path, with the ring at `ring` if given;
  // `frames` of them, so that ImGui's layout settles.
  void buildFrames(const Settings& settings, const std::string& scenePath, std::optional<ImVec2> ring, int frames = 1) {
    for (int i = 0; i < frames; ++i) {
      gl_.newImGuiPlatformFrame();
      newImGuiGlFrame();
      ImGui::NewFrame();
      Settings draft = settings;
      std::string path = scenePath;
      const PanelView view{stats_, metrics_, noText_, "", {}, noText_};
      column_ = static_cast<int>(std::lround(drawPanels(draft, path, view).columnWidth));
      if (ring) ImGui::GetForegroundDrawList()->AddCircle(*ring, 12.0f, IM_COL32(255, 230, 80, 255), 24, 2.0f);
      ImGui::Render();
    }
  }

  // The image, to both: the compositor takes the pixels `changed`, the live blit all of them.
  void upload(const std::vector<std::uint8_t>& rgba, glm::ivec2 size, PixelRect changed) {
    compositor_->upload(rgba, size.x, size.y, changed);
    liveBlit_->upload(rgba, size.x, size.y, {0, 0, size.x, size.y});
  }

  // The frame drawn whole and live into its own framebuffer, and composed into the kept one: their
  // pixels, and how many pixels the compositor drew.
  struct Pictures {
    std::vector<std::uint8_t> live, composed;
    long long drawn = 0;
  };
  Pictures draw() {
    Pictures pictures;
    glBindFramebuffer(GL_FRAMEBUFFER, liveFramebuffer_);
    liveBlit_->draw(kSize, column_, {0, 0, kSize.x, kSize.y});
    renderImGuiGl(*ImGui::GetDrawData());
    pictures.live = readFramebufferRgb(kSize);
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(keptFramebuffer_));
    const long long before = compositor_->pixelsDrawn();
    compositor_->draw(*ImGui::GetDrawData(), kSize, column_, /*whole=*/false);
    pictures.composed = readFramebufferRgb(kSize);
    pictures.drawn = compositor_->pixelsDrawn() - before;
    return pictures;
  }

  HeadlessGl gl_{kSize.x, kSize.y};
  GLint keptFramebuffer_ = 0;
  GLuint liveFramebuffer_ = 0, liveColor_ = 0;
  std::unique_ptr<FrameCompositor> compositor_;
  std::unique_ptr<GlBlit> liveBlit_;
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


TEST_F(FrameCompositorTest, DrawingOnlyWhatChangedGivesTheWholeLiveFrame) {
  const Settings settings = defaultSettings();
  buildFrames(settings, "scene.json", ImVec2(300.0f, 120.0f), 3);
  ASSERT_EQ(column_, 250);
  const glm::ivec2 imageSize{kSize.x - column_, kSize.y};
  upload(testImage(imageSize), imageSize, {0, 0, imageSize.x, imageSize.y});
  Pictures frame = draw();
  EXPECT_EQ(differing(frame.composed, frame.live), 0) << "the first frame";
  EXPECT_EQ(frame.drawn, kWhole) << "the first frame is drawn whole";
  EXPECT_EQ(compositor_->panels().columnDraws(), 1);

  // The same frame again: only the lists over the image (Stats, the ring) are drawn; the column is kept.
  buildFrames(settings, "scene.json", ImVec2(300.0f, 120.0f));
  frame = draw();
  EXPECT_EQ(differing(frame.composed, frame.live), 0) << "the same frame";
  EXPECT_LT(frame.drawn, kWhole / 2);
  EXPECT_EQ(compositor_->panels().columnDraws(), 1);
  EXPECT_EQ(compositor_->panels().columnKeeps(), 1);

  // A patch of the image changes and the ring moves: the patch, the ring's old and new places.
  buildFrames(settings, "scene.json", ImVec2(400.0f, 200.0f));
  const PixelRect patch{60, 100, 140, 170};
  upload(testImage(imageSize, patch, 90), imageSize, patch);
  frame = draw();
  EXPECT_EQ(differing(frame.composed, frame.live), 0) << "a patch of the image changed, the ring moved";
  EXPECT_LT(frame.drawn, kWhole / 2);

  // The ring lets go: its place is drawn again without it.
  buildFrames(settings, "scene.json", std::nullopt);
  frame = draw();
  EXPECT_EQ(differing(frame.composed, frame.live), 0) << "the ring gone";

  // The Scene section's path field changes: the column is drawn afresh, and shown.
  buildFrames(settings, "another_scene.json", std::nullopt, 3);
  frame = draw();
  EXPECT_EQ(differing(frame.composed, frame.live), 0) << "the column changed";
  EXPECT_EQ(compositor_->panels().columnDraws(), 2);
}

TEST_F(FrameCompositorTest, AStretchedImageRedrawsEveryPixelAChangedTexelReaches) {
  const Settings settings = defaultSettings();
  buildFrames(settings, "scene.json", ImVec2(300.0f, 120.0f), 3);
  // A third of the view's size, stretched bilinearly over it (the adaptive resolution's smallest).
  const glm::ivec2 imageSize{(kSize.x - column_) / 3, kSize.y / 3};
  upload(testImage(imageSize), imageSize, {0, 0, imageSize.x, imageSize.y});
  Pictures frame = draw();
  EXPECT_EQ(differing(frame.composed, frame.live), 0) << "the first stretched frame";
  PixelRect last;  // the last frame's tinted patch, untinted again in the next
  for (const PixelRect& patch : {PixelRect{10, 10, 11, 11}, PixelRect{0, 0, 5, 3}, PixelRect{70, 80, 76, 90}}) {
    buildFrames(settings, "scene.json", ImVec2(300.0f, 120.0f));
    upload(testImage(imageSize, patch, 120), imageSize, patch.unitedWith(last));
    last = patch;
    frame = draw();
    EXPECT_EQ(differing(frame.composed, frame.live), 0) << "texels [" << patch.x0 << ", " << patch.x1 << ") × ["
                                                        << patch.y0 << ", " << patch.y1 << ") changed";
    EXPECT_LT(frame.drawn, kWhole / 2);
  }
}

TEST_F(FrameCompositorTest, ListsReachingPastTheColumnAreDrawnAsOverlays) {
  buildFrames(defaultSettings(), "scene.json", ImVec2(300.0f, 120.0f), 3);
  const glm::ivec2 imageSize{kSize.x - column_, kSize.y};
  upload(testImage(imageSize), imageSize, {0, 0, imageSize.x, imageSize.y});
  // A column narrower than the window in it: nothing lies wholly inside, everything is an overlay.
  column_ -= 20;
  for (int frame = 0; frame < 2; ++frame) {
    const Pictures pictures = draw();
    EXPECT_EQ(differing(pictures.composed, pictures.live), 0) << "frame " << frame;
  }
  EXPECT_EQ(compositor_->panels().columnDraws() + compositor_->panels().columnKeeps(), 0);
}

TEST(DisjointRectangles, OverlappingOnesMergeAndEveryPixelIsInOne) {
  std::vector<PixelRect> rects;
  addDisjoint(rects, {0, 0, 10, 10});
  addDisjoint(rects, {20, 0, 30, 10});   // apart: kept apart
  addDisjoint(rects, {5, 5, 8, 8});      // inside the first
  addDisjoint(rects, {});                // nothing
  EXPECT_EQ(rects.size(), 2u);
  addDisjoint(rects, {9, 2, 21, 4});     // bridges both: one box of all three
  ASSERT_EQ(rects.size(), 1u);
  EXPECT_EQ(rects[0], (PixelRect{0, 0, 30, 10}));
  addDisjoint(rects, {30, 0, 40, 10});   // touching, not overlapping: apart
  EXPECT_EQ(rects.size(), 2u);
}

}  // namespace
}  // namespace slime
