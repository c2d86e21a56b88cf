#include "app/viewer/imgui_gl.h"

#include "app/viewer/gl.h"
#include "app/viewer/gl_program.h"

#include <imgui.h>

#include <cstddef>
#include <cstdint>

namespace slime {
namespace {

// ImGui's GLSL 330 shaders (imgui_impl_opengl3.cpp, vertex_shader_glsl_130 / fragment_shader_glsl_130).
constexpr const char* kVertexShader = R"(#version 330 core
uniform mat4 ProjMtx;
in vec2 Position;
in vec2 UV;
in vec4 Color;
out vec2 Frag_UV;
out vec4 Frag_Color;
void main() {
  Frag_UV = UV;
  Frag_Color = Color;
  gl_Position = ProjMtx * vec4(Position.xy, 0, 1);
})";
constexpr const char* kFragmentShader = R"(#version 330 core
uniform sampler2D Texture;
in vec2 Frag_UV;
in vec4 Frag_Color;
out vec4 Out_Color;
void main() { Out_Color = Frag_Color * texture(Texture, Frag_UV.st); })";

struct Objects {
  GLuint program = 0, fontTexture = 0, vertexArray = 0, vertexBuffer = 0, indexBuffer = 0;
  GLint texture = -1, projection = -1, position = -1, uv = -1, color = -1;
};

Objects* objects() { return static_cast<Objects*>(ImGui::GetIO().BackendRendererUserData); }


void createObjects(Objects& o) {
  o.program = linkShaderProgram(kVertexShader, kFragmentShader, "panels (the ImGui renderer)");
  o.texture = glGetUniformLocation(o.program, "Texture");
  o.projection = glGetUniformLocation(o.program, "ProjMtx");
  o.position = glGetAttribLocation(o.program, "Position");
  o.uv = glGetAttribLocation(o.program, "UV");
  o.color = glGetAttribLocation(o.program, "Color");
  glGenBuffers(1, &o.vertexBuffer);
  glGenBuffers(1, &o.indexBuffer);
  glGenVertexArrays(1, &o.vertexArray);

  ImGuiIO& io = ImGui::GetIO();
  unsigned char* pixels = nullptr;
  int width = 0, height = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  GLint lastTexture = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &lastTexture);
  glGenTextures(1, &o.fontTexture);
  glBindTexture(GL_TEXTURE_2D, o.fontTexture);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(o.fontTexture)));
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(lastTexture));
}

// The GL state the draw changes, restored afterwards as ImGui's back-end does.
struct SavedState {
  SavedState() {
    glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &arrayBuffer);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertexArray);
    glGetIntegerv(GL_VIEWPORT, viewport);
    glGetIntegerv(GL_SCISSOR_BOX, scissorBox);
    glGetIntegerv(GL_BLEND_SRC_RGB, &blendSrcRgb);
    glGetIntegerv(GL_BLEND_DST_RGB, &blendDstRgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &blendSrcAlpha);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &blendDstAlpha);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &blendEquation);
    for (int i = 0; i < kCapabilities; ++i) enabled[i] = glIsEnabled(kCapability[i]);
  }
  ~SavedState() {
    glUseProgram(static_cast<GLuint>(program));
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(texture));
    glActiveTexture(static_cast<GLenum>(activeTexture));
    glBindVertexArray(static_cast<GLuint>(vertexArray));
    glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(arrayBuffer));
    glBlendEquation(static_cast<GLenum>(blendEquation));
    glBlendFuncSeparate(static_cast<GLenum>(blendSrcRgb), static_cast<GLenum>(blendDstRgb),
                        static_cast<GLenum>(blendSrcAlpha), static_cast<GLenum>(blendDstAlpha));
    for (int i = 0; i < kCapabilities; ++i) (enabled[i] ? glEnable : glDisable)(kCapability[i]);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glScissor(scissorBox[0], scissorBox[1], scissorBox[2], scissorBox[3]);
  }
  SavedState(const SavedState&) = delete;
  SavedState& operator=(const SavedState&) = delete;

  static constexpr int kCapabilities = 5;
  static constexpr GLenum kCapability[kCapabilities] = {GL_BLEND, GL_CULL_FACE, GL_DEPTH_TEST, GL_STENCIL_TEST,
                                                        GL_SCISSOR_TEST};
  GLint activeTexture = 0, program = 0, texture = 0, arrayBuffer = 0, vertexArray = 0;
  GLint viewport[4] = {}, scissorBox[4] = {};
  GLint blendSrcRgb = 0, blendDstRgb = 0, blendSrcAlpha = 0, blendDstAlpha = 0, blendEquation = 0;
  GLboolean enabled[kCapabilities] = {};
};

void setUpState(const Objects& o, const ImDrawData& data, int width, int height) {
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_SCISSOR_TEST);
  glViewport(0, 0, width, height);
  // Orthographic projection of the display rectangle to clip space, y down (ImGui's back-end).
  const float l = data.DisplayPos.x, r = data.DisplayPos.x + data.DisplaySize.x;
  const float t = data.DisplayPos.y, b = data.DisplayPos.y + data.DisplaySize.y;
  const float projection[16] = {2.0f / (r - l), 0.0f, 0.0f, 0.0f, 0.0f, 2.0f / (t - b), 0.0f, 0.0f,
                                0.0f, 0.0f, -1.0f, 0.0f, (r + l) / (l - r), (t + b) / (b - t), 0.0f, 1.0f};
  glUseProgram(o.program);
  glUniform1i(o.texture, 0);
  glUniformMatrix4fv(o.projection, 1, GL_FALSE, projection);
  glBindVertexArray(o.vertexArray);
  glBindBuffer(GL_ARRAY_BUFFER, o.vertexBuffer);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, o.indexBuffer);
  glEnableVertexAttribArray(static_cast<GLuint>(o.position));
  glEnableVertexAttribArray(static_cast<GLuint>(o.uv));
  glEnableVertexAttribArray(static_cast<GLuint>(o.color));
  const auto stride = static_cast<GLsizei>(sizeof(ImDrawVert));
  glVertexAttribPointer(static_cast<GLuint>(o.position), 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(offsetof(ImDrawVert, pos)));
  glVertexAttribPointer(static_cast<GLuint>(o.uv), 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(offsetof(ImDrawVert, uv)));
  glVertexAttribPointer(static_cast<GLuint>(o.color), 4, GL_UNSIGNED_BYTE, GL_TRUE, stride,
                        reinterpret_cast<void*>(offsetof(ImDrawVert, col)));
}

}  // namespace

void initImGuiGl() {
  ImGuiIO& io = ImGui::GetIO();
  io.BackendRendererUserData = new Objects();
  io.BackendRendererName = "slime_imgui_gl";
}

void newImGuiGlFrame() {
  Objects* o = objects();
  if (o->program == 0) createObjects(*o);
}

void renderImGuiGl(const ImDrawData& data) {
  const int width = static_cast<int>(data.DisplaySize.x * data.FramebufferScale.x);
  const int height = static_cast<int>(data.DisplaySize.y * data.FramebufferScale.y);
  if (width <= 0 || height <= 0) return;
  const Objects& o = *objects();
  const SavedState saved;
  setUpState(o, data, width, height);
  const ImVec2 offset = data.DisplayPos, scale = data.FramebufferScale;
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& list = *data.CmdLists[n];
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(list.VtxBuffer.Size) * sizeof(ImDrawVert),
                 list.VtxBuffer.Data, GL_STREAM_DRAW);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(list.IdxBuffer.Size) * sizeof(ImDrawIdx),
                 list.IdxBuffer.Data, GL_STREAM_DRAW);
    for (const ImDrawCmd& command : list.CmdBuffer) {
      if (command.UserCallback != nullptr) {
        if (command.UserCallback == ImDrawCallback_ResetRenderState)
          setUpState(o, data, width, height);
        else
          command.UserCallback(&list, &command);
        continue;
      }
      // The clip rectangle in framebuffer pixels, y up for glScissor.
      const ImVec2 lo((command.ClipRect.x - offset.x) * scale.x, (command.ClipRect.y - offset.y) * scale.y);
      const ImVec2 hi((command.ClipRect.z - offset.x) * scale.x, (command.ClipRect.w - offset.y) * scale.y);
      if (hi.x <= lo.x || hi.y <= lo.y) continue;
      glScissor(static_cast<int>(lo.x), static_cast<int>(static_cast<float>(height) - hi.y),
                static_cast<int>(hi.x - lo.x), static_cast<int>(hi.y - lo.y));
      glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(reinterpret_cast<std::intptr_t>(command.GetTexID())));
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(command.ElemCount),
                     sizeof(ImDrawIdx) == 2 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT,
                     reinterpret_cast<void*>(command.IdxOffset * sizeof(ImDrawIdx)));
    }
  }
}

void shutdownImGuiGl() {
  ImGuiIO& io = ImGui::GetIO();
  Objects* o = objects();
  if (o == nullptr) return;
  if (o->program != 0) {
    glDeleteVertexArrays(1, &o->vertexArray);
    glDeleteBuffers(1, &o->vertexBuffer);
    glDeleteBuffers(1, &o->indexBuffer);
    glDeleteProgram(o->program);
    glDeleteTextures(1, &o->fontTexture);
    io.Fonts->SetTexID(nullptr);
  }
  delete o;
  io.BackendRendererUserData = nullptr;
  io.BackendRendererName = nullptr;
}

}  // namespace slime
