#pragma once
// A thin RAII layer over SQLite for merge and report: statements, bindings, errors as
// CampaignError with the file and the statement that failed.
#include <sqlite3.h>

#include <optional>
#include <string>
#include <vector>

namespace criticality::campaign {

class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql, const std::string& file);
  ~Statement();
  Statement(Statement&& o) noexcept;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement& operator=(Statement&&) = delete;

  Statement& Bind(int i, const std::string& v);
  Statement& Bind(int i, long long v);
  Statement& Bind(int i, double v);
  Statement& BindNull(int i);
  /** True while a row is available. */
  bool Step();
  /** Runs to completion (for statements without rows). */
  void Run();
  void Reset();

  bool IsNull(int col) const;
  long long Int(int col) const;
  double Real(int col) const;
  std::string Text(int col) const;
  std::optional<double> OptReal(int col) const;
  int columns() const;
  std::string ColumnName(int col) const;

 private:
  sqlite3* db_;
  sqlite3_stmt* s_{nullptr};
  std::string file_;
  std::string sql_;
};

class SqliteDb {
 public:
  /** Opens `path` (read-write, created when `create`; read-only when `read_only`). */
  SqliteDb(const std::string& path, bool create, bool read_only = false);
  ~SqliteDb();
  SqliteDb(const SqliteDb&) = delete;
  SqliteDb& operator=(const SqliteDb&) = delete;

  void Exec(const std::string& sql);
  Statement Prepare(const std::string& sql);
  sqlite3* handle() { return db_; }
  const std::string& path() const { return path_; }

  /** Column names of a table (PRAGMA table_info); empty when the table does not exist. */
  std::vector<std::string> Columns(const std::string& table, const std::string& schema = "main");
  bool HasTable(const std::string& table, const std::string& schema = "main");

 private:
  std::string path_;
  sqlite3* db_{nullptr};
};

/** "name" quoted as an SQL identifier. */
std::string QuoteId(const std::string& name);

}  // namespace criticality::campaign
