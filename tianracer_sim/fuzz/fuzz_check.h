// What a harness does when a parser breaks one of its promises: it names the harness and the
// promise on stderr and aborts, which libFuzzer reports as a crash with the input that caused it.
#ifndef TIANRACER_SIM_FUZZ_FUZZ_CHECK_H
#define TIANRACER_SIM_FUZZ_FUZZ_CHECK_H

#include <cstdio>
#include <cstdlib>

namespace tianracer_sim_fuzz {

struct PromiseCheck {
  const char* harness;
  void operator()(bool ok, const char* what) const {
    if (!ok) {
      std::fprintf(stderr, "%s: broken promise: %s\n", harness, what);
      std::abort();
    }
  }
};

}  // namespace tianracer_sim_fuzz

#endif  // TIANRACER_SIM_FUZZ_FUZZ_CHECK_H
