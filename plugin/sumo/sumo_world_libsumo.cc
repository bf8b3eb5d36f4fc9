// SumoWorld on libsumo: SUMO runs inside this process.
#include <libsumo/libsumo.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#define CRIT_SUMO libsumo
#include "plugin/sumo/sumo_world_impl.inc"

namespace criticality::plugin {

namespace {

// SUMO prints its load errors itself, over several lines. Capture its standard error while
// loading, so that the driver reports one line that includes SUMO's reasons.
class StderrCapture {
 public:
  StderrCapture() {
    std::fflush(stderr);
    file_ = std::tmpfile();
    saved_ = dup(2);
    if (file_ && saved_ >= 0) dup2(fileno(file_), 2);
  }
  ~StderrCapture() { Restore(); }
  /** Restores stderr and returns what was written, errors first, on one line. */
  std::string Restore() {
    if (saved_ < 0) return "";
    std::fflush(stderr);
    dup2(saved_, 2);
    close(saved_);
    saved_ = -1;
    std::string text, errors;
    if (file_) {
      std::rewind(file_);
      char buf[512];
      while (std::fgets(buf, sizeof buf, file_)) {
        std::string line(buf);
        while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
        if (line.rfind("Error:", 0) == 0) errors += (errors.empty() ? "" : "; ") + line.substr(7);
        text += line + "\n";
      }
      std::fclose(file_);
      file_ = nullptr;
    }
    captured_ = text;
    return errors;
  }
  const std::string& text() const { return captured_; }

 private:
  std::FILE* file_{nullptr};
  int saved_{-1};
  std::string captured_;
};

}  // namespace

std::unique_ptr<SumoWorld> StartLibsumo(const std::vector<std::string>& args) {
  StderrCapture capture;
  std::string failure;
  try {
    libsumo::Simulation::load(args);
  } catch (const libsumo::FatalTraCIError& e) {
    failure = e.what();
  } catch (const libsumo::TraCIException& e) {
    failure = e.what();
  } catch (const std::exception& e) {
    failure = e.what();
  }
  const std::string errors = capture.Restore();
  if (!failure.empty()) {
    throw SumoError("loading SUMO failed: " + failure +
                    (errors.empty() ? "" : " (" + errors + ")"));
  }
  // SUMO goes on after some errors of its own (an invalid value of an option such as
  // collision.action: it runs with the default and still exits 0); the run would not be the one
  // asked for. The campaign's plan check refuses them too.
  if (!errors.empty()) {
    try {
      libsumo::Simulation::close();
    } catch (...) {  // the load's errors are the message
    }
    throw SumoError("SUMO reported errors while loading (" + errors +
                    "); fix the SUMO configuration or options");
  }
  std::fputs(capture.text().c_str(), stderr);  // warnings of a successful load stay visible
  return std::make_unique<World>();
}

}  // namespace criticality::plugin
