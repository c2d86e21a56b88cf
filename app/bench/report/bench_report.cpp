#include "app/bench/report/bench_report.h"

#include "core/settings/file_output.h"

#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace slime {
namespace {

std::string formatValue(const nlohmann::json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "1" : "0";
  if (value.is_number_integer() || value.is_number_unsigned()) return value.dump();
  if (value.is_number()) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value.get<double>());
    return text;
  }
  return "";  // null: an empty cell, which gnuplot skips
}

void writeText(const std::string& text, const std::string& path) { writeFileAtomically(path, text); }

}  // namespace

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

nlohmann::json loadAverage() {
  std::ifstream file("/proc/loadavg");
  double one = 0, five = 0, fifteen = 0;
  if (!(file >> one >> five >> fifteen)) return nullptr;
  return nlohmann::json::array({one, five, fifteen});
}

nlohmann::json machineJson() {
  // The model name, and its family and model numbers (a hypervisor may show only "AMD EPYC", which
  // spans processors of very different speed).
  std::string model = "unknown", family, number;
  std::ifstream cpuinfo("/proc/cpuinfo");
  const auto value = [](const std::string& line) {
    const std::size_t colon = line.find(':');
    const std::size_t start = colon == std::string::npos ? std::string::npos : line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? std::string() : line.substr(start);
  };
  for (std::string line; std::getline(cpuinfo, line) && !line.empty();) {
    if (line.rfind("model name", 0) == 0) model = value(line);
    else if (line.rfind("cpu family", 0) == 0) family = value(line);
    else if (line.rfind("model\t", 0) == 0 || line.rfind("model :", 0) == 0) number = value(line);
  }
  if (!family.empty() && !number.empty()) model += " (family " + family + ", model " + number + ")";
#if defined(__AVX512F__)
  const char* vectors = "AVX-512";
#elif defined(__AVX2__)
  const char* vectors = "AVX2";
#elif defined(__AVX__)
  const char* vectors = "AVX";
#else
  const char* vectors = "SSE2";
#endif
  return {{"date", utcNow()},
          {"cpu", model},
          {"cores", std::thread::hardware_concurrency()},
          {"compiled_for", vectors},
          {"load_average", loadAverage()}};
}

void CsvTable::add(const std::vector<nlohmann::json>& values) {
  std::vector<std::string> row;
  row.reserve(values.size());
  for (const nlohmann::json& value : values) row.push_back(formatValue(value));
  rows.push_back(std::move(row));
}

void writeJsonFile(const nlohmann::json& document, const std::string& path) { writeText(document.dump(2) + "\n", path); }

void writeCsvFile(const CsvTable& table, const std::string& path) {
  std::ostringstream text;
  for (std::size_t i = 0; i < table.columns.size(); ++i) text << (i ? "," : "") << table.columns[i];
  text << "\n";
  for (const auto& row : table.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) text << (i ? "," : "") << row[i];
    text << "\n";
  }
  writeText(text.str(), path);
}

std::string siblingCsvPath(const std::string& csvPath, const std::string& name) {
  const std::size_t dot = csvPath.rfind('.');
  const std::size_t slash = csvPath.find_last_of('/');
  const bool hasExtension = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  const std::string stem = hasExtension ? csvPath.substr(0, dot) : csvPath;
  return stem + "_" + name + ".csv";
}

std::vector<int> parseIntegerList(const std::string& text) {
  std::vector<int> values;
  std::stringstream stream(text);
  std::string item;
  const auto number = [&](const std::string& part) {
    std::size_t used = 0;
    const int value = part.empty() ? -1 : std::stoi(part, &used);
    if (part.empty() || used != part.size()) throw std::invalid_argument("not a number: '" + part + "' in '" + text + "'");
    return value;
  };
  while (std::getline(stream, item, ',')) {
    const std::size_t dash = item.find('-', 1);
    if (dash == std::string::npos) {
      values.push_back(number(item));
      continue;
    }
    const int first = number(item.substr(0, dash)), last = number(item.substr(dash + 1));
    if (last < first) throw std::invalid_argument("empty range '" + item + "' in '" + text + "'");
    for (int value = first; value <= last; ++value) values.push_back(value);
  }
  if (values.empty()) throw std::invalid_argument("empty list '" + text + "'");
  return values;
}

}  // namespace slime
