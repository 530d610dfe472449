// mo2d plot CSV COLUMN... [-o OUT.png|svg|pdf] [--x COLUMN] [--title TEXT] [--log-x] [--log-y]
// [--markers]: draws columns of a CSV file written by mo2d (or any CSV with a header of names)
// against time, or against another column, on linear or logarithmic axes (a cell "nan", or <= 0
// on a log axis, is a gap), with the project's renderer (mo2d/render/plot.hpp). The axis labels
// carry the units: from the CSV's units row (--units-row) or else from the JSON summary next to it
// (NAME_inverse.json "columns"). An unknown column is a usage error (status 2) listing the close
// names; a cell that is not a number is an error at its line and column (status 1).
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "command.hpp"
#include "mo2d/error.hpp"
#include "mo2d/render.hpp"
#include "scene_options.hpp"

namespace mo2d::cli {

namespace {

struct PlotCliOptions {
  std::string csv{};
  std::vector<std::string> columns{};
  std::string out{};  // default: next to the CSV, STEM_plot.png
  std::string x{};    // default: t, else the first column
  std::string title{};
  bool log_x = false, log_y = false;  // logarithmic axes (decades)
  bool markers = false;               // a dot at every point
};

// A CSV file as read back: names, units (empty strings when the file has no units row), values.
struct CsvData {
  std::vector<std::string> names{}, units{};
  std::vector<std::vector<double>> columns{};
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream s(line);
  while (std::getline(s, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
    cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

bool parse_number(const std::string& cell, double& v) {
  const char* end = cell.data() + cell.size();
  const auto [p, ec] = std::from_chars(cell.data(), end, v);
  return ec == std::errc() && p == end;
}

CsvData read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open the CSV file");
  CsvData d;
  std::string line;
  if (!std::getline(in, line)) throw Error(path + ": empty file (expected a header of names)");
  d.names = split(line);
  d.columns.resize(d.names.size());
  for (int n = 2; std::getline(in, line); ++n) {
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = split(line);
    if (cells.size() != d.names.size())
      throw Error(path + ":" + std::to_string(n) + ": " + std::to_string(cells.size()) +
                  " cells, the header has " + std::to_string(d.names.size()));
    std::vector<double> row(cells.size());
    bool numbers = true;
    std::size_t bad = 0;
    for (std::size_t j = 0; j < cells.size() && numbers; ++j)
      if (!parse_number(cells[j], row[j])) numbers = false, bad = j;
    if (!numbers && n == 2 && d.units.empty()) {  // a units row (mo2d inverse --units-row)
      d.units = cells;
      continue;
    }
    if (!numbers)
      throw Error(path + ":" + std::to_string(n) + ": column '" + d.names[bad] + "': '" +
                  cells[bad] + "' is not a number");
    for (std::size_t j = 0; j < cells.size(); ++j) d.columns[j].push_back(row[j]);
  }
  if (d.units.empty()) d.units.assign(d.names.size(), "");
  return d;
}

// Units from the JSON summary beside the CSV (same name, .json), when the CSV has no units row.
void units_from_summary(const std::string& csv, CsvData& d) {
  if (std::any_of(d.units.begin(), d.units.end(), [](const auto& u) { return !u.empty(); })) return;
  std::ifstream in(std::filesystem::path(csv).replace_extension(".json"));
  if (!in) return;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.contains("columns") || !j["columns"].is_object()) return;
  for (std::size_t k = 0; k < d.names.size(); ++k)
    if (const auto it = j["columns"].find(d.names[k]); it != j["columns"].end() && it->is_string())
      d.units[k] = it->get<std::string>();
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// "no column 'crank.torqe' in out/x.csv; close names: crank.torque, ..." (or the first names).
[[noreturn]] void unknown_column(const std::string& name, const std::string& path,
                                 const std::vector<std::string>& names) {
  std::vector<std::pair<std::size_t, std::string>> close;
  const std::size_t limit = std::max<std::size_t>(2, name.size() / 6);
  for (const auto& n : names) {
    const std::size_t d = edit_distance(name, n);
    if (d <= limit || n.find(name) != std::string::npos) close.emplace_back(d, n);
  }
  std::stable_sort(close.begin(), close.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string list;
  const std::size_t shown = std::min<std::size_t>(close.empty() ? names.size() : close.size(), 8);
  for (std::size_t k = 0; k < shown; ++k)
    list += (k ? ", " : "") + (close.empty() ? names[k] : close[k].second);
  throw UsageError("plot: no column '" + name + "' in " + path +
                   (close.empty() ? "; its columns are " : "; close names: ") + list +
                   (shown < (close.empty() ? names.size() : close.size()) ? ", ..." : ""));
}

std::size_t column_of(const std::string& name, const std::string& path, const CsvData& d) {
  const auto it = std::find(d.names.begin(), d.names.end(), name);
  if (it == d.names.end()) unknown_column(name, path, d.names);
  return static_cast<std::size_t>(it - d.names.begin());
}

std::string with_unit(const std::string& label, const std::string& unit) {
  return unit.empty() ? label : label + " (" + unit + ")";
}

int plot(const PlotCliOptions& o) {
  std::filesystem::path out = o.out;
  if (out.empty())
    out = std::filesystem::path(o.csv).replace_filename(
        std::filesystem::path(o.csv).stem().string() + "_plot.png");
  const std::string ext = out.extension().string();
  if (ext != ".png" && ext != ".svg" && ext != ".pdf")
    throw UsageError("plot: -o " + out.string() + ": the plot is a .png, .svg or .pdf file");
  CsvData d = read_csv(o.csv);
  units_from_summary(o.csv, d);
  const std::string xname =
      !o.x.empty()
          ? o.x
          : (std::find(d.names.begin(), d.names.end(), "t") != d.names.end() ? "t"
                                                                             : d.names.front());
  const std::size_t xc = column_of(xname, o.csv, d);
  Plot p;
  p.title = o.title.empty() ? std::filesystem::path(o.csv).filename().string() : o.title;
  p.x.label = xname == "t" ? with_unit("time", d.units[xc]) : with_unit(xname, d.units[xc]);
  std::vector<std::string> units;
  for (const std::string& name : o.columns) {
    const std::size_t c = column_of(name, o.csv, d);
    p.series.push_back(
        Series{.label = name, .x = d.columns[xc], .y = d.columns[c], .markers = o.markers});
    if (std::find(units.begin(), units.end(), d.units[c]) == units.end())
      units.push_back(d.units[c]);
  }
  // the y axis: the columns' common unit; several units are named in the legend instead
  if (units.size() == 1)
    p.y.label = with_unit(o.columns.size() == 1 ? o.columns.front() : "value", units.front());
  else
    for (std::size_t k = 0; k < o.columns.size(); ++k)
      p.series[k].label = with_unit(o.columns[k], d.units[column_of(o.columns[k], o.csv, d)]);
  p.legend = o.columns.size() > 1 || units.size() > 1;
  p.x.log = o.log_x;
  p.y.log = o.log_y;
  if (std::error_code ec;
      out.has_parent_path() && (std::filesystem::create_directories(out.parent_path(), ec), ec))
    throw Error("plot: -o " + out.string() + ": cannot create the folder " +
                out.parent_path().string() + ": " + ec.message());
  write_plot(p, out.string());
  std::printf("  wrote %s\n", out.string().c_str());
  return 0;
}

}  // namespace

Command add_plot_command(CLI::App& app) {
  auto o = std::make_shared<PlotCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "plot", "Plot columns of a CSV file (mo2d's or any with a header) against time or a column");
  sub->add_option("CSV", o->csv, "the CSV file (a header of names, then rows of numbers)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("COLUMN", o->columns, "the columns to plot (one or more)")->required();
  sub->add_option("-o,--output", o->out,
                  "the plot: .png, .svg or .pdf (default: beside the CSV, STEM_plot.png)");
  sub->add_option("--x", o->x, "the column on the horizontal axis (default: t, else the first)");
  sub->add_option("--title", o->title, "the plot's title (default: the CSV's file name)");
  sub->add_flag("--log-x", o->log_x, "logarithmic horizontal axis (values <= 0 are gaps)");
  sub->add_flag("--log-y", o->log_y, "logarithmic vertical axis (values <= 0 are gaps)");
  sub->add_flag("--markers", o->markers, "a dot at every point (tables: error against step)");
  return {sub, [o] { return plot(*o); }};
}

}  // namespace mo2d::cli
