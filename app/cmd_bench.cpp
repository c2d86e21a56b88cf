// TEMPORARY until the bench subcommand lands: registers the name so the program links.
#include "app/commands.h"

#include <cstdio>

namespace slime {

void registerBenchCommand(CLI::App& root, int& exitCode) {
  auto* command = root.add_subcommand("bench", "(not yet implemented)");
  command->callback([&exitCode] {
    std::fprintf(stderr, "slime bench: not implemented yet\n");
    exitCode = 1;
  });
}

}  // namespace slime
