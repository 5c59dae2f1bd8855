#pragma once
// The precision profiles' arithmetic where it is more than IEEE float in source order
// (render/precision_profile.h): llvmpipe's and softpipe's log2 and the denormal flushing of
// fragment arithmetic.

#include "render/precision_profile.h"

namespace vt::reference {

// llvmpipe's log2 (DESIGN section 7, rule 8), bit for bit.
float llvmpipeLog2(float x);

// softpipe's log2 (reference/softpipe-arithmetic.md, 5.2): logf(x) * 1.442695f, bit for bit on
// the machine whose C library softpipe calls.
float softpipeLog2(float x);

// The profile's log2.
float profileLog2(PrecisionProfile profile, float x);

// Sets the calling thread's denormal flushing to what `profile` does, or as `flush` says;
// restores on destruction.
class DenormalMode {
 public:
  explicit DenormalMode(PrecisionProfile profile);
  explicit DenormalMode(bool flush);
  ~DenormalMode();
  DenormalMode(const DenormalMode&) = delete;
  DenormalMode& operator=(const DenormalMode&) = delete;

 private:
  unsigned saved_;
};

}  // namespace vt::reference
