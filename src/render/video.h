#pragma once
// The MP4 of a run, encoded by ffmpeg from the PNG frames. ffmpeg is started with an
// argument vector (posix_spawnp), never through a shell.
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sluice::render {

// ffmpeg missing or failing; the message names the command and its log file.
class VideoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// encode_video stopped ffmpeg because job.cancelled() said so; the partial file is removed.
class VideoInterrupted : public VideoError {
 public:
  using VideoError::VideoError;
};

struct VideoJob {
  std::string frames_pattern;  // e.g. DIR/frames/frame_%05d.png
  int start_number = 0;        // first frame index
  double fps = 30;
  std::string output;          // DIR/<scene>.mp4
  std::string log;             // ffmpeg's stderr goes here
  std::function<bool()> cancelled;  // polled while ffmpeg runs: true stops it (e.g. SIGTERM)
};

// The ffmpeg argument vector of the job (argv[0] = "ffmpeg"): H.264 (libx264),
// yuv420p with BT.709 matrix and tags, +faststart; writes output + ".tmp.mp4".
std::vector<std::string> ffmpeg_arguments(const VideoJob& job);
// The same as one line for messages (shell-quoted for copy and paste).
std::string command_line(const std::vector<std::string>& args);
// Runs ffmpeg and renames the temporary file to job.output; throws VideoError, or
// VideoInterrupted after stopping ffmpeg when job.cancelled() turns true.
void encode_video(const VideoJob& job);

}  // namespace sluice::render
