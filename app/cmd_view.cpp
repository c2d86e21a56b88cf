// TEMPORARY until the view subcommand lands: registers the name so the program links.
#include "app/commands.h"

#include <cstdio>

namespace slime {

void registerViewCommand(CLI::App& root, int& exitCode) {
  auto* command = root.add_subcommand("view", "(not yet implemented)");
  command->callback([&exitCode] {
    std::fprintf(stderr, "slime view: not implemented yet\n");
    exitCode = 1;
  });
}

}  // namespace slime
