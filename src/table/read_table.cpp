// A table from a CSV file (see mo2d/table.hpp): header, columns by name, every error at file:line.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include "mo2d/table.hpp"
#include "model/suggest.hpp"

namespace mo2d {

namespace {

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return std::string(s.substr(first, last - first + 1));
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string_view rest = line;
  for (;;) {
    const auto comma = rest.find(',');
    out.push_back(trim(rest.substr(0, comma)));
    if (comma == std::string_view::npos) return out;
    rest.remove_prefix(comma + 1);
  }
}

std::string unquote(std::string_view s) {
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
  return std::string(s);
}

struct Reading {
  std::string path;
  std::string table;
  [[noreturn]] void fail(int line, const std::string& what) const {
    throw Error(
        path + (line > 0 ? ":" + std::to_string(line) : "") + ": table '" + table + "': " + what,
        table);
  }
};

size_t column(const Reading& r, const std::vector<std::string>& header, const std::string& name,
              size_t fallback, int line) {
  if (name.empty()) {
    if (fallback >= header.size())
      r.fail(line, "the header has " + std::to_string(header.size()) +
                       " column(s); a table needs two (x and y)");
    return fallback;
  }
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) {
    std::string list;
    for (const auto& h : header) list += (list.empty() ? "'" : ", '") + h + "'";
    r.fail(line,
           "no column '" + name + "'" + did_you_mean(name, header) + "; the header has " + list);
  }
  return static_cast<size_t>(it - header.begin());
}

bool is_number(const std::string& cell) {
  char* end = nullptr;
  std::strtod(cell.c_str(), &end);
  return !cell.empty() && end == cell.c_str() + cell.size();
}

double number(const Reading& r, const std::string& cell, const std::string& column, int line) {
  if (cell.empty()) r.fail(line, "column '" + column + "' is empty");
  char* end = nullptr;
  const double v = std::strtod(cell.c_str(), &end);
  if (end != cell.c_str() + cell.size())
    r.fail(line, "column '" + column + "': '" + cell + "' is not a number");
  if (!std::isfinite(v)) r.fail(line, "column '" + column + "': " + cell + " is not finite");
  return v;
}

std::string text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The cell's number times the column's scale, refused at its own line when the product is not
// finite (a value that is finite as written may overflow once scaled).
double scaled(const Reading& r, const std::string& cell, const std::string& column, double scale,
              const char* scale_key, int line) {
  const double v = number(r, cell, column, line);
  const double out = scale * v;
  if (!std::isfinite(out))
    r.fail(line, "column '" + column + "': " + cell + " times " + scale_key + " = " + text(scale) +
                     " is out of range (" + text(out) + ")");
  return out;
}

}  // namespace

LookupTable read_table_csv(const std::string& path, std::string name, const CsvColumns& columns,
                           TableOptions options) {
  const Reading r{path, name};
  if (!(columns.scale_x > 0) || !std::isfinite(columns.scale_x))
    r.fail(0, "scale_x must be a finite number > 0 (x must keep increasing), got " +
                  std::to_string(columns.scale_x));
  if (!std::isfinite(columns.scale_y)) r.fail(0, "scale_y must be finite");
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    r.fail(0, "not a regular file");  // a device or a folder: /dev/zero would never end
  std::ifstream in(path, std::ios::binary);
  if (!in) r.fail(0, "cannot open the file");
  std::vector<std::string> header;
  size_t ix = 0, iy = 1;
  std::vector<double> x, y;
  std::vector<int> lines;
  std::string previous;  // x as written on the previous data line
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    const std::string t = trim(text);
    if (t.empty() || t.front() == '#') continue;
    std::vector<std::string> row = cells(t);
    if (header.empty()) {
      if (std::all_of(row.begin(), row.end(), is_number))
        r.fail(line,
               "the first row holds numbers: a header row of column names is expected "
               "before the data (e.g. 'angle, lift')");
      for (const auto& c : row) header.push_back(unquote(c));
      ix = column(r, header, columns.x, 0, line);
      iy = column(r, header, columns.y, 1, line);
      continue;
    }
    if (std::max(ix, iy) >= row.size())
      r.fail(line, "the row has " + std::to_string(row.size()) + " value(s), the column '" +
                       header[std::max(ix, iy)] + "' is number " +
                       std::to_string(std::max(ix, iy) + 1));
    x.push_back(scaled(r, row[ix], header[ix], columns.scale_x, "scale_x", line));
    y.push_back(scaled(r, row[iy], header[iy], columns.scale_y, "scale_y", line));
    lines.push_back(line);
    if (x.size() > 1 && !(x.back() > x[x.size() - 2]))
      r.fail(line, "x must increase: " + header[ix] + " = " + row[ix] + " after " + previous +
                       " on line " + std::to_string(lines[lines.size() - 2]));
    previous = row[ix];
  }
  if (header.empty()) r.fail(0, "the file is empty (a header row of column names is expected)");
  if (x.size() < 2) r.fail(line, "at least 2 points are needed, got " + std::to_string(x.size()));
  try {
    return LookupTable(std::move(name), std::move(x), std::move(y), options);
  } catch (const Error& e) {  // periodic ends that differ: at the last data line
    std::string what = e.what();
    const std::string prefix = "table '" + r.table + "': ";
    if (what.starts_with(prefix)) what.erase(0, prefix.size());
    r.fail(lines.back(), what);
  }
}

}  // namespace mo2d
