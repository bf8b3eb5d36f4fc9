// A stand-in for sumo-criticality in the campaign tool's tests and benchmark: the same
// interface (options, --output FILE, --no-progress, `--` SUMO options, a JSON summary as the last
// stdout line, exit codes), no SUMO and no estimator. What it writes is a deterministic function
// of its options, so tests know every number the report must show.
//
// Its own options (put them on a campaign's grid to shape runs):
//   --stand-in-exit N        exit with N after writing (2: bad input before writing anything)
//   --stand-in-sleep S       sleep S seconds first (SIGTERM ends it as "interrupted", exit 0)
//   --stand-in-ignore-term   ignore SIGTERM (for the SIGKILL escalation)
//   --stand-in-steps N       steps per run (default 10, time 0.1 s apart), one ego "ego"
//   --stand-in-collide T     a collision of ego with "other" at time T (lane e1_0, pos 12.5),
//                            unless --act brake (braking avoids it)
//   --stand-in-warn T        a warning episode of ego starting at T, ending 0.5 s later
//   --stand-in-overlap T     a critical event at T: ego's body overlaps person "p1" (table
//                            critical_events, as the driver writes it)
//   --stand-in-newer         write the columns and tables of a newer driver (warnings x_m, y_m,
//                            edge; collisions x_m, y_m, involves_ego; an ego_events table;
//                            runs.step_length_s 0.1; egos: ego a "passenger"; warning_scenes)
//   --stand-in-class C       with --stand-in-newer: the ego's vehicle class (default passenger)
//   --stand-in-no-anticipation  a collisions table without the anticipation_s column
//   --stand-in-no-db         write no database at all (pure process overhead)
//   --stand-in-log FILE      append "<working directory>\n" to FILE (counts executions)
//   --check-options          check --act and --warn-threshold as the driver does, print
//                            "options ok" and exit 0, or the driver's one-line error and exit 2
// The p of step k is a deterministic function of the seed (`-- --seed N`) and k.
#include <fcntl.h>
#include <signal.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

volatile sig_atomic_t g_term = 0;
extern "C" void OnTerm(int) { g_term = 1; }

const char* kOptions[] = {"config",
                          "sumo-config",
                          "ego",
                          "all-vehicles",
                          "act",
                          "warn-threshold",
                          "warn-release",
                          "brake-threshold",
                          "backend",
                          "threads",
                          "profiles",
                          "horizon",
                          "range",
                          "end",
                          "output",
                          "no-progress",
                          "stand-in-exit",
                          "stand-in-sleep",
                          "stand-in-ignore-term",
                          "stand-in-steps",
                          "stand-in-collide",
                          "stand-in-warn",
                          "stand-in-overlap",
                          "stand-in-newer",
                          "stand-in-no-db",
                          "stand-in-no-anticipation",
                          "stand-in-log",
                          "check-options",
                          "stand-in-class"};

bool Exec(sqlite3* db, const std::string& sql) {
  char* err = nullptr;
  if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    std::fprintf(stderr, "stand-in: sqlite: %s\n", err ? err : "?");
    sqlite3_free(err);
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  std::string output, config, log, act = "warn", vclass = "passenger";
  int exit_code = 0, steps = 10, seed = 0, profiles = 6;
  double sleep_s = 0, collide = -1, warn = -1, overlap = -1;
  bool newer = false, no_db = false, ignore_term = false, no_anticipation = false;
  bool check_options = false;
  std::string warn_threshold = "0.9";
  std::string command;  // SQL-quoted below
  for (int i = 0; i < argc; ++i) {
    for (const char* c = argv[i]; *c; ++c)
      command += *c == '\'' ? std::string("''") : std::string(1, *c);
    command += i + 1 < argc ? " " : "";
  }
  bool sumo = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--") {
      sumo = true;
    } else if (sumo) {
      if (a == "--seed") seed = std::atoi(next().c_str());
    } else if (a == "--help") {
      std::printf("stand-in for sumo-criticality\n");
      for (const char* o : kOptions) std::printf("  --%s arg\n", o);
      return 0;
    } else if (a == "--output") {
      output = next();
    } else if (a == "--config" || a == "--sumo-config") {
      config = next();
    } else if (a == "--act") {
      act = next();
    } else if (a == "--profiles") {
      profiles = std::atoi(next().c_str());
    } else if (a == "--stand-in-exit") {
      exit_code = std::atoi(next().c_str());
    } else if (a == "--stand-in-sleep") {
      sleep_s = std::atof(next().c_str());
    } else if (a == "--stand-in-steps") {
      steps = std::atoi(next().c_str());
    } else if (a == "--stand-in-collide") {
      collide = std::atof(next().c_str());
    } else if (a == "--stand-in-warn") {
      warn = std::atof(next().c_str());
    } else if (a == "--stand-in-overlap") {
      overlap = std::atof(next().c_str());
    } else if (a == "--stand-in-newer") {
      newer = true;
    } else if (a == "--stand-in-no-anticipation") {
      no_anticipation = true;
    } else if (a == "--stand-in-no-db") {
      no_db = true;
    } else if (a == "--stand-in-ignore-term") {
      ignore_term = true;
    } else if (a == "--stand-in-log") {
      log = next();
    } else if (a == "--stand-in-class") {
      vclass = next();
    } else if (a == "--check-options") {
      check_options = true;
    } else if (a == "--warn-threshold") {
      warn_threshold = next();
    } else if (a == "--all-vehicles" || a == "--no-progress") {
    } else if (a.rfind("--", 0) == 0) {
      bool known = false;
      for (const char* o : kOptions) known = known || a == std::string("--") + o;
      if (!known) {
        std::fprintf(stderr, "sumo-criticality: error: unrecognised option '%s'\n", a.c_str());
        return 2;
      }
      next();
    }
  }
  if (check_options) {  // the driver's own checks of these two values, in its words
    const double t = std::atof(warn_threshold.c_str());
    if (act != "none" && act != "warn" && act != "brake") {
      std::fprintf(stderr, "sumo-criticality: error: --act '%s': use none, warn or brake\n",
                   act.c_str());
      return 2;
    }
    if (!(t > 0.0 && t <= 1.0)) {
      std::fprintf(stderr, "sumo-criticality: error: --warn-threshold %s: must be in (0, 1]\n",
                   warn_threshold.c_str());
      return 2;
    }
    std::printf("sumo-criticality: options ok\n");
    return 0;
  }
  if (!log.empty()) {
    char cwd[4096] = {};
    if (getcwd(cwd, sizeof cwd)) {
      const int fd = open(log.c_str(), O_WRONLY | O_APPEND | O_CREAT, 0644);
      const std::string line = std::string(cwd) + "\n";
      if (fd >= 0) {
        (void)!write(fd, line.data(), line.size());
        close(fd);
      }
    }
  }
  if (exit_code == 2) {
    std::fprintf(stderr, "sumo-criticality: error: bad input (stand-in)\n");
    std::printf("{\"status\":\"failed\",\"exit_code\":2,\"error\":\"bad input (stand-in)\"}\n");
    return 2;
  }
  if (output.empty()) {
    std::fprintf(stderr, "sumo-criticality: error: no --output FILE.sqlite given\n");
    return 2;
  }
  signal(SIGTERM, ignore_term ? SIG_IGN : OnTerm);
  signal(SIGINT, OnTerm);
  std::string status = "completed";
  if (sleep_s > 0) {
    const double until = sleep_s;
    double slept = 0;
    while (slept < until && !g_term) {
      usleep(10000);
      slept += 0.01;
    }
    if (g_term) status = "interrupted";
  }
  int collisions = 0, warnings = 0;
  if (!no_db) {
    sqlite3* db = nullptr;
    if (access(output.c_str(), F_OK) == 0 || sqlite3_open(output.c_str(), &db) != SQLITE_OK) {
      std::fprintf(stderr, "sumo-criticality: error: cannot create output '%s'\n", output.c_str());
      return 4;
    }
    std::string schema =
        std::string(
            "CREATE TABLE runs(id INTEGER PRIMARY KEY, started_utc TEXT, ended_utc TEXT, "
            "status TEXT, sumo_version TEXT, egos TEXT, options TEXT") +
        (newer ? ", step_length_s REAL);" : ");") +
        "CREATE TABLE steps(run_id INTEGER, time_s REAL, ego TEXT, p_collision REAL, estimator_ms"
        " REAL, objects INTEGER, speed_mps REAL, acting INTEGER);"
        "CREATE TABLE actions(run_id INTEGER, time_s REAL, ego TEXT, kind TEXT, accel_mps2 REAL,"
        " speed_mps REAL, p_collision REAL);";
    schema += newer ? "CREATE TABLE warnings(id INTEGER PRIMARY KEY, run_id INTEGER, ego TEXT,"
                      " start_s REAL, end_s REAL, peak_p REAL, x_m REAL, y_m REAL, edge TEXT);"
                      "CREATE TABLE collisions(run_id INTEGER, time_s REAL, collider TEXT, victim"
                      " TEXT, type TEXT, lane TEXT, pos_m REAL, anticipation_s REAL, x_m REAL,"
                      " y_m REAL, involves_ego INTEGER);"
                      "CREATE TABLE ego_events(run_id INTEGER, time_s REAL, ego TEXT, event TEXT);"
                      "CREATE TABLE egos(run_id INTEGER, ego TEXT, vehicle_class TEXT, vehicle_type"
                      " TEXT, length_m REAL, width_m REAL, first_s REAL);"
                      "CREATE TABLE warning_scenes(warning_id INTEGER, run_id INTEGER, ego TEXT,"
                      " time_s REAL, scene TEXT);"
                    : std::string(
                          "CREATE TABLE warnings(id INTEGER PRIMARY KEY, run_id INTEGER, ego TEXT,"
                          " start_s REAL, end_s REAL, peak_p REAL);"
                          "CREATE TABLE collisions(run_id INTEGER, time_s REAL, collider TEXT,"
                          " victim TEXT, type TEXT, lane TEXT, pos_m REAL") +
                          (no_anticipation ? ");" : ", anticipation_s REAL);");
    if (!Exec(db, schema)) return 4;
    Exec(db, "BEGIN");
    Exec(db,
         "INSERT INTO runs(id, started_utc, ended_utc, status, sumo_version, egos, options) "
         "VALUES(1, '2000-01-01T00:00:00Z', NULL, 'running', 'stand-in', "
         "'ego', '" +
             command + "')");
    for (int k = 1; k <= steps; ++k) {
      const double t = 0.1 * k;
      const double p = std::fmod(0.37 * k + 0.11 * seed + 0.05 * profiles, 1.0);
      Exec(db, "INSERT INTO steps VALUES(1, " + std::to_string(t) + ", 'ego', " +
                   std::to_string(p) + ", " + std::to_string(1.0 + 0.1 * (k % 3)) + ", 2, 10, 0)");
    }
    if (warn >= 0) {
      Exec(db, "INSERT INTO warnings(run_id, ego, start_s, end_s, peak_p" +
                   std::string(newer ? ", x_m, y_m, edge" : "") + ") VALUES(1, 'ego', " +
                   std::to_string(warn) + ", " + std::to_string(warn + 0.5) + ", 0.9" +
                   (newer ? ", 10.0, 1.5, 'e1'" : "") + ")");
      ++warnings;
    }
    if (collide >= 0 && act != "brake") {
      const bool warned = warn >= 0 && warn <= collide && collide <= warn + 0.5;
      Exec(db, "INSERT INTO collisions(run_id, time_s, collider, victim, type, lane, pos_m" +
                   std::string(no_anticipation ? "" : ", anticipation_s") +
                   (newer ? ", x_m, y_m, involves_ego" : "") + ") VALUES(1, " +
                   std::to_string(collide) + ", 'ego', 'other', 'collision', 'e1_0', 12.5" +
                   (no_anticipation ? ""
                    : warned        ? ", " + std::to_string(collide - warn)
                                    : ", NULL") +
                   (newer ? ", 12.5, -1.6, 1" : "") + ")");
      ++collisions;
    }
    if (newer) {
      Exec(db, "INSERT INTO ego_events VALUES(1, 0.1, 'ego', 'departed')");
      Exec(db, "UPDATE runs SET step_length_s = 0.1");
      Exec(db, "INSERT INTO egos VALUES(1, 'ego', '" + vclass + "', 'car', 4.5, 1.8, 0.1)");
      if (warn >= 0) {
        // The ego on a straight lane, 'other' standing 20 m ahead: a scene file's text.
        Exec(db, "INSERT INTO warning_scenes VALUES(1, 1, 'ego', " + std::to_string(warn) +
                     ", 'criticality-scene 1\nego ego 0 0 0 10 0 0 0 4.5 1.8 -\nlane own 0 0 1.6 "
                     "40 1.6 80 1.6 0 -1.6 40 -1.6 80 -1.6\nvehicle other 20 0 0 0 0 0 0 4.5 1.8 "
                     "- 0\n')");
      }
    }
    if (overlap >= 0) {
      Exec(db,
           "CREATE TABLE critical_events(run_id INTEGER, time_s REAL, ego TEXT, kind TEXT, other "
           "TEXT, value REAL)");
      Exec(db, "INSERT INTO critical_events VALUES(1, " + std::to_string(overlap) +
                   ", 'ego', 'overlap', 'p1', 2.5)");
    }
    Exec(db, "UPDATE runs SET status = '" + status + "', ended_utc = '2000-01-01T00:00:01Z'");
    Exec(db, "COMMIT");
    sqlite3_close(db);
  }
  std::printf(
      "{\"status\":\"%s\",\"sim_time_s\":%.1f,\"steps\":%d,\"egos\":1,\"estimates\":%d,"
      "\"warnings\":%d,\"actions\":0,\"collisions\":%d,\"estimator_ms_mean\":1.1,"
      "\"output\":\"%s\"}\n",
      status.c_str(), 0.1 * steps, steps, steps, warnings, collisions, output.c_str());
  return exit_code;
}
