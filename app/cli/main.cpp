// slime: the real-time ray-traced slime simulator. `slime` alone opens the viewer.
#include "app/cli/commands.h"
#include "core/settings/settings_io.h"

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  CLI::App app{"Slime: a real-time, ray-traced, interactive simulator of the toy slime"};
  app.require_subcommand(0, 1);
  int exitCode = 0;
  slime::registerViewCommand(app, exitCode);
  slime::registerSnapshotCommand(app, exitCode);
  slime::registerSimCommand(app, exitCode);
  slime::registerBenchCommand(app, exitCode);
  slime::registerSettingsCommand(app, exitCode);
  slime::registerRecordCommand(app, exitCode);
  try {
    app.parse(argc, argv);
    if (app.get_subcommands().empty()) app.get_subcommand("view")->parse(std::vector<std::string>{});
  } catch (const CLI::ParseError& e) {
    // CLI11 uses exit code 0 for --help; every real parse error becomes exit code 2.
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const slime::SettingsError& e) {
    std::fprintf(stderr, "slime: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "slime: error: %s\n", e.what());
    return 1;
  }
  return exitCode;
}
