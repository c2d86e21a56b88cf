// Writing an output file whole or not at all: the bytes go to a temporary file beside the target,
// which is renamed over it only once every byte is written and the file closed. A reader sees the old
// file or the new one, and a failed write (no such directory, a full disk) leaves nothing behind.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace slime {

// Throws std::runtime_error "cannot write PATH: REASON" on failure, after removing the temporary file.
void writeFileAtomically(const std::string& path, const void* bytes, std::size_t size);
void writeFileAtomically(const std::string& path, const std::string& text);

// Several files (path, bytes) that belong together, e.g. an .obj and its .mtl: every temporary is
// written before any is renamed over its target, in the order given, so a failed write leaves none.
void writeFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace slime
