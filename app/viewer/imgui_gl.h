// The panels' GL 3.3 renderer: Dear ImGui's draw lists drawn with the entry points of app/viewer/gl.h.
// It replaces ImGui's own OpenGL3 back-end, whose loader only finds GLVND's libGL and so cannot draw
// into an OSMesa context; it follows that back-end's state and scissor rules (imgui_impl_opengl3.cpp).
#pragma once

struct ImDrawData;

namespace slime {

void initImGuiGl();      // after ImGui::CreateContext, with the context current
void newImGuiGlFrame();  // before ImGui::NewFrame: makes the font texture once the fonts are built
void renderImGuiGl(const ImDrawData& data);  // GL state as it was is restored afterwards
void shutdownImGuiGl();

}  // namespace slime
