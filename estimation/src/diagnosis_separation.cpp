// The experiment that would separate two candidate effects which explain the
// same residual on this log: both are evaluated, with their fitted
// parameters, over conditions a user can set up (insertion depth, which joint
// is pushed and how hard and which way, how long into the session, holding or
// moving), each as a change from the log's typical push; the condition where
// the two predicted changes differ most is named, with both predictions.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "diagnosis_internal.h"

namespace pliant::estimation::diagnosis {
namespace {

struct Condition {
  int joint = 0;
  double depth_m = 0.155;
  double load_nm = 1.0;
  double time_s = 0.0;
  bool moving = false;
};

// What a term changes in the modelled residual at a condition, in mm at the tip.
Eigen::Vector2d Change(const Sample& typical, const BaseModel& model, const std::vector<Term>& fixed,
                       const Term& term, const Condition& c) {
  Sample s = typical;
  s.state.insertion_depth_m = c.depth_m;
  s.state.compliance_rad_per_nm = models::CompliancesAt(model.parameters().joints, c.depth_m);
  s.state.external_torque_nm.setZero();
  s.state.external_torque_nm[c.joint] = c.load_nm;
  s.state.time_s = c.time_s;
  s.state.velocity_rad_s.setZero();
  s.state.effort_rate_nm_s.setZero();
  if (c.moving) {
    // A slow ramp into the load: 0.05 rad/s, 1 N·m/s, in the load's direction.
    s.state.velocity_rad_s[c.joint] = std::copysign(0.05, c.load_nm);
    s.state.effort_rate_nm_s[c.joint] = std::copysign(1.0, c.load_nm);
  }
  std::vector<Term> with = fixed;
  with.push_back(term);
  std::vector<const double*> values;
  for (const Term& t : with) values.push_back(t.parameters.data());
  const Eigen::Vector2d a = ModelResidual<double>(s, model, fixed, values);
  const Eigen::Vector2d b = ModelResidual<double>(s, model, with, values);
  return (a - b).cwiseProduct(typical.mm_per_rad);
}

// A log of poses has no time to name (its t is a pose index).
std::string Describe(const Condition& c, bool poses) {
  char text[200];
  std::snprintf(text, sizeof text, "%s joint %d to %+.1f N·m at depth %.3f m", c.moving ? "ramp" : "hold",
                c.joint + 1, c.load_nm, c.depth_m);
  std::string out = text;
  if (!poses) {
    std::snprintf(text, sizeof text, ", %.0f s into the log", c.time_s);
    out += text;
  }
  return out;
}

}  // namespace

std::string SeparatingExperiment(const Problem& problem, const BaseModel& model,
                                 const std::vector<Term>& fixed, const Term& a, const Term& b) {
  if (problem.samples.empty()) return "";
  // The log's typical push: its median sample, pushed +1 N·m on its first
  // recorded joint.
  const Sample& typical = problem.samples[problem.samples.size() / 2];
  double t_end = 0.0;
  for (const Sample& s : problem.samples) t_end = std::max(t_end, s.state.time_s);
  const auto& joint1 = model.parameters().joints[0];
  const double depth_lo = joint1.depth_min_m > 0.0 ? joint1.depth_min_m : 0.09;
  const double depth_hi = joint1.depth_max_m > depth_lo ? joint1.depth_max_m : 0.22;
  // Only what the log can show: a recorded joint, and no time or motion on a
  // log of poses.
  const int first = problem.joint_recorded[0] ? 0 : 1;
  const bool poses = problem.quasi_static;
  Condition reference{first, typical.state.insertion_depth_m, 1.0, 0.5 * t_end, false};
  const Eigen::Vector2d ra = Change(typical, model, fixed, a, reference);
  const Eigen::Vector2d rb = Change(typical, model, fixed, b, reference);
  Condition best = reference;
  double best_gap = -1.0;
  Eigen::Vector2d best_a = ra, best_b = rb;
  for (int joint = first; joint < 2; ++joint) {
    if (!problem.joint_recorded[joint]) continue;
    for (double depth : {depth_lo, 0.5 * (depth_lo + depth_hi), depth_hi}) {
      for (double load : {-2.0, -1.0, -0.5, 0.5, 1.0, 2.0}) {
        for (double time : {0.0, 0.5 * t_end, std::max(600.0, 2.0 * t_end)}) {
          for (bool moving : {false, true}) {
            if (poses && (moving || time != reference.time_s)) continue;
            const Condition c{joint, depth, load, time, moving};
            const Eigen::Vector2d ca = Change(typical, model, fixed, a, c) - ra;
            const Eigen::Vector2d cb = Change(typical, model, fixed, b, c) - rb;
            const double gap = (ca - cb).norm();
            if (gap > best_gap + 1e-12) best_gap = gap, best = c, best_a = ca, best_b = cb;
          }
        }
      }
    }
  }
  char text[400];
  std::snprintf(text, sizeof text,
                "%s: %s predicts %.3f mm at the tip, %s %.3f mm (each against a hold of joint %d "
                "at +1 N·m, depth %.3f m, mid-log); they differ by %.3f mm there",
                Describe(best, poses).c_str(), a.name.c_str(), best_a.norm(), b.name.c_str(),
                best_b.norm(), first + 1, reference.depth_m, best_gap);
  return text;
}

}  // namespace pliant::estimation::diagnosis
