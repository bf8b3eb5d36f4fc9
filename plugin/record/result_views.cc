#include "plugin/record/result_views.h"

#include <charconv>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

#include "result_views_sql.h"  // generated from result_views.sql (result_views.cmake)

namespace criticality::plugin {
namespace {

constexpr const char* kCreateView = "CREATE VIEW {{schema}}.";

bool IsIdentifier(const std::string& s) {
  if (s.empty()) return false;
  for (const char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '.';
    if (!ok) return false;
  }
  return true;
}

std::string Identifier(const std::string& what, const std::string& s) {
  if (!IsIdentifier(s)) {
    throw std::invalid_argument("result views: " + what + " '" + s +
                                "' is not a plain SQL identifier");
  }
  return s;
}

// The names the template creates, in its order.
std::vector<std::string> ViewNames() {
  std::vector<std::string> names;
  const std::string& sql = ResultViewsTemplate();
  const std::string create = kCreateView;
  for (auto at = sql.find(create); at != std::string::npos; at = sql.find(create, at + 1)) {
    const std::size_t from = at + create.size();
    std::size_t to = from;
    while (to < sql.size() && IsIdentifier(std::string(1, sql[to]))) ++to;
    names.push_back(sql.substr(from, to - from));
  }
  return names;
}

std::string Fill(const std::string& text, const std::map<std::string, std::string>& values) {
  std::string out;
  std::size_t at = 0;
  while (true) {
    const std::size_t open = text.find("{{", at);
    if (open == std::string::npos) break;
    const std::size_t close = text.find("}}", open);
    if (close == std::string::npos) throw std::logic_error("result views: unclosed '{{'");
    const std::string name = text.substr(open + 2, close - open - 2);
    const auto it = values.find(name);
    if (it == values.end()) throw std::logic_error("result views: no value for {{" + name + "}}");
    out.append(text, at, open - at);
    out += it->second;
    at = close + 2;
  }
  out.append(text, at, std::string::npos);
  return out;
}

int SignificantDigits(const std::string& decimal) {
  int digits = 0;
  bool leading = true;
  for (const char c : decimal) {
    if (c == 'e' || c == 'E') break;
    if (c < '0' || c > '9') continue;
    if (leading && c == '0') continue;
    leading = false;
    ++digits;
  }
  return digits;
}

// value = m / 2^k with m an integer: exact in SQLite, whose decimal reader may round a long
// decimal differently from the C library (SQLite 3.40 reads 2.024585207138345 one ulp off).
std::string ExactQuotient(double value) {
  int exponent = 0;
  const double fraction = std::frexp(value, &exponent);
  long long m = static_cast<long long>(std::ldexp(fraction, 53));
  int k = 53 - exponent;
  while (k > 0 && m % 2 == 0) {
    m /= 2;
    --k;
  }
  if (k < -9 || k > 62) throw std::invalid_argument("result views: number out of range");
  const std::string integer = std::to_string(k < 0 ? m * (1LL << -k) : m);
  if (k <= 0) return "CAST(" + integer + " AS REAL)";
  return "(CAST(" + integer + " AS REAL) / " + std::to_string(1LL << k) + ")";
}

}  // namespace

ResultViewKeys ResultViewKeys::RunFile() { return ResultViewKeys{}; }

ResultViewKeys ResultViewKeys::Campaign(double grace_s) {
  ResultViewKeys k;
  k.schema = "temp";
  k.run_key = "run_index";
  k.runs_key = "run_index";
  k.grace_s = grace_s;
  return k;
}

const std::string& ResultViewsTemplate() {
  static const std::string text = kResultViewsSqlText;
  return text;
}

std::string SqlRealLiteral(double value) {
  if (!std::isfinite(value)) throw std::invalid_argument("result views: number not finite");
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, value);
  std::string s(buf, res.ptr);
  if (SignificantDigits(s) > 15) return ExactQuotient(value);
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

std::string ResultViewsSql(const ResultViewKeys& keys) {
  return Fill(ResultViewsTemplate(),
              {{"schema", Identifier("schema", keys.schema)},
               {"run_key", Identifier("run key", keys.run_key)},
               {"runs_key", Identifier("runs key", keys.runs_key)},
               {"warnings", Identifier("warnings table", keys.warnings)},
               {"collisions", Identifier("collisions table", keys.collisions)},
               {"critical_events", Identifier("critical events table", keys.critical_events)},
               {"runs", Identifier("runs table", keys.runs)},
               {"steps", Identifier("steps table", keys.steps)},
               {"attributed", keys.attributed ? "1" : "0"},
               {"step_main_object", keys.attributed ? "s.main_object" : "NULL"},
               {"grace_s", SqlRealLiteral(keys.grace_s)}});
}

std::string DropResultViewsSql(const ResultViewKeys& keys) {
  const std::string schema = Identifier("schema", keys.schema);
  const std::vector<std::string> names = ViewNames();
  std::string sql;
  for (auto it = names.rbegin(); it != names.rend(); ++it) {
    sql += "DROP VIEW IF EXISTS " + schema + "." + *it + ";\n";
  }
  return sql;
}

}  // namespace criticality::plugin
