#include "app/bench/physics/bench_peers.h"

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

extern char** environ;

namespace slime {
namespace {

using nlohmann::json;

struct PeerRun {
  json report;              // what the program wrote with --json (an array, one entry a run)
  double cpuSeconds = 0.0;  // its whole process
};

// Runs `program` with `arguments` and --json FILE; the report it wrote, or null if it failed.
PeerRun runPeer(const std::string& program, std::vector<std::string> arguments) {
  const std::string jsonPath = (std::filesystem::temp_directory_path() /
                                ("slime_bench_peer_" + std::to_string(getpid()) + ".json")).string();
  arguments.insert(arguments.end(), {"--json", jsonPath});
  std::vector<const char*> argv{program.c_str()};
  for (const std::string& argument : arguments) argv.push_back(argument.c_str());
  argv.push_back(nullptr);
  std::fflush(stdout);
  PeerRun run;
  pid_t child = 0;
  if (posix_spawn(&child, program.c_str(), nullptr, nullptr, const_cast<char* const*>(argv.data()), environ) != 0)
    return run;
  int status = 0;
  rusage usage{};
  const bool ok = wait4(child, &status, 0, &usage) == child && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  std::ifstream file(jsonPath);
  json report = ok ? json::parse(file, nullptr, false) : json();
  std::filesystem::remove(jsonPath);
  if (report.is_discarded() || report.empty() || !(report.is_array() || report.is_object())) return run;
  run.report = report;
  run.cpuSeconds = usage.ru_utime.tv_sec + 1e-6 * usage.ru_utime.tv_usec + usage.ru_stime.tv_sec +
                   1e-6 * usage.ru_stime.tv_usec;
  return run;
}

}  // namespace

std::string findPeerProgram(const std::string& configured, const std::string& name) {
  if (!configured.empty()) return configured;
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return "";
  const std::filesystem::path candidate = self.parent_path() / "bench" / name;
  return access(candidate.c_str(), X_OK) == 0 ? candidate.string() : "";
}

json runBulletBall(const std::string& program, int level, double seconds) {
  const PeerRun run = runPeer(program, {"--levels", std::to_string(level), "--seconds", std::to_string(seconds)});
  if (!run.report.is_array()) return nullptr;
  json ball = run.report[0];
  const double simulated = ball["seconds"].get<double>();
  ball["cpu_seconds"] = run.cpuSeconds;
  ball["cpu_ms_per_simulated_s"] = simulated > 0.0 ? 1e3 * run.cpuSeconds / simulated : 0.0;
  ball["wall_ms_per_simulated_s"] = 1e3 * ball["ms_per_step"].get<double>();  // 1 ms steps
  return ball;
}

json runBulletTets(const std::string& program, int resolution, double seconds) {
  const PeerRun run =
      runPeer(program, {"--resolutions", std::to_string(resolution), "--seconds", std::to_string(seconds)});
  if (!run.report.is_array()) return nullptr;
  json body = run.report[0];
  body["process_cpu_seconds"] = run.cpuSeconds;
  body["cpu_ms_per_simulated_s"] = 1e3 * body["cpu_ms_per_simulated_ms"].get<double>();
  return body;
}

json runPeerFront(const std::string& program, const std::vector<std::string>& arguments) {
  const PeerRun run = runPeer(program, arguments);
  return run.report.is_object() ? run.report : json();
}

}  // namespace slime
