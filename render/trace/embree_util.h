// Small pieces every user of Embree here needs: rays filled the way Debian's build requires, device
// errors turned into messages, and flush-to-zero while tracing (SPEC §10).
#pragma once

#include "render/trace/ray.h"

#include <embree3/rtcore.h>
#include <xmmintrin.h>

#include <string>

namespace slime {

// Fills an Embree ray from ours. Debian's Embree has ray masks on, so mask is all ones; flags 0.
inline void toEmbreeRay(const Ray& ray, RTCRay& out) {
  out.org_x = ray.origin.x;
  out.org_y = ray.origin.y;
  out.org_z = ray.origin.z;
  out.dir_x = ray.direction.x;
  out.dir_y = ray.direction.y;
  out.dir_z = ray.direction.z;
  out.tnear = ray.tNear;
  out.tfar = ray.tFar;
  out.time = 0.0f;
  out.mask = 0xFFFFFFFFu;
  out.id = 0;
  out.flags = 0;
}

// An rtcSetDeviceErrorFunction callback: stores the message in the std::string at userPtr, to be
// thrown by the caller after the call that failed.
inline void recordEmbreeError(void* userPtr, RTCError code, const char* message) {
  *static_cast<std::string*>(userPtr) =
      "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "(no message)");
}

// Flush-to-zero and denormals-are-zero while in scope (SPEC §10), restoring the caller's MXCSR after.
class FlushDenormals {
 public:
  FlushDenormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }  // FTZ = bit 15, DAZ = bit 6
  ~FlushDenormals() { _mm_setcsr(saved_); }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  unsigned saved_;
};

}  // namespace slime
