#pragma once
// A headless OpenGL 3.3 core context through EGL: no window system, no surface; the
// caller renders into its own framebuffer objects.
#include <optional>
#include <string>

namespace sluice::render {

// automatic: Mesa's surfaceless platform, then the EGL device platform.
enum class EglPlatform { automatic, surfaceless, device };

std::optional<EglPlatform> parse_egl_platform(const std::string& s);  // auto | surfaceless | device

class EglContext {
 public:
  // Creates the context, makes it current on this thread and loads the GL functions.
  // Throws RenderError listing every platform and device tried and why each failed.
  explicit EglContext(EglPlatform platform);
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // e.g. "surfaceless, llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6"
  const std::string& description() const { return description_; }

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string description_;
};

}  // namespace sluice::render
