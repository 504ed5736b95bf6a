#include "render/video.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

extern char** environ;

namespace sluice::render {

std::vector<std::string> ffmpeg_arguments(const VideoJob& job) {
  char fps[32];
  std::snprintf(fps, sizeof fps, "%.9g", job.fps);
  return {"ffmpeg", "-nostdin", "-hide_banner", "-loglevel", "error", "-y",
          "-framerate", fps, "-start_number", std::to_string(job.start_number), "-i", job.frames_pattern,
          // RGB -> Y'CbCr with the BT.709 matrix, matching the tags below
          "-vf", "scale=out_color_matrix=bt709:out_range=tv,format=yuv420p",
          "-c:v", "libx264", "-preset", "medium", "-crf", "18", "-pix_fmt", "yuv420p",
          "-colorspace", "bt709", "-color_primaries", "bt709", "-color_trc", "bt709",
          "-movflags", "+faststart", job.output + ".tmp.mp4"};
}

std::string command_line(const std::vector<std::string>& args) {
  std::string s;
  for (const std::string& a : args) {
    if (!s.empty()) s += ' ';
    const bool plain = !a.empty() && a.find_first_of(" '\"\\$`*?!;&|<>()%") == std::string::npos;
    if (plain) {
      s += a;
      continue;
    }
    s += '\'';
    for (char c : a) s += c == '\'' ? std::string("'\\''") : std::string(1, c);
    s += '\'';
  }
  return s;
}

void encode_video(const VideoJob& job) {
  const std::vector<std::string> args = ffmpeg_arguments(job);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string cmd = command_line(args);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, job.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    // The child opened the log before exec failed; an empty log would suggest ffmpeg ran.
    std::error_code ignored;
    std::filesystem::remove(job.log, ignored);
    throw VideoError("cannot start ffmpeg (" + std::string(std::strerror(rc)) +
                     "; install it, e.g. apt-get install ffmpeg): " + cmd);
  }
  int status = 0;
  const std::string partial = job.output + ".tmp.mp4";
  // Polled, not a blocking wait: a signal to sluice must stop ffmpeg too, not orphan it.
  bool stopped = false;
  while (true) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) throw VideoError("waiting for ffmpeg failed: " + std::string(std::strerror(errno)));
    if (!stopped && job.cancelled && job.cancelled()) {
      kill(pid, SIGTERM);
      stopped = true;
    }
    usleep(20000);
  }
  if (stopped || (job.cancelled && job.cancelled())) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    throw VideoInterrupted("ffmpeg stopped before the video was complete; no video written");
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                              : "killed by signal " + std::to_string(WTERMSIG(status));
    std::error_code ignored;
    std::filesystem::remove(job.output + ".tmp.mp4", ignored);
    throw VideoError("ffmpeg failed (" + how + "; its messages are in " + job.log + "): " + cmd);
  }
  std::error_code ec;
  std::filesystem::rename(job.output + ".tmp.mp4", job.output, ec);
  if (ec) throw VideoError(job.output + ": cannot rename the encoded video: " + ec.message());
}

}  // namespace sluice::render
