// ThreadSanitizer cannot see the synchronisation inside Debian's TBB (libtbb is not instrumented), so
// the hand-over of data between the thread that starts a parallel_for and the workers that run it
// looks like a race. These two calls tell it what TBB guarantees: everything before handOff() on one
// thread happens before everything after takeOver() on another, for the same token. In builds
// without -fsanitize=thread they compile to nothing.
#pragma once

#if defined(__SANITIZE_THREAD__)
extern "C" void __tsan_acquire(void* address);
extern "C" void __tsan_release(void* address);
#endif

namespace slime {

inline void handOff([[maybe_unused]] void* token) {
#if defined(__SANITIZE_THREAD__)
  __tsan_release(token);
#endif
}

inline void takeOver([[maybe_unused]] void* token) {
#if defined(__SANITIZE_THREAD__)
  __tsan_acquire(token);
#endif
}

}  // namespace slime
