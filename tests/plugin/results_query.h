#pragma once
// Reading a results database in the plugin's tests: the first column of the first row of a
// query, as text ("NULL" for NULL, "<no row>" when there is none or the query fails).
#include <sqlite3.h>

#include <string>

namespace criticality::plugin::testing {

inline std::string Query(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* s = nullptr;
  std::string out = "<no row>";
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr) == SQLITE_OK &&
      sqlite3_step(s) == SQLITE_ROW) {
    const unsigned char* t = sqlite3_column_text(s, 0);
    out = t ? reinterpret_cast<const char*>(t) : "NULL";
  }
  sqlite3_finalize(s);
  sqlite3_close(db);
  return out;
}

}  // namespace criticality::plugin::testing
