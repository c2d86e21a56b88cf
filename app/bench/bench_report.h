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

// A few comma-separated integers or ranges: "0-6", "1,2", "3,5-6". Throws std::invalid_argument.
std::vector<int> parseIntegerList(const std::string& text);

}  // namespace slime
