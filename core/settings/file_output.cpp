#include "core/settings/file_output.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace slime {

namespace {

std::string temporaryOf(const std::string& path) { return path + ".partial-" + std::to_string(::getpid()); }

[[noreturn]] void failWriting(const std::string& path, int error) {
  std::remove(temporaryOf(path).c_str());
  throw std::runtime_error("cannot write " + path + ": " + std::strerror(error));
}

// Writes the bytes to path's temporary file and closes it; throws (leaving no temporary) on failure.
void writeTemporary(const std::string& path, const void* bytes, std::size_t size) {
  std::FILE* file = std::fopen(temporaryOf(path).c_str(), "wb");
  if (!file) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  const bool written = size == 0 || std::fwrite(bytes, 1, size, file) == size;
  const int writeError = errno;
  if (std::fclose(file) != 0 || !written) failWriting(path, written ? errno : writeError);
}

void renameTemporary(const std::string& path) {
  if (std::rename(temporaryOf(path).c_str(), path.c_str()) != 0) failWriting(path, errno);
}

}  // namespace

void writeFileAtomically(const std::string& path, const void* bytes, std::size_t size) {
  writeTemporary(path, bytes, size);
  renameTemporary(path);
}

void writeFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files) {
  std::size_t written = 0;
  try {
    for (; written < files.size(); ++written)
      writeTemporary(files[written].first, files[written].second.data(), files[written].second.size());
  } catch (...) {
    for (std::size_t i = 0; i < written; ++i) std::remove(temporaryOf(files[i].first).c_str());
    throw;
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    try {
      renameTemporary(files[i].first);
    } catch (...) {  // renaming within one directory hardly fails; if it does, leave no temporary behind
      for (std::size_t j = i + 1; j < files.size(); ++j) std::remove(temporaryOf(files[j].first).c_str());
      throw;
    }
  }
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  writeFileAtomically(path, text.data(), text.size());
}

}  // namespace slime
