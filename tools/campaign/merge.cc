#include "tools/campaign/merge.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <set>

#include "tools/campaign/campaign_error.h"
#include "tools/campaign/sqlite_db.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace criticality::campaign {
namespace {

const std::set<std::string> kOwnTables = {"campaign", "campaign_runs", "plan_params"};

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS campaign(key TEXT PRIMARY KEY, value TEXT);
CREATE TABLE IF NOT EXISTS campaign_runs(
  run_index INTEGER PRIMARY KEY, scenario TEXT, scenario_path TEXT, label TEXT,
  repetition INTEGER, status TEXT, exit_code INTEGER, signal INTEGER, error TEXT,
  driver_status TEXT, wall_s REAL, max_rss_kb INTEGER, started_utc TEXT, ended_utc TEXT,
  host TEXT, attempt TEXT, command TEXT, stderr_tail TEXT, summary TEXT, merge_note TEXT);
CREATE TABLE IF NOT EXISTS plan_params(
  run_index INTEGER NOT NULL, name TEXT NOT NULL, value TEXT, PRIMARY KEY(run_index, name));
)sql";

std::string JsonText(const json& v) {
  return v.dump(-1, ' ', false, json::error_handler_t::replace);
}

void BindJson(Statement& s, int i, const json& v) {
  if (v.is_null()) {
    s.BindNull(i);
  } else if (v.is_string()) {
    s.Bind(i, v.get<std::string>());
  } else if (v.is_number_integer()) {
    s.Bind(i, v.get<long long>());
  } else if (v.is_number()) {
    s.Bind(i, v.get<double>());
  } else {
    s.Bind(i, JsonText(v));
  }
}

std::string CommandText(const json& argv) {
  std::string s;
  if (!argv.is_array()) return s;
  for (const json& a : argv) {
    std::string arg = a.is_string() ? a.get<std::string>() : JsonText(a);
    const bool quote = arg.empty() || arg.find_first_of(" \t\"'") != std::string::npos;
    s += (s.empty() ? "" : " ") + (quote ? "'" + arg + "'" : arg);
  }
  return s;
}

class Merger {
 public:
  Merger(const CampaignFolder& folder, SqliteDb& db) : folder_(folder), db_(db) {
    db_.Exec(kSchema);
    Statement s = db_.Prepare("SELECT run_index, attempt FROM campaign_runs");
    while (s.Step()) merged_[static_cast<std::size_t>(s.Int(0))] = s.Text(1);
    LoadTables();
  }

  // The tables holding run rows (with a run_index column) and their columns.
  void LoadTables() {
    tables_.clear();
    Statement t = db_.Prepare("SELECT name FROM sqlite_master WHERE type='table'");
    while (t.Step()) {
      const std::string name = t.Text(0);
      if (name.rfind("sqlite_", 0) == 0) continue;
      const auto cols = db_.Columns(name);
      if (std::find(cols.begin(), cols.end(), "run_index") != cols.end())
        tables_[name] = std::set<std::string>(cols.begin(), cols.end());
    }
  }

  void WriteCampaignInfo() {
    const json& info = folder_.info();
    Statement s = db_.Prepare("INSERT OR REPLACE INTO campaign(key, value) VALUES(?, ?)");
    for (const char* key :
         {"name", "fingerprint", "runs", "campaign_file", "repetitions", "scenarios", "axes"}) {
      if (!info.contains(key)) continue;
      s.Bind(1, std::string(key));
      const json& v = info[key];
      s.Bind(2, v.is_string() ? v.get<std::string>() : JsonText(v));
      s.Run();
    }
  }

  MergeTotals Run() {
    MergeTotals t;
    t.runs = folder_.runs();
    for (std::size_t i = 0; i < folder_.runs(); ++i) {
      const auto have = merged_.find(i);
      if (!folder_.IsComplete(i)) {
        if (have != merged_.end()) {
          db_.Exec("BEGIN");
          DeleteRun(i);
          db_.Exec("COMMIT");
          ++t.removed;
        }
        ++t.incomplete;
        continue;
      }
      ++t.complete;
      const fs::path dir = folder_.RunDir(i);
      json record;
      {
        std::ifstream in(dir / "run.json");
        try {
          record = json::parse(in);
        } catch (const json::exception& e) {
          throw CampaignError((dir / "run.json").string() + ": not a valid run record (" +
                              e.what() + "); remove the folder " + dir.string() +
                              " and run the campaign again to redo it");
        }
      }
      const std::string attempt = record.value("attempt", "");
      if (have != merged_.end() && have->second == attempt) {
        ++t.unchanged;
        continue;
      }
      try {
        MergeRun(i, dir, record);
      } catch (const CampaignError& e) {
        // One unreadable run file must not stop the campaign's merge: keep the run's record.
        const std::string note = std::string("results not merged: ") + e.what();
        MergeRun(i, dir, record, false, note);
        t.unreadable.push_back("run " + std::to_string(i) + ": " + note);
      }
      ++t.merged;
    }
    // Runs beyond the plan: the campaign file changed and has fewer runs now.
    for (auto it = merged_.lower_bound(folder_.runs()); it != merged_.end(); ++it) {
      db_.Exec("BEGIN");
      DeleteRun(it->first);
      db_.Exec("COMMIT");
      ++t.removed;
    }
    t.tables = 0;
    for (const auto& [name, cols] : tables_) t.tables += kOwnTables.count(name) ? 0 : 1;
    return t;
  }

 private:
  void DeleteRun(std::size_t i) {
    for (const auto& [name, cols] : tables_) {
      db_.Prepare("DELETE FROM " + QuoteId(name) + " WHERE run_index = ?")
          .Bind(1, static_cast<long long>(i))
          .Run();
    }
  }

  // A run's rows in one transaction. Without `with_results` (its file could not be read), only
  // its campaign_runs row, with `note` saying why.
  void MergeRun(std::size_t i, const fs::path& dir, const json& r, bool with_results = true,
                const std::string& note = "") {
    const fs::path results = dir / "run.sqlite";
    const bool attach =
        with_results && r.contains("results") && r["results"].is_string() && fs::exists(results);
    if (attach) {
      db_.Prepare("ATTACH DATABASE ? AS r").Bind(1, results.string()).Run();
    }
    try {
      db_.Exec("BEGIN");
      DeleteRun(i);
      Statement run = db_.Prepare(
          "INSERT INTO campaign_runs(run_index, scenario, scenario_path, label, repetition, "
          "status, exit_code, signal, error, driver_status, wall_s, max_rss_kb, started_utc, "
          "ended_utc, host, attempt, command, stderr_tail, summary, merge_note) "
          "VALUES(?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)");
      run.Bind(1, static_cast<long long>(i));
      int k = 2;
      for (const char* key : {"scenario", "scenario_path", "label", "repetition", "status",
                              "exit_code", "signal", "error", "driver_status", "wall_s",
                              "max_rss_kb", "started_utc", "ended_utc", "host", "attempt"}) {
        BindJson(run, k++, r.contains(key) ? r[key] : json());
      }
      run.Bind(k++, CommandText(r.value("command", json::array())));
      BindJson(run, k++, r.contains("stderr_tail") ? r["stderr_tail"] : json());
      const json summary = r.contains("summary") ? r["summary"] : json();
      if (summary.is_null())
        run.BindNull(k++);
      else
        run.Bind(k++, JsonText(summary));
      if (note.empty())
        run.BindNull(k++);
      else
        run.Bind(k++, note);
      run.Run();
      if (r.contains("params") && r["params"].is_object()) {
        Statement p = db_.Prepare("INSERT INTO plan_params(run_index, name, value) VALUES(?,?,?)");
        for (const auto& [name, value] : r["params"].items()) {
          p.Bind(1, static_cast<long long>(i)).Bind(2, name);
          BindJson(p, 3, value);
          p.Run();
        }
      }
      if (attach) CopyTables(i);
      db_.Exec("COMMIT");
    } catch (...) {
      sqlite3_exec(db_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
      if (attach) sqlite3_exec(db_.handle(), "DETACH DATABASE r", nullptr, nullptr, nullptr);
      LoadTables();  // tables created in the rolled-back transaction are gone
      throw;
    }
    if (attach) db_.Exec("DETACH DATABASE r");
  }

  void CopyTables(std::size_t i) {
    std::vector<std::string> names;
    {
      Statement t = db_.Prepare(
          "SELECT name FROM r.sqlite_master WHERE type='table' AND name NOT LIKE 'sqlite_%' "
          "ORDER BY name");
      while (t.Step()) names.push_back(t.Text(0));
    }
    for (const std::string& name : names) {
      const std::string target = kOwnTables.count(name) ? "run_" + name : name;
      std::vector<std::pair<std::string, std::string>> cols;  // name, declared type
      {
        Statement c = db_.Prepare("PRAGMA r.table_info(" + QuoteId(name) + ")");
        while (c.Step()) cols.emplace_back(c.Text(1), c.Text(2));
      }
      if (cols.empty()) continue;
      auto it = tables_.find(target);
      if (it == tables_.end()) {
        std::string ddl = "CREATE TABLE " + QuoteId(target) + "(run_index INTEGER NOT NULL";
        for (const auto& [c, type] : cols)
          ddl += ", " + QuoteId(c) + (type.empty() ? "" : " " + type);
        db_.Exec(ddl + ")");
        db_.Exec("CREATE INDEX " + QuoteId(target + "_by_run") + " ON " + QuoteId(target) +
                 "(run_index)");
        std::set<std::string> have{"run_index"};
        for (const auto& [c, type] : cols) have.insert(c);
        it = tables_.emplace(target, std::move(have)).first;
      } else {
        for (const auto& [c, type] : cols) {
          if (it->second.count(c)) continue;
          db_.Exec("ALTER TABLE " + QuoteId(target) + " ADD COLUMN " + QuoteId(c) +
                   (type.empty() ? "" : " " + type));
          it->second.insert(c);
        }
      }
      std::string list;
      for (const auto& [c, type] : cols) list += ", " + QuoteId(c);
      db_.Prepare("INSERT INTO main." + QuoteId(target) + "(run_index" + list + ") SELECT ?" +
                  list + " FROM r." + QuoteId(name))
          .Bind(1, static_cast<long long>(i))
          .Run();
    }
  }

  const CampaignFolder& folder_;
  SqliteDb& db_;
  std::map<std::size_t, std::string> merged_;
  std::map<std::string, std::set<std::string>> tables_;  ///< tables holding run rows: columns
};

}  // namespace

MergeTotals MergeCampaign(const CampaignFolder& folder) {
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path path = folder.dir() / "campaign.sqlite";
  SqliteDb db(path.string(), true);
  db.Exec("PRAGMA synchronous=NORMAL");
  Merger m(folder, db);
  db.Exec("BEGIN");
  m.WriteCampaignInfo();
  db.Exec("COMMIT");
  MergeTotals t = m.Run();
  t.database = path;
  t.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

}  // namespace criticality::campaign
