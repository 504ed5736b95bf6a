// libFuzzer entry point for the scene parser (built and run by scripts/fuzz.sh).
//
// The input's bytes up to the first NUL are the scene file; the bytes after it are
// `--set` overrides, one per line, so that apply_override is fuzzed as well. A
// SceneError is the parser's answer to bad input and is expected; any other exception,
// a crash, a sanitizer report, a timeout or running out of memory is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return lines;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  const std::string text = input.substr(0, nul);
  const std::vector<std::string> overrides =
      nul == std::string::npos ? std::vector<std::string>{} : split_lines(input.substr(nul + 1));
  try {
    const sluice::Scene scene = sluice::parse_scene(text, "fuzz.json", overrides);
    // The program writes the resolved scene into summary.json; serialise it the same way.
    const std::string resolved = scene.resolved.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
    (void)resolved;
  } catch (const sluice::SceneError&) {
    // bad input, reported with a message: the expected outcome
  }
  return 0;
}
