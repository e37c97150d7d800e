#pragma once
// Reads Prism's numeric table files (data/**.csv): '#' comment lines, one header line naming
// the columns, then rows of comma-separated numbers. Errors name the file and the line.

#include <filesystem>
#include <string>
#include <vector>

namespace prism {

struct NumericTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;  // columns[c][row]

  const std::vector<double>& column(const std::string& name) const;
  size_t rows() const { return columns.empty() ? 0 : columns[0].size(); }
};

NumericTable read_numeric_table(const std::filesystem::path& file);

}  // namespace prism
