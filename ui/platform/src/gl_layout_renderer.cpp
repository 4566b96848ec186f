#include "airr/ui/platform/gl_layout_renderer.hpp"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <glm/gtc/type_ptr.hpp>

namespace airr::ui {

namespace {

const char* vertex_source = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 mvp;
uniform mat4 model;
out vec3 world_normal;
void main() {
  world_normal = mat3(model) * normal;
  gl_Position = mvp * vec4(position, 1.0);
}
)";

// Two-sided Lambert from a light over the viewer's shoulder, plus ambient; lines are unlit.
const char* fragment_source = R"(#version 330 core
in vec3 world_normal;
uniform vec4 colour;
uniform int lit;
out vec4 frag;
void main() {
  if (lit == 0) { frag = colour; return; }
  vec3 n = normalize(world_normal);
  float d = abs(dot(n, normalize(vec3(0.35, 0.8, 0.5))));
  frag = vec4(colour.rgb * (0.35 + 0.65 * d), colour.a);
}
)";

unsigned compile(unsigned kind, const char* source, std::string& error) {
  const unsigned s = glCreateShader(kind);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  int ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[512] = {0};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    error = std::string("shader: ") + log;
    glDeleteShader(s);
    return 0;
  }
  return s;
}

// Position and face normal per vertex, for the triangles given as consecutive point triples.
std::vector<float> with_normals(const std::vector<glm::vec3>& p) {
  std::vector<float> out;
  out.reserve(p.size() * 6);
  for (std::size_t i = 0; i + 2 < p.size(); i += 3) {
    const glm::vec3 n = glm::cross(p[i + 1] - p[i], p[i + 2] - p[i]);
    for (int k = 0; k < 3; ++k) out.insert(out.end(), {p[i + k].x, p[i + k].y, p[i + k].z, n.x, n.y, n.z});
  }
  return out;
}

void set_layout() {
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
}

}  // namespace

gl_layout_renderer::~gl_layout_renderer() {
  for (auto& [key, m] : meshes_) {
    glDeleteBuffers(1, &m.vbo);
    glDeleteVertexArrays(1, &m.vao);
  }
  if (scratch_vbo_) glDeleteBuffers(1, &scratch_vbo_);
  if (scratch_vao_) glDeleteVertexArrays(1, &scratch_vao_);
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (colour_) glDeleteTextures(1, &colour_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
  if (program_) glDeleteProgram(program_);
}

bool gl_layout_renderer::ensure_program() {
  if (program_) return true;
  if (!error_.empty()) return false;
  const unsigned vs = compile(GL_VERTEX_SHADER, vertex_source, error_);
  const unsigned fs = vs ? compile(GL_FRAGMENT_SHADER, fragment_source, error_) : 0;
  if (!vs || !fs) return false;
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  int ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    error_ = "cannot link the 3D view's shaders";
    glDeleteProgram(program_);
    program_ = 0;
    return false;
  }
  loc_mvp_ = glGetUniformLocation(program_, "mvp");
  loc_model_ = glGetUniformLocation(program_, "model");
  loc_colour_ = glGetUniformLocation(program_, "colour");
  loc_lit_ = glGetUniformLocation(program_, "lit");
  glGenVertexArrays(1, &scratch_vao_);
  glGenBuffers(1, &scratch_vbo_);
  return true;
}

void gl_layout_renderer::ensure_target(int width, int height) {
  if (fbo_ && width == width_ && height == height_) return;
  if (!fbo_) {
    glGenFramebuffers(1, &fbo_);
    glGenTextures(1, &colour_);
    glGenRenderbuffers(1, &depth_);
  }
  width_ = width;
  height_ = height;
  glBindTexture(GL_TEXTURE_2D, colour_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
}

const gl_layout_renderer::gpu_mesh& gl_layout_renderer::upload(const std::shared_ptr<const triangle_mesh>& mesh) {
  // Meshes that died free their buffers; a live one is uploaded once.
  for (auto it = meshes_.begin(); it != meshes_.end();) {
    if (it->second.source.expired()) {
      glDeleteBuffers(1, &it->second.vbo);
      glDeleteVertexArrays(1, &it->second.vao);
      it = meshes_.erase(it);
    } else {
      ++it;
    }
  }
  auto it = meshes_.find(mesh.get());
  if (it != meshes_.end()) return it->second;
  std::vector<glm::vec3> points;
  points.reserve(mesh->indices.size());
  for (std::uint32_t i : mesh->indices) points.push_back(mesh->positions[i]);
  const std::vector<float> data = with_normals(points);
  gpu_mesh g;
  g.source = mesh;
  g.vertices = int(points.size());
  glGenVertexArrays(1, &g.vao);
  glGenBuffers(1, &g.vbo);
  glBindVertexArray(g.vao);
  glBindBuffer(GL_ARRAY_BUFFER, g.vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(), GL_STATIC_DRAW);
  set_layout();
  return meshes_[mesh.get()] = g;
}

void gl_layout_renderer::draw_vertices(const std::vector<float>& interleaved, unsigned mode) {
  glBindVertexArray(scratch_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, scratch_vbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(interleaved.size() * sizeof(float)), interleaved.data(), GL_STREAM_DRAW);
  set_layout();
  glDrawArrays(mode, 0, GLsizei(interleaved.size() / 6));
}

bool gl_layout_renderer::render(int width, int height, const glm::mat4& view_projection,
                                const std::vector<gl_draw_item>& items) {
  if (width < 1 || height < 1 || !ensure_program()) return false;
  GLint previous_fbo = 0, viewport[4];
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &previous_fbo);
  glGetIntegerv(GL_VIEWPORT, viewport);
  ensure_target(width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width, height);
  glClearColor(0.094f, 0.102f, 0.118f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glUseProgram(program_);
  // Opaque items first, then the translucent ones without writing depth.
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      glEnable(GL_BLEND);
      glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
      glDepthMask(GL_FALSE);
    }
    for (const auto& item : items) {
      if ((item.colour.a < 1.0f) != (pass == 1)) continue;
      const glm::mat4 mvp = view_projection * item.model;
      glUniformMatrix4fv(loc_mvp_, 1, GL_FALSE, glm::value_ptr(mvp));
      glUniformMatrix4fv(loc_model_, 1, GL_FALSE, glm::value_ptr(item.model));
      glUniform4fv(loc_colour_, 1, glm::value_ptr(item.colour));
      glUniform1i(loc_lit_, item.lines.empty() ? 1 : 0);
      if (item.mesh && !item.mesh->indices.empty()) {
        const gpu_mesh& g = upload(item.mesh);
        glBindVertexArray(g.vao);
        glDrawArrays(GL_TRIANGLES, 0, g.vertices);
      }
      if (!item.triangles.empty()) draw_vertices(with_normals(item.triangles), GL_TRIANGLES);
      if (!item.lines.empty()) {
        std::vector<float> data;
        for (const auto& p : item.lines) data.insert(data.end(), {p.x, p.y, p.z, 0, 0, 0});
        draw_vertices(data, GL_LINES);
      }
    }
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(previous_fbo));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  return true;
}

}  // namespace airr::ui
