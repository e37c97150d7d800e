#include "core/base/table_file.h"

#include <charconv>
#include <fstream>
#include <sstream>

#include "core/base/error.h"

namespace prism {

namespace {
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    const auto first = cell.find_first_not_of(" \t\r");
    const auto last = cell.find_last_not_of(" \t\r");
    cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
  }
  return cells;
}
}  // namespace

const std::vector<double>& NumericTable::column(const std::string& name) const {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return columns[i];
  fail("table has no column '{}'", name);
}

NumericTable read_numeric_table(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) fail("{}: cannot open", file.string());
  NumericTable table;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto cells = split(line);
    if (table.names.empty()) {
      table.names = cells;
      table.columns.resize(cells.size());
      continue;
    }
    if (cells.size() != table.names.size())
      fail("{}:{}: expected {} values, found {}", file.string(), line_no, table.names.size(), cells.size());
    for (size_t c = 0; c < cells.size(); ++c) {
      double v = 0;
      const auto [end, ec] = std::from_chars(cells[c].data(), cells[c].data() + cells[c].size(), v);
      if (ec != std::errc() || end != cells[c].data() + cells[c].size())
        fail("{}:{}: '{}' is not a number", file.string(), line_no, cells[c]);
      table.columns[c].push_back(v);
    }
  }
  if (table.rows() == 0) fail("{}: no data rows", file.string());
  return table;
}

}  // namespace prism
