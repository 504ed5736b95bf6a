#include "render/gl_renderer.h"

#include <glad/gl.h>

#include <string>
#include <vector>

namespace sluice::render {

const char* shader_source(const char* name);  // generated from shaders/*.glsl

namespace {

struct Instance {
  float x, y;                 // centre relative to the view origin (floats keep precision there)
  std::uint8_t r, g, b, pad;  // colour
};

GLuint compile(GLenum type, const char* name) {
  const char* src = shader_source(name);
  if (!src) throw RenderError(std::string("shader ") + name + " is not embedded in this build");
  GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw RenderError(std::string("shader ") + name + " does not compile: " + log);
  }
  return s;
}

GLuint link_program(const char* vert, const char* frag) {
  GLuint v = compile(GL_VERTEX_SHADER, vert), f = compile(GL_FRAGMENT_SHADER, frag);
  GLuint p = glCreateProgram();
  glAttachShader(p, v);
  glAttachShader(p, f);
  glLinkProgram(p);
  glDeleteShader(v);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    throw RenderError(std::string("shader program does not link: ") + log);
  }
  return p;
}

void check_framebuffer(const char* what) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%s framebuffer incomplete (status 0x%04x)", what, status);
    throw RenderError(buf);
  }
}

}  // namespace

struct GlRenderer::Gl {
  GLuint program = 0, vao = 0, quad = 0, instances = 0;
  GLuint fbo = 0, color = 0;            // single-sampled target read back
  GLuint msaa_fbo = 0, msaa_color = 0;  // multisampled target resolved into fbo
  GLint u_world_to_ndc = -1, u_ndc_offset = -1, u_pixel_to_ndc = -1, u_radius_px = -1;
  std::vector<Instance> staging;
};

GlRenderer::GlRenderer(int width, int height, int msaa, EglPlatform platform)
    : egl_(std::make_unique<EglContext>(platform)),
      gl_(std::make_unique<Gl>()),
      width_(width),
      height_(height),
      msaa_(msaa) {
  if (width < 1 || height < 1) throw RenderError("image size must be positive");
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width > max_size || height > max_size)
    throw RenderError("resolution " + std::to_string(width) + "x" + std::to_string(height) +
                      " exceeds this OpenGL's largest framebuffer (" + std::to_string(max_size) + ")");
  Gl& g = *gl_;
  g.program = link_program("disc.vert.glsl", "disc.frag.glsl");
  g.u_world_to_ndc = glGetUniformLocation(g.program, "u_world_to_ndc");
  g.u_ndc_offset = glGetUniformLocation(g.program, "u_ndc_offset");
  g.u_pixel_to_ndc = glGetUniformLocation(g.program, "u_pixel_to_ndc");
  g.u_radius_px = glGetUniformLocation(g.program, "u_radius_px");

  // One quad as a triangle strip, instanced per particle.
  const float corners[] = {-1, -1, 1, -1, -1, 1, 1, 1};
  glGenVertexArrays(1, &g.vao);
  glBindVertexArray(g.vao);
  glGenBuffers(1, &g.quad);
  glBindBuffer(GL_ARRAY_BUFFER, g.quad);
  glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glGenBuffers(1, &g.instances);
  glBindBuffer(GL_ARRAY_BUFFER, g.instances);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(Instance), reinterpret_cast<void*>(offsetof(Instance, x)));
  glVertexAttribDivisor(1, 1);
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 3, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(Instance),
                        reinterpret_cast<void*>(offsetof(Instance, r)));
  glVertexAttribDivisor(2, 1);

  glGenRenderbuffers(1, &g.color);
  glBindRenderbuffer(GL_RENDERBUFFER, g.color);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGB8, width, height);
  glGenFramebuffers(1, &g.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, g.fbo);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, g.color);
  check_framebuffer("RGB8");
  if (msaa_ > 0) {
    glGenRenderbuffers(1, &g.msaa_color);
    glBindRenderbuffer(GL_RENDERBUFFER, g.msaa_color);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, msaa_, GL_RGB8, width, height);
    glGenFramebuffers(1, &g.msaa_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, g.msaa_fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, g.msaa_color);
    check_framebuffer("multisampled RGB8");
  }
  glViewport(0, 0, width, height);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
}

GlRenderer::~GlRenderer() {
  Gl& g = *gl_;
  glDeleteFramebuffers(1, &g.fbo);
  glDeleteRenderbuffers(1, &g.color);
  if (g.msaa_fbo) glDeleteFramebuffers(1, &g.msaa_fbo);
  if (g.msaa_color) glDeleteRenderbuffers(1, &g.msaa_color);
  glDeleteBuffers(1, &g.quad);
  glDeleteBuffers(1, &g.instances);
  glDeleteVertexArrays(1, &g.vao);
  glDeleteProgram(g.program);
}

const std::string& GlRenderer::description() const { return egl_->description(); }

void GlRenderer::clear(Rgb bg) {
  glBindFramebuffer(GL_FRAMEBUFFER, msaa_ > 0 ? gl_->msaa_fbo : gl_->fbo);
  glClearColor(bg.r / 255.0f, bg.g / 255.0f, bg.b / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

void GlRenderer::draw_discs(const ViewWindow& view, double diameter, std::span<const double> xy,
                            std::span<const Rgb> colors) {
  const size_t n = colors.size();
  if (n == 0) return;
  if (xy.size() != 2 * n) throw RenderError("draw_discs: positions and colours differ in count");
  Gl& g = *gl_;
  g.staging.resize(n);
  for (size_t i = 0; i < n; ++i)
    g.staging[i] = {static_cast<float>(xy[2 * i] - view.x0),
                    static_cast<float>(xy[2 * i + 1] - view.y0),
                    colors[i].r,
                    colors[i].g,
                    colors[i].b,
                    0};
  glBindBuffer(GL_ARRAY_BUFFER, g.instances);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(n * sizeof(Instance)), g.staging.data(), GL_STREAM_DRAW);

  // Rows are drawn top-down (y flipped) so glReadPixels returns the image top row first.
  const double sx = 2.0 / (view.x1 - view.x0), sy = 2.0 / (view.y1 - view.y0);
  glUseProgram(g.program);
  glUniform2f(g.u_world_to_ndc, static_cast<float>(sx), static_cast<float>(-sy));
  glUniform2f(g.u_ndc_offset, -1.0f, 1.0f);
  glUniform2f(g.u_pixel_to_ndc, 2.0f / static_cast<float>(width_), 2.0f / static_cast<float>(height_));
  glUniform1f(g.u_radius_px, static_cast<float>(0.5 * diameter * width_ / (view.x1 - view.x0)));
  glBindVertexArray(g.vao);
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(n));
}

void GlRenderer::finish() { glFinish(); }

void GlRenderer::read(Image& out) {
  Gl& g = *gl_;
  if (msaa_ > 0) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, g.msaa_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, g.fbo);
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, g.fbo);
  if (out.width != width_ || out.height != height_) out = Image(width_, height_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, out.rgb.data());
  const GLenum err = glGetError();
  if (err != GL_NO_ERROR) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "OpenGL error 0x%04x while rendering", err);
    throw RenderError(buf);
  }
}

}  // namespace sluice::render
