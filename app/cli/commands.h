// The subcommands of the one executable `slime`. Each registers itself on the root CLI11 app;
// main() runs the parser and turns SettingsError and CLI errors into a message and exit code 2.
#pragma once

#include "core/settings/settings.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace slime {

// What every scene-reading subcommand accepts: --scene FILE, --set key=value..., --scenario FILE.
struct SceneOptions {
  std::string sceneFile;
  std::vector<std::string> overrides;
  std::string scenarioFile;
};

// Adds --scene, --set and --scenario to a subcommand.
void addSceneOptions(CLI::App& command, SceneOptions& options);

// Defaults, then the scene file, then the overrides; validated. Throws SettingsError.
Settings loadSettings(const SceneOptions& options);

// Each register function adds its subcommand with its own options and callback.
// The callback sets `exitCode` (0 on success) so main() can return it.
void registerSimCommand(CLI::App& root, int& exitCode);
void registerSnapshotCommand(CLI::App& root, int& exitCode);
void registerViewCommand(CLI::App& root, int& exitCode);   // also what `slime` alone runs
void registerBenchCommand(CLI::App& root, int& exitCode);
void registerSettingsCommand(CLI::App& root, int& exitCode);
void registerRecordCommand(CLI::App& root, int& exitCode);

}  // namespace slime
