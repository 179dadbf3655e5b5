#pragma once
// Command line and timing loop shared by the C++ runners of the comparison
// benchmark (ember_bench run, cgal_runner). See docs/benchmark.md.
//
//   RUNNER A.bin B.bin [--ops union,intersection,difference] [--runs R]
//          [--budget-ms B] [--threads T] [--warmup W]
//
// For every operation one JSON line goes to stdout (flushed at once, so a
// crash in a later operation keeps the earlier ones):
//   {"tool":..,"op":..,"ok":true,"runs":n,"median_ms":..,"times_ms":[..],"cold_ms":..,
//    "out_polygons":..,"out_volume":..,"in_triangles":..,"peak_rss_kib":..,"error":"",...}
// --warmup W runs the operation W times untimed first (the first of them,
// in a fresh process, is reported as cold_ms): the median then describes a
// Boolean in a loop, as in the users' milling and batch workloads, and
// cold_ms the one-shot cost (first touch of memory, thread start-up).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "meshbin.hpp"

namespace bench {

struct RunnerArgs {
  std::string a, b;
  std::vector<std::string> ops{"union", "intersection", "difference"};
  int runs = 5;
  double budget_ms = 1e300;  // stop repeating once this much time was spent (at least one run)
  int threads = 1;
  int warmup = 0;          // untimed runs before the timed ones (the first reported as cold_ms)
  bool solid = false;      // ember only: BooleanOptions::all_solid (--assume-solid)
  bool no_detect = false;  // ember only: BooleanOptions::detect_solid = false
};

inline RunnerArgs parse_runner_args(int argc, char** argv, int first) {
  RunnerArgs r;
  std::vector<std::string> pos;
  for (int i = first; i < argc; ++i) {
    std::string s = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error("missing value after " + s);
      return argv[++i];
    };
    if (s == "--ops") {
      r.ops.clear();
      std::stringstream ss(next());
      for (std::string op; std::getline(ss, op, ',');)
        if (!op.empty()) r.ops.push_back(op);
    } else if (s == "--runs") {
      r.runs = std::max(1, std::stoi(next()));
    } else if (s == "--budget-ms") {
      r.budget_ms = std::stod(next());
    } else if (s == "--threads") {
      r.threads = std::stoi(next());
    } else if (s == "--warmup") {
      r.warmup = std::max(0, std::stoi(next()));
    } else if (s == "--solid") {
      r.solid = true;
    } else if (s == "--no-detect") {
      r.no_detect = true;
    } else {
      pos.push_back(s);
    }
  }
  if (pos.size() != 2) throw std::runtime_error("expected two mesh files");
  r.a = pos[0];
  r.b = pos[1];
  return r;
}

/// The median (mean of the middle two for an even count); 0 for none.
inline double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

/// What one timed Boolean produced (filled by the tool's run function).
struct OpOutput {
  bool ok = true;
  std::string error;
  std::size_t polygons = 0;
  double volume = 0;
};

/// Runs `once` up to args.runs times (fewer if the budget is spent) and prints
/// the JSON line. `once(out)` performs one complete timed run; its wall time
/// (steady clock) is what is measured. `post(out)` runs after the last timing
/// (untimed) to compute volume and counts from the last result. `extra()`,
/// if given, returns more JSON members (",\"name\":value...") to append.
inline void time_op(const char* tool, const RunnerArgs& args, const std::string& op, std::size_t in_triangles,
                    const std::function<void(OpOutput&)>& once, const std::function<void(OpOutput&)>& post,
                    const std::function<std::string()>& extra = {}) {
  std::vector<double> times;
  OpOutput out;
  double total = 0;
  double cold_ms = -1;
  for (int r = 0; r < args.warmup + args.runs; ++r) {
    OpOutput o;
    auto t0 = std::chrono::steady_clock::now();
    try {
      once(o);
    } catch (const std::exception& e) {
      o.ok = false;
      o.error = std::string("exception: ") + e.what();
    } catch (...) {
      o.ok = false;
      o.error = "unknown exception";
    }
    auto t1 = std::chrono::steady_clock::now();
    double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    out = o;
    if (!o.ok) break;
    if (r < args.warmup) {
      if (r == 0) cold_ms = ms;
      continue;
    }
    times.push_back(ms);
    total += ms;
    if (total >= args.budget_ms) break;
  }
  if (out.ok) {
    try {
      post(out);
    } catch (const std::exception& e) {
      out.ok = false;
      out.error = std::string("exception while reading result: ") + e.what();
    }
  }
  const double median = median_of(times);
  std::string ts;
  for (double t : times) {
    if (!ts.empty()) ts += ',';
    ts += json_number(t);
  }
  std::printf(
      "{\"tool\":\"%s\",\"op\":\"%s\",\"threads\":%d,\"ok\":%s,\"runs\":%zu,\"median_ms\":%s,\"times_ms\":[%s],"
      "\"cold_ms\":%s,\"out_polygons\":%zu,\"out_volume\":%s,\"in_triangles\":%zu,\"peak_rss_kib\":%ld,\"error\":\"%"
      "s\"%s}\n",
      tool, op.c_str(), args.threads, out.ok ? "true" : "false", times.size(),
      out.ok ? json_number(median).c_str() : "null", ts.c_str(), cold_ms >= 0 ? json_number(cold_ms).c_str() : "null",
      out.polygons, out.ok ? json_number(out.volume).c_str() : "null", in_triangles, peak_rss_kib(),
      json_escape(out.error).c_str(), out.ok && extra ? extra().c_str() : "");
  std::fflush(stdout);
}

}  // namespace bench
