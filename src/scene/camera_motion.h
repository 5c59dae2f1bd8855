#pragma once
// Camera motion between frames, for prediction (thesis 4.2.4) and the hot spot (4.2.3.1).
//
// LookAhead camera: the current camera with the last frame's motion applied once more, i.e. the
// previous camera moved twice (a 45 degree turn in one frame predicts 90 degrees from where it
// started). The thesis's fix for a sudden stop (4.2.4.1), as implemented here: the predicted step
// is scaled by max(0, 1 - |a| / |v|), v the last motion and a its change from the motion before
// (the second derivative), over position and target together: steady motion is predicted in
// full, a motion that starts or changes abruptly not at all.
//
// Hot spot: the screen point the heuristic weights most. Fixed: the centre. Shifted: moved to the
// screen's border in the direction the camera turned (new content enters there). Sliding: moved by
// the turn's share of half the field of view, up to the border.

#include <glm/glm.hpp>
#include <string>

#include "common/enum_names.h"
#include "scene/camera.h"

namespace vt {

enum class LookAhead { kNone, kPlain, kStopFix };
enum class HotSpotMode { kFixed, kShifted, kSliding };

inline constexpr EnumNames<LookAhead, 3> kLookAheadNames = {{
    {LookAhead::kNone, "none"},
    {LookAhead::kPlain, "plain"},
    {LookAhead::kStopFix, "stopfix"},
}};
inline constexpr EnumNames<HotSpotMode, 3> kHotSpotModeNames = {{
    {HotSpotMode::kFixed, "fixed"},
    {HotSpotMode::kShifted, "shifted"},
    {HotSpotMode::kSliding, "sliding"},
}};

// Throw std::invalid_argument naming the value and the table's names.
LookAhead parseLookAhead(const std::string& name);
HotSpotMode parseHotSpotMode(const std::string& name);
std::string toString(LookAhead mode);
std::string toString(HotSpotMode mode);

Camera lookAheadCamera(const Camera& beforePrevious, const Camera& previous, const Camera& current,
                       LookAhead mode);

// The hot spot in pixels (window y up) for a turn from `previous` to `current`.
glm::vec2 hotSpot(const Camera& previous, const Camera& current, Viewport viewport,
                  HotSpotMode mode);

}  // namespace vt
