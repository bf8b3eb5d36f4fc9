#pragma once
// Tables of the report: one header and rows of cells, written as CSV (RFC 4180 quoting) and as
// a Markdown table.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace criticality::campaign {

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
};

/** A number for a table: `digits` after the point, trailing zeros trimmed; "" when absent. */
std::string Cell(double v, int digits = 3);
std::string Cell(std::optional<double> v, int digits = 3);
std::string Cell(long long v);
/** A number with `significant` significant digits, never in exponent form (0.000123, 4560);
 *  "" when absent. For rates, whose size varies over orders of magnitude. */
std::string SigCell(std::optional<double> v, int significant = 3);

void WriteCsv(const Table& t, const std::filesystem::path& file);
/** At most `max_rows` rows (0: all), with a line saying how many were left out. */
std::string MarkdownTable(const Table& t, std::size_t max_rows = 0);

}  // namespace criticality::campaign
