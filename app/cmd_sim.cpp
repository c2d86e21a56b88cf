// TEMPORARY until the sim subcommand lands: registers the name so the program links.
#include "app/commands.h"

#include <cstdio>

namespace slime {

void registerSimCommand(CLI::App& root, int& exitCode) {
  auto* command = root.add_subcommand("sim", "(not yet implemented)");
  command->callback([&exitCode] {
    std::fprintf(stderr, "slime sim: not implemented yet\n");
    exitCode = 1;
  });
}

}  // namespace slime
