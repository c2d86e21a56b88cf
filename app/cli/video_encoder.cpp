#include "app/cli/video_encoder.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/settings/settings_io.h"

extern char** environ;

namespace slime {
namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// The directory the clip goes to; "." for a bare file name.
fs::path directoryOf(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

}  // namespace

ClipFormat clipFormatOf(const std::string& path) {
  const std::string extension = lowerExtension(path);
  if (extension == ".mp4") return ClipFormat::Mp4;
  if (extension == ".gif") return ClipFormat::Gif;
  if (extension == ".webp") return ClipFormat::Webp;
  throw SettingsError("-o " + path + ": unknown extension '" + extension + "'; expected .mp4, .gif or .webp");
}

std::vector<std::string> ffmpegArguments(const ClipSpec& spec, ClipFormat format, const std::string& output) {
  std::vector<std::string> arguments = {
      "-hide_banner", "-loglevel", "error", "-y", "-filter_threads", "1", "-filter_complex_threads", "1",
      "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
      std::to_string(spec.width) + "x" + std::to_string(spec.height), "-r", std::to_string(spec.fps), "-i",
      "pipe:0",
      // Same frames, same bytes: no encoder version or time stamps in the file, one thread.
      "-threads", "1", "-fflags", "+bitexact", "-flags", "+bitexact", "-map_metadata", "-1"};
  const auto add = [&](std::initializer_list<std::string> more) { arguments.insert(arguments.end(), more); };
  switch (format) {
    case ClipFormat::Mp4:
      add({"-c:v", "libx264", "-preset", "medium", "-crf", "20", "-pix_fmt", "yuv420p", "-movflags",
           "+faststart", "-f", "mp4"});
      break;
    case ClipFormat::Gif:
      // One palette for the whole clip, then ordered dithering: stable colours, small files.
      add({"-filter_complex",
           "split[frames][copy];[copy]palettegen=stats_mode=full[palette];"
           "[frames][palette]paletteuse=dither=bayer:bayer_scale=4",
           "-loop", "0", "-f", "gif"});
      break;
    case ClipFormat::Webp:
      add({"-c:v", "libwebp_anim", "-lossless", "0", "-quality", "70", "-loop", "0", "-f", "webp"});
      break;
  }
  arguments.push_back(output);
  return arguments;
}

std::string findOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream directories(path);
  std::string directory;
  while (std::getline(directories, directory, ':')) {
    const fs::path candidate = fs::path(directory.empty() ? "." : directory) / program;
    if (access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) return candidate.string();
  }
  return "";
}

VideoEncoder::VideoEncoder(const ClipSpec& spec) : spec_(spec) {
  const ClipFormat format = clipFormatOf(spec.path);
  if (format == ClipFormat::Mp4 && (spec.width % 2 != 0 || spec.height % 2 != 0))
    throw SettingsError("--size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                        ": an .mp4 (H.264, yuv420p) needs an even width and height");
  const std::string ffmpeg = findOnPath("ffmpeg");
  if (ffmpeg.empty())
    throw SettingsError("-o " + spec.path +
                        ": the ffmpeg program is not on PATH; install it (Debian: apt install "
                        "ffmpeg, or scripts/setup.sh)");
  const fs::path directory = directoryOf(spec.path);
  if (!fs::is_directory(directory))
    throw SettingsError("-o " + spec.path + ": the directory " + directory.string() + " does not exist");
  if (fs::is_directory(spec.path))
    throw SettingsError("-o " + spec.path + ": is a directory; expected a file name");

  // The temporary clip beside the target (so the rename stays on one file system); ffmpeg's messages
  // go to a temporary log, read if it fails.
  // (Appended piece by piece: GCC 12 at -O3 warns falsely about "." + a temporary string, -Wrestrict.)
  std::string name = ".";
  name += fs::path(spec.path).filename().string();
  name += ".partial-XXXXXX";
  std::string temporary = (directory / name).string();
  const int temporaryFile = mkstemp(temporary.data());
  if (temporaryFile < 0)
    throw SettingsError("-o " + spec.path + ": cannot write in " + directory.string() + ": " +
                        std::strerror(errno));
  // mkstemp makes the file private (0600); the clip gets the permissions any new file would.
  const mode_t mask = umask(0);
  umask(mask);
  fchmod(temporaryFile, 0666 & ~mask);
  close(temporaryFile);
  temporaryPath_ = temporary;
  std::string log = (fs::temp_directory_path() / "slime-ffmpeg-XXXXXX").string();
  const int logFile = mkstemp(log.data());
  if (logFile < 0) {
    abandon();
    throw std::runtime_error(std::string("cannot create a temporary file: ") + std::strerror(errno));
  }
  logPath_ = log;

  int pipeEnds[2];
  if (pipe2(pipeEnds, O_CLOEXEC) != 0) {
    close(logFile);
    abandon();
    throw std::runtime_error(std::string("cannot create a pipe to ffmpeg: ") + std::strerror(errno));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipeEnds[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, logFile, STDERR_FILENO);
  std::vector<std::string> arguments = ffmpegArguments(spec, format, temporaryPath_);
  arguments.insert(arguments.begin(), ffmpeg);
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  const int spawned = posix_spawn(&process_, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipeEnds[0]);
  close(logFile);
  if (spawned != 0) {
    close(pipeEnds[1]);
    process_ = -1;
    abandon();
    throw SettingsError("cannot run " + ffmpeg + ": " + std::strerror(spawned));
  }
  input_ = pipeEnds[1];
  signal(SIGPIPE, SIG_IGN);  // a dead ffmpeg shows as EPIPE from write(), not as our own death
}

VideoEncoder::~VideoEncoder() { abandon(); }

void VideoEncoder::write(const std::vector<std::uint8_t>& rgb) {
  std::size_t written = 0;
  while (written < rgb.size()) {
    const ssize_t count = ::write(input_, rgb.data() + written, rgb.size() - written);
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) throw std::runtime_error("ffmpeg stopped taking frames: " + ffmpegMessage());
    written += static_cast<std::size_t>(count);
  }
}

void VideoEncoder::finish() {
  close(input_);
  input_ = -1;
  int status = 0;
  while (waitpid(process_, &status, 0) < 0 && errno == EINTR) {
  }
  process_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string message = ffmpegMessage();
    abandon();
    throw std::runtime_error("ffmpeg failed to write " + spec_.path + ": " + message);
  }
  std::error_code error;
  fs::rename(temporaryPath_, spec_.path, error);
  if (error) {
    abandon();
    throw std::runtime_error("cannot move the clip to " + spec_.path + ": " + error.message());
  }
  temporaryPath_.clear();
  abandon();  // only the log is left to remove
}

void VideoEncoder::abandon() {
  if (input_ >= 0) close(input_), input_ = -1;
  if (process_ > 0) {
    kill(process_, SIGTERM);
    int status = 0;
    waitpid(process_, &status, 0);
    process_ = -1;
  }
  std::error_code ignored;
  if (!temporaryPath_.empty()) fs::remove(temporaryPath_, ignored), temporaryPath_.clear();
  if (!logPath_.empty()) fs::remove(logPath_, ignored), logPath_.clear();
}

std::string VideoEncoder::ffmpegMessage() const {
  std::ifstream log(logPath_);
  std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return text.empty() ? "(no message)" : text;
}

}  // namespace slime
