// LeakSanitizer's end-of-process check, run before third-party libraries tear themselves down.
#pragma once

#include <cstdlib>

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(leak_sanitizer)
#define VS11_LEAK_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) && !defined(VS11_LEAK_SANITIZER)
#define VS11_LEAK_SANITIZER 1
#endif
#ifdef VS11_LEAK_SANITIZER
#include <sanitizer/lsan_interface.h>
#endif

namespace vs11 {

// In a sanitizer build, LeakSanitizer's end-of-process check, now (a leak ends the process with its
// report); elsewhere nothing. The check runs once: later calls, and the one at exit, do nothing.
inline void CheckForLeaksNow() {
#ifdef VS11_LEAK_SANITIZER
  __lsan_do_leak_check();
#endif
}

// Calls CheckForLeaksNow when this guard (declared first in main) goes out of scope, before the
// static destructors run. Why: OpenImageIO loads OpenVDB, whose log4cplus shuts its thread pool down
// in a static destructor by letting the workers detach and exit on their own. LeakSanitizer's check
// at exit stops every thread of the process, and a thread in the middle of exiting crashes its tracer
// now and then ("Tracer caught signal 11", an abort): CI's ASan stage lost two irrmap batch runs that
// way. At the end of main those workers are idle.
class EndOfMainLeakCheck {
 public:
  EndOfMainLeakCheck() = default;
  EndOfMainLeakCheck(const EndOfMainLeakCheck&) = delete;
  EndOfMainLeakCheck& operator=(const EndOfMainLeakCheck&) = delete;
  ~EndOfMainLeakCheck() { CheckForLeaksNow(); }
};

// Registers CheckForLeaksNow with std::atexit, once. exit runs its handlers and the static
// destructors in the reverse order of their registration, so the check runs before the destructors
// of every library loaded so far. For a library dlopen'ed while the process runs (the OpenImageIO
// module), in a process whose main is not ours (a libFuzzer target), and so without
// EndOfMainLeakCheck.
inline void CheckForLeaksBeforeLoadedLibrariesUnload() {
#ifdef VS11_LEAK_SANITIZER
  static const bool registered = std::atexit(CheckForLeaksNow) == 0;
  (void)registered;
#endif
}

}  // namespace vs11
