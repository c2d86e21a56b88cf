// Where bench results go: the JSON document (every figure) and flat CSV tables for the charts.
// A CSV named FILE.csv gets sibling tables FILE_<name>.csv (e.g. render_bvh.csv).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace slime {

struct CsvTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  // Appends a row; values are formatted with up to 6 significant digits (strings as they are).
  void add(const std::vector<nlohmann::json>& values);
};

// Writes JSON (indented) or a CSV table; throws std::runtime_error naming the path on failure.
void writeJsonFile(const nlohmann::json& document, const std::string& path);
void writeCsvFile(const CsvTable& table, const std::string& path);

// "docs/bench/render.csv" + "bvh" → "docs/bench/render_bvh.csv".
std::string siblingCsvPath(const std::string& csvPath, const std::string& name);

// Now in UTC, ISO 8601 ("2026-11-25T00:40:12Z").
std::string utcNow();

// The 1-, 5- and 15-minute load averages: how busy the shared machine was while it measured (null
// where /proc/loadavg cannot be read).
nlohmann::json loadAverage();

// The machine a bench ran on, so that figures from different machines are never compared unawares:
// the date, the processor's model name (/proc/cpuinfo), its cores, the widest vector instructions this
// build was compiled for, and the load averages.
nlohmann::json machineJson();

// A few comma-separated integers or ranges: "0-6", "1,2", "3,5-6". Throws std::invalid_argument.
std::vector<int> parseIntegerList(const std::string& text);

}  // namespace slime
