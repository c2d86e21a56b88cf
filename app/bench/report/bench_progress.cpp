#include "app/bench/report/bench_progress.h"

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace slime {
namespace {

constexpr int kBarWidth = 30;
constexpr double kRedrawSeconds = 0.1;  // at most ten redraws a second

}  // namespace

BenchProgress::BenchProgress(std::string label, double total)
    : label_(std::move(label)), total_(std::max(total, 1e-9)), enabled_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()), lastDraw_(start_) {
  if (enabled_) draw("");
}

BenchProgress::~BenchProgress() { finish(); }

void BenchProgress::advance(double amount, const std::string& what) {
  done_ += amount;
  const auto now = std::chrono::steady_clock::now();
  if (enabled_ && std::chrono::duration<double>(now - lastDraw_).count() >= kRedrawSeconds) {
    lastDraw_ = now;
    draw(what);
  }
}

void BenchProgress::finish() {
  if (finished_) return;
  finished_ = true;
  if (!enabled_) return;
  done_ = total_;
  draw("done");
  std::fputc('\n', stderr);
}

void BenchProgress::draw(const std::string& what) {
  const double fraction = std::clamp(done_ / total_, 0.0, 1.0);
  const int filled = static_cast<int>(fraction * kBarWidth);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kBarWidth, '.');
  // \r returns to the line start; \033[K clears what a longer previous line left behind.
  std::fprintf(stderr, "\r%s [%s] %3.0f%% %6.1f s  %s\033[K", label_.c_str(), bar.c_str(), 100.0 * fraction,
               elapsed, what.c_str());
  std::fflush(stderr);
}

}  // namespace slime
