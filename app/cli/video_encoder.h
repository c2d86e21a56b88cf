// Encodes a clip by piping raw RGB frames to the `ffmpeg` program, run as a separate process (Slime
// does not link libavcodec: Debian builds it with GPL parts). MP4 (H.264), GIF (palettegen and
// paletteuse) or animated WebP, chosen by the file's extension. Bit-exact flags and one thread make
// the same frames give the same bytes. The clip is written to a temporary file in the target's
// directory and renamed at the end; a failure at any point leaves no file.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace slime {

enum class ClipFormat { Mp4, Gif, Webp };

struct ClipSpec {
  std::string path;  // the clip to write: .mp4, .gif or .webp
  int width = 0;
  int height = 0;
  int fps = 30;
};

// The format of `path` by its extension; throws SettingsError naming the allowed ones otherwise.
ClipFormat clipFormatOf(const std::string& path);

// The ffmpeg command line (after the program's name) that encodes `spec` into `output`.
std::vector<std::string> ffmpegArguments(const ClipSpec& spec, ClipFormat format, const std::string& output);

// The full path of a program found on PATH, or "" when there is none.
std::string findOnPath(const std::string& program);

class VideoEncoder {
 public:
  // Checks everything that can be checked before the first frame (format, size, ffmpeg on PATH, a
  // writable directory) and starts ffmpeg; throws SettingsError naming what is wrong.
  explicit VideoEncoder(const ClipSpec& spec);
  ~VideoEncoder();  // unfinished: stops ffmpeg and deletes the temporary file
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  // One frame: width × height × 3 bytes, top row first. Throws std::runtime_error if ffmpeg died.
  void write(const std::vector<std::uint8_t>& rgb);

  // Waits for ffmpeg and renames the clip into place; throws std::runtime_error with ffmpeg's
  // message when it failed.
  void finish();

 private:
  void abandon();
  std::string ffmpegMessage() const;

  ClipSpec spec_;
  std::string temporaryPath_;
  std::string logPath_;
  pid_t process_ = -1;
  int input_ = -1;  // ffmpeg's stdin
};

}  // namespace slime
