#include "tools/campaign/table_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "tools/campaign/campaign_error.h"

namespace criticality::campaign {

std::string Cell(std::optional<double> v, int digits) { return v ? Cell(*v, digits) : ""; }

std::string Cell(double v, int digits) {
  if (!std::isfinite(v)) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  std::string s = buf;
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s == "-0" ? "0" : s;
}

std::string Cell(long long v) { return std::to_string(v); }

std::string SigCell(std::optional<double> v, int significant) {
  if (!v || !std::isfinite(*v)) return "";
  if (*v == 0.0) return "0";
  const int magnitude = static_cast<int>(std::floor(std::log10(std::fabs(*v))));
  return Cell(*v, std::max(0, significant - 1 - magnitude));
}

void WriteCsv(const Table& t, const std::filesystem::path& file) {
  std::ofstream out(file);
  auto write_row = [&](const std::vector<std::string>& row) {
    for (std::size_t k = 0; k < row.size(); ++k) {
      const std::string& c = row[k];
      if (k) out << ',';
      if (c.find_first_of(",\"\n\r") != std::string::npos) {
        out << '"';
        for (char ch : c) out << (ch == '"' ? "\"\"" : std::string(1, ch));
        out << '"';
      } else {
        out << c;
      }
    }
    out << '\n';
  };
  write_row(t.columns);
  for (const auto& r : t.rows) write_row(r);
  if (!out) throw CampaignError("cannot write '" + file.string() + "'");
}

std::string MarkdownTable(const Table& t, std::size_t max_rows) {
  auto escape = [](const std::string& c) {
    std::string s;
    for (char ch : c) {
      if (ch == '|')
        s += "\\|";
      else if (ch == '\n')
        s += ' ';
      else
        s += ch;
    }
    return s;
  };
  std::string s = "|";
  for (const auto& c : t.columns) s += " " + escape(c) + " |";
  s += "\n|";
  for (std::size_t k = 0; k < t.columns.size(); ++k) s += "---|";
  s += "\n";
  const std::size_t n = max_rows ? std::min(max_rows, t.rows.size()) : t.rows.size();
  for (std::size_t r = 0; r < n; ++r) {
    s += "|";
    for (const auto& c : t.rows[r]) s += " " + escape(c) + " |";
    s += "\n";
  }
  if (n < t.rows.size())
    s += "\n(" + std::to_string(t.rows.size() - n) + " more rows in the CSV file)\n";
  return s;
}

}  // namespace criticality::campaign
