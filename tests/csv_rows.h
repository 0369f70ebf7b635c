// The rows of a run's CSV output (energy.csv, reactions.csv, …) as maps from the header's column
// names to numbers, for tests that read a curve back from what a run wrote. Every cell must be a
// number (std::stod throws otherwise, which fails the test that asked).
#pragma once

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace nmm::test {

inline std::vector<std::map<std::string, double>> csv_rows(const std::string& path) {
  std::vector<std::map<std::string, double>> rows;
  std::ifstream csv(path);
  std::string line, cell;
  std::getline(csv, line);
  std::vector<std::string> names;
  for (std::istringstream head(line); std::getline(head, cell, ',');) names.push_back(cell);
  while (std::getline(csv, line)) {
    std::map<std::string, double> row;
    std::istringstream in(line);
    for (const std::string& n : names) {
      std::getline(in, cell, ',');
      row[n] = std::stod(cell);
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace nmm::test
