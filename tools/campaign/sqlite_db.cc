#include "tools/campaign/sqlite_db.h"

#include "tools/campaign/campaign_error.h"

namespace criticality::campaign {

std::string QuoteId(const std::string& name) {
  std::string out = "\"";
  for (char c : name) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

Statement::Statement(sqlite3* db, const std::string& sql, const std::string& file)
    : db_(db), file_(file), sql_(sql) {
  if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &s_, nullptr) != SQLITE_OK) {
    throw CampaignError(file_ + ": " + sqlite3_errmsg(db_) + " (in: " + sql_.substr(0, 120) + ")");
  }
}
Statement::~Statement() { sqlite3_finalize(s_); }
Statement::Statement(Statement&& o) noexcept
    : db_(o.db_), s_(o.s_), file_(std::move(o.file_)), sql_(std::move(o.sql_)) {
  o.s_ = nullptr;
}

Statement& Statement::Bind(int i, const std::string& v) {
  sqlite3_bind_text(s_, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
  return *this;
}
Statement& Statement::Bind(int i, long long v) {
  sqlite3_bind_int64(s_, i, v);
  return *this;
}
Statement& Statement::Bind(int i, double v) {
  sqlite3_bind_double(s_, i, v);
  return *this;
}
Statement& Statement::BindNull(int i) {
  sqlite3_bind_null(s_, i);
  return *this;
}

bool Statement::Step() {
  const int rc = sqlite3_step(s_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  throw CampaignError(file_ + ": " + sqlite3_errmsg(db_) + " (in: " + sql_.substr(0, 120) + ")");
}
void Statement::Run() {
  while (Step()) {
  }
  Reset();
}
void Statement::Reset() {
  sqlite3_reset(s_);
  sqlite3_clear_bindings(s_);
}

bool Statement::IsNull(int col) const { return sqlite3_column_type(s_, col) == SQLITE_NULL; }
long long Statement::Int(int col) const { return sqlite3_column_int64(s_, col); }
double Statement::Real(int col) const { return sqlite3_column_double(s_, col); }
std::string Statement::Text(int col) const {
  const unsigned char* t = sqlite3_column_text(s_, col);
  return t ? reinterpret_cast<const char*>(t) : "";
}
std::optional<double> Statement::OptReal(int col) const {
  if (IsNull(col)) return std::nullopt;
  return Real(col);
}
int Statement::columns() const { return sqlite3_column_count(s_); }
std::string Statement::ColumnName(int col) const { return sqlite3_column_name(s_, col); }

SqliteDb::SqliteDb(const std::string& path, bool create, bool read_only) : path_(path) {
  const int flags =
      read_only ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE | (create ? SQLITE_OPEN_CREATE : 0);
  if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    const std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw CampaignError("cannot open '" + path + "': " + msg);
  }
  sqlite3_busy_timeout(db_, 10000);
}
SqliteDb::~SqliteDb() { sqlite3_close(db_); }

void SqliteDb::Exec(const std::string& sql) {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string msg = err ? err : "unknown error";
    sqlite3_free(err);
    throw CampaignError(path_ + ": " + msg + " (in: " + sql.substr(0, 120) + ")");
  }
}

Statement SqliteDb::Prepare(const std::string& sql) { return Statement(db_, sql, path_); }

std::vector<std::string> SqliteDb::Columns(const std::string& table, const std::string& schema) {
  std::vector<std::string> cols;
  Statement s = Prepare("PRAGMA " + QuoteId(schema) + ".table_info(" + QuoteId(table) + ")");
  while (s.Step()) cols.push_back(s.Text(1));
  return cols;
}

bool SqliteDb::HasTable(const std::string& table, const std::string& schema) {
  Statement s =
      Prepare("SELECT 1 FROM " + QuoteId(schema) + ".sqlite_master WHERE type='table' AND name=?");
  s.Bind(1, table);
  return s.Step();
}

}  // namespace criticality::campaign
