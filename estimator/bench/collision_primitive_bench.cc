// collision-primitive-bench: the collision primitive alone (is this pair of oriented boxes
// overlapping?) on one seeded set of oriented-box pairs, for our separating-axis test, FCL's
// box-box test (Debian libfcl-dev) and Boost.Geometry's intersects on the same pairs:
// throughput per core (one thread) and agreement (pairs within 1e-6 m of touching excluded).
// A separate program from criticality-bench so that the latter needs no FCL on a GPU machine.
#include <fcl/fcl.h>

#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "bench/whole_option_names.h"
#include "core/geometry.h"
#include "core/oriented_box.h"

namespace bg = boost::geometry;
namespace po = boost::program_options;
using criticality::core::OrientedBox;

namespace {

using BgPoint = bg::model::d2::point_xy<double>;
using BgPolygon = bg::model::polygon<BgPoint, false, true>;  // counter-clockwise, closed

struct Pair {
  double x[2], y[2], yaw[2], hl[2], hw[2];
};

BgPolygon ToPolygon(const OrientedBox<double>& b) {
  BgPolygon p;
  const double sx[4] = {1, -1, -1, 1}, sy[4] = {1, 1, -1, -1};
  for (int k = 0; k <= 4; ++k) {
    const int q = k % 4;
    const double lx = sx[q] * b.hl, ly = sy[q] * b.hw;
    bg::append(p.outer(), BgPoint(b.cx + b.c * lx - b.s * ly, b.cy + b.s * lx + b.c * ly));
  }
  return p;
}

template <typename Fn>
double TimeMs(Fn fn) {
  const auto t0 = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int pairs = 1000000, repeat = 3;
  unsigned seed = 20190609;
  bool json = false;
  po::options_description desc(
      "collision-primitive-bench: our oriented-box overlap test against FCL (box-box) and\n"
      "Boost.Geometry (intersects) on the same seeded pairs, one thread.\n\nOptions");
  desc.add_options()("help,h", "show this help")("pairs", po::value(&pairs)->default_value(pairs),
                                                 "number of box pairs")(
      "repeat", po::value(&repeat)->default_value(repeat),
      "timed passes per method (median reported)")("seed", po::value(&seed)->default_value(seed),
                                                   "random seed of the pairs")(
      "json", po::bool_switch(&json), "one JSON object as the last line");
  try {
    po::variables_map vm;
    criticality::bench::StoreWholeNames(argc, argv, desc, &vm);
    if (vm.count("help")) {
      std::cout << desc;
      return 0;
    }
    po::notify(vm);
    if (pairs < 1 || repeat < 1) throw po::error("--pairs and --repeat must be >= 1");
  } catch (const po::error& e) {
    std::cerr << "collision-primitive-bench: error: " << e.what() << " (see --help)\n";
    return 2;
  }

  // Pairs: centres in an 8 m square, any heading, half sizes 0.1-3 m (pedestrians to trucks):
  // about half overlap, many of them crossing without a corner inside the other.
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(-4.0, 4.0),
      yaw(-criticality::core::kPi, criticality::core::kPi), half(0.1, 3.0);
  std::vector<OrientedBox<double>> a(pairs), b(pairs);
  std::vector<fcl::Boxd> fa, fb;
  std::vector<fcl::Transform3d> ta(pairs), tb(pairs);
  std::vector<BgPolygon> pa(pairs), pb(pairs);
  fa.reserve(pairs);
  fb.reserve(pairs);
  std::vector<char> near_touch(pairs, 0);
  for (int k = 0; k < pairs; ++k) {
    Pair p;
    for (int s = 0; s < 2; ++s) {
      p.x[s] = pos(rng);
      p.y[s] = pos(rng);
      p.yaw[s] = yaw(rng);
      p.hl[s] = half(rng);
      p.hw[s] = half(rng);
    }
    a[k] = criticality::core::MakeBox(p.x[0], p.y[0], p.yaw[0], p.hl[0], p.hw[0]);
    b[k] = criticality::core::MakeBox(p.x[1], p.y[1], p.yaw[1], p.hl[1], p.hw[1]);
    fa.emplace_back(2.0 * p.hl[0], 2.0 * p.hw[0], 1.0);
    fb.emplace_back(2.0 * p.hl[1], 2.0 * p.hw[1], 1.0);
    for (int s = 0; s < 2; ++s) {
      fcl::Transform3d& t = s == 0 ? ta[k] : tb[k];
      t.setIdentity();
      t.linear() = Eigen::AngleAxisd(p.yaw[s], Eigen::Vector3d::UnitZ()).toRotationMatrix();
      t.translation() = Eigen::Vector3d(p.x[s], p.y[s], 0.0);
    }
    pa[k] = ToPolygon(a[k]);
    pb[k] = ToPolygon(b[k]);
    // Within 1e-6 m of touching: growing and shrinking b by 1e-6 m changes the answer.
    const OrientedBox<double> grown{b[k].cx, b[k].cy,        b[k].c,
                                    b[k].s,  b[k].hl + 1e-6, b[k].hw + 1e-6};
    const OrientedBox<double> shrunk{b[k].cx, b[k].cy,        b[k].c,
                                     b[k].s,  b[k].hl - 1e-6, b[k].hw - 1e-6};
    near_touch[k] = criticality::core::BoxesOverlap(a[k], grown) !=
                    criticality::core::BoxesOverlap(a[k], shrunk);
  }

  std::vector<char> ours(pairs), ours_f(pairs), fcl_out(pairs), bg_out(pairs);
  std::vector<double> t_ours, t_ours_f, t_fcl, t_bg;
  std::vector<OrientedBox<float>> af(pairs), bf(pairs);
  for (int k = 0; k < pairs; ++k) {
    af[k] = OrientedBox<float>{float(a[k].cx), float(a[k].cy), float(a[k].c),
                               float(a[k].s),  float(a[k].hl), float(a[k].hw)};
    bf[k] = OrientedBox<float>{float(b[k].cx), float(b[k].cy), float(b[k].c),
                               float(b[k].s),  float(b[k].hl), float(b[k].hw)};
  }
  const fcl::CollisionRequestd request;  // boolean answer, one contact
  for (int r = 0; r < repeat; ++r) {
    t_ours.push_back(TimeMs([&] {
      for (int k = 0; k < pairs; ++k) ours[k] = criticality::core::BoxesOverlap(a[k], b[k]);
    }));
    t_ours_f.push_back(TimeMs([&] {
      for (int k = 0; k < pairs; ++k) ours_f[k] = criticality::core::BoxesOverlap(af[k], bf[k]);
    }));
    t_fcl.push_back(TimeMs([&] {
      for (int k = 0; k < pairs; ++k) {
        fcl::CollisionResultd result;
        fcl::collide(&fa[k], ta[k], &fb[k], tb[k], request, result);
        fcl_out[k] = result.isCollision();
      }
    }));
    t_bg.push_back(TimeMs([&] {
      for (int k = 0; k < pairs; ++k) bg_out[k] = bg::intersects(pa[k], pb[k]);
    }));
  }
  auto disagree = [&](const std::vector<char>& v) {
    long long n = 0;
    for (int k = 0; k < pairs; ++k) n += !near_touch[k] && v[k] != ours[k];
    return n;
  };
  long long overlapping = 0, excluded = 0;
  for (int k = 0; k < pairs; ++k) {
    overlapping += ours[k];
    excluded += near_touch[k];
  }
  const double m_ours = Median(t_ours), m_f = Median(t_ours_f), m_fcl = Median(t_fcl),
               m_bg = Median(t_bg);
  std::printf(
      "%d seeded oriented-box pairs (seed %u), %lld overlapping, %lld within 1e-6 m of touching "
      "excluded from agreement\n",
      pairs, seed, overlapping, excluded);
  std::printf("%-28s %10s %14s %12s %s\n", "method (one thread)", "median ms", "pairs/s", "x ours",
              "disagreements");
  auto row = [&](const char* name, double ms, long long dis) {
    std::printf("%-28s %10.2f %14.3e %12.2f %lld\n", name, ms, pairs / (ms * 1e-3), ms / m_ours,
                dis);
  };
  row("ours: SAT, double", m_ours, 0);
  row("ours: SAT, float", m_f, disagree(ours_f));
  row("FCL 0.7 box-box", m_fcl, disagree(fcl_out));
  row("Boost.Geometry intersects", m_bg, disagree(bg_out));
  if (json) {
    std::printf(
        "{\"pairs\":%d,\"seed\":%u,\"overlapping\":%lld,\"near_touch_excluded\":%lld,"
        "\"ours_ms\":%.3f,\"ours_float_ms\":%.3f,\"fcl_ms\":%.3f,\"boost_geometry_ms\":%.3f,"
        "\"speedup_vs_fcl\":%.2f,\"speedup_vs_boost_geometry\":%.2f,\"fcl_disagreements\":%lld,"
        "\"boost_geometry_disagreements\":%lld,\"float_disagreements\":%lld}\n",
        pairs, seed, overlapping, excluded, m_ours, m_f, m_fcl, m_bg, m_fcl / m_ours, m_bg / m_ours,
        disagree(fcl_out), disagree(bg_out), disagree(ours_f));
  }
  return 0;
}
