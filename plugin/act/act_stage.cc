#include "plugin/act/act_stage.h"

#include <algorithm>
#include <cstdio>

#include "plugin/act/present_contacts.h"

namespace criticality::plugin {

double WarnValue(WarnOn on, const Result& r) {
  switch (on) {
    case WarnOn::kPCollision:
      return r.p_collision;
    case WarnOn::kPReference:
      return r.p_reference;
    case WarnOn::kUnavoidability:
      return r.unavoidability;
  }
  return r.p_collision;
}

std::string WarnOnName(WarnOn on) {
  switch (on) {
    case WarnOn::kPCollision:
      return "p_collision";
    case WarnOn::kPReference:
      return "p_reference";
    case WarnOn::kUnavoidability:
      return "unavoidability";
  }
  return "?";
}

std::string ActName(Act act) {
  switch (act) {
    case Act::kNone:
      return "none";
    case Act::kWarn:
      return "warn";
    case Act::kBrake:
      return "brake";
  }
  return "?";
}

ActStage::ActStage(const ActConfig& config, SumoWorld* world, double step_s,
                   std::function<Result(const Scene&)> estimate)
    : config_(config),
      world_(world),
      estimate_(estimate),
      episodes_(config.warning),
      closed_loop_(config.closed_loop, world, step_s,
                   estimate
                       ? ClosedLoop::SceneRisk([estimate, on = config.warn_on](const Scene& scene) {
                           return WarnValue(on, estimate(scene));
                         })
                       : ClosedLoop::SceneRisk{}) {}

void ActStage::Leaving(const Observation& obs, ActOutcome* out) {
  for (const EgoEvent& e : obs.ego_events) {
    if (e.kind == EgoEventKind::kTeleportEnd) closed_loop_.TeleportEnded(e.ego);
    if (!LeavesTheRoad(e.kind)) continue;
    const bool teleport = e.kind == EgoEventKind::kTeleportStart;
    if (episodes_.Leave(e.ego)) {
      WarningEvent w;
      w.ego = e.ego;
      w.change = WarningChange::kClose;
      out->warnings.push_back(std::move(w));
    }
    closed_loop_.Leave(e.ego, teleport);
    standing_contacts_.erase(e.ego);
  }
}

void ActStage::Warn(const ObjectSnapshot& ego, const Result& r, double t, double p, bool publish,
                    ActOutcome* out) {
  if (const auto change = episodes_.Update(ego.id, t, p)) {
    WarningEvent w;
    w.ego = ego.id;
    w.change = *change;
    w.p_collision = p;
    if (*change == WarningChange::kOpen) {
      w.x_m = ego.state.x_m;
      w.y_m = ego.state.y_m;
      w.edge = ego.edge;
      const ObjectResult* main = MainObject(r);
      w.object = main ? main->id : "";
    }
    out->warnings.push_back(std::move(w));
  }
  if (publish) world_->Publish(ego.id, p, episodes_.Warning(ego.id));
}

EgoStep ActStage::Row(const ObjectSnapshot& ego, const Result& r) const {
  EgoStep step;
  step.ego = ego.id;
  step.speed_mps = ego.state.speed_mps;
  step.p_collision = r.p_collision;
  step.p_reference = r.p_reference;
  step.unavoidability = r.unavoidability;
  step.estimator_ms = r.times.total_ms;
  step.objects = static_cast<int>(r.objects.size());
  for (const ObjectResult& obj : r.objects) step.objects_in_reach += obj.out_of_reach ? 0 : 1;
  step.shortcut = r.answered_by_reach_shortcut;
  step.acting = closed_loop_.Acting(ego.id);
  if (const ObjectResult* main = MainObject(r)) step.main_object = main->id;
  return step;
}

void ActStage::CloseTheLoop(double t, const ObjectSnapshot& ego, const Scene& scene,
                            const Result& r, double p, ActOutcome* out) {
  // For a standing ego the closed loop decides on the scene without the objects in contact
  // with it now (present_contacts.h), and for a moving one without those of them that stay in
  // contact since it stood (standing_contacts_): re-estimated only where it would act on p
  // (engaged, or p at the engage threshold) and there is such a contact.
  std::vector<std::string> contacts;
  const bool would_act = closed_loop_.PhaseOf(ego.id) != ClosedLoop::Phase::kIdle ||
                         p >= config_.closed_loop.policy.engage_threshold;
  const auto stood = standing_contacts_.find(ego.id);
  if (estimate_ && would_act) {
    const std::vector<std::string> now = ObjectsInContact(scene);
    if (ego.state.speed_mps < ClosedLoop::kStandstill) {
      contacts = now;
    } else if (stood != standing_contacts_.end()) {
      for (const std::string& id : now) {
        if (std::find(stood->second.begin(), stood->second.end(), id) != stood->second.end())
          contacts.push_back(id);
      }
    }
  }
  // A contact that ended, or any while the loop would not act, is forgotten.
  if (!contacts.empty()) {
    standing_contacts_[ego.id] = contacts;
  } else if (stood != standing_contacts_.end()) {
    standing_contacts_.erase(stood);
  }
  if (contacts.empty()) {
    closed_loop_.Step(t, ego, scene, r, p, &out->actions);
    return;
  }
  const Scene cleared = WithoutObjects(scene, contacts);
  const Result without = estimate_(cleared);
  const size_t first_new = out->actions.size();
  closed_loop_.Step(t, ego, cleared, without, WarnValue(config_.warn_on, without), &out->actions);
  std::string names;
  for (const std::string& id : contacts) names += (names.empty() ? "" : " ") + id;
  char b[96];
  std::snprintf(b, sizeof b, " (%.3f with them)", p);
  for (size_t a = first_new; a < out->actions.size(); ++a)
    out->actions[a].detail += "; decided without the objects in contact now: " + names + b;
}

ActOutcome ActStage::Run(const Observation& obs, const SceneBatch& batch,
                         const std::vector<Result>& results, const PublishTo& publish) {
  ActOutcome out;
  Leaving(obs, &out);
  for (size_t k = 0; k < batch.scenes.size(); ++k) {
    const ObjectSnapshot& ego = batch.EgoOf(k);
    const Result& r = results[k];
    const double p = WarnValue(config_.warn_on, r);
    if (config_.act != Act::kNone) Warn(ego, r, obs.time_s, p, publish.Reaches(ego.id), &out);
    if (config_.act == Act::kBrake) CloseTheLoop(obs.time_s, ego, batch.scenes[k], r, p, &out);
    out.steps.push_back(Row(ego, r));
  }
  return out;
}

}  // namespace criticality::plugin
