#pragma once
// The shader math of the arithmetic's families (render/arithmetic.h) where it is more than one
// IEEE operation: the members of the log2 family, and the denormal mode of fragment arithmetic.

#include "render/arithmetic.h"

namespace vt::reference {

// log2 as a degree-4 minimax polynomial in y = (m - 1) / (m + 1) (docs/design.md section 7, rule
// 8), evaluated with fused multiply-adds or with a product and a sum in their place. Its
// coefficients c0..c4, which the lanes' version (lane_shading.h) shares:
inline constexpr float kLog2Coefficients[5] = {
    2.88539009343309178325f, 0.961791550404184197881f, 0.577440339438736392009f,
    0.403343858251329912514f, 0.406718052498846252698f};
float polynomialLog2(float x, bool fused);

// logf(x) * 1.442695f (reference/softpipe-arithmetic.md, 5.2), bit for bit on the machine whose
// C library the implementation calls.
float naturalTimesLog2e(float x);

// The member `form` of the log2 family.
float log2Of(Log2Form form, float x);
// The arithmetic's log2: its measured table where it has one (render/measured_table.h), else its
// form.
inline float log2Of(const Arithmetic& arithmetic, float x) {
  return arithmetic.log2Table.table ? arithmetic.log2Table.table->of(x)
                                    : log2Of(arithmetic.log2, x);
}

// Sets the calling thread's denormal flushing (DAZ and FTZ) as `flush` says; restores it on
// destruction.
class DenormalMode {
 public:
  explicit DenormalMode(bool flush);
  ~DenormalMode();
  DenormalMode(const DenormalMode&) = delete;
  DenormalMode& operator=(const DenormalMode&) = delete;

 private:
  unsigned saved_;
};

}  // namespace vt::reference
