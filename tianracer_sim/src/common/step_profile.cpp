#include "tianracer_sim/common/step_profile.h"

#include <algorithm>
#include <cstdio>

namespace tianracer_sim {

int StepProfile::row(const std::string& name) {
  std::lock_guard<std::mutex> lock(mutex_);
  const int n = count_.load(std::memory_order_acquire);
  for (int i = 0; i < n; ++i) {
    if (rows_[i].name == name) return i;
  }
  if (n == kMaxRows - 1) {
    if (rows_[n].name.empty()) {
      rows_[n].name = "other";
      count_.store(n + 1, std::memory_order_release);
    }
    return n;
  }
  if (n == kMaxRows) return n - 1;
  rows_[n].name = name;
  count_.store(n + 1, std::memory_order_release);
  return n;
}

void StepProfile::reset() {
  const int n = count_.load(std::memory_order_acquire);
  for (int i = 0; i < n; ++i) {
    rows_[i].ns.store(0, std::memory_order_relaxed);
    rows_[i].calls.store(0, std::memory_order_relaxed);
  }
  steps_.store(0, std::memory_order_relaxed);
}

std::vector<StepProfile::Figure> StepProfile::figures() const {
  std::vector<Figure> out;
  const int n = count_.load(std::memory_order_acquire);
  for (int i = 0; i < n; ++i) {
    Figure f;
    f.name = rows_[i].name;
    f.seconds = 1e-9 * static_cast<double>(rows_[i].ns.load(std::memory_order_relaxed));
    f.calls = rows_[i].calls.load(std::memory_order_relaxed);
    f.part = f.name.find(" / ") != std::string::npos;
    out.push_back(std::move(f));
  }
  return out;
}

std::string StepProfile::table() const {
  const std::vector<Figure> rows = figures();
  const double steps = static_cast<double>(std::max<std::uint64_t>(1, this->steps()));
  std::string out;
  char line[256];
  std::snprintf(line, sizeof(line), "%-48s | %12s | %10s | %12s\n", "row", "us per step",
                "calls/step", "us per call");
  out += line;
  out += std::string(48, '-') + "-|-" + std::string(12, '-') + "-|-" + std::string(10, '-') +
         "-|-" + std::string(12, '-') + "\n";
  double step_total = 0.0, bullet = 0.0;
  for (const Figure& f : rows) {
    if (f.calls == 0) continue;
    if (f.name == kStep || f.name.rfind(kBetweenSteps, 0) == 0) step_total += f.seconds;
    if (f.name == kBullet) bullet = f.seconds;
    const std::string name = f.part ? "  " + f.name : f.name;
    std::snprintf(line, sizeof(line), "%-48s | %12.3f | %10.4f | %12.3f\n", name.c_str(),
                  1e6 * f.seconds / steps, static_cast<double>(f.calls) / steps,
                  1e6 * f.seconds / static_cast<double>(f.calls));
    out += line;
  }
  std::snprintf(line, sizeof(line), "%-48s | %12.3f |\n", "step outside Bullet",
                1e6 * (step_total - bullet) / steps);
  out += line;
  std::snprintf(line, sizeof(line), "%llu steps\n",
                static_cast<unsigned long long>(this->steps()));
  out += line;
  return out;
}

}  // namespace tianracer_sim
