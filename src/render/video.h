#pragma once
// The video of a run (MP4, WebM or GIF), encoded by ffmpeg from the PNG frames. ffmpeg is started with an
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

enum class VideoFormat { mp4, webm, gif };

// "mp4" | "webm" | "gif"; false for anything else.
bool parse_video_format(const std::string& text, VideoFormat& f);
const char* extension(VideoFormat f);  // "mp4", "webm", "gif"
// The CRF range of the format's encoder (x264 0..51, VP9 0..63) and its default; GIF
// has none (max_crf < 0).
int max_crf(VideoFormat f);
int default_crf(VideoFormat f);

struct VideoJob {
  std::string frames_pattern;  // e.g. DIR/frames/frame_%05d.png
  int start_number = 0;        // first frame index
  double fps = 30;
  VideoFormat format = VideoFormat::mp4;
  int crf = -1;                     // < 0: the format's default
  std::string output;               // DIR/<scene>.<format>
  std::string log;                  // ffmpeg's stderr goes here
  std::function<bool()> cancelled;  // polled while ffmpeg runs: true stops it (e.g. SIGTERM)
};

// Where ffmpeg writes before the rename: output + ".tmp." + extension.
std::string temporary_output(const VideoJob& job);
// The ffmpeg argument vector of the job (argv[0] = "ffmpeg"). MP4: H.264 (libx264),
// yuv420p with BT.709 matrix and tags, +faststart. WebM: VP9 (libvpx-vp9) in
// constant-quality mode, the same colour handling. GIF: one palette made for the whole
// video (palettegen/paletteuse), no dithering noise between frames.
std::vector<std::string> ffmpeg_arguments(const VideoJob& job);
// The same as one line for messages (shell-quoted for copy and paste).
std::string command_line(const std::vector<std::string>& args);
// Runs ffmpeg and renames the temporary file to job.output; throws VideoError, or
// VideoInterrupted after stopping ffmpeg when job.cancelled() turns true.
void encode_video(const VideoJob& job);

}  // namespace sluice::render
