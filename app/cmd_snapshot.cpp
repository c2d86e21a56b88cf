// TEMPORARY until the snapshot subcommand lands: registers the name so the program links.
#include "app/commands.h"

#include <cstdio>

namespace slime {

void registerSnapshotCommand(CLI::App& root, int& exitCode) {
  auto* command = root.add_subcommand("snapshot", "(not yet implemented)");
  command->callback([&exitCode] {
    std::fprintf(stderr, "slime snapshot: not implemented yet\n");
    exitCode = 1;
  });
}

}  // namespace slime
