#pragma once

#include <glm/vec2.hpp>
#include <type_traits>

namespace vt {

// Two draws of one random engine as a point, the second coordinate drawn first. C++ leaves the
// order in which a call's arguments are evaluated unspecified (GCC evaluates the last first, clang
// the first), so glm::vec2(draw(), draw()) is a different point under each compiler, and a probe
// folder recorded by a vt built with one is refused by a vt built with the other. The order here
// is GCC's, the one the records already made (data/gpus/) were drawn in.
template <class Draw>
auto drawPoint(Draw&& draw) {
  using Value = std::decay_t<decltype(draw())>;
  const Value y = draw();
  const Value x = draw();
  return glm::vec<2, Value>(x, y);
}

}  // namespace vt
