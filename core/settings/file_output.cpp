#include "core/settings/file_output.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace slime {

void writeFileAtomically(const std::string& path, const void* bytes, std::size_t size) {
  const std::string temporary = path + ".partial-" + std::to_string(::getpid());
  const auto fail = [&](int error) {
    std::remove(temporary.c_str());
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(error));
  };
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (!file) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  const bool written = size == 0 || std::fwrite(bytes, 1, size, file) == size;
  const int writeError = errno;
  if (std::fclose(file) != 0 || !written) fail(written ? errno : writeError);
  if (std::rename(temporary.c_str(), path.c_str()) != 0) fail(errno);
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  writeFileAtomically(path, text.data(), text.size());
}

}  // namespace slime
